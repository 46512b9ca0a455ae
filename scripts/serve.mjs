// A small static file server for the built page (dist/), with no dependencies.
//   node scripts/serve.mjs [--port 8080] [--dir dist]
// Used by `npm start` and by the browser tests. Serves only files under the directory.
// Compressed: the build writes `file.br` and `file.gz` beside each file, and the server sends
// the one the browser accepts (Accept-Encoding), with Content-Encoding and Vary. Cached: files
// under assets/ have their content's hash in their name and are kept for a year; the others
// (index.html, sw.js, presets) are revalidated on every use with an ETag (a 304 costs no body).
import { createServer } from 'node:http';
import { readFile, stat } from 'node:fs/promises';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.ico': 'image/x-icon',
  '.csv': 'text/csv; charset=utf-8',
  '.txt': 'text/plain; charset=utf-8',
  '.webmanifest': 'application/manifest+json',
};

/** The encodings the request accepts, in the server's order of preference (q=0 refuses). */
function accepted(header = '') {
  const ok = new Set();
  for (const part of header.toLowerCase().split(',')) {
    const [name, ...params] = part.trim().split(';');
    const q = params.map((p) => p.trim()).find((p) => p.startsWith('q='));
    if (name && !(q && Number(q.slice(2)) === 0)) ok.add(name.trim());
  }
  return ['br', 'gzip'].filter((e) => ok.has(e) || ok.has('*'));
}

const SUFFIX = { br: '.br', gzip: '.gz' };

/** Starts serving `dir` on `port` (0 picks a free one); resolves to { server, url }. */
export function serve(dir, port = 0, host = '127.0.0.1') {
  const root = resolve(dir);
  const server = createServer(async (req, res) => {
    try {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      let file = normalize(join(root, path));
      if (file !== root && !file.startsWith(root + sep)) {
        res.writeHead(403).end('forbidden');
        return;
      }
      let info = await stat(file).catch(() => null);
      if (info?.isDirectory()) {
        file = join(file, 'index.html');
        info = await stat(file).catch(() => null);
      }
      if (!info?.isFile()) throw new Error('not found');
      const headers = {
        'content-type': TYPES[extname(file)] ?? 'application/octet-stream',
        'cache-control': file.startsWith(join(root, 'assets') + sep) ? 'public, max-age=31536000, immutable' : 'no-cache',
        'x-content-type-options': 'nosniff',
        vary: 'Accept-Encoding',
      };
      // The smallest variant the browser accepts: a precompressed file when the build wrote one.
      let body = null;
      let encoding = null;
      for (const e of accepted(req.headers['accept-encoding'])) {
        body = await readFile(file + SUFFIX[e]).catch(() => null);
        if (body) {
          encoding = e;
          break;
        }
      }
      const etag = `"${info.size.toString(36)}-${Math.floor(info.mtimeMs).toString(36)}${encoding ? `-${encoding}` : ''}"`;
      headers.etag = etag;
      if (encoding) headers['content-encoding'] = encoding;
      for (const [k, v] of Object.entries(headers)) res.setHeader(k, v);
      if (req.headers['if-none-match']?.split(',').some((t) => t.trim().replace(/^W\//, '') === etag)) {
        res.writeHead(304).end();
        return;
      }
      body ??= await readFile(file);
      res.setHeader('content-length', body.length);
      res.writeHead(200);
      res.end(req.method === 'HEAD' ? undefined : body);
    } catch {
      res.writeHead(404, { 'content-type': 'text/plain' }).end('not found');
    }
  });
  return new Promise((ok, fail) => {
    server.once('error', fail);
    server.listen(port, host, () => {
      const a = server.address();
      ok({ server, url: `http://${host === '127.0.0.1' ? 'localhost' : host}:${a.port}/` });
    });
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const arg = (name, fallback) => {
    const i = process.argv.indexOf(name);
    return i > 0 ? process.argv[i + 1] : fallback;
  };
  const dir = arg('--dir', fileURLToPath(new URL('../dist', import.meta.url)));
  let port = Number(arg('--port', process.env.PORT ?? 8080));
  for (let attempt = 0; ; attempt++) {
    try {
      const { url } = await serve(dir, port);
      console.log(`\n  Five-axis accuracy calculator is being served at ${url}\n  (serving ${dir}; press Ctrl+C to stop)\n`);
      break;
    } catch (err) {
      if (err.code !== 'EADDRINUSE' || attempt > 20) throw err;
      port += 1;
    }
  }
}
