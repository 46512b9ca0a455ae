import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

// The page lives in www/, static assets (presets, sample data) in public/, the engine package
// that wasm-pack builds in crate/pkg/. `npm run build` writes a self-contained static folder
// dist/ that any static file server can host (relative paths, no server-side code).
export default defineConfig({
  root: 'www',
  base: './',
  publicDir: fileURLToPath(new URL('./public', import.meta.url)),
  resolve: {
    alias: {
      '@engine': fileURLToPath(new URL('./crate/pkg/fiveaxis.js', import.meta.url)),
    },
  },
  worker: { format: 'es' },
  build: {
    outDir: fileURLToPath(new URL('./dist', import.meta.url)),
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 5000,
  },
  server: { fs: { allow: ['..'] } },
});
