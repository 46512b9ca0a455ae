// Every export is declared once (crate/src/api.rs, `for_each_export!`) and three things are
// generated from it: the module's function, its `schema()` entry and its TypeScript types. This
// test reads all three and checks they agree, and reads the generated `.d.ts` for units: an
// angle crosses the edge in degrees, so no declaration may document one in radians only (a rate
// per radian, N·m·s/rad, is a unit the input takes as it is).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
const dts = readFileSync(new URL('../../wasm/pkg/fiveaxis.d.ts', import.meta.url), 'utf8');

/** `export function name(params): Result;` of the .d.ts, with the types named. */
const declared = new Map(
  [...dts.matchAll(/^export function (\w+)\(([^)]*)\): ([^;]+);/gm)].map(([, name, params, ret]) => [name, { params, ret }]),
);
/** Names of the types the .d.ts declares. */
const types = new Set([...dts.matchAll(/^export (?:interface|type|class|enum) (\w+)/gm)].map((m) => m[1]));

// Not exports of the engine: the schema itself, the loader, and wasm-bindgen's start function.
const NO_INPUT = new Set(['schema', 'initSync', 'start']);

test('every schema() export is a function of the module and of the .d.ts, and back', () => {
  const exports = Object.keys(fa.schema().exports);
  assert.ok(exports.length >= 25, `only ${exports.length} exports in schema()`);
  for (const name of exports) {
    assert.equal(typeof fa[name], 'function', `schema() lists ${name}, the module has no such function`);
    assert.ok(declared.has(name), `schema() lists ${name}, the .d.ts declares no such function`);
  }
  const functions = Object.entries(fa).filter(([n, f]) => typeof f === 'function' && /^[a-z]/.test(n) && !NO_INPUT.has(n) && n !== 'default');
  for (const [name] of functions) {
    assert.ok(exports.includes(name), `the module exports ${name}, schema() has no entry for it`);
  }
});

test('every declared function names input and result types the .d.ts declares', () => {
  const builtin = new Set(['string', 'number', 'boolean', 'any', 'void', 'Float64Array', 'Uint8Array', 'InitOutput', 'SyncInitInput', 'Promise', 'object']);
  for (const [name, { params, ret }] of declared) {
    for (const t of [...params.matchAll(/:\s*([A-Za-z_]\w*)/g)].map((m) => m[1]).concat([...ret.matchAll(/([A-Za-z_]\w*)/g)].map((m) => m[1]))) {
      if (builtin.has(t) || t === 'null' || t === 'undefined' || t === 'readonly') continue;
      assert.ok(types.has(t), `${name}: type ${t} is not declared in the .d.ts`);
    }
  }
});

test('no type is declared twice in the .d.ts (tsify names a type by its Rust struct, whatever its module)', () => {
  const names = [...dts.matchAll(/^export (?:interface|type|class|enum) (\w+)/gm)].map((m) => m[1]);
  const twice = names.filter((n, i) => names.indexOf(n) !== i);
  assert.deepEqual(twice, [], 'two engine types with one name: rename one');
});

test('the .d.ts documents no field or input in radians: angles cross in degrees', () => {
  const docs = [...dts.matchAll(/\/\*\*([\s\S]*?)\*\//g)].map((m) => m[1].replace(/^\s*\*\s?/gm, ' ').replace(/\s+/g, ' ').trim());
  assert.ok(docs.length > 200, `only ${docs.length} doc comments read`);
  const radians = docs.filter((d) => /(?<![/·])\brad\b|radians?/.test(d) && !/degree/.test(d));
  assert.deepEqual(radians, [], 'documented in radians, but the export takes and gives degrees');
});

test('an angle held in radians crosses in degrees: the volumetric map tilt and the worst point agree with a pitch entered in degrees', () => {
  // A pitch of the spindle-side Y axis (E_AY) tilts the tool by the same angle everywhere.
  const preset = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8'));
  const machine = structuredClone(preset.presets.find((p) => p.name.startsWith('C/A double turntable')).machine);
  machine.motions = { E_AY: 0.01 };
  const r = fa.volumetricMap({ machine, region: { steps: 3 } });
  assert.ok(r.tilt instanceof Float64Array && r.deviation.every((d) => d instanceof Float64Array));
  for (const t of r.tilt) assert.ok(Math.abs(t - 0.01) < 1e-12, `tilt ${t}°, want 0.01°`);
  assert.ok(Math.abs(r.worst.tilt - 0.01) < 1e-12);
});
