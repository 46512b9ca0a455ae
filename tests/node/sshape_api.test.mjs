// The S-shape API as a Node script uses it (the README's example), checked against closed forms:
// Appendix A's E_X0B column and the eq 14 reference, the sample file's known errors.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../crate/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../crate/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const machine = { l0: 499.889, rTool: 10, lTool: 35 };

test('README example: defects of E_X0B follow Appendix A at every point', () => {
  const part = fa.sshapePart();
  const d = fa.sshapeDefects({ machine, errors: { E_X0B: 0.0294 } });
  assert.ok(d.total instanceof Float64Array && d.total.length === 100);
  // E_X0B moves the tip by (cos C, −sin C, 0) in workpiece coordinates (Appendix A), minus the
  // same at the reference pose (C = 0): (cos C − 1, −sin C, 0)·n.
  part.points.forEach((p, k) => {
    const c = (d.poses[k].c * Math.PI) / 180;
    const expected = 0.0294 * ((Math.cos(c) - 1) * p.normal[0] - Math.sin(c) * p.normal[1]);
    assert.ok(Math.abs(d.total[k] - expected) < 1e-12, `point ${k}`);
  });
});

test('README example: identifying the sample file', () => {
  const f = fa.sshapeIdentify({ machine, csv: readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8') });
  const get = (n) => f.estimates.find((e) => e.name === n);
  assert.ok(Math.abs(get('E_X0B').value - 0.0294) < 4 * get('E_X0B').stdError);
  assert.ok(Math.abs(get('E_A0B').value - (3.2419e-4 * 180) / Math.PI) < 4 * get('E_A0B').stdError);
  assert.equal(get('E_A0B').unit, '°');
  assert.ok(f.residuals instanceof Float64Array && f.residuals.length === 100);
  assert.throws(() => fa.sshapeIdentify({ machine, csv: 'curve,point,deviation_mm\ntop,1,x' }), (e) => e instanceof Error && /^csv: line 2: /.test(e.message));
});
