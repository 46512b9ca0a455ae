// `node tests/run.mjs [file or folder …]`: the Node tests and the browser end-to-end tests
// (by default tests/node/ and tests/e2e/), with one Chromium and one server of dist/ shared by
// every browser test. Each test file runs in a Node process of its own, as under `node --test`,
// TEST_CONCURRENCY files at a time (default 3); a browser test makes browser contexts of its own
// (nothing stored is shared between tests) on the shared Chromium, through
// FIVEAXIS_E2E_BROWSER and FIVEAXIS_E2E_URL (tests/e2e/harness.mjs). Exits non-zero when a
// test fails.
import { readdirSync, statSync } from 'node:fs';
import { join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { run } from 'node:test';
import { spec } from 'node:test/reporters';
import { chromium } from 'playwright-core';
import { serve } from '../scripts/serve.mjs';
import { LAUNCH } from './e2e/harness.mjs';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const HERE = fileURLToPath(new URL('.', import.meta.url));
const concurrency = Number(process.env.TEST_CONCURRENCY ?? 3);

/**
 * The files that take longest (over a minute alone on two cores), started first so that none of
 * them is left to run alone at the end. A file not named here starts after them; a name here
 * that is gone is ignored.
 */
const SLOW_FIRST = [
  'e2e/validation.test.mjs',
  'e2e/state.test.mjs',
  'node/fuzz.test.mjs',
  'e2e/phone.test.mjs',
  'e2e/verdict.test.mjs',
];

const testFiles = (path) =>
  statSync(path).isDirectory()
    ? readdirSync(path).sort().flatMap((f) => testFiles(join(path, f)))
    : /\.test\.m?js$/.test(path)
      ? [path]
      : [];
const args = process.argv.slice(2);
const found = (args.length ? args : [join(HERE, 'node'), join(HERE, 'e2e')]).flatMap((a) => (statSync(a).isDirectory() ? testFiles(a) : [a]));
const rank = (f) => {
  const i = SLOW_FIRST.indexOf(relative(HERE, f).split(sep).join('/'));
  return i < 0 ? SLOW_FIRST.length : i;
};
const files = found.map((f) => resolve(f)).sort((a, b) => rank(a) - rank(b));

const { server, url } = await serve(join(ROOT, 'dist'));
const browser = await chromium.launchServer(LAUNCH);
process.env.FIVEAXIS_E2E_BROWSER = browser.wsEndpoint();
process.env.FIVEAXIS_E2E_URL = url;

console.log(`${files.length} test files, ${concurrency} at a time, one Chromium (${browser.wsEndpoint()}) and one server (${url})`);
const stream = run({ files, concurrency });
stream.on('test:fail', () => {
  process.exitCode = 1;
});
stream.compose(new spec()).pipe(process.stdout);
stream.on('close', async () => {
  await browser.close();
  await new Promise((r) => server.close(r));
});
