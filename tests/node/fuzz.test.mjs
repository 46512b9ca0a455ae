// Property test of the exported API: arbitrary JSON-ish inputs (NaN, ±Infinity, huge numbers,
// negative lengths, wrong types, missing and extra fields) never panic and always give either a
// result made of finite numbers or a JavaScript Error with a message.
//   FUZZ_CASES=1000000 FUZZ_SEED=7 node --test tests/node/fuzz.test.mjs   (longer runs)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../crate/pkg/fiveaxis.js';

const bytes = readFileSync(new URL('../../crate/pkg/fiveaxis_bg.wasm', import.meta.url));
fa.initSync({ module: bytes });

const CASES = Number(process.env.FUZZ_CASES ?? 100_000);
const SEED = Number(process.env.FUZZ_SEED ?? 20261122);

/** mulberry32: a small seeded generator, so a failure can be replayed. */
function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const TYPES = ['ABX', 'ACX', 'BCY', 'BAY', 'CAZ', 'CBZ', 'ABZ', 'ACY', 'BCX', 'BAZ', 'CAY', 'CBX'];
// Templates: how a valid input looks. Leaves are generators of plausible values.
const angle = (r) => (r() - 0.5) * 720;
const small = (lo, hi) => (r) => Math.round(lo + r() * (hi - lo));
const pose = { k: angle, m: angle };
// The cubic test: errors up to ±1 mm / ±1° (the engine accepts ±5), a set-up, the switches.
const err = (r) => (r() - 0.5) * 2;
const cubicCase = {
  errors: { dxBY: err, dyBY: err, dzBY: err, alphaBY: err, betaBY: err, gammaBY: err, alphaCB: err, dxCB: err },
  setup: { tableAboveB: (r) => (r() - 0.5) * 200, workpieceHeight: (r) => r() * 100, cOffset: (r) => (r() - 0.5) * 100, zoneSize: (r) => 2 + r() * 20, pick: (r) => 0.3 + r() * 2, stock: (r) => r() },
  transform: (r) => r() < 0.5,
  reference: (r) => ['workpiece', 'zone1-height', 'zone1-plane'][Math.floor(r() * 3)],
};
// The S-shape machine: a few values only, so that the engine's small cache of designs is used.
const pick = (list) => (r) => list[Math.floor(r() * list.length)];
const SSHAPE_MACHINE = {
  l0: pick([499.889, 350]), rTool: pick([10, 8]), lTool: 35,
  branch: pick(['paper', 'continuous']), reference: pick(['workOrigin', 'axesZero']), point: 'tip',
};
/** A measurement file of 100 rows, sometimes with one line damaged, dropped or repeated. */
function sshapeCsv(r) {
  const lines = ['curve,point,deviation_mm'];
  for (const curve of ['top', 'bottom']) for (let k = 1; k <= 50; k++) lines.push(`${curve},${k},${((r() - 0.5) * 0.2).toFixed(4)}`);
  const i = 1 + Math.floor(r() * 100);
  const q = r();
  if (q < 0.1) lines.splice(i, 1);
  else if (q < 0.2) lines.push(lines[i]);
  else if (q < 0.3) lines[i] = lines[i].replace(/,/, ';');
  else if (q < 0.4) lines[i] = lines[i].replace(/\d$/, 'x');
  return lines.join('\n');
}
export const SPECS = {
  rotaryTypes: { args: [] },
  machineLayout: { args: [(r) => TYPES[Math.floor(r() * 12)], (r) => ['table-table', 'head-head', 'head-table'][Math.floor(r() * 3)]] },
  toolVector: { args: [{ type: (r) => TYPES[Math.floor(r() * 12)], k: angle, m: angle }] },
  inverseKinematics: { args: [{ type: (r) => TYPES[Math.floor(r() * 12)], vector: [(r) => r() - 0.5, (r) => r() - 0.5, (r) => r() - 0.5], previous: pose }] },
  nonlinearMove: { args: [{ type: (r) => TYPES[Math.floor(r() * 12)], length: (r) => r() * 500, start: pose, end: pose, samples: small(2, 300) }] },
  nonlinearSweepK: { args: [{ type: (r) => TYPES[Math.floor(r() * 12)], length: (r) => r() * 500, thetaM: angle, dK: angle, dM: angle, from: angle, to: angle, n: small(2, 40) }] },
  nonlinearSweepM: { args: [{ type: (r) => TYPES[Math.floor(r() * 12)], length: (r) => r() * 500, dM: angle, ratios: [(r) => r() * 6 - 3, (r) => r() * 6 - 3], from: angle, to: angle, n: small(2, 40) }] },
  nonlinearGrid: { args: [{ type: (r) => TYPES[Math.floor(r() * 12)], length: (r) => r() * 500, thetaM: angle, dK: { from: angle, to: angle }, dM: { from: angle, to: angle }, nx: small(2, 12), ny: small(2, 12) }] },
  nonlinearCompareTypes: { args: [{ length: (r) => r() * 500, start: pose, end: pose }] },
  nonlinearMaxErrors: { args: [(r) => TYPES[Math.floor(r() * 12)], (r) => r() * 500, (r) => new Float64Array(Array.from({ length: 4 * small(0, 5)(r) }, () => angle(r)))] },
  cubicErrors: { args: [] },
  cubicTest: { args: [cubicCase] },
  cubicHeightMap: { args: [{ ...cubicCase, nx: small(4, 24), ny: small(4, 24) }] },
  sshapePart: { args: [{ nu: small(2, 30), nv: small(2, 6) }] },
  sshapeOvercut: { args: [{ rTool: (r) => 5 + 10 * r(), lTool: (r) => 31 + 30 * r(), nu: small(2, 6), nv: small(2, 3) }] },
  sshapeDefects: { args: [{ machine: SSHAPE_MACHINE, errors: { E_X0B: (r) => (r() - 0.5) * 0.1, E_A0B: (r) => (r() - 0.5) * 0.05, E_A0Z: (r) => (r() - 0.5) * 0.05 }, dR: (r) => (r() - 0.5) * 0.04 }] },
  sshapeIdentify: { args: [{ machine: SSHAPE_MACHINE, csv: sshapeCsv, radiusTerm: (r) => r() < 0.5, rtol: (r) => 10 ** (-1 - 5 * r()) }] },
};

const WEIRD = [NaN, Infinity, -Infinity, 1e308, -1e308, 1e300, -1, 0, -0, 5e-324, 2 ** 53, '', 'abc', '12', true, null, undefined, {}, [], [1, 2], { k: 1 }, new Float64Array(2)];

function build(t, r) {
  if (typeof t === 'function') return t(r);
  if (Array.isArray(t)) return t.map((x) => build(x, r));
  if (t && typeof t === 'object') return Object.fromEntries(Object.entries(t).map(([k, v]) => [k, build(v, r)]));
  return t;
}

/** Replaces, deletes or adds something at a random place of `value`. */
function mutate(value, r, depth = 0) {
  const p = r();
  if (depth > 0 && p < 0.25) return WEIRD[Math.floor(r() * WEIRD.length)];
  if (Array.isArray(value) && value.length) {
    const out = value.slice();
    const i = Math.floor(r() * out.length);
    if (r() < 0.15) out.splice(i, 1);
    else out[i] = mutate(out[i], r, depth + 1);
    return out;
  }
  if (value && typeof value === 'object' && !ArrayBuffer.isView(value)) {
    const out = { ...value };
    const keys = Object.keys(out);
    const q = r();
    if (q < 0.15 && keys.length) delete out[keys[Math.floor(r() * keys.length)]];
    else if (q < 0.25) out[`extra${Math.floor(r() * 3)}`] = WEIRD[Math.floor(r() * WEIRD.length)];
    else if (keys.length) {
      const k = keys[Math.floor(r() * keys.length)];
      out[k] = mutate(out[k], r, depth + 1);
    }
    return out;
  }
  if (ArrayBuffer.isView(value) && value.length && r() < 0.5) {
    const out = value.slice();
    out[Math.floor(r() * out.length)] = [NaN, Infinity, -1e308, 1e9][Math.floor(r() * 4)];
    return out;
  }
  return WEIRD[Math.floor(r() * WEIRD.length)];
}

/** Every number reachable in `v` is finite (typed arrays included; null allowed). */
function allFinite(v, path = 'result') {
  if (typeof v === 'number') return Number.isFinite(v) ? null : `${path} = ${v}`;
  if (ArrayBuffer.isView(v)) {
    for (let i = 0; i < v.length; i++) if (!Number.isFinite(v[i])) return `${path}[${i}] = ${v[i]}`;
    return null;
  }
  if (Array.isArray(v)) {
    for (let i = 0; i < v.length; i++) {
      const bad = allFinite(v[i], `${path}[${i}]`);
      if (bad) return bad;
    }
    return null;
  }
  if (v && typeof v === 'object') {
    for (const [k, x] of Object.entries(v)) {
      const bad = allFinite(x, `${path}.${k}`);
      if (bad) return bad;
    }
  }
  return null;
}

test(`fuzz: ${CASES} cases over the exported API (seed ${SEED})`, () => {
  const r = rng(SEED);
  const names = Object.keys(SPECS);
  for (const name of Object.keys(fa)) {
    if (typeof fa[name] === 'function' && !['default', 'initSync', 'start'].includes(name)) {
      assert.ok(SPECS[name], `export ${name} has no fuzz spec: add one`);
    }
  }
  const counts = { ok: 0, error: 0 };
  for (let i = 0; i < CASES; i++) {
    const name = names[Math.floor(r() * names.length)];
    let args = build(SPECS[name].args, r);
    const mutations = r() < 0.2 ? 0 : 1 + Math.floor(r() * 3);
    for (let m = 0; m < mutations; m++) args = mutate(args, r);
    if (!Array.isArray(args)) args = [args];
    let result;
    try {
      result = fa[name](...args);
    } catch (err) {
      const replay = `case ${i}: ${name}(${describe(args)})`;
      assert.ok(!(err instanceof WebAssembly.RuntimeError), `panic (${err.message}) in ${replay}`);
      assert.ok(err instanceof Error && typeof err.message === 'string' && err.message.length > 3, `not an Error with a message: ${String(err)} in ${replay}`);
      counts.error++;
      continue;
    }
    const bad = allFinite(result);
    assert.equal(bad, null, `non-finite number in case ${i}: ${name}(${describe(args)}): ${bad}`);
    counts.ok++;
  }
  // Both outcomes must be exercised, or the generator is broken.
  assert.ok(counts.ok > CASES * 0.05 && counts.error > CASES * 0.05, JSON.stringify(counts));
});

function describe(args) {
  return JSON.stringify(args, (_, v) => (typeof v === 'number' && !Number.isFinite(v) ? String(v) : ArrayBuffer.isView(v) ? Array.from(v) : v === undefined ? '<undefined>' : v));
}
