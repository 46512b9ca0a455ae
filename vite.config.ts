import { defineConfig, type Plugin } from 'vite';
import { fileURLToPath } from 'node:url';
import { createHash } from 'node:crypto';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';

const publicDir = fileURLToPath(new URL('./public', import.meta.url));

function listFiles(dir: string): string[] {
  return readdirSync(dir).flatMap((name) => {
    const p = join(dir, name);
    return statSync(p).isDirectory() ? listFiles(p) : [p];
  });
}

/**
 * Writes sw.js, the service worker that makes the page work offline after the first visit:
 * it precaches every file of the build (the bundle, the engine, Plotly, presets) under a cache
 * named after their content, serves them cache-first, and pages network-first.
 */
function serviceWorker(): Plugin {
  return {
    name: 'fiveaxis-service-worker',
    apply: 'build',
    generateBundle(_options, bundle) {
      const files = [
        ...Object.keys(bundle),
        ...listFiles(publicDir).map((f) => relative(publicDir, f).split('\\').join('/')),
      ].filter((f) => f !== 'sw.js' && !f.endsWith('.map'));
      const hash = createHash('sha256');
      for (const f of files.sort()) {
        const item = bundle[f];
        hash.update(f);
        if (item) hash.update(item.type === 'chunk' ? item.code : item.source);
        else hash.update(readFileSync(join(publicDir, f)));
      }
      const version = hash.digest('hex').slice(0, 16);
      const source = readFileSync(fileURLToPath(new URL('./www/sw-template.js', import.meta.url)), 'utf8')
        .replace('__VERSION__', version)
        .replace('__ASSETS__', JSON.stringify(['./', 'index.html', ...files]));
      this.emitFile({ type: 'asset', fileName: 'sw.js', source });
    },
  };
}

// The page lives in www/, static assets (presets, sample data) in public/, the engine package
// that wasm-pack builds in wasm/pkg/. `npm run build` writes a self-contained static folder
// dist/ that any static file server can host (relative paths, no server-side code).
export default defineConfig({
  root: 'www',
  base: './',
  publicDir,
  plugins: [serviceWorker()],
  resolve: {
    alias: {
      '@engine': fileURLToPath(new URL('./wasm/pkg/fiveaxis.js', import.meta.url)),
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
