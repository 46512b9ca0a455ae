// The documents: docs/api.md is what scripts/api-doc.mjs generates from the built package (not
// stale), it names every function the JS module exports, and the README stays short.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, existsSync } from 'node:fs';
import * as mod from '../../wasm/pkg/fiveaxis.js';
import { generate, exportedNames } from '../../scripts/api-doc.mjs';

const root = new URL('../../', import.meta.url);
const read = (path) => readFileSync(new URL(path, root), 'utf8');

test('docs/api.md is what `node scripts/api-doc.mjs` generates from the built package', async () => {
  const fresh = await generate();
  const stale = 'docs/api.md is stale: run `node scripts/api-doc.mjs` (after `npm run build:wasm`) and commit it';
  assert.ok(existsSync(new URL('docs/api.md', root)), stale);
  const onDisk = read('docs/api.md');
  if (onDisk !== fresh) {
    const a = onDisk.split('\n');
    const b = fresh.split('\n');
    const i = a.findIndex((line, k) => line !== b[k]);
    assert.fail(`${stale}; first difference at line ${i + 1}:\n  on disk:   ${a[i]}\n  generated: ${b[i]}`);
  }
});

test('docs/api.md names every function and class the JS module exports', () => {
  const api = read('docs/api.md');
  const skip = new Set(['default', 'initSync', '__wbg_init']);
  const names = Object.keys(mod).filter((n) => !skip.has(n) && typeof mod[n] === 'function');
  assert.ok(names.length > 20, `only ${names.length} exports found`);
  const missing = names.filter((n) => !api.includes(`### ${n}\n`));
  assert.deepEqual(missing, [], `not documented in docs/api.md (run \`node scripts/api-doc.mjs\`): ${missing.join(', ')}`);
  // The .d.ts and the module agree on what is exported.
  const dts = exportedNames(read('wasm/pkg/fiveaxis.d.ts')).filter((n) => !skip.has(n));
  assert.deepEqual([...dts].sort(), [...names].sort());
});

test('every export of schema() has its inputs in docs/api.md', () => {
  mod.initSync({ module: readFileSync(new URL('wasm/pkg/fiveaxis_bg.wasm', root)) });
  const api = read('docs/api.md');
  for (const name of Object.keys(mod.schema().exports)) {
    assert.ok(api.includes(`**Inputs** (\`schema().exports.${name}\`)`), name);
  }
});

test('README.md is at most 250 lines', () => {
  const lines = read('README.md').split('\n').length - 1;
  assert.ok(lines <= 250, `README.md has ${lines} lines; move detail to docs/ (at most 250)`);
});

test('the README and the docs link only to files that exist', () => {
  for (const doc of ['README.md', 'CONTRIBUTING.md', 'docs/science.md', 'docs/testing.md', 'docs/using.md', 'docs/page.md']) {
    const text = read(doc);
    const base = new URL(doc, root);
    for (const [, target] of text.matchAll(/\]\(([^)#\s]+)(?:#[^)]*)?\)/g)) {
      if (/^[a-z]+:/.test(target)) continue;
      assert.ok(existsSync(new URL(target, base)), `${doc}: link to ${target}, which does not exist`);
    }
  }
});
