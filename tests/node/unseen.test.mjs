// Which errors entered a study cannot see: the page names them in each verdict from the engine's
// own results (the cubic test's `visibility.invisible`, the volumetric map's error budget, the
// S-shape study's sensitivities; the nonlinear error and the toolpath comparison are computed
// without the machine's errors). Each is checked here by finite differences: an error is unseen
// exactly when a small change of it (1 µm, 1e-4°) changes the study's result by less than 0.1 nm
// (what is left is second order: the error times the others, about 1e-8 mm here), while an error
// the study sees moves it by far more.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fa, preset } from '../papers.mjs';

const TRUNNION = preset('A/C trunnion table');
const ERRORS = { E_X0C: 0.012, E_Y0C: -0.008, E_Z0A: 0.02, E_A0C: 0.001, E_Y0A: 0.005, E_C0C: 0.002, E_B0A: 0.001 };
const withErrors = (errors) => ({ ...TRUNNION, errors });
/** A small change of one error: 1 µm or 1e-4°. */
const step = (name) => (/^E_[ABC]/.test(name) ? 1e-4 : 1e-3);

/** The names whose change by `step` changes `result` (a list of numbers) by more than `tol`. */
function seen(result, tol) {
  const base = result(ERRORS);
  return Object.keys(ERRORS).filter((name) => {
    const moved = result({ ...ERRORS, [name]: ERRORS[name] + step(name) });
    return moved.some((v, i) => Math.abs(v - base[i]) > tol);
  });
}

test('the cubic test cannot see exactly the errors its engine calls invisible', () => {
  const r = fa.cubicTest({ machine: withErrors(ERRORS) });
  const fd = seen((e) => fa.cubicTest({ machine: withErrors(e) }).zones.map((z) => z.height), 1e-7);
  const invisible = Object.keys(ERRORS).filter((n) => r.visibility.invisible.includes(n));
  assert.deepEqual(invisible.sort(), Object.keys(ERRORS).filter((n) => !fd.includes(n)).sort());
  // The case: on an A/C trunnion the C axis's position is not seen.
  assert.ok(invisible.includes('E_X0C') && invisible.includes('E_Y0C'), String(invisible));
  assert.ok(!invisible.includes('E_Z0A'));
});

test('the volumetric map sees exactly the errors in its budget', () => {
  const region = {};
  const r = fa.volumetricMap({ machine: withErrors(ERRORS), region });
  const fd = seen((e) => Array.from(fa.volumetricMap({ machine: withErrors(e), region }).norm), 1e-7);
  const inBudget = r.budget.filter((b) => b.max > 0).map((b) => b.name);
  assert.deepEqual(inBudget.filter((n) => n in ERRORS).sort(), fd.sort());
});

test('the S-shape part sees exactly the errors with a sensitivity', () => {
  const chanal = preset('B swivel head, C rotary table');
  const errors = { E_X0B: 0.01, E_Z0B: 0.01, E_X0C: 0.01, E_C0C: 0.002, E_B0B: 0.001 };
  const d = fa.sshapeDefects({ machine: { ...chanal, errors } });
  const n = d.names.length;
  const sens = (name) => {
    const j = d.names.indexOf(name);
    return Array.from({ length: d.total.length }, (_, i) => d.sensitivity[i * n + j]).some((v) => Math.abs(v) > 1e-9);
  };
  const fdSeen = Object.keys(errors).filter((name) => {
    const moved = fa.sshapeDefects({ machine: { ...chanal, errors: { ...errors, [name]: errors[name] + step(name) } } }).total;
    return moved.some((v, i) => Math.abs(v - d.total[i]) > 1e-7);
  });
  assert.deepEqual(Object.keys(errors).filter(sens).sort(), fdSeen.sort());
});

test('the nonlinear error and the toolpath comparison do not change with any error', () => {
  const move = (e) => {
    const r = fa.nonlinearMove({ machine: withErrors(e), start: { k: 0, m: 10 }, end: { k: 30, m: 25 } });
    return [r.max, ...r.delta];
  };
  assert.deepEqual(seen(move, 0), []);
  const points = new Float64Array([0, 0, 0, 0, 0, 1, 10, 0, 0, 0.3, 0, 0.95, 20, 5, 0, 0.5, 0.2, 0.84]);
  const path = (e) => {
    const a = fa.toolpathAnalyse({ machine: withErrors(e), tolerance: 0.01 }, points);
    return [...a.delta, ...a.k, ...a.m];
  };
  assert.deepEqual(seen(path, 0), []);
});
