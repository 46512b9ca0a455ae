// The examples of README.md and docs/using.md: first each file's `js` blocks run as written (as
// a Node script in the repository's root runs them), then each example's values checked against
// a value derived here independently of the engine (closed forms written out below).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import * as engine from '../../wasm/pkg/fiveaxis.js';
import { initSync, nonlinearMove, cubicTest, sshapeDefects, sshapeIdentify, toolpathParse, toolpathCompare, volumetricMap, reversalSimulate } from '../../wasm/pkg/fiveaxis.js';

initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
const presets = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const rad = (d) => (d * Math.PI) / 180;

// A document's `js` blocks as one script: its imports of node:fs and of the built package become
// lookups in those modules (so a name the package does not export fails), run from the root, with
// the named variables returned.
function runBlocks(doc, names) {
  const text = readFileSync(new URL(`../../${doc}`, import.meta.url), 'utf8');
  const blocks = [...text.matchAll(/^```js\n([\s\S]*?)^```$/gm)].map((m) => m[1]);
  assert.ok(blocks.length > 0, `${doc} has no js block`);
  const modules = { 'node:fs': fs, './wasm/pkg/fiveaxis.js': engine };
  const code = blocks.join('\n').replace(/import\s*\{([^}]*)\}\s*from\s*'([^']+)';/g, (_, list, from) => {
    assert.ok(from in modules, `${doc} imports from ${from}`);
    return list.split(',').map((n) => n.trim()).filter(Boolean)
      .map((n) => { assert.ok(n in modules[from], `${doc}: ${from} has no export ${n}`); return `const ${n} = __modules[${JSON.stringify(from)}].${n};`; }).join('\n');
  });
  const cwd = process.cwd();
  process.chdir(fileURLToPath(new URL('../../', import.meta.url)));
  try {
    return new Function('__modules', `${code}\nreturn { ${names.join(', ')} };`)(modules);
  } finally {
    process.chdir(cwd);
  }
}

test('README.md: its example runs as written and gives the values its comments state', () => {
  const { r, c } = runBlocks('README.md', ['r', 'c']);
  assert.equal(r.length, 100);
  assert.ok(Math.abs(r.max - 10.94) < 0.005, `${r.max}`);
  assert.ok(r.delta instanceof Float64Array && r.delta.length === r.u.length);
  assert.equal(c.zones[1].name, 'II-1');
  assert.ok(Math.abs(c.zones[1].k - 90) < 1e-9 && Math.abs(c.zones[1].m - 30) < 1e-9);
  assert.ok(Math.abs(c.zones[1].height - -0.00296) < 5e-6);
  assert.equal(c.kHeight.length, 9 * c.errorNames.length);
  for (const name of ['E_Z0C', 'E_C0C']) assert.ok(c.visibility.invisible.includes(name), name);
});

test('docs/using.md: its examples run as written and give the values their comments state', () => {
  const x = runBlocks('docs/using.md', ['r', 'n', 'v', 'd', 'f', 'g', 'a', 'b']);
  assert.ok(Math.abs(x.r.zones[1].height - -0.0053976) < 1e-7);
  assert.ok(Math.abs(x.r.kHeight[x.n + x.r.errorNames.indexOf('E_X0B')] - 0.5) < 1e-12);
  assert.equal(x.v.budget[0].name, 'E_C0Y');
  assert.match(x.v.summary, /^The tool tip is off by up to 6\.2 µm \(at X 300, Y -200, Z 0 mm\)/);
  assert.equal(x.d.total.length, 100);
  assert.equal(x.f.estimates[0].name, 'E_C0Y');
  assert.deepEqual(x.g.estimates.filter((e) => e.verdict === 'present').map((e) => e.name), ['E_X0B', 'E_A0B', 'dR']);
  assert.equal(x.g.goodness.explains, true);
  assert.ok(Math.abs(x.b.dent.depth / x.a.dent.depth - 2) < 0.01);
  assert.deepEqual(x.a.directions.map((e) => [e.name, e.reverses]), [['X', false], ['Y', false], ['Z', false]]);
});

const machine = { kind: 'table-table', type: 'CAZ', geometry: { tableHeight: 100 }, rotary: { mFrom: -120, mTo: 30 }, errors: { E_Z0A: -0.02, E_A0C: 0.001 } };

test('README: a nonlinear move on an A/C trunnion, L from the machine', () => {
  const r = nonlinearMove({ machine, start: { k: 0, m: 0 }, end: { k: 30, m: 50 } });
  assert.equal(r.length, 100);
  // From the pole (θm = 0) the error is L·|sin(u·Δθm)·sin((1 − u)·Δθk)|: its maximum by a fine
  // search here.
  let best = 0;
  for (let i = 0; i <= 100000; i++) {
    const u = i / 100000;
    best = Math.max(best, 100 * Math.abs(Math.sin(u * rad(50)) * Math.sin((1 - u) * rad(30))));
  }
  assert.ok(Math.abs(r.max - best) < 1e-6, `${r.max} vs ${best}`);
  assert.ok(Math.abs(r.max - 10.94) < 0.005);
});

test('README: the cubic test on the trunnion, II-1 by hand', () => {
  const c = cubicTest({ machine });
  const z = c.zones[1];
  assert.equal(z.name, 'II-1');
  // Tool (0.5, 0, √3/2) = R_Z(C)·R_X(A)·e_z: A = 30°, C = 90°.
  assert.ok(Math.abs(z.k - 90) < 1e-9 && Math.abs(z.m - 30) < 1e-9);
  // Workpiece set at zero: an error (ω, t) of A moves the workpiece point P0 by
  // (ω − Qᵀω)×P0 + (t − Qᵀt), Qᵀ = R_Z(c)·R_X(a); one of C by the same with R_Z(c) alone.
  // E_Z0A (t = e_z): z of t − Qᵀt = 1 − cos a. E_A0C (ω = e_x): z of (ω − R_Z(c)ω)×P0 =
  // (1 − cos c)·y + sin c·x at the zone centre (x, y) = (−16, 0).
  const [a, cc] = [rad(30), rad(90)];
  const first = -0.02 * (1 - Math.cos(a)) + rad(0.001) * ((1 - Math.cos(cc)) * 0 + Math.sin(cc) * -16);
  assert.ok(Math.abs(z.linearHeight - first) < 1e-12, `${z.linearHeight} vs ${first}`);
  assert.ok(Math.abs(z.height - -0.00296) < 5e-6);
  // C's axial position and zero position move nothing: t = e_z and ω = e_z are kept by R_Z(c).
  for (const name of ['E_Z0C', 'E_C0C']) assert.ok(c.visibility.invisible.includes(name), name);
  assert.equal(c.kHeight.length, 9 * c.errorNames.length);
});

test('docs/using.md: Li et al.\'s Table 5 machine', () => {
  const li = structuredClone(presets[0].machine);
  li.errors = { E_X0B: -0.0146, E_Y0B: 0.0089, E_Z0B: 0.0142, E_A0B: 0.0023, E_B0B: -0.0029, E_C0B: 0.00002, E_A0C: 0.00017, E_X0C: -0.0094 };
  const r = cubicTest({ machine: li });
  assert.equal(r.zones[1].k, 0);
  assert.ok(Math.abs(r.zones[1].m - 30) < 1e-9);
  // First order at II-1 (C = 0°) in the paper's terms: −sin 30°·δxBY + (cos 30° − 1)·δzBY.
  const ii1 = -0.5 * 0.0146 + (Math.cos(rad(30)) - 1) * -0.0142;
  assert.ok(Math.abs(r.zones[1].linearHeight - ii1) < 1e-12);
  assert.ok(Math.abs(r.zones[1].height - -0.0053976) < 1e-7);
  const n = r.errorNames.length;
  assert.ok(Math.abs(r.kHeight[n + r.errorNames.indexOf('E_X0B')] - 0.5) < 1e-12);
});

test('docs/using.md: the S-shape on Chanal et al.\'s machine', () => {
  const chanal = presets[1].machine;
  const d = sshapeDefects({ machine: { ...chanal, errors: { E_X0B: 0.0294, E_A0B: 0.018575 } } });
  assert.equal(d.total.length, 100);
  const csv = readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8');
  const paper = ['E_C0Y', 'E_A0Z', 'E_B0Z', 'E_A0C', 'E_B0C', 'E_X0B', 'E_A0B', 'E_C0B'];
  const f = sshapeIdentify({ machine: chanal, csv, parameters: paper });
  const x0b = f.estimates.find((e) => e.name === 'E_X0B');
  // The sample was simulated with Table 4's E_X0B = 0.0294 mm.
  assert.ok(Math.abs(x0b.value - 0.0294) < 4 * x0b.stdError);
  assert.equal(f.estimates[0].unit, 'deg');
  // All 15 errors: the part cannot separate them all; E_X0B falls into a group.
  const all = sshapeIdentify({ machine: chanal, csv });
  assert.equal(all.estimates.length, 16);
  assert.ok(all.rank < 16);
  assert.ok(all.groups.some((g) => g.members.includes('E_X0B')));
  // The decisions (docs/using.md, Identification API): with the sample's stated 2 µm noise and a 5 µm
  // tolerance, present are exactly the errors its header says it was made with (Table 4's E_X0B
  // and E_A0B, the tool 0.02 mm small), each within three standard errors of its estimate (a
  // 95 % interval misses the truth in one draw of twenty: this draw puts E_A0B 2.3 σ off).
  const g = sshapeIdentify({ machine: chanal, csv, parameters: paper, decision: { noise: 0.002, tolerance: 0.005 } });
  assert.deepEqual(g.estimates.filter((e) => e.verdict === 'present').map((e) => e.name), ['E_X0B', 'E_A0B', 'dR']);
  const truth = { E_X0B: 0.0294, E_A0B: (3.2419e-4 * 180) / Math.PI, dR: -0.02 };
  for (const [n, t] of Object.entries(truth)) {
    const [lo, hi] = g.estimates.find((e) => e.name === n).interval;
    const sigma = (hi - lo) / 2 / 1.96;
    assert.ok(Math.abs(t - (lo + hi) / 2) < 3 * sigma, `${n}: ${t} within 3σ of [${lo}, ${hi}]`);
  }
  assert.equal(g.goodness.explains, true);
  assert.match(g.summary[0], /^E_X0B = 29\.6 µm ± 0\.536 µm: the B axis line lies 29\.6 µm towards \+X/);
});

test('docs/using.md: the dome sample on the twelve types', () => {
  const p = toolpathParse(readFileSync(new URL('../../public/samples/dome-past-the-pole.csv', import.meta.url), 'utf8'), {});
  assert.equal(p.count, 81);
  const rows = toolpathCompare({ machine: { type: 'CBZ' }, tolerance: 0.01 }, p.path);
  const row = (t) => rows.find((r) => r.type === t);
  // Passing 0.3° beside the vertical with 1° steps, K about Z swings by about
  // 2·atan(0.5/0.3) ≈ 118° on one side of the vertical: one flip before and one after it.
  for (const t of ['CAZ', 'CBZ', 'CAY', 'CBX']) assert.equal(row(t).flips, 2, t);
  // A vertical tool is 90° from X; ABX and ACX's M travels ±120° but the path starts 40° beyond.
  for (const t of ['ABX', 'ACX']) assert.equal(row(t).unreachable.point, 0, t);
  assert.deepEqual(rows.slice(-2).map((r) => r.type).sort(), ['ABX', 'ACX']);
  assert.ok(row('BCY').max < 0.0025 && row('CAZ').max > 0.1);
});

test('docs/using.md: the volumetric map of an X table with positioning, pitch and squareness, by hand', () => {
  const tanLim = { kind: 'table-table', type: 'CAZ', linear: 'table-x', geometry: { toolLength: 100 },
    rotary: { mFrom: -120, mTo: 120 },
    errors: { E_C0Y: 0.001 },
    motions: { E_XX: { poly: [0, 1e-5] }, E_BX: { position: [-300, 0, 300], value: [-0.0003, 0, 0.0002] } } };
  const v = volumetricMap({ machine: tanLim, region: { plane: 'XY', uFrom: -300, uTo: 300, vFrom: -200, vTo: 200, at: 0, steps: 41 } });
  // With A and C at zero the tip is (X, Y, −100) from the X carriage's reference point, in table
  // coordinates. To first order: E_XX moves it (1e-5·X, 0, 0); the squareness ε of Y turns the
  // spindle side about Z: ε·ẑ × (0, Y, −100) = (−ε·Y, 0, 0); the table's pitch b(X) turns the
  // tool relative to the table about Y: b·ŷ × (X, Y, −100) = (−100·b, 0, −b·X).
  const eps = rad(0.001);
  const pitch = (x) => rad(x < 0 ? -0.0003 * (x / -300) : 0.0002 * (x / 300));
  const parts = (x, y) => [[1e-5 * x, 0, 0], [-eps * y, 0, 0], [-100 * pitch(x), 0, -pitch(x) * x]];
  let worst = { n: -1 };
  const dot = [0, 0, 0];
  let total2 = 0;
  for (let j = 0; j < 41; j++) {
    for (let i = 0; i < 41; i++) {
      const [x, y] = [-300 + 15 * i, -200 + 10 * j];
      const p = parts(x, y);
      const d = [0, 1, 2].map((c) => p[0][c] + p[1][c] + p[2][c]);
      const n = Math.hypot(...d);
      if (n > worst.n) worst = { n, x, y, d };
      total2 += n * n;
      p.forEach((c, e) => (dot[e] += c[0] * d[0] + c[1] * d[1] + c[2] * d[2]));
    }
  }
  assert.deepEqual(v.worst.position, [worst.x, worst.y, 0]);
  assert.ok(Math.abs(v.worst.norm - worst.n) < 1e-8, `${v.worst.norm} vs ${worst.n}`);
  assert.ok(Math.abs(v.worst.norm - 0.0062) < 5e-5);
  const share = Object.fromEntries(v.budget.map((c) => [c.name, c.share]));
  ['E_XX', 'E_C0Y', 'E_BX'].forEach((name, e) => assert.ok(Math.abs(share[name] - dot[e] / total2) < 1e-6, `${name}: ${share[name]} vs ${dot[e] / total2}`));
  assert.equal(v.budget[0].name, 'E_C0Y');
  assert.ok(Math.abs(v.budget[0].share - 0.61) < 0.005);
  assert.match(v.summary, /^The tool tip is off by up to 6\.2 µm \(at X 300, Y -200, Z 0 mm\)/);
});

test('docs/using.md: the reversal dent doubles with r, X and Y keep their direction', () => {
  const a = reversalSimulate({ test: { offset: 25 } });
  const b = reversalSimulate({ test: { offset: 50 } });
  // The dent is C's error at the reversal copied onto the circle at the radius r (Figs 12, 13):
  // twice r, twice the dent; it sits just after C turns at 180°.
  assert.ok(Math.abs(b.dent.depth / a.dent.depth - 2) < 0.01, `${b.dent.depth / a.dent.depth}`);
  assert.ok(a.dent.angle > 180 && a.dent.angle < 183, `${a.dent.angle}`);
  assert.ok(a.dent.depth > 0.005 && a.dent.depth < 0.01, `${a.dent.depth}`);
  assert.deepEqual(a.directions.map((d) => [d.name, d.reverses]), [['X', false], ['Y', false], ['Z', false]]);
});
