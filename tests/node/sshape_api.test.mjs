// The S-shape API as a Node script uses it, on Chanal et al.'s machine (the page's machine
// preset), checked against closed forms: Appendix A's E_X0B column and the eq 14 reference, and
// the sample file's known errors.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const CHANAL = MACHINES.find((p) => p.name === 'B swivel head, C rotary table, Y under the table (Chanal et al. 2022)').machine;
const tool = { rTool: 10, lTool: 35 };
/** The eight errors Chanal et al. identify (Section 5.2). */
const PAPER_PARAMETERS = ['E_C0Y', 'E_A0Z', 'E_B0Z', 'E_A0C', 'E_B0C', 'E_X0B', 'E_A0B', 'E_C0B'];
const SAMPLE = readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8');

test('Chanal et al.\'s machine: L0 = 499.889 mm from B to the tool tip', () => {
  const g = CHANAL.geometry;
  assert.ok(Math.abs(g.pivotLength + g.toolLength - 499.889) < 1e-9);
  assert.equal(fa.machineSchematic({ machine: CHANAL }).swingLength, g.pivotLength + g.toolLength);
});

test('defects of E_X0B follow Appendix A at every point', () => {
  const part = fa.sshapePart();
  const d = fa.sshapeDefects({ machine: { ...CHANAL, errors: { E_X0B: 0.0294 } }, tool });
  assert.ok(d.total instanceof Float64Array && d.total.length === 100);
  const n = d.names.length;
  assert.equal(d.contributions.length, 100 * n);
  assert.equal(d.units[d.names.indexOf('E_X0B')], 'mm');
  assert.equal(d.units[d.names.indexOf('E_A0B')], 'deg');
  // The head-table machine with Y under the table: its axes in chain order, C and B among them.
  assert.deepEqual([...d.axes].sort(), ['B', 'C', 'X', 'Y', 'Z']);
  const c = d.axes.indexOf('C');
  // E_X0B moves the tip by (cos C, −sin C, 0) in workpiece coordinates (Appendix A), minus the
  // same at the reference pose (C = 0): (cos C − 1, −sin C, 0)·n.
  const ix = d.names.indexOf('E_X0B');
  part.points.forEach((p, k) => {
    const cr = (d.poses[k].values[c] * Math.PI) / 180;
    const expected = 0.0294 * ((Math.cos(cr) - 1) * p.normal[0] - Math.sin(cr) * p.normal[1]);
    assert.ok(Math.abs(d.total[k] - expected) < 1e-12, `point ${k}`);
    assert.ok(Math.abs(d.contributions[k * n + ix] - expected) < 1e-12, `point ${k}: its contribution`);
  });
  // A tool-radius error moves every point along its normal by −dR·sin θ, θ between the normal
  // and the tool (a larger tool cuts deeper); flank milling: the tool nearly square to the normal.
  const r = fa.sshapeDefects({ machine: CHANAL, tool, dR: 0.02 });
  assert.ok(Array.from(r.radius).every((v) => v >= -0.02 - 1e-15 && v < -0.0199), `${r.radius}`);
});

test('identifying the sample file (E_X0B = 0.0294 mm, E_A0B = 3.2419e-4 rad, a tool 0.02 mm small)', () => {
  const f = fa.sshapeIdentify({ machine: CHANAL, tool, csv: SAMPLE, parameters: PAPER_PARAMETERS });
  const get = (n) => f.estimates.find((e) => e.name === n);
  assert.deepEqual(f.estimates.map((e) => e.name), [...PAPER_PARAMETERS, 'dR']);
  assert.ok(Math.abs(get('E_X0B').value - 0.0294) < 4 * get('E_X0B').stdError);
  assert.ok(Math.abs(get('E_A0B').value - (3.2419e-4 * 180) / Math.PI) < 4 * get('E_A0B').stdError);
  assert.ok(Math.abs(get('dR').value + 0.02) < 4 * get('dR').stdError);
  assert.equal(get('E_A0B').unit, 'deg');
  assert.equal(get('E_X0B').unit, 'mm');
  assert.equal(f.rank, 9);
  assert.ok(f.residuals instanceof Float64Array && f.residuals.length === 100);
  // The sample's noise is 2 µm.
  assert.ok(f.rms > 0.001 && f.rms < 0.003, `${f.rms}`);
  // Without a list: every error of the machine (its B, C and squareness errors) and dR.
  const all = fa.sshapeIdentify({ machine: CHANAL, tool, csv: SAMPLE });
  assert.equal(all.estimates.length, fa.sshapeDefects({ machine: CHANAL }).names.length + 1);
});

test('bad files and names are refused with the path and the line', () => {
  const refused = (input, re) => assert.throws(() => fa.sshapeIdentify({ machine: CHANAL, tool, ...input }), (e) => e instanceof Error && re.test(e.message), re.source);
  refused({ csv: 'curve,point,deviation_mm\ntop,1,x' }, /^csv: line 2: /);
  refused({ csv: SAMPLE, parameters: ['E_X0A'] }, /^parameters\[0\]: E_X0A is not an error of this machine/);
  refused({ csv: SAMPLE, parameters: ['E_X0B', 'E_A0b'] }, /^parameters\[1\]: unknown error name.*Did you mean E_A0B\?/);
  refused({ csv: SAMPLE, model: { reference: 'axisZero' } }, /^model\.reference: /);
});
