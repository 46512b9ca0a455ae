// Property test of the exported API: arbitrary JSON-ish inputs (NaN, ±Infinity, huge numbers,
// negative lengths, wrong types, missing and extra fields) never panic and always give either a
// result made of finite numbers or a JavaScript Error with a message. Every study gets a machine:
// one of the page's presets (public/presets/machines.json), sometimes of another kind or type,
// with random errors of its axes.
//   FUZZ_CASES=1000000 FUZZ_SEED=7 node --test tests/node/fuzz.test.mjs   (longer runs)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';

const bytes = readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url));
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
const KINDS = ['table-table', 'head-table', 'head-head'];
const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets.map((p) => p.machine);
const SCHEMA = fa.schema();
const ERROR_TABLE = SCHEMA.errors;
/** The machine kinds each geometry input applies to (empty: all). */
const GEOMETRY_KINDS = Object.fromEntries(SCHEMA.machine.filter((f) => f.path.startsWith('machine.geometry.')).map((f) => [f.path.split('.')[2], f.kinds]));
// Templates: how a valid input looks. Leaves are generators of plausible values.
const pick = (list) => (r) => list[Math.floor(r() * list.length)];
const angle = (r) => (r() - 0.5) * 720;
const small = (lo, hi) => (r) => Math.round(lo + r() * (hi - lo));
const maybe = (gen, p = 0.7) => (r) => (r() < p ? gen(r) : undefined);
const pose = { k: angle, m: angle };
/** The errors a machine of this type can have: its rotary axes' and the squareness errors. */
const errorsOf = (type) => ERROR_TABLE.filter((e) => e.axis === type[0] || e.axis === type[1] || ['X', 'Y', 'Z'].includes(e.axis));
/**
 * A machine: one of the page's presets (sometimes with another kind or type), with up to five
 * of its errors at random values, mostly up to ±1 mm / ±1°, sometimes up to the limit (±5).
 */
function machine(r) {
  const m = structuredClone(pick(MACHINES)(r));
  if (r() < 0.2) {
    // Another kind: without the geometry that does not apply to it (the engine refuses that).
    m.kind = pick(KINDS)(r);
    for (const g of Object.keys(m.geometry)) if (GEOMETRY_KINDS[g].length && !GEOMETRY_KINDS[g].includes(m.kind)) delete m.geometry[g];
  }
  if (r() < 0.2) m.type = pick(TYPES)(r);
  const names = errorsOf(m.type);
  const errors = {};
  for (let i = Math.floor(r() * 6); i > 0; i--) {
    const e = pick(names)(r);
    errors[e.name] = (r() - 0.5) * 2 * (r() < 0.1 ? e.limit : 1);
  }
  m.errors = errors;
  return m;
}
const length = maybe((r) => r() * 500);
/** A machine with up to four error motions of its axes: constants, polynomials or tables. */
function machineWithMotions(r) {
  const m = machine(r);
  const names = SCHEMA.motions.filter((e) => e.axis === m.type[0] || e.axis === m.type[1] || ['X', 'Y', 'Z'].includes(e.axis));
  const motions = {};
  for (let i = Math.floor(r() * 5); i > 0; i--) {
    const e = pick(names)(r);
    const q = r();
    motions[e.name] = q < 0.3 ? (r() - 0.5) * 0.01 : q < 0.6 ? { poly: Array.from({ length: small(1, 4)(r) }, () => (r() - 0.5) * 1e-5) } : { position: [-400, 0, 400], value: [(r() - 0.5) * 0.01, 0, (r() - 0.5) * 0.01] };
  }
  m.motions = motions;
  return m;
}
/** A short error-motion table as CSV, sometimes with a broken line. */
function motionCsv(r) {
  const lines = ['X (mm), E_XX (µm)', '0, 0', '100, 1.5', '200, 2'];
  if (r() < 0.3) lines[1 + Math.floor(r() * 3)] = 'x, 1';
  return lines.join('\n');
}
const region = {
  plane: pick(['XY', 'XZ', 'YZ']), uFrom: (r) => -200 * r(), uTo: (r) => 200 * r() + 1, vFrom: (r) => -200 * r(), vTo: (r) => 200 * r() + 1,
  at: (r) => (r() - 0.5) * 200, steps: small(2, 8), k: maybe(angle), m: maybe(angle),
};
// The cubic test: a machine, a set-up, the switches.
const cubicCase = {
  machine,
  setup: {
    workpieceHeight: (r) => r() * 100, workpieceX: (r) => (r() - 0.5) * 100, workpieceY: (r) => (r() - 0.5) * 100,
    zoneSize: (r) => 2 + r() * 20, toolRadius: (r) => 0.5 + r() * 5, pick: (r) => 0.3 + r() * 2, stock: (r) => r(),
  },
  transform: (r) => r() < 0.5,
  reference: pick(['workpiece', 'zone1-height', 'zone1-plane']),
};
const tool = { rTool: (r) => 5 + 10 * r(), lTool: (r) => 31 + 30 * r() };
const model = { branch: pick(['paper', 'continuous']), reference: pick(['workOrigin', 'axesZero']), point: pick(['tip', 'contact']) };
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
/** The identification: a machine and a choice among its errors (or all of them). */
function sshapeIdentifyCase(r) {
  const m = machine(r);
  const names = errorsOf(m.type).map((e) => e.name).filter(() => r() < 0.5);
  return build({ tool, model, csv: sshapeCsv, radiusTerm: (r) => r() < 0.5, rtol: (r) => 10 ** (-1 - 5 * r()), decision }, r, { machine: m, ...(r() < 0.5 ? { parameters: names } : {}) });
}
/** A file of measured zones (the paper's names, heights in µm, sometimes slopes), sometimes with a line damaged or repeated. */
function cubicCsv(r) {
  const slopes = r() < 0.5;
  const lines = [slopes ? 'zone,height_um,slope_x,slope_y' : 'zone,height_um'];
  for (const z of ['I', 'II-1', 'II-2', 'II-3', 'II-4', 'III-1', 'III-2', 'III-3', 'III-4']) {
    if (r() < 0.1) continue;
    const h = ((r() - 0.5) * 20).toFixed(3);
    lines.push(slopes ? `${z},${h},${((r() - 0.5) * 1e-3).toExponential(3)},${r() < 0.2 ? '' : ((r() - 0.5) * 1e-3).toExponential(3)}` : `${z},${h}`);
  }
  const i = 1 + Math.floor(r() * (lines.length - 1));
  const q = r();
  if (q < 0.1) lines.push(lines[i]);
  else if (q < 0.2) lines[i] = lines[i].replace(/\d(,|$)/, 'x$1');
  return lines.join('\n');
}
const decision = { alpha: maybe((r) => 0.001 + r() * 0.2), noise: maybe((r) => r() * 0.01), tolerance: maybe((r) => r() * 0.01) };
/** A short random toolpath: [x, y, z, i, j, k] per point, the tool axis within 60° of +Z. */
function toolpathPoints(r) {
  const n = small(0, 8)(r);
  const out = [];
  for (let i = 0; i < n; i++) out.push(r() * 100, r() * 100, r() * 50, r() - 0.5, r() - 0.5, 1);
  return new Float64Array(out);
}
/** A path object: points and sometimes motion codes, angles for CAZ. */
function toolpathPath(r) {
  const points = toolpathPoints(r);
  const n = points.length / 6;
  const motions = r() < 0.5 ? new Float64Array(Array.from({ length: n }, () => small(0, 2)(r))) : undefined;
  const withAngles = r() < 0.4;
  return {
    points,
    ...(motions ? { motions } : {}),
    ...(withAngles ? { angles: new Float64Array(Array.from({ length: 2 * n }, () => angle(r))), readFor: 'CAZ' } : {}),
  };
}
/** A short toolpath file as text (CSV, APT, or NC in the three dialects for a C/A machine), sometimes with a broken line. */
function toolpathText(r) {
  const n = small(0, 6)(r);
  const num = () => (r() * 200 - 100).toFixed(3);
  const sg = () => { const v = num(); return v.startsWith('-') ? v : `+${v}`; };
  const kind = small(0, 5)(r);
  const lines = kind === 4 ? ['0 BEGIN PGM F MM', '1 CC X+0 Y+0'] : kind === 5 ? ['0 BEGIN PGM F INCH'] : [];
  for (let i = 0; i < n; i++) {
    if (kind === 0) lines.push([num(), num(), num(), (r() - 0.5).toFixed(3), (r() - 0.5).toFixed(3), '1'].join(','));
    else if (kind === 1) lines.push(pick([`GOTO/${[num(), num(), num(), (r() - 0.5).toFixed(3), (r() - 0.5).toFixed(3), '1'].join(',')}`, 'RAPID', `CIRCLE/0,0,0,0,0,1,${Math.abs(Number(num()))}`, 'MSYS/0,0,0,0,1,0,1,0,0', 'UNITS/INCHES'])(r));
    else if (kind === 2) lines.push(`N${i} ${pick(['G0', 'G1', 'G2', 'G3', 'G91', 'G20', 'G68 R30', 'G28'])(r)} X${num()} Y${num()} Z${num()} A${num()} C${num()}${r() < 0.3 ? ` I${num()} J${num()}` : ''}`);
    else if (kind === 3) lines.push(`N${i} ${pick(['G0', 'G1', 'TRAORI', 'TRANS', 'ROT Z30', 'R1=5'])(r)} X=${num()} Y${num()} Z${num()} A${num()} C${num()}`);
    else lines.push(`${i + 2} ${pick(['L', 'C', 'CR', 'CC', 'PLANE SPATIAL SPA+0 SPB+30 SPC+0 STAY', 'M128'])(r)} X${sg()} Y${sg()} Z${sg()} A${sg()} C${sg()} R+5 DR${pick(['+', '-'])(r)} ${pick(['FMAX', 'F100', ''])(r)}`);
  }
  if (lines.length && r() < 0.3) {
    const i = Math.floor(r() * lines.length);
    lines[i] = lines[i].replace(/\d/, pick(['x', '.', ',', ' ', 'e', ''])(r));
  }
  return lines.join(pick(['\n', '\r\n', '\r'])(r));
}
const toolpathRead = {
  machine: (r) => (r() < 0.5 ? { type: 'CAZ' } : undefined),
  format: maybe(pick(['auto', 'csv', 'apt', 'nc', 'siemens', 'heidenhain'])),
  unit: maybe(pick(['auto', 'mm', 'inch'])),
  aptFrame: maybe(pick(['apply', 'ignore'])),
  chordTolerance: maybe((r) => 1e-4 + r() * 0.1),
};
// The reversal test: short, fast runs (a small circle at a high feed, a coarse step) so that a
// case costs well under a millisecond unless a mutation takes the defaults back.
const reversalCase = {
  machine,
  test: { radius: (r) => 3 + 20 * r(), offset: (r) => 30 * r(), feed: (r) => 5000 + 25000 * r(), reversalAngle: maybe((r) => 1 + 179 * r()), accelTime: maybe((r) => 1 + 20 * r()), reversalTime: maybe((r) => 0.5 + 10 * r()) },
  linear: maybe((r) => build({ mass: (q) => 10 + 1000 * q(), positionGain: (q) => 5 + 60 * q(), friction: maybe((q) => 100 * q()) }, r)),
  c: maybe((r) => build({ inertia: (q) => 0.1 + 5 * q(), friction: (q) => 30 * q(), frictionSlope: (q) => 10 ** (1 + 4 * q()), torqueLimit: maybe((q) => 1 + 500 * q()) }, r)),
  feedForward: maybe(pick(['none', 'velocity', 'full'])),
  step: (r) => 0.5 + 1.5 * r(),
  samples: maybe(small(100, 400)),
};
/** A measured trace: a few points round the circle, sometimes a dense run over the reversal,
 *  sometimes a damaged line. */
function reversalCsv(r) {
  const lines = [pick(['angle_deg,deviation_mm', 'angle_deg;deviation_um', 'angle,deviation'])(r)];
  const n = small(0, 70)(r);
  const dense = r() < 0.3;
  for (let k = 0; k < n; k++) {
    const a = dense ? 170 + (20 * k) / Math.max(1, n) : (360 * (k + 0.5)) / Math.max(1, n);
    lines.push(`${a.toFixed(3)}${lines[0].includes(';') ? ';' : ','}${((r() - 0.5) * 0.02).toFixed(5)}`);
  }
  if (lines.length > 1 && r() < 0.3) {
    const i = 1 + Math.floor(r() * (lines.length - 1));
    lines[i] = lines[i].replace(/\d/, pick(['x', '', '-', 'e'])(r));
  }
  return lines.join('\n');
}
/** A positioning test (ISO 230-2) in one of the three layouts, sometimes with a damaged cell,
 *  a missing run or a unit left out. */
function positioningCsv(r) {
  const m = small(0, 6)(r);
  const n = small(1, 5)(r);
  const unit = pick(['(mm)', '(deg)', '', '(µm)'])(r);
  const vunit = pick(['(µm)', '(arcsec)', '(mm)', ''])(r);
  const dev = () => ((r() - 0.5) * 10).toFixed(2);
  const lines = [];
  if (r() < 0.5) {
    lines.push(`target ${unit};direction;run;deviation ${vunit}`);
    for (let i = 0; i < m; i++) for (const d of ['up', 'down']) for (let j = 1; j <= n; j++) lines.push(`${i * 100};${d};${j};${dev()}`);
  } else {
    const cols = ['up', 'down'].flatMap((d) => Array.from({ length: n }, (_, j) => `${d} ${j + 1} ${vunit}`));
    lines.push([`target ${unit}`, ...cols].join(','));
    for (let i = 0; i < m; i++) lines.push([i * 100, ...cols.map(dev)].join(','));
  }
  if (lines.length > 1 && r() < 0.3) {
    const i = 1 + Math.floor(r() * (lines.length - 1));
    lines[i] = r() < 0.5 ? lines[i].replace(/\d/, pick(['x', '', 'e'])(r)) : lines[i].split(/[;,]/).slice(0, -1).join(';');
  }
  return lines.join(pick(['\n', '\r\n'])(r));
}
/** A ball-bar trace: points round the circle one or both ways, sometimes with a radius line,
 *  sometimes a damaged cell. */
function ballbarCsv(r) {
  const lines = [];
  if (r() < 0.8) lines.push(`# radius: ${(50 + r() * 250).toFixed(1)} ${pick(['mm', 'in', 'furlongs'])(r)}`);
  if (r() < 0.5) lines.push(`# feed: ${(100 + r() * 5000).toFixed(0)} mm/min`);
  lines.push(pick(['angle (deg); deviation (µm); direction', 'angle (deg); ccw (µm); cw (µm)', 'angle; deviation'])(r));
  const n = small(0, 200)(r);
  for (let k = 0; k < n; k++) {
    const a = ((360 * k) / Math.max(1, n)).toFixed(2);
    const v = () => ((r() - 0.5) * 10).toFixed(3);
    const wide = lines.some((l) => l.includes('ccw ('));
    lines.push(wide ? `${a}; ${v()}; ${v()}` : `${a}; ${v()}; ${pick(['ccw', 'cw', 'x'])(r)}`);
  }
  if (lines.length > 3 && r() < 0.3) lines[3] = lines[3].replace(/\d/, 'x');
  return lines.join('\n');
}
/** Probed sphere centres: a header naming the machine's axes or not, a few poses, sometimes a
 *  damaged cell or a decimal comma. */
function probeCsv(r) {
  const lines = [pick(['pose;C_deg;B_deg;X_mm;Y_mm;Z_mm', 'C (deg), A (deg), X (mm), Y (mm), Z (mm)', 'k m x y z'])(r)];
  const sep = lines[0].includes(';') ? ';' : lines[0].includes(',') ? ',' : ' ';
  const n = small(0, 14)(r);
  for (let i = 0; i < n; i++) {
    const cells = [((i * 30) % 360).toFixed(1), ((r() - 0.5) * 120).toFixed(1), ((r() - 0.5) * 400).toFixed(4), ((r() - 0.5) * 400).toFixed(4), (r() * 300).toFixed(4)];
    lines.push((sep === ';' ? [String(i + 1), ...cells.map((c) => c.replace('.', ','))] : cells).join(sep));
  }
  if (lines.length > 1 && r() < 0.3) lines[1] = lines[1].replace(/\d/, 'x');
  return lines.join(pick(['\n', '\r\n'])(r));
}
const sphere = maybe((r) => ({ x: (r() - 0.5) * 400, y: (r() - 0.5) * 400, height: r() * 200 }));
/** A ball-bar test of a rotary axis: the axis moved, the ball, the bar, the sweep (coarse). */
const rotaryTest = (r) =>
  build({
    name: maybe(pick(['', 'C radial', '2', 'tilt'])),
    axis: maybe(pick(['k', 'm'])),
    hold: maybe((q) => (q() - 0.5) * 120),
    ball: maybe((q) => ({ x: (q() - 0.5) * 400, y: (q() - 0.5) * 400, height: q() * 200 })),
    length: maybe((q) => 10 + q() * 300),
    direction: maybe(pick(['radial', 'tangential', 'axial'])),
    from: maybe((q) => (q() - 0.5) * 240),
    to: maybe((q) => q() * 360),
    step: (q) => 5 + 40 * q(),
  }, r);
const rotaryTests = (r) => Array.from({ length: small(0, 3)(r) }, () => rotaryTest(r));
/** Measured ball-bar traces of rotary tests: a header with or without a test column, units,
 *  points both ways, sometimes a decimal comma or a damaged cell. */
function rotaryCsv(r) {
  const header = pick(['angle (deg);deviation (µm);direction', 'test;angle (deg);deviation (µm);direction', 'angle_deg,deviation_mm,dir', 'angle (deg);ccw (µm);cw (µm)', 'angle;deviation'])(r);
  const sep = header.includes(';') ? ';' : ',';
  const lines = [header];
  const n = small(0, 40)(r);
  for (let i = 0; i < n; i++) {
    const a = ((360 * i) / Math.max(1, n)).toFixed(2);
    const v = () => ((r() - 0.5) * 20).toFixed(3);
    const cells = header.startsWith('test') ? [pick(['1', '2', 'C radial', '9'])(r), a, v(), pick(['ccw', 'cw'])(r)] : header.includes('ccw (') ? [a, v(), v()] : header.includes('dir') ? [a, v(), pick(['ccw', 'cw', '+', '-'])(r)] : [a, v()];
    lines.push(sep === ';' ? cells.join(';').replace(/\./g, ',') : cells.join(','));
  }
  if (lines.length > 2 && r() < 0.3) lines[2] = lines[2].replace(/\d/, pick(['x', '', 'e'])(r));
  return lines.join(pick(['\n', '\r\n'])(r));
}
export const SPECS = {
  schema: { args: [] },
  rotaryTypes: { args: [] },
  machineSchematic: { args: [{ machine, k: maybe(angle), m: maybe(angle), standoff: maybe((r) => r() * 200) }] },
  machineInverse: { args: [{ machine, vector: [(r) => r() - 0.5, (r) => r() - 0.5, (r) => r() - 0.5], previous: maybe((r) => ({ k: angle(r), m: angle(r) })), rule: maybe(pick(['smallest-tilt', 'nearest'])) }] },
  toolVector: { args: [{ machine, k: angle, m: angle }] },
  nonlinearMove: { args: [{ machine, length, start: pose, end: pose, samples: small(2, 300) }] },
  nonlinearSweepK: { args: [{ machine, length, thetaM: angle, dK: angle, dM: angle, from: angle, to: angle, n: small(2, 40) }] },
  nonlinearSweepM: { args: [{ machine, length, dM: angle, ratios: [(r) => r() * 6 - 3, (r) => r() * 6 - 3], from: angle, to: angle, n: small(2, 40) }] },
  nonlinearGrid: { args: [{ machine, length, thetaM: angle, dK: { from: angle, to: angle }, dM: { from: angle, to: angle }, nx: small(2, 12), ny: small(2, 12) }] },
  nonlinearCompareTypes: { args: [{ machine, length, start: pose, end: pose }] },
  nonlinearMaxErrors: { args: [pick(TYPES), (r) => r() * 500, (r) => new Float64Array(Array.from({ length: 4 * small(0, 5)(r) }, () => angle(r)))] },
  cubicTest: { args: [cubicCase] },
  cubicHeightMap: { args: [{ ...cubicCase, nx: small(4, 24), ny: maybe(small(4, 24)) }] },
  cubicIdentify: { args: [{ ...cubicCase, csv: cubicCsv, rtol: maybe((r) => 10 ** (-1 - 5 * r())), decision }] },
  // Small designs (a 2 × 2 face, tilts to 20°): a full one takes a tenth of a second.
  cubicDesign: { args: [{ ...cubicCase, grid: small(2, 2), maxTilt: (r) => 10 + 10 * r(), slopes: (r) => r() < 0.5, secondSetup: maybe((r) => (r() - 0.5) * 200), noise: maybe((r) => 1e-4 + r() * 0.01) }] , weight: 0.1 },
  sshapePart: { args: [{ nu: small(2, 30), nv: small(2, 6) }] },
  sshapeOvercut: { args: [{ tool, nu: small(14, 20), nv: small(2, 3) }] },
  sshapeDefects: { args: [{ machine, tool, model, dR: (r) => (r() - 0.5) * 0.04 }] },
  sshapeIdentify: { args: [sshapeIdentifyCase] },
  toolpathAnalyse: { args: [{ machine, length, tolerance: maybe((r) => r() * 0.05) }, (r) => (r() < 0.5 ? toolpathPoints(r) : toolpathPath(r))] },
  toolpathParse: { args: [toolpathText, toolpathRead] },
  toolpathWrite: { args: [{ machine: (r) => (r() < 0.5 ? { type: 'CAZ' } : undefined), format: pick(['csv', 'apt', 'nc']) }, toolpathPath] },
  // A class: new, two pieces fed, finished.
  ToolpathReader: {
    args: [toolpathRead, toolpathText, toolpathText, (r) => r() < 0.5],
    // Text or bytes (sometimes a byte that is not UTF-8, sometimes an image's signature).
    run: ([options, a, b, asBytes]) => {
      const reader = new fa.ToolpathReader(options);
      const bytes = (t) => {
        const e = new TextEncoder().encode(t);
        if (e.length && t.length % 7 === 3) e[t.length % e.length] = 0xb5;
        if (t.length % 11 === 5) return new Uint8Array([0x89, 0x50, 0x4e, 0x47, ...e]);
        return e;
      };
      reader.feed(asBytes ? bytes(a) : a);
      reader.feed(asBytes ? bytes(b) : b);
      return reader.finish();
    },
  },
  toolpathCompare: { args: [{ machine, length, tolerance: maybe((r) => r() * 0.05) }, toolpathPath, maybe((r) => TYPES.filter(() => r() < 0.3))] },
  toolpathRefine: { args: [{ machine, length, tolerance: (r) => 0.001 + r() * 0.05 }, toolpathPath] },
  volumetricMap: { args: [{ machine: machineWithMotions, region }] },
  volumetricPaper: { args: [{ machine: (r) => (r() < 0.7 ? { ...machineWithMotions(r), kind: 'table-table', type: 'CAZ', linear: 'table-x', geometry: { toolLength: 100 } } : machineWithMotions(r)), x: angle, y: angle, z: angle, k: maybe(angle), m: maybe(angle) }] },
  volumetricReadTable: { args: [{ name: pick(['E_XX', 'E_BX', 'E_X0B', 'E_CC']), text: motionCsv }] },
  ballbarEvaluate: { args: [{ csv: ballbarCsv, plane: maybe(pick(['XY', 'YZ', 'ZX', 'XZ'])), radius: maybe((r) => r() * 300), feed: maybe((r) => r() * 5000), tolerance: maybe((r) => r() * 0.05) }] },
  // The designer searches a grid of poses (a second or more at the default 15°): a coarse grid
  // and few cases.
  probeDesign: { args: [{ machine, sphere, step: pick([45, 60, 90]), count: maybe(small(4, 12)) }], weight: 0.005 },
  probeSimulate: { args: [{ machine, sphere, k: (r) => Array.from({ length: small(1, 6)(r) }, () => angle(r)), m: (r) => Array.from({ length: small(1, 6)(r) }, () => (r() - 0.5) * 120) }], weight: 0.2 },
  probeReadCsv: { args: [{ machine, csv: probeCsv }], weight: 0.2 },
  probeIdentify: { args: [{ machine, sphere, csv: probeCsv }], weight: 0.05 },
  positioningEvaluate: { args: [{ csv: positioningCsv, axis: maybe(pick(['X', 'C', 'Q'])), tolerance: maybe((r) => build({ a: maybe((q) => q() * 0.01), e: maybe((q) => q() * 0.01), r: maybe((q) => q() * 0.01) }, r)), rotaryTolerance: maybe((r) => build({ a: maybe((q) => q() * 0.003), b: maybe((q) => q() * 0.003), m: maybe((q) => q() * 0.003) }, r)) }] },
  reversalSimulate: { args: [{ ...reversalCase, checkStep: maybe((r) => r() < 0.3) }] , weight: 0.1 },
  reversalDents: { args: [{ ...reversalCase, test: { ...reversalCase.test, radius: (r) => 1 + 4 * r() } }] , weight: 0.1 },
  reversalFit: { args: [{ ...reversalCase, csv: reversalCsv }] , weight: 0.1 },
  reversalTrace: { args: [{ ...reversalCase, csv: reversalCsv }] },
  // Each simulated point costs a Jacobian of the chain: coarse sweeps, fewer cases.
  ballbarRotarySimulate: { args: [{ machine: machineWithMotions, tests: rotaryTests, parameters: maybe((r) => errorsOf('CBZ').filter(() => r() < 0.3).map((e) => e.name)) }], weight: 0.2 },
  ballbarRotaryIdentify: { args: [{ machine, tests: rotaryTests, csv: rotaryCsv, rtol: maybe((r) => 10 ** (-1 - 5 * r())), decision }], weight: 0.2 },
};

const WEIRD = [NaN, Infinity, -Infinity, 1e308, -1e308, 1e300, -1, 0, -0, 5e-324, 2 ** 53, '', 'abc', '12', true, null, undefined, {}, [], [1, 2], { k: 1 }, new Float64Array(2)];

/** A value from a template (`extra`: fields given as they are); undefined fields are left out. */
function build(t, r, extra = {}) {
  if (typeof t === 'function') return t(r);
  if (Array.isArray(t)) return t.map((x) => build(x, r));
  if (t && typeof t === 'object') {
    const out = Object.fromEntries(Object.entries(t).map(([k, v]) => [k, build(v, r)]).filter(([, v]) => v !== undefined));
    return Object.assign(out, extra);
  }
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
  // Exports that simulate or search for tens to hundreds of milliseconds at their defaults (a
  // mutation that drops a key brings the default back) get a tenth of the cases.
  const weight = (name) => SPECS[name].weight ?? 1;
  const totalWeight = names.reduce((s, n) => s + weight(n), 0);
  const pickName = () => {
    let x = r() * totalWeight;
    for (const n of names) if ((x -= weight(n)) < 0) return n;
    return names[names.length - 1];
  };
  for (const name of Object.keys(fa)) {
    if (typeof fa[name] === 'function' && !['default', 'initSync', 'start'].includes(name)) {
      assert.ok(SPECS[name], `export ${name} has no fuzz spec: add one`);
    }
  }
  const counts = { ok: 0, error: 0, repeated: 0 };
  // Mutations often reduce an input to the same few values ([], [{}], [null]): the engine is
  // deterministic, so an input already tried is not run again (some, such as the overcut maps
  // at their default grid, take a fifth of a second).
  const tried = new Set();
  for (let i = 0; i < CASES; i++) {
    const name = pickName();
    let args = build(SPECS[name].args, r);
    const mutations = r() < 0.2 ? 0 : 1 + Math.floor(r() * 3);
    for (let m = 0; m < mutations; m++) args = mutate(args, r);
    if (!Array.isArray(args)) args = [args];
    const key = `${name}(${exactly(args)})`;
    if (tried.has(key)) {
      counts.repeated++;
      continue;
    }
    tried.add(key);
    let result;
    try {
      result = SPECS[name].run ? SPECS[name].run(args) : fa[name](...args);
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

/** The input as text that tells apart everything the engine could (−0 from 0, a string from a
 *  number, a typed array from a list, undefined from null). */
function exactly(args) {
  return JSON.stringify(args, function (k, v) {
    const raw = this[k];
    if (typeof raw === 'number') return Object.is(raw, -0) ? '#-0' : Number.isFinite(raw) ? raw : `#${raw}`;
    if (typeof raw === 'string') return `'${raw}`;
    if (ArrayBuffer.isView(raw)) return { '#typed': Array.from(raw) };
    return raw === undefined ? '#undefined' : v;
  });
}

function describe(args) {
  return JSON.stringify(args, (_, v) => (typeof v === 'number' && !Number.isFinite(v) ? String(v) : ArrayBuffer.isView(v) ? Array.from(v) : v === undefined ? '<undefined>' : v));
}
