// The engine as a Node script uses it: the built package wasm/pkg, loaded with initSync. Every
// study takes one object with an optional `machine`; results are checked against closed forms
// (Geng et al.'s eq 26, the δ(u) curve from the pole) and facts written here, not against the
// engine's own output.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const rad = (d) => (d * Math.PI) / 180;
/** From the pole of Group I, δ(u) = L |sin(u Δm) sin((1 − u) Δk)|: its maximum by brute force. */
function poleMax(L, dK, dM) {
  let best = 0;
  for (let i = 0; i <= 100000; i++) {
    const u = i / 100000;
    best = Math.max(best, L * Math.abs(Math.sin(u * rad(dM)) * Math.sin((1 - u) * rad(dK))));
  }
  return best;
}

test('one move on a CAZ machine: its maximum, and eq 26 at the pole', () => {
  const r = fa.nonlinearMove({ machine: { type: 'CAZ' }, length: 100, start: { k: 0, m: 0 }, end: { k: 30, m: 50 } });
  const best = poleMax(100, 30, 50);
  assert.ok(Math.abs(r.max - best) < 1e-6, `${r.max} vs ${best}`);
  // Eq 26 is the curve at u = 0.5, a little below the maximum since |Δk| != |Δm|.
  assert.ok(Math.abs(r.closedForm - 100 * Math.sin(rad(25)) * Math.sin(rad(15))) < 1e-12);
  assert.ok(r.closedForm < r.max);
  assert.ok(r.delta instanceof Float64Array && r.u instanceof Float64Array);
  assert.equal(r.reference, 'plane');
  assert.equal(r.type, 'CAZ');
  assert.equal(r.length, 100);
  // Equal increments from the pole: eq 26 is exact, L·sin²(Δ/2).
  const eq = fa.nonlinearMove({ machine: { type: 'CAZ' }, length: 100, start: { k: 0, m: 0 }, end: { k: 45, m: 45 } });
  assert.ok(Math.abs(eq.max - 100 * Math.sin(rad(22.5)) ** 2) < 1e-9, `${eq.max}`);
});

test('L from the machine when left out: table height (table-table), pivot + tool (heads)', () => {
  // A table-table machine: L is the table surface's distance from the rotary centre.
  const t = fa.nonlinearMove({ machine: { kind: 'table-table', type: 'CAZ', geometry: { tableHeight: 150 } }, start: { k: 0, m: 0 }, end: { k: 30, m: 50 } });
  assert.equal(t.length, 150);
  assert.ok(Math.abs(t.max - poleMax(150, 30, 50)) < 1e-6, `${t.max}`);
  // A head-head machine: pivot to spindle nose plus the tool.
  const h = fa.nonlinearMove({ machine: { kind: 'head-head', type: 'CAZ', geometry: { pivotLength: 200, toolLength: 50 } }, start: { k: 0, m: 0 }, end: { k: 30, m: 50 } });
  assert.equal(h.length, 250);
  assert.ok(Math.abs(h.max - poleMax(250, 30, 50)) < 1e-6, `${h.max}`);
  // The schematic reports the same distance.
  assert.equal(fa.machineSchematic({ machine: { kind: 'head-head', type: 'CAZ', geometry: { pivotLength: 200, toolLength: 50 } } }).swingLength, 250);
  // A table at the rotary centre gives none: the message asks for L.
  assert.throws(
    () => fa.nonlinearMove({ machine: { geometry: { tableHeight: 0 } }, start: { k: 0, m: 0 }, end: { k: 1, m: 1 } }),
    (e) => e instanceof Error && /^length: .*enter L/.test(e.message),
  );
});

test('bad input throws an Error whose message starts with the input\'s path', () => {
  const refused = (input, re) => assert.throws(() => fa.nonlinearMove(input), (e) => e instanceof Error && re.test(e.message), re.source);
  refused({ machine: { type: 'CAZ' }, length: 0, start: { k: 0, m: 0 }, end: { k: 1, m: 1 } }, /^length: /);
  refused({ machine: { type: 'CAZ' }, length: 10, start: { k: 0, m: Infinity }, end: { k: 1, m: 1 } }, /^start\.m: /);
  refused({ machine: { kind: 'gantry' } }, /^machine\.kind: /);
  refused({ machine: { type: 'CZA' } }, /^machine\.type: /);
  // Unknown keys anywhere are refused, not ignored, with the nearest known name.
  refused({ lenght: 3 }, /^lenght: unknown input.*Did you mean "length"/);
  refused({ machine: { geometry: { height: 6 } } }, /^machine\.geometry\.height: unknown input/);
  refused({ machine: { errors: { E_A0b: 0.001 } } }, /^machine\.errors\.E_A0b: unknown error name.*Did you mean E_A0B\?/);
  // An error the machine cannot have (no such axis), and one beyond the limit (5°).
  refused({ machine: { type: 'CBZ', errors: { E_X0A: 0.01 } } }, /^machine\.errors\.E_X0A: this machine has no A axis/);
  refused({ machine: { errors: { E_A0B: 6 } } }, /^machine\.errors\.E_A0B: must be between -5 degrees and 5 degrees/);
});

test('bulk maximum errors of many moves', () => {
  const moves = new Float64Array([0, 0, 40, 40, 0, 10, 0, 80, 5, 30, 5, 30]);
  const out = fa.nonlinearMaxErrors('CAZ', 2, moves);
  assert.ok(Math.abs(out[0] - 2 * Math.sin(rad(20)) ** 2) < 1e-9, 'equal increments from the pole');
  assert.ok(out[1] < 1e-12, 'M alone: no error');
  assert.equal(out[2], 0, 'no move: no error');
});

test('the machine in words, its inverse kinematics and tool vector', () => {
  const s = fa.machineSchematic({ machine: { kind: 'table-table', type: 'CBZ' }, k: 0, m: 0 });
  assert.equal(s.group, 'I');
  assert.deepEqual([s.k, s.m, s.home], ['C', 'B', 'Z']);
  assert.deepEqual(s.face, ['X', 'Y', 'Z']);
  // Chain order: the table's rotary axes from the bed up (B carries C), then the spindle's X, Y, Z.
  assert.deepEqual(s.axes.map((a) => a.name), ['B', 'C', 'X', 'Y', 'Z']);
  const c = s.axes.find((a) => a.name === 'C');
  assert.deepEqual([c.motion, c.side, c.role], ['rotary', 'table', 'K']);
  // In words: C, the K axis, sits on B and carries the workpiece.
  assert.match(c.description, /^C \(K\): .*\bon B\b.*carries the workpiece/);
  // Zone II-3 of the cubic test (Li et al.'s Table 2): B = 30°, C = 180°; continuity keeps C
  // near 170° (the other solution, C = 0°, B = −30°, is farther).
  const ik = fa.machineInverse({ machine: { type: 'CBZ' }, vector: [-0.5, 0, Math.sqrt(3) / 2], previous: { k: 170, m: 30 } });
  const chosen = ik.solutions[ik.chosen];
  assert.ok(Math.abs(chosen.m - 30) < 1e-9 && Math.abs(chosen.k - 180) < 1e-9, JSON.stringify(ik));
  assert.equal(ik.solutions.length, 2);
  assert.ok(Math.abs(ik.poleAngle - 30) < 1e-9);
  assert.equal(ik.singular, false);
  // The tool along C: singular, C kept at the previous value.
  const pole = fa.machineInverse({ machine: { type: 'CBZ' }, vector: [0, 0, 1], previous: { k: 40, m: 0 } });
  assert.ok(pole.singular && Math.abs(pole.solutions[pole.chosen].k - 40) < 1e-9 && Math.abs(pole.solutions[pole.chosen].m) < 1e-9, JSON.stringify(pole));
  // Beyond the travel of B (±120° on Li et al.'s machine, ±20° here): none chosen, a message.
  const out = fa.machineInverse({ machine: { type: 'CBZ', rotary: { mFrom: -20, mTo: 20 } }, vector: [-0.5, 0, Math.sqrt(3) / 2] });
  assert.equal(out.chosen, null);
  assert.ok(out.unreachable && out.solutions.every((x) => !x.inTravel), JSON.stringify(out));
  // The forward direction: the table turned C = 180°, tilted B = 30° puts the tool at
  // (−sin 30°, 0, cos 30°) in workpiece coordinates.
  const v = fa.toolVector({ machine: { type: 'CBZ' }, k: 180, m: 30 });
  [-0.5, 0, Math.sqrt(3) / 2].forEach((x, i) => assert.ok(Math.abs(v[i] - x) < 1e-12, `${v}`));
  assert.equal(fa.rotaryTypes().length, 12);
  assert.deepEqual(fa.rotaryTypes().filter((t) => t.group === 'I').map((t) => t.name).sort(), ['ABX', 'ACX', 'BAY', 'BCY', 'CAZ', 'CBZ']);
});

test('the sample toolpaths are what scripts/samples.mjs writes', async () => {
  const { execFileSync } = await import('node:child_process');
  const { mkdtempSync, readFileSync: read } = await import('node:fs');
  const { tmpdir } = await import('node:os');
  const dir = mkdtempSync(`${tmpdir()}/samples-`);
  execFileSync(process.execPath, [new URL('../../scripts/samples.mjs', import.meta.url).pathname, dir]);
  for (const name of ['impeller-swarf.apt', 'dome-past-the-pole.csv']) {
    assert.equal(read(`${dir}/${name}`, 'utf8'), read(new URL(`../../public/samples/${name}`, import.meta.url), 'utf8'), name);
  }
});

test('a toolpath file read from its bytes: UTF-8, Windows-1252 with a note, images refused', () => {
  const machine = { type: 'CAZ' };
  // UTF-8 split inside "Ø" (C3 98) between two pieces: the same points as the whole text.
  const text = 'G0 X0 Y0 Z0 (Ø6)\nG1 X1\n';
  const bytes = new TextEncoder().encode(text);
  const cut = bytes.indexOf(0xc3) + 1;
  const reader = new fa.ToolpathReader({ machine });
  reader.feed(bytes.slice(0, cut));
  reader.feed(bytes.slice(cut));
  const p = reader.finish();
  assert.equal(p.count, 2);
  assert.equal(p.report.notes.length, 0);
  // A comment with µ as the byte 0xB5 (Windows-1252) on line 2: read, and said so.
  const legacy = new Uint8Array([...new TextEncoder().encode('G0 X0 Y0 Z0\n(Abweichung '), 0xb5, ...new TextEncoder().encode('m)\nG1 X1\n')]);
  const q = fa.toolpathParse(legacy, { machine });
  assert.equal(q.count, 2);
  assert.match(q.report.notes[0].text, /^line 2: the file is not UTF-8 text; it is read as Windows-1252/);
  // A PNG image dropped as a toolpath.
  assert.throws(() => fa.toolpathParse(new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0]), {}), /^Error: toolpath: the file is a PNG image, not a toolpath/);
});
