// Units and keys of the exported API, as a Node script sees them (the built package wasm/pkg).
// Every expected value here is computed by a second method written in this file: closed forms
// of the machine's chain (Chanal et al.'s Appendix A, worked out below), the tool vector of the
// rotary-axis type, unit identities (per degree = per radian × π/180, µm = mm × 1000), and the
// definitions of the outputs. Nothing is compared against a copy of the engine's output.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const PRESETS = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const preset = (prefix) => structuredClone(PRESETS.find((p) => p.name.startsWith(prefix)).machine);
const CHANAL = preset('B swivel head, C rotary table, Y under the table');
const L0 = CHANAL.geometry.pivotLength + CHANAL.geometry.toolLength;
const SAMPLE = readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8');
const rad = (d) => (d * Math.PI) / 180;
const deg = (r) => (r * 180) / Math.PI;
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.sqrt(dot(a, a));
const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (tol ${tol})`);

// ---------------------------------------------------------------------------------------------
// Chanal et al.'s machine in closed form (Section 5.2, Appendix A; docs/using.md "The machine"):
// chain Y (under the table), C (table, turning the table by +C), X, Z, B (head); every axis
// through the origin at zero, the tool tip L0 below B along the tool. With the axes at
// (X, Y, Z, B, C):
//   tool tip, bed frame          t_b = (X − L0·sin B, 0, Z − L0·cos B)
//   table frame in the bed       R = R_Z(C), origin (0, −Y, 0)
//   tip, workpiece frame         t_w = Rᵀ·(X − L0·sin B, Y, Z − L0·cos B)
//   tool axis, workpiece frame   a_w = Rᵀ·(sin B, 0, cos B)
// A location error turns or shifts its axis frame (ISO 230-1). To first order, with ε in rad:
//   E_A0Z, E_B0Z (the Z slide turned about X, Y at its origin; the tip is t_b − (X, 0, 0) from
//     it):  d = Rᵀ·(e × (t_b − X·e_x))·ε;  the axis turns by Rᵀ·(e × a_b)·ε
//   E_A0C, E_B0C (the table turned about X, Y): d = −((Rᵀe) × t_w)·ε; the axis by −((Rᵀe) × a_w)·ε
//   E_C0Y (the Y slide turned about Z, carrying the table): d = −Rᵀ·(e_z × t_b)·ε
//   E_A0B, E_C0B (the head turned about X, Z at B): d = Rᵀ·(e × (−L0·sin B, 0, −L0·cos B))·ε
//   E_X0B: d = Rᵀ·e_x·δ
// Eq 14 subtracts the tip's shift at the reference pose (the tip at the work origin with the
// rotary axes at zero: X = Y = 0, Z = L0, B = C = 0; or every axis at zero) and reads the
// displacement along the point's outward normal; "contact" moves the tool axis's point at the
// measured height h: d + h·(axis turn).
const E = { X: [1, 0, 0], Y: [0, 1, 0], Z: [0, 0, 1] };
function chanalShift(name, q) {
  const { X, Y, Z, B, C } = q;
  const Rt = (v) => [v[0] * Math.cos(C) + v[1] * Math.sin(C), -v[0] * Math.sin(C) + v[1] * Math.cos(C), v[2]];
  const tb = [X - L0 * Math.sin(B), 0, Z - L0 * Math.cos(B)];
  const tw = Rt([X - L0 * Math.sin(B), Y, Z - L0 * Math.cos(B)]);
  const ab = [Math.sin(B), 0, Math.cos(B)];
  const aw = Rt(ab);
  const neg = (v) => v.map((x) => -x);
  const fromZ = [tb[0] - X, tb[1], tb[2]];
  const fromB = [-L0 * Math.sin(B), 0, -L0 * Math.cos(B)];
  const zero = [0, 0, 0];
  switch (name) {
    case 'E_A0Z': return { tip: Rt(cross(E.X, fromZ)), axis: Rt(cross(E.X, ab)) };
    case 'E_B0Z': return { tip: Rt(cross(E.Y, fromZ)), axis: Rt(cross(E.Y, ab)) };
    case 'E_A0C': return { tip: neg(cross(Rt(E.X), tw)), axis: neg(cross(Rt(E.X), aw)) };
    case 'E_B0C': return { tip: neg(cross(Rt(E.Y), tw)), axis: neg(cross(Rt(E.Y), aw)) };
    case 'E_C0Y': return { tip: neg(Rt(cross(E.Z, tb))), axis: neg(Rt(cross(E.Z, ab))) };
    case 'E_A0B': return { tip: Rt(cross(E.X, fromB)), axis: Rt(cross(E.X, ab)) };
    case 'E_C0B': return { tip: Rt(cross(E.Z, fromB)), axis: Rt(cross(E.Z, ab)) };
    case 'E_X0B': return { tip: Rt(E.X), axis: zero };
    default: throw new Error(name);
  }
}
/** Eq 14 per unit of the error (mm per mm or per rad) at point k, in closed form. */
function chanalColumn(name, d, k, normal, model = {}) {
  const v = d.poses[k].values;
  const at = (axis) => v[d.axes.indexOf(axis)];
  const q = { X: at('X'), Y: at('Y'), Z: at('Z'), B: rad(at('B')), C: rad(at('C')) };
  const s = chanalShift(name, q);
  const ref = chanalShift(name, model.reference === 'axesZero' ? { X: 0, Y: 0, Z: 0, B: 0, C: 0 } : { X: 0, Y: 0, Z: L0, B: 0, C: 0 });
  const h = model.point === 'contact' ? d.height[k] : 0;
  return dot([0, 1, 2].map((i) => s.tip[i] - ref.tip[i] + h * s.axis[i]), normal);
}
const CHANAL_ERRORS = ['E_C0Y', 'E_A0Z', 'E_B0Z', 'E_A0C', 'E_B0C', 'E_X0B', 'E_A0B', 'E_C0B'];

test('sshapeDefects: each of Chanal et al.\'s errors alone, in mm or degrees, is its closed-form column; sensitivity per degree = per rad × π/180', () => {
  const points = fa.sshapePart().points;
  for (const model of [{}, { point: 'contact' }, { reference: 'axesZero' }, { point: 'contact', reference: 'axesZero' }]) {
    for (const name of CHANAL_ERRORS) {
      const angle = name !== 'E_X0B';
      const api = angle ? 0.002 : 0.002; // 0.002° or 2 µm
      const perApi = angle ? rad(1) : 1; // engine units (rad, mm) per API unit (°, mm)
      const d = fa.sshapeDefects({ machine: { ...CHANAL, errors: { [name]: api } }, model });
      const j = d.names.indexOf(name);
      const n = d.names.length;
      assert.equal(d.units[j], angle ? 'deg' : 'mm', name);
      let largest = 0;
      points.forEach((p, k) => {
        const perEngine = chanalColumn(name, d, k, p.normal, model);
        const what = `${name} ${JSON.stringify(model)} point ${k}`;
        // The value entered in degrees acts as api·π/180 rad.
        close(d.total[k], perEngine * api * perApi, 1e-12, `${what}: total`);
        close(d.contributions[k * n + j], perEngine * api * perApi, 1e-12, `${what}: contribution`);
        // Sensitivity per degree (per mm for E_X0B).
        close(d.sensitivity[k * n + j], perEngine * perApi, 1e-10, `${what}: sensitivity`);
        for (let i = 0; i < n; i++) if (i !== j) assert.ok(d.contributions[k * n + i] === 0, `${what}: only its own column`);
        largest = Math.max(largest, Math.abs(perEngine * api * perApi));
      });
      // Every error moves some point by far more than the tolerance (no vacuous check).
      assert.ok(largest > 1e-6, `${name}: ${largest}`);
    }
  }
});

test('sshapeDefects: each other input alone (dR, tool.rTool, tool.lTool, model.branch), against geometry', () => {
  const points = fa.sshapePart().points;
  // dR alone: a tool larger by dR cuts dR deeper square to its axis; the axis lies in the
  // surface (flank milling), so along the normal −dR·sin θ with sin θ within 0.4 % of 1.
  const r = fa.sshapeDefects({ machine: CHANAL, dR: 0.01 });
  for (let k = 0; k < 100; k++) {
    assert.ok(r.radius[k] <= -0.01 * 0.996 && r.radius[k] >= -0.01 - 1e-15, `radius ${k}: ${r.radius[k]}`);
    close(r.total[k], r.radius[k], 1e-15, `dR alone is the total ${k}`);
  }
  // The tool tip in workpiece coordinates from the poses (closed form above).
  const tips = (d) => d.poses.map((p) => {
    const at = (a) => p.values[d.axes.indexOf(a)];
    const [X, Y, Z, B, C] = [at('X'), at('Y'), at('Z'), rad(at('B')), rad(at('C'))];
    const t = [X - L0 * Math.sin(B), Y, Z - L0 * Math.cos(B)];
    return { tip: [t[0] * Math.cos(C) + t[1] * Math.sin(C), -t[0] * Math.sin(C) + t[1] * Math.cos(C), t[2]], axis: [Math.sin(B) * Math.cos(C), -Math.sin(B) * Math.sin(C), Math.cos(B)] };
  });
  // Eq 2: tip = S(u, 1) + R·N(u, 1) − L·(ruling). rTool alone, 10 → 12 mm, at the same u:
  // the tip moves by 2·N(u, 1), a unit normal square to the ruling (the tool axis), on the
  // outward side of the measured point.
  const a = fa.sshapeDefects({ machine: CHANAL, tool: { rTool: 10 } });
  const b = fa.sshapeDefects({ machine: CHANAL, tool: { rTool: 12 } });
  const ta = tips(a);
  const tb = tips(b);
  points.forEach((p, k) => {
    const move = [0, 1, 2].map((i) => tb[k].tip[i] - ta[k].tip[i]);
    close(norm(move), 2, 1e-9, `rTool at ${k}: 2 mm`);
    close(dot(move, ta[k].axis), 0, 1e-9, `rTool at ${k}: square to the tool`);
    assert.ok(dot(move, p.normal) > 0, `rTool at ${k}: outwards`);
  });
  // lTool alone, 35 → 50 mm: eq 2 moves the tip 15 mm further down the ruling (the tool
  // axis), so every point sits 15 mm higher on the tool; always between the tip and lTool.
  const heights = [35, 50].map((lTool) => {
    const d = fa.sshapeDefects({ machine: CHANAL, tool: { lTool } });
    const t = tips(d);
    points.forEach((p, k) => {
      assert.ok(d.height[k] > 0 && d.height[k] <= lTool + 1e-9, `lTool ${lTool} at ${k}: ${d.height[k]}`);
      // The height is the point's distance above the tip along the axis.
      const rel = [0, 1, 2].map((i) => p.point[i] - t[k].tip[i]);
      close(dot(rel, t[k].axis), d.height[k], 1e-9, `height ${k}`);
    });
    return d.height;
  });
  for (let k = 0; k < 100; k++) close(heights[1][k] - heights[0][k], 15, 1e-9, `lTool at ${k}`);
  // branch alone: another solution of the same tool orientation (a_w from the poses).
  const c = fa.sshapeDefects({ machine: CHANAL, model: { branch: 'continuous' } });
  const tc = tips(c);
  const tp = tips(a);
  for (let k = 0; k < 100; k++) for (let i = 0; i < 3; i++) close(tc[k].axis[i], tp[k].axis[i], 1e-9, `branch: axis ${k}`);
  // The paper's branch has B ≥ 0 (tan B = √(x² + y²)/z ≥ 0).
  a.poses.forEach((p, k) => assert.ok(p.values[a.axes.indexOf('B')] >= -1e-9, `B ≥ 0 at ${k}`));
});

test('sshapeIdentify: a file in µm is the same file in mm; angles come out in degrees', () => {
  const lines = SAMPLE.split('\n').filter((l) => l && !l.startsWith('#'));
  const um = ['curve,point,deviation_um', ...lines.slice(1).map((l) => {
    const [c, p, v] = l.split(',');
    return `${c},${p},${(Number(v) * 1000).toFixed(1)}`;
  })].join('\n');
  const params = CHANAL_ERRORS;
  const mm = fa.sshapeIdentify({ machine: CHANAL, csv: SAMPLE, parameters: params });
  const u = fa.sshapeIdentify({ machine: CHANAL, csv: um, parameters: params });
  mm.estimates.forEach((e, i) => close(u.estimates[i].value, e.value, 1e-12 * Math.max(1, Math.abs(e.value)), e.name));
  // parameters alone: only those, then dR; radiusTerm false: no dR.
  const two = fa.sshapeIdentify({ machine: CHANAL, csv: SAMPLE, parameters: ['E_X0B', 'E_A0B'], radiusTerm: false });
  assert.deepEqual(two.estimates.map((e) => e.name), ['E_X0B', 'E_A0B']);
  // The sample's E_A0B = 3.2419e-4 rad (its header) is 0.018575°: the estimate in degrees.
  const a0b = mm.estimates.find((e) => e.name === 'E_A0B');
  assert.equal(a0b.unit, 'deg');
  assert.ok(Math.abs(a0b.value - deg(3.2419e-4)) < 4 * a0b.stdError, `${a0b.value}`);
  // Fitted = measured − residuals, in mm.
  for (let k = 0; k < 100; k++) close(mm.fitted[k] + mm.residuals[k], mm.measured[k], 1e-15, `${k}`);
});

// ---------------------------------------------------------------------------------------------
// The nonlinear study. Type CAZ: V = R_Z(k)·R_X(m)·e_z = (sin m·sin k, −sin m·cos k, cos m).
const cazVector = (k, m) => [Math.sin(rad(m)) * Math.sin(rad(k)), -Math.sin(rad(m)) * Math.cos(rad(k)), Math.cos(rad(m))];

test('nonlinearMove: start/end in degrees, sweepAngle in degrees, approx, approxShortfall, planeSine, length and samples by their definitions', () => {
  const input = { machine: { type: 'CAZ' }, length: 100, start: { k: 10, m: 20 }, end: { k: 50, m: 60 } };
  const r = fa.nonlinearMove(input);
  const v0 = cazVector(10, 20);
  const v1 = cazVector(50, 60);
  for (let i = 0; i < 3; i++) {
    close(r.startVector[i], v0[i], 1e-12, 'V0');
    close(r.endVector[i], v1[i], 1e-12, 'V1');
  }
  // The angle between V0 and V1, in degrees.
  close(r.sweepAngle, deg(Math.acos(dot(v0, v1))), 1e-9, 'sweepAngle (degrees)');
  close(r.planeSine, norm(cross(v0, v1)), 1e-12, 'planeSine');
  // δ(0.5) = L·|V(0.5)·n|, n the unit normal of the plane through V0 and V1 (the angles
  // interpolated linearly: k = 30°, m = 40° at u = 0.5); eq 25 (Group I) is that value.
  const n = cross(v0, v1).map((x) => x / norm(cross(v0, v1)));
  const half = 100 * Math.abs(dot(cazVector(30, 40), n));
  close(r.atHalf, half, 1e-9, 'δ(0.5)');
  close(r.approx, half, 1e-9, 'eq 25');
  // approxShortfall = (max − approx)/max: positive when the approximation falls short.
  assert.ok(r.max >= r.approx, `${r.max} ${r.approx}`);
  close(r.approxShortfall, (r.max - r.approx) / r.max, 1e-12, 'approxShortfall');
  assert.ok(r.approxShortfall > 0);
  // The maximum by dense sampling of the same definition.
  let best = 0;
  for (let i = 0; i <= 20000; i++) {
    const u = i / 20000;
    best = Math.max(best, 100 * Math.abs(dot(cazVector(10 + 40 * u, 20 + 40 * u), n)));
  }
  close(r.max, best, 1e-6, 'max');
  // length alone scales δ; samples alone sets the curve's length, u from 0 to 1.
  const l = fa.nonlinearMove({ ...input, length: 250 });
  close(l.max, 2.5 * r.max, 1e-9, 'length');
  const s = fa.nonlinearMove({ ...input, samples: 11 });
  assert.equal(s.u.length, 11);
  assert.equal(s.delta.length, 11);
  s.u.forEach((u, i) => {
    close(u, i / 10, 1e-15, 'u');
    close(s.delta[i], 100 * Math.abs(dot(cazVector(10 + 40 * u, 20 + 40 * u), n)), 1e-9, `δ(${u})`);
  });
});

test('nonlinearGrid, nonlinearSweepK, nonlinearSweepM: increments and start angles in degrees', () => {
  // From the pole of CAZ (m = 0): δ(u) = L·|sin(u·Δm)·sin((1 − u)·Δk)| (docs/science.md, eq 26's curve).
  const poleMax = (L, dK, dM) => {
    let best = 0;
    for (let i = 0; i <= 20000; i++) {
      const u = i / 20000;
      best = Math.max(best, L * Math.abs(Math.sin(u * rad(dM)) * Math.sin((1 - u) * rad(dK))));
    }
    return best;
  };
  const g = fa.nonlinearGrid({ machine: { type: 'CAZ' }, length: 100, thetaM: 0, dK: { from: 10, to: 40 }, dM: { from: 20, to: 50 }, nx: 4, ny: 4 });
  [10, 20, 30, 40].forEach((v, i) => close(g.dK[i], v, 1e-12, 'dK (degrees)'));
  [20, 30, 40, 50].forEach((v, i) => close(g.dM[i], v, 1e-12, 'dM (degrees)'));
  for (let iy = 0; iy < 4; iy++) for (let ix = 0; ix < 4; ix++) close(g.max[iy * 4 + ix], poleMax(100, g.dK[ix], g.dM[iy]), 1e-6, `grid ${ix} ${iy}`);
  // Fig 4: the maximum does not depend on the start angle of K (a turn of the whole path
  // about the K axis), here equal to the pole's.
  const k = fa.nonlinearSweepK({ machine: { type: 'CAZ' }, length: 100, thetaM: 0, dK: 30, dM: 40, from: -90, to: 90, n: 5 });
  [-90, -45, 0, 45, 90].forEach((v, i) => close(k.k[i], v, 1e-12, 'k (degrees)'));
  for (const v of k.max) close(v, poleMax(100, 30, 40), 1e-6, 'sweepK');
  const m = fa.nonlinearSweepM({ machine: { type: 'CAZ' }, length: 100, dM: 10, ratios: [1], from: 0, to: 40, n: 5 });
  [0, 10, 20, 30, 40].forEach((v, i) => close(m.m[i], v, 1e-12, 'm (degrees)'));
  // At the pole with Δk = Δm = 10°: eq 26, L·sin²(5°).
  close(m.curves[0].exact[0], 100 * Math.sin(rad(5)) ** 2, 1e-9, 'sweepM at the pole');
});

test('ballbarRotarySimulate and ballbarRotaryIdentify: angles, hold and sensitivities in degrees, against closed forms and finite differences', () => {
  // Li et al.'s B/C table: C on B, both through the origin, the table surface there (tableHeight
  // 0), the tool ball at the spindle nose. The table ball at (150, 0, 50), a radial bar of
  // L = 100 mm along +X on the table.
  const BC = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
  const L = 100;
  const e = 0.01;
  const tests = [{ ball: { x: 150, y: 0, height: 50 }, length: L, step: 15 }];
  const r = fa.ballbarRotarySimulate({ machine: { ...BC, errors: { E_X0C: e } }, tests, parameters: ['E_X0C', 'E_A0C'] });
  const t = r.tests[0];
  assert.equal(t.angle.length, 2 * 25);
  close(t.angle[1], 15, 1e-12, 'C in degrees');
  close(t.hold, 0, 0, 'hold');
  // The C line e off along X: the table ball at R_Z(−C)·p + e·x̂, the tool ball at R_Z(−C)·t, so
  // ΔL = √(L² − 2·L·e·cos C + e²) − L (C the command, in degrees here).
  t.angle.forEach((a, i) => close(t.deviation[i], Math.sqrt(L * L - 2 * L * e * Math.cos(rad(a)) + e * e) - L, 1e-11, `E_X0C at C ${a}°`));
  // A tilt of C about X by α turns the table ball by α·x̂ × (R_Z(−C)·p): along the bar
  // R_Z(−C)·x̂ that is 50·α·sin C, so the bar shortens by 50·sin C·α: per degree
  // −50·sin C·π/180, and the central difference over ±0.001° agrees.
  const s = t.sensitivities.find((x) => x.name === 'E_A0C');
  assert.equal(s.per, 'deg');
  const at = (h) => fa.ballbarRotarySimulate({ machine: { ...BC, errors: { E_A0C: h } }, tests }).tests[0].deviation;
  const [up, down] = [at(0.001), at(-0.001)];
  s.values.forEach((v, i) => {
    close(v, -50 * Math.sin(rad(t.angle[i])) * (Math.PI / 180), 1e-9, `per degree at C ${t.angle[i]}°`);
    close(v, (up[i] - down[i]) / 0.002, 1e-7, `finite difference at C ${t.angle[i]}°`);
  });
  // The identification of a tilt of 0.002° from its own trace gives 0.002 in degrees, in
  // machine.errors' units, and the correction in degrees.
  const trace = fa.ballbarRotarySimulate({ machine: { ...BC, errors: { E_A0C: 0.002 } }, tests }).csv;
  const id = fa.ballbarRotaryIdentify({ machine: BC, tests, parameters: ['E_A0C'], csv: trace });
  close(id.errors.E_A0C, 0.002, 1e-6, 'E_A0C in degrees');
  assert.equal(id.corrections[0].unit, 'deg');
  assert.equal(id.identification.estimates[0].unit, 'deg');
  close(id.tests[0].angle[1], 15, 1e-12, 'the fitted trace\'s angles in degrees');
});

test('toolVector and machineInverse: angles in degrees', () => {
  const v = fa.toolVector({ machine: { type: 'CAZ' }, k: 30, m: 50 });
  cazVector(30, 50).forEach((x, i) => close(v[i], x, 1e-12, 'toolVector'));
  const inv = fa.machineInverse({ machine: { type: 'CAZ', rotary: { mFrom: -120, mTo: 120 } }, vector: cazVector(30, 50), rule: 'smallest-tilt' });
  // Two solutions of equal tilt (k, m) and (k + 180°, −m); M ≥ 0 first.
  close(inv.solutions[inv.chosen].k, 30, 1e-9, 'k');
  close(inv.solutions[inv.chosen].m, 50, 1e-9, 'm');
});

// ---------------------------------------------------------------------------------------------
// The cubic-machining test on Li et al.'s B/C table (Table 2: B = 30° on every zone but ZONE I).

test('cubicTest: the B axis offset alone against its closed form; per-degree sensitivities against finite differences of the exact heights', () => {
  const LI = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
  // With the workpiece set at B = C = 0 (the set-up transform), a B axis line t off its place
  // moves the table at B by (I − R_Y(B))·t and not at all at B = 0. Along the tool (machine +Z,
  // material left positive): E_X0B = x gives x·sin B, E_Z0B = z gives z·(1 − cos B); C turns
  // about Z and keeps it. So ZONE I stays at 0 and every tilted zone moves alike.
  for (const [name, factor] of [['E_X0B', Math.sin(rad(30))], ['E_Z0B', 1 - Math.cos(rad(30))]]) {
    const r = fa.cubicTest({ machine: { ...LI, errors: { [name]: 0.01 } }, transform: true });
    const j = r.errorNames.indexOf(name);
    assert.equal(r.errorUnits[j], 'mm');
    r.zones.forEach((z, i) => {
      const f = z.name === 'I' ? 0 : factor;
      close(z.height, 0.01 * f, 1e-9, `${name} ${z.name}`);
      close(r.kHeight[i * r.errorNames.length + j], f, 1e-9, `${name} ${z.name}: per mm`);
    });
  }
  // An angular error entered in degrees: the sensitivity per degree is the central difference
  // of the exact heights over ±0.01° (its remainder is of order (0.01° in rad)² times the lever
  // arm, far below the 1e-6 allowed; a radian/degree mix-up would be off by a factor of 57).
  const base = fa.cubicTest({ machine: LI });
  const angles = base.errorNames.filter((n, j) => base.errorUnits[j] === 'deg');
  assert.ok(angles.length >= 4, `${angles}`);
  let largest = 0;
  for (const name of angles) {
    const j = base.errorNames.indexOf(name);
    const h = (e) => fa.cubicTest({ machine: { ...LI, errors: { [name]: e } } }).zones.map((z) => z.height);
    const [up, down] = [h(0.01), h(-0.01)];
    base.zones.forEach((z, i) => {
      const fd = (up[i] - down[i]) / 0.02;
      largest = Math.max(largest, Math.abs(fd));
      close(base.kHeight[i * base.errorNames.length + j], fd, 1e-6 * Math.max(1, Math.abs(fd)), `${name} ${z.name}: per degree`);
    });
  }
  assert.ok(largest > 0.01, `some zone moves by more than 0.01 mm per degree: ${largest}`);
});

// ---------------------------------------------------------------------------------------------
// A misspelt key is refused, for every input field of every export the schema declares.

const toolpathText = readFileSync(new URL('../../public/samples/dome-past-the-pole.csv', import.meta.url), 'utf8');
const points = fa.toolpathParse(toolpathText, {}).path;
const REVERSAL = readFileSync(new URL('../../public/samples/reversal-measured.csv', import.meta.url), 'utf8');
/** A valid input of each export (first argument) and its other arguments. */
const BASE = {
  cubicDesign: [{ grid: 2, maxTilt: 20 }],
  cubicHeightMap: [{ nx: 8, ny: 8 }],
  cubicIdentify: [{ csv: 'zone,height_um\nI,1\nII-1,2\nII-2,3\nII-3,4\nII-4,5\nIII-1,6\nIII-2,7\nIII-3,8\nIII-4,9' }],
  cubicTest: [{}],
  machineInverse: [{ vector: [0, 0.5, 1] }],
  machineSchematic: [{}],
  nonlinearCompareTypes: [{ start: { k: 0, m: 10 }, end: { k: 20, m: 30 }, length: 100 }],
  nonlinearGrid: [{ length: 100, thetaM: 0, dK: { from: 0, to: 10 }, dM: { from: 0, to: 10 }, nx: 2, ny: 2 }],
  nonlinearMove: [{ length: 100 }],
  nonlinearMaxErrors: ['CAZ', 100, new Float64Array([0, 0, 10, 20])],
  nonlinearSweepK: [{ length: 100, thetaM: 0, dK: 10, dM: 10, from: 0, to: 10, n: 2 }],
  nonlinearSweepM: [{ length: 100, dM: 10, ratios: [1], from: 0, to: 10, n: 2 }],
  reversalDents: [{}],
  reversalFit: [{ csv: REVERSAL }],
  reversalSimulate: [{}],
  reversalTrace: [{ csv: REVERSAL }],
  rotaryTypes: [{}],
  sshapeDefects: [{ machine: CHANAL }],
  sshapeIdentify: [{ machine: CHANAL, csv: SAMPLE }],
  sshapeOvercut: [{ nu: 14, nv: 2 }],
  sshapePart: [{}],
  toolVector: [{ k: 0, m: 0 }],
  toolpathAnalyse: [{ length: 100 }, points],
  toolpathCompare: [{ length: 100 }, points],
  toolpathParse: [{}],
  toolpathRefine: [{ length: 100, tolerance: 0.01 }, points],
  toolpathWrite: [{ format: 'csv' }, points],
  volumetricMap: [{}],
  volumetricPaper: [{ machine: preset('C/A double turntable on an X table'), x: 0, y: 0, z: 0 }],
  volumetricReadTable: [{ name: 'E_XX', text: 'X (mm), E_XX (um)\n0, 0\n100, 1' }],
  ballbarEvaluate: [{ csv: '# radius: 100 mm\nangle (deg); deviation (µm); direction\n0; -2; ccw\n18; 0; ccw\n36; 2; ccw\n54; -1; ccw\n72; 1; ccw\n90; -2; ccw\n108; 0; ccw\n126; 2; ccw\n144; -1; ccw\n162; 1; ccw\n180; -2; ccw\n198; 0; ccw\n216; 2; ccw\n234; -1; ccw\n252; 1; ccw\n270; -2; ccw\n288; 0; ccw\n306; 2; ccw\n324; -1; ccw\n342; 1; ccw\n360; -2; cw\n378; 0; cw\n396; 2; cw\n414; -1; cw\n432; 1; cw\n450; -2; cw\n468; 0; cw\n486; 2; cw\n504; -1; cw\n522; 1; cw\n540; -2; cw\n558; 0; cw\n576; 2; cw\n594; -1; cw\n612; 1; cw\n630; -2; cw\n648; 0; cw\n666; 2; cw\n684; -1; cw\n702; 1; cw' }],
  probeDesign: [{ step: 90 }],
  probeSimulate: [{ k: [0, 90], m: [0, 30] }],
  probeReadCsv: [{ csv: 'pose;C_deg;B_deg;X_mm;Y_mm;Z_mm\n1;0;0;0;0;100\n2;90;0;0;0;100' }],
  probeIdentify: [{ csv: 'pose;C_deg;B_deg;X_mm;Y_mm;Z_mm\n1;0;0;0;0;100\n2;90;0;0;0;100\n3;180;0;0;0;100\n4;270;0;0;0;100\n5;0;30;0;0;100\n6;0;-30;0;0;100\n7;90;30;0;0;100\n8;90;-30;0;0;100' }],
  positioningEvaluate: [{ csv: 'target (mm); direction; deviation (µm)\n0; up; 1\n0; up; 2\n0; down; 1\n0; down; 3\n100; up; 2\n100; up; 2\n100; down; 1\n100; down; 1' }],
  ballbarRotarySimulate: [{ tests: [{ step: 30 }] }],
  ballbarRotaryIdentify: [{ tests: [{ step: 30 }], parameters: ['E_X0C', 'E_Y0C'], csv: 'angle (deg); deviation (µm); direction\n0; 1; ccw\n45; 0,7; ccw\n90; 0; ccw\n135; -0,7; ccw\n180; -1; ccw\n225; -0,7; ccw\n270; 0; ccw\n315; 0,7; ccw\n360; 1; ccw' }],
};
/** `toolLength` → `toollength`, `nu` → `Nu`: what a user mistypes. */
const misspell = (key) => (/[A-Z]/.test(key.slice(1)) ? key[0] + key.slice(1).toLowerCase() : key[0].toUpperCase() + key.slice(1));

test('every export refuses a misspelt key of every one of its inputs, naming it and the right one', () => {
  const exports = fa.schema().exports;
  assert.deepEqual(Object.keys(exports).sort(), Object.keys(BASE).sort(), 'a valid input for every export');
  let checked = 0;
  for (const [name, fields] of Object.entries(exports)) {
    const [base, ...rest] = BASE[name];
    const call = (input) => (name === 'toolpathParse' ? fa.toolpathParse(toolpathText, input) : fa[name](input, ...rest));
    call(structuredClone(base)); // valid as it is
    for (const { path } of fields) {
      const parts = path.split('.');
      const right = parts.at(-1);
      const wrong = misspell(right);
      const input = structuredClone(base);
      let o = input;
      for (const seg of parts.slice(0, -1)) {
        o[seg] = o[seg] && typeof o[seg] === 'object' && !Array.isArray(o[seg]) ? o[seg] : {};
        o = o[seg];
      }
      const value = o[right] ?? (fields.find((f) => f.path === path).default ?? 1);
      delete o[right];
      o[wrong] = value;
      const where = [...parts.slice(0, -1), wrong].join('.');
      assert.throws(
        () => call(input),
        (e) => e instanceof Error && e.message.startsWith(`${where}: unknown input`) && e.message.includes(`Did you mean "${right}"`),
        `${name}: ${where}`,
      );
      checked++;
    }
  }
  assert.ok(checked > 400, `${checked}`);
});
