// The engine as a Node script uses it: the built package crate/pkg, loaded with initSync.
// This is the README's example, checked against closed forms.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../crate/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../crate/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const rad = (d) => (d * Math.PI) / 180;

test('README example: one move, its maximum, and the paper approximation', () => {
  const r = fa.nonlinearMove({ type: 'CAZ', length: 100, start: { k: 0, m: 0 }, end: { k: 30, m: 50 } });
  // From the pole, δ(u) = L |sin(u Δm) sin((1-u) Δk)|: maximise it here by brute force.
  let best = 0;
  for (let i = 0; i <= 100000; i++) {
    const u = i / 100000;
    best = Math.max(best, 100 * Math.abs(Math.sin(u * rad(50)) * Math.sin((1 - u) * rad(30))));
  }
  assert.ok(Math.abs(r.max - best) < 1e-6, `${r.max} vs ${best}`);
  // Eq 26 is the curve at u = 0.5, a little below the maximum since |Δk| != |Δm|.
  assert.ok(Math.abs(r.closedForm - 100 * Math.sin(rad(25)) * Math.sin(rad(15))) < 1e-12);
  assert.ok(r.closedForm < r.max);
  assert.ok(r.delta instanceof Float64Array && r.u instanceof Float64Array);
  assert.equal(r.reference, 'plane');
});

test('bad input throws an Error whose message names the field', () => {
  assert.throws(
    () => fa.nonlinearMove({ type: 'CAZ', length: 0, start: { k: 0, m: 0 }, end: { k: 1, m: 1 } }),
    (e) => e instanceof Error && /^length: /.test(e.message),
  );
  assert.throws(
    () => fa.nonlinearMove({ type: 'CAZ', length: 10, start: { k: 0, m: Infinity }, end: { k: 1, m: 1 } }),
    (e) => e instanceof Error && /^start\.m: /.test(e.message),
  );
  assert.throws(() => fa.machineLayout('CAZ', 'gantry'), (e) => e instanceof Error && /^machine: /.test(e.message));
});

test('bulk maximum errors of many moves', () => {
  const moves = new Float64Array([0, 0, 40, 40, 0, 10, 0, 80, 5, 30, 5, 30]);
  const out = fa.nonlinearMaxErrors('CAZ', 2, moves);
  assert.ok(Math.abs(out[0] - 2 * Math.sin(rad(20)) ** 2) < 1e-9, 'equal increments from the pole');
  assert.ok(out[1] < 1e-12, 'M alone: no error');
  assert.equal(out[2], 0, 'no move: no error');
});

test('machine layout and inverse kinematics', () => {
  const l = fa.machineLayout('CBZ', 'table-table');
  assert.equal(l.group, 'I');
  assert.match(l.kRole, /^C: secondary table axis/);
  const ik = fa.inverseKinematics({ type: 'CBZ', vector: [-0.5, 0, Math.sqrt(3) / 2], previous: { k: 170, m: 30 } });
  // Zone II-3 of the cubic test: B = 30°, C = 180° (continuity keeps C near 170°).
  assert.ok(Math.abs(ik.chosen.m - 30) < 1e-9 && Math.abs(ik.chosen.k - 180) < 1e-9, JSON.stringify(ik));
  assert.equal(fa.rotaryTypes().length, 12);
});
