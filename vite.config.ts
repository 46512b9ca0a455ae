import { defineConfig, type Plugin } from 'vite';
import { fileURLToPath } from 'node:url';
import { createHash } from 'node:crypto';
import { readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { extname, join, relative } from 'node:path';
import { brotliCompressSync, constants, gzipSync } from 'node:zlib';

const publicDir = fileURLToPath(new URL('./public', import.meta.url));

function listFiles(dir: string): string[] {
  return readdirSync(dir).flatMap((name) => {
    const p = join(dir, name);
    return statSync(p).isDirectory() ? listFiles(p) : [p];
  });
}

/**
 * Writes sw.js, the service worker that makes the page work offline after the first visit: it
 * keeps the files of the build that the page fetched (it downloads none of its own) under a
 * cache named after the build's content, serves them cache-first, and pages network-first.
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

/** Files worth compressing (text and the engine; images here are SVG, already text). */
const COMPRESSIBLE = new Set(['.html', '.js', '.mjs', '.css', '.json', '.wasm', '.svg', '.csv', '.txt', '.webmanifest', '.map']);

/**
 * Writes `file.br` and `file.gz` beside each compressible file of the build, so that any static
 * host that serves precompressed files (and scripts/serve.mjs) sends a fraction of the bytes.
 * A variant that would not be smaller than the file is not written.
 */
function precompress(): Plugin {
  let outDir = '';
  return {
    name: 'fiveaxis-precompress',
    apply: 'build',
    configResolved(config) {
      outDir = config.build.outDir;
    },
    closeBundle() {
      for (const file of listFiles(outDir)) {
        if (!COMPRESSIBLE.has(extname(file))) continue;
        const raw = readFileSync(file);
        const br = brotliCompressSync(raw, {
          params: { [constants.BROTLI_PARAM_QUALITY]: 11, [constants.BROTLI_PARAM_SIZE_HINT]: raw.length },
        });
        const gz = gzipSync(raw, { level: 9 });
        if (br.length < raw.length) writeFileSync(`${file}.br`, br);
        if (gz.length < raw.length) writeFileSync(`${file}.gz`, gz);
      }
    },
  };
}

/**
 * Plotly's modular core requires maplibre-gl's style sheet when a map trace registers; the page
 * registers none, so the 80 kB sheet is left out.
 */
function noMapStyles(): Plugin {
  const id = '\0fiveaxis-empty-style';
  return {
    name: 'fiveaxis-no-map-styles',
    enforce: 'pre',
    resolveId(source) {
      return source === 'maplibre-gl/dist/maplibre-gl.css' ? id : null;
    },
    load(source) {
      return source === id ? '' : null;
    },
  };
}

/**
 * Starts the engine's download with the page: `<link rel="preload">` for the engine worker's
 * script and the engine (wasm), which the page needs before it can show anything (its forms come
 * from the engine's schema). Without them the browser finds the worker only once the page's
 * script runs, and the engine only once the worker runs: two round trips later, one after the
 * other. The worker's own requests then find both in the browser's HTTP cache (hashed names,
 * cached for a year by scripts/serve.mjs and most static hosts).
 */
function preloadEngine(): Plugin {
  return {
    name: 'fiveaxis-preload-engine',
    apply: 'build',
    transformIndexHtml: {
      order: 'post',
      handler(html, ctx) {
        const files = Object.values(ctx.bundle ?? {});
        const wasm = files.find((f) => /fiveaxis_bg-[^/]*\.wasm$/.test(f.fileName));
        const worker = files.find((f) => f.fileName.includes('worker-') && (f.type === 'chunk' ? f.code : String(f.source)).includes('unknown engine function'));
        if (!wasm || !worker) throw new Error('preload-engine: the engine or its worker is missing from the bundle');
        return [worker, wasm].map((f) => ({
          tag: 'link',
          attrs: { rel: 'preload', href: `./${f.fileName}`, as: 'fetch', crossorigin: '' },
          injectTo: 'head' as const,
        }));
      },
    },
  };
}

// The page lives in www/, static assets (presets, sample data) in public/, the engine package
// that scripts/build-wasm.sh builds in wasm/pkg/. `npm run build` writes a self-contained static
// folder dist/ that any static file server can host (relative paths, no server-side code).
export default defineConfig({
  root: 'www',
  base: './',
  publicDir,
  plugins: [noMapStyles(), preloadEngine(), serviceWorker(), precompress()],
  resolve: {
    alias: {
      '@engine': fileURLToPath(new URL('./wasm/pkg/fiveaxis.js', import.meta.url)),
    },
  },
  // Plotly's modules are written for browserify, which provides Node's `global`.
  define: { global: 'globalThis' },
  worker: { format: 'es' },
  build: {
    outDir: fileURLToPath(new URL('./dist', import.meta.url)),
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 5000,
  },
  server: { fs: { allow: ['..'] } },
});
