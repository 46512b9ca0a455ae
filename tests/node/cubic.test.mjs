// The cubic-machining exports as a Node script uses them, on Li et al.'s machine (the page's
// machine preset), checked against the paper's Table 2, first-order closed forms of its eq 10
// and the ball's scallop height. Li et al.'s errors are entered by their ISO 230-1 names:
// E_X0B = −δxBY and so on (the minus sign: ISO's error is the axis's displacement, the paper's
// symbol its correction).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fa, preset, T5, T5_ISO } from '../papers.mjs';

const LI = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
const errors = T5_ISO;
const machine = { ...LI, errors };
const rad = (d) => (d * Math.PI) / 180;
/** Li et al.'s Table 2: (C, B) per zone in Table 1's order, degrees. */
const TABLE_2 = { I: [0, 0], 'II-1': [0, 30], 'II-2': [90, 30], 'II-3': [180, 30], 'II-4': [270, 30], 'III-1': [45, 30], 'III-2': [135, 30], 'III-3': [225, 30], 'III-4': [315, 30] };

test('zone heights of the Table 5 machine: Table 2 angles, eq 10 to first order', () => {
  const r = fa.cubicTest({ machine });
  assert.deepEqual(r.zones.map((z) => z.name), Object.keys(TABLE_2));
  // K = C, M = B on this machine.
  for (const z of r.zones) {
    const [c, b] = TABLE_2[z.name];
    assert.ok(Math.abs(z.k - c) < 1e-9 && Math.abs(z.m - b) < 1e-9, `${z.name}: C ${z.k}, B ${z.m}`);
  }
  assert.ok(r.zones[0].singular, 'ZONE I: the tool along C');
  // II-1 (C = 0°) with M_WC, first order: δxBY·(−sin 30°) + δzBY·(cos 30° − 1); the others
  // vanish there (αBY, αCB ∝ sin C, βBY ∝ 1 − cos C, γBY, δyBY, δxCB 0).
  const ii1 = -0.5 * T5.dxBY + (Math.cos(rad(30)) - 1) * T5.dzBY;
  const z1 = r.zones[1];
  assert.equal(z1.name, 'II-1');
  assert.ok(Math.abs(z1.height - ii1) < 1e-7, `${z1.height} vs ${ii1}`);
  assert.ok(Math.abs(z1.linearHeight - ii1) < 1e-12, `${z1.linearHeight} vs ${ii1}`);
  // Sensitivities, 9 × n zone-major, per mm or per degree of the ISO error (E = −ε).
  const n = r.errorNames.length;
  const k = (zone, name) => r.kHeight[zone * n + r.errorNames.indexOf(name)];
  assert.ok(r.kHeight instanceof Float64Array && r.kHeight.length === 9 * n);
  assert.equal(r.errorUnits[r.errorNames.indexOf('E_X0B')], 'mm');
  assert.equal(r.errorUnits[r.errorNames.indexOf('E_B0B')], 'deg');
  assert.ok(Math.abs(k(1, 'E_X0B') - 0.5) < 1e-12, 'II-1: +sin 30° per mm of E_X0B');
  assert.ok(Math.abs(k(1, 'E_Z0B') - (1 - Math.cos(rad(30)))) < 1e-12, 'II-1: 1 − cos 30° per mm of E_Z0B');
  // II-3 (C = 180°): βBY acts with 2·16 mm per rad, here per degree and with E_B0B = −βBY.
  assert.ok(Math.abs(k(3, 'E_B0B') + rad(32)) < 1e-9, `${k(3, 'E_B0B')}`);
  // ZONE I is the reference of the workpiece set at zero: 0.
  assert.equal(r.zones[0].height, 0);
  assert.equal(r.transform, true);
  assert.equal(r.reference, 'workpiece');
  // Without M_WC ZONE I follows the B axis's height error: δzBY (first order).
  const plain = fa.cubicTest({ machine, transform: false });
  assert.ok(Math.abs(plain.zones[0].height - T5.dzBY) < 1e-5, `${plain.zones[0].height}`);
});

test('what the heights cannot see: δyBY and δxCB (Section 4.3), and errors that act alike', () => {
  const r = fa.cubicTest({ machine });
  for (const name of ['E_Y0B', 'E_X0C']) assert.ok(r.visibility.invisible.includes(name), `${name} invisible: ${r.visibility.invisible}`);
  // αBY and αCB act alike on the heights (Section 4.3).
  const alike = r.visibility.alike.map((g) => g.map((m) => m.name));
  assert.ok(alike.some((g) => g.includes('E_A0B') && g.includes('E_A0C')), JSON.stringify(alike));
  // δxBY and δzBY act alike too; at II-1 (closed form above) their ratio is (1 − cos 30°)/sin 30°
  // = tan 15°.
  const xz = r.visibility.alike.find((g) => g.some((m) => m.name === 'E_X0B'));
  const z = xz.find((m) => m.name === 'E_Z0B');
  assert.ok(z && Math.abs(z.factor - Math.tan(rad(15))) < 1e-9, JSON.stringify(xz));
});

test('the height map relative to ZONE I', () => {
  const m = fa.cubicHeightMap({ machine, reference: 'zone1-height', nx: 385, ny: 385 });
  assert.equal(m.height.length, 385 * 385);
  assert.equal(m.zoneAverage.length, 9);
  // Scallop height of a 3 mm ball at 0.1 mm pick feed.
  assert.ok(Math.abs(m.scallop - (3 - Math.sqrt(9 - 0.05 ** 2))) < 1e-15);
  // The zone averages follow the exact zone heights within the strips where a lower
  // neighbour's ball cuts across a border (about 0.2 µm here).
  const r = fa.cubicTest({ machine, reference: 'zone1-height' });
  r.zones.forEach((z, i) => assert.ok(Math.abs(m.zoneAverage[i] - z.height) < 3e-4, `${z.name}: ${m.zoneAverage[i]} vs ${z.height}`));
  assert.deepEqual(m.zones.map((z) => z.name), r.zones.map((z) => z.name));
});

test('a misspelt error or a paper symbol is refused, not taken as zero', () => {
  const refused = (input, re) => assert.throws(() => fa.cubicTest(input), (e) => e instanceof Error && re.test(e.message), re.source);
  refused({ machine: { ...LI, errors: { E_Z0b: 0.01 } } }, /^machine\.errors\.E_Z0b: unknown error name.*Did you mean E_Z0B\?/);
  // Li et al.'s symbols (earlier versions of the API) name the ISO error and its sign.
  refused({ machine: { ...LI, errors: { dzBY: 0.01 } } }, /^machine\.errors\.dzBY: .*E_Z0B = −δzBY/);
  refused({ machine: { ...LI, errors: { E_Z0B: 6 } } }, /^machine\.errors\.E_Z0B: /);
  refused({ machine: LI, setup: { pick: 7 } }, /^setup\.pick: .*diameter/);
  refused({ machine: LI, setup: { tableAboveB: 1 } }, /^setup\.tableAboveB: unknown input/);
  // The error table: 21 location errors, each limited to 5 mm or 5°; Li et al.'s eight
  // symbols are aliases of eight of them, each with the minus sign.
  const table = fa.schema().errors;
  assert.equal(table.length, 21);
  assert.ok(table.every((e) => e.limit === 5 && e.kind === 'location'));
  const li = table.filter((e) => e.aliases.some((a) => /^Li et al/.test(a.source)));
  assert.deepEqual(li.map((e) => e.name).sort(), Object.keys(errors).sort());
  for (const e of li) assert.ok(e.aliases.filter((a) => /^Li et al/.test(a.source)).every((a) => a.sign === -1), e.name);
});
