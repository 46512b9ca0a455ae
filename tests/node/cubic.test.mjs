// The cubic-machining exports as a Node script uses them (the README's example), checked
// against first-order closed forms of the paper's eq 10 and the ball's scallop height.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../crate/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../crate/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const errors = { dxBY: 0.0146, dyBY: -0.0089, dzBY: -0.0142, alphaBY: -0.0023, betaBY: 0.0029, gammaBY: -0.00002, alphaCB: -0.00017, dxCB: 0.0094 };
const rad = (d) => (d * Math.PI) / 180;

test('README example: zone heights of the Table 5 machine', () => {
  const r = fa.cubicTest({ errors });
  assert.equal(r.zones[1].name, 'II-1');
  assert.ok(Math.abs(r.zones[1].b - 30) < 1e-9 && Math.abs(r.zones[1].c) < 1e-9);
  // II-1 (C = 0°) with M_WC, first order: δxBY·(−sin 30°) + δzBY·(cos 30° − 1); the others
  // vanish there (αBY, αCB ∝ sin C, βBY ∝ 1 − cos C, γBY, δyBY, δxCB 0).
  const ii1 = -0.5 * errors.dxBY + (Math.cos(rad(30)) - 1) * errors.dzBY;
  assert.ok(Math.abs(r.zones[1].height - ii1) < 1e-7, `${r.zones[1].height} vs ${ii1}`);
  assert.ok(Math.abs(r.kHeight[1 * 8 + 0] + 0.5) < 1e-12);
  // II-3 (C = 180°): βBY acts with 2·16 mm per rad, here per degree.
  assert.ok(Math.abs(r.kHeight[3 * 8 + 4] - rad(32)) < 1e-9);
  assert.ok(r.kHeight instanceof Float64Array && r.kHeight.length === 72);
  assert.equal(r.zones[0].height, 0);
});

test('README example: the height map relative to ZONE I', () => {
  const m = fa.cubicHeightMap({ errors, reference: 'zone1-height', nx: 385, ny: 385 });
  assert.equal(m.height.length, 385 * 385);
  assert.equal(m.zoneAverage.length, 9);
  // Scallop height of a 3 mm ball at 0.1 mm pick feed.
  assert.ok(Math.abs(m.scallop - (3 - Math.sqrt(9 - 0.05 ** 2))) < 1e-15);
  // The zone averages follow the exact zone heights within the strips where a lower
  // neighbour's ball cuts across a border (about 0.2 µm here).
  const r = fa.cubicTest({ errors, reference: 'zone1-height' });
  r.zones.forEach((z, i) => assert.ok(Math.abs(m.zoneAverage[i] - z.height) < 3e-4, `${z.name}: ${m.zoneAverage[i]} vs ${z.height}`));
});

test('a misspelt error is refused, not taken as zero', () => {
  assert.throws(() => fa.cubicTest({ errors: { dzBy: 0.01 } }), (e) => e instanceof Error && /^errors: unknown field `dzBy`/.test(e.message));
  assert.throws(() => fa.cubicTest({ errors: { dzBY: 6 } }), (e) => /^errors\.dzBY: /.test(e.message));
  assert.equal(fa.cubicErrors().length, 8);
});
