// `node tests/run.mjs [file or folder …]`: the Node tests and the browser end-to-end tests
// (by default tests/node/ and tests/e2e/), with one Chromium and one server of dist/ shared by
// every browser test. Each test file runs in a Node process of its own, as under `node --test`:
// first the files that must run alone (ALONE), then the others TEST_CONCURRENCY at a time
// (default 3), slowest first. A browser test makes browser contexts of its own (nothing stored
// is shared between tests) on the shared Chromium, through FIVEAXIS_E2E_BROWSER and
// FIVEAXIS_E2E_URL (tests/e2e/harness.mjs). One report; exits non-zero when a test fails.
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
  'e2e/toolpath_big.test.mjs',
  'e2e/validation.test.mjs',
  'e2e/state.test.mjs',
  'node/fuzz.test.mjs',
  'e2e/phone.test.mjs',
  'e2e/verdict.test.mjs',
];

/**
 * Files run on their own, before the others: none now (no test bounds a time; a file that needs
 * the machine to itself would be named here).
 */
const ALONE = [];

const testFiles = (path) =>
  statSync(path).isDirectory()
    ? readdirSync(path).sort().flatMap((f) => testFiles(join(path, f)))
    : /\.test\.m?js$/.test(path)
      ? [path]
      : [];
const args = process.argv.slice(2);
const found = (args.length ? args : [join(HERE, 'node'), join(HERE, 'e2e')]).flatMap((a) => (statSync(a).isDirectory() ? testFiles(a) : [a]));
/** A test file's name as in the lists above. */
const name = (f) => relative(HERE, f).split(sep).join('/');
const rank = (f) => {
  const i = SLOW_FIRST.indexOf(name(f));
  return i < 0 ? SLOW_FIRST.length : i;
};
const files = found.map((f) => resolve(f)).sort((a, b) => rank(a) - rank(b));

const { server, url } = await serve(join(ROOT, 'dist'));
const browser = await chromium.launchServer(LAUNCH);
process.env.FIVEAXIS_E2E_BROWSER = browser.wsEndpoint();
process.env.FIVEAXIS_E2E_URL = url;

const alone = files.filter((f) => ALONE.includes(name(f)));
const shared = files.filter((f) => !ALONE.includes(name(f)));
console.log(`${files.length} test files: ${alone.length} alone, then ${shared.length} ${concurrency} at a time; ` +
  `one Chromium (${browser.wsEndpoint()}) and one server (${url})`);

// One report for both runs: each run's closing counts are held back and added up at the end.
const reporter = new spec();
reporter.pipe(process.stdout);
const SUMMARY = /^(tests|suites|pass|fail|cancelled|skipped|todo|duration_ms) ([\d.]+)$/;
const totals = new Map();
try {
  for (const [group, n] of [[alone, 1], [shared, concurrency]]) {
    if (!group.length) continue;
    for await (const event of run({ files: group, concurrency: n })) {
      if (event.type === 'test:fail') process.exitCode = 1;
      const m = event.type === 'test:diagnostic' && event.data.nesting === 0 && SUMMARY.exec(event.data.message);
      if (m) totals.set(m[1], (totals.get(m[1]) ?? 0) + Number(m[2]));
      else reporter.write(event);
    }
  }
  for (const [what, n] of totals) reporter.write({ type: 'test:diagnostic', data: { nesting: 0, message: `${what} ${n}` } });
} finally {
  reporter.end();
  await browser.close();
  await new Promise((r) => server.close(r));
}
