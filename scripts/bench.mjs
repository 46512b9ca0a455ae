// `npm run bench`: times the engine's heavy kernels natively (crate/examples/bench.rs, release
// build) and as WebAssembly in Node (the release package wasm/pkg) on the same inputs, and
// prints both times and their ratio (and, for the nonlinear maxima, the orientation evaluations
// per move, counted natively). Rounds alternate native and wasm, each round a process of its
// own on each side (BENCH_ROUNDS, default 3); each kernel's best time over the rounds is kept.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import * as fa from '../wasm/pkg/fiveaxis.js';

const root = fileURLToPath(new URL('..', import.meta.url));
fa.initSync({ module: readFileSync(new URL('../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
const presets = JSON.parse(readFileSync(new URL('../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const preset = (name) => structuredClone(presets.find((p) => p.name.startsWith(name)).machine);

/** Same formula as crate/examples/bench.rs. */
function moves(n) {
  const out = new Float64Array(4 * n);
  for (let i = 0; i < n; i++) {
    const x = i * 0.001;
    const k0 = 180 * Math.sin(7.3 * x);
    const m0 = 90 * Math.sin(3.1 * x + 1);
    out.set([k0, m0, k0 + 60 * Math.sin(1.7 * x + 2), m0 + 60 * Math.sin(2.9 * x + 3)], 4 * i);
  }
  return out;
}

/** Short moves (real toolpath segments, |Δθk| + |Δθm| < 5°): same formula as crate/examples/bench.rs. */
function shortMoves(n) {
  const out = new Float64Array(4 * n);
  for (let i = 0; i < n; i++) {
    const x = i * 0.001;
    const k0 = 180 * Math.sin(7.3 * x);
    const m0 = 90 * Math.sin(3.1 * x + 1);
    out.set([k0, m0, k0 + 2.5 * Math.sin(1.3 * x + 0.5), m0 + 2.5 * Math.sin(2.3 * x + 1.5)], 4 * i);
  }
  return out;
}

/**
 * Best of `repeat` runs after one untimed run: the steady state, as natively. (Node compiles
 * WebAssembly first with a fast baseline compiler and optimises hot functions while they run;
 * a short kernel timed cold measures the compiler, 2-6x slower than its steady state.)
 */
function time(repeat, f, check) {
  f();
  let best = Infinity;
  let sum = 0;
  for (let i = 0; i < repeat; i++) {
    const t = performance.now();
    const r = f();
    best = Math.min(best, performance.now() - t);
    sum = check(r);
  }
  return { ms: best, check: sum };
}
const total = (a) => a.reduce((s, v) => s + v, 0);

/** The sphere test's benchmark input: same formulas as probe_input in crate/examples/bench.rs
 *  (200 poses, centres from probeSimulate with the sample's errors, ±1 µm of integer-formula
 *  noise, 6 decimals). */
function probeInput() {
  const machine = preset('B/C tilting table');
  const sphere = { x: 150, y: 0, height: 50 };
  const poses = Array.from({ length: 200 }, (_, i) => [((i * 37) % 360) - 180, ((i * 53) % 181) - 90]);
  const sim = fa.probeSimulate({
    machine: { ...machine, errors: { E_X0B: 0.012, E_Z0B: -0.008, E_A0B: 0.005, E_C0B: -0.003 } },
    sphere, k: poses.map((p) => p[0]), m: poses.map((p) => p[1]),
  });
  let csv = 'pose;C_deg;B_deg;X_mm;Y_mm;Z_mm\n';
  sim.poses.forEach((s, i) => {
    const c = [0, 1, 2].map((a) => s.measured[a] + ((((3 * i + a) * 7919) % 2001) - 1000) * 1e-6);
    csv += `${i + 1};${poses[i][0]};${poses[i][1]};${c.map((v) => v.toFixed(6)).join(';')}\n`;
  });
  return { machine, sphere, csv };
}
/** Same as probe_check in crate/examples/bench.rs. */
const probeCheck = (r) => r.estimates.reduce((s, e) => s + (e.value ?? 0), 0) + r.after.sigma;

/** One round of the WebAssembly timings, by kernel. */
// A new pivot per eq 14 run, over all rounds (the engine caches designs): round r starts after
// the 4 (r − 1) pivots of the rounds before, as crate/examples/bench.rs does.
let ssRun = 4 * (Number(process.env.BENCH_ROUND ?? 1) - 1);
function runWasm() {
  const wasm = {};
  const mv = moves(1_000_000);
  wasm['nonlinear: exact max of 10^6 moves'] = time(3, () => fa.nonlinearMaxErrors('CAZ', 1, mv), total);
  const short = shortMoves(1_000_000);
  wasm['nonlinear: exact max of 10^6 short moves (< 5°)'] = time(3, () => fa.nonlinearMaxErrors('CAZ', 1, short), total);
  wasm['nonlinear: 361x361 increment grid'] = time(
    3,
    () => fa.nonlinearGrid({ machine: { type: 'CAZ' }, length: 1, thetaM: 10, dK: { from: -90, to: 90 }, dM: { from: -90, to: 90 }, nx: 361, ny: 361 }),
    (g) => total(g.max),
  );

  // Volumetric: the same machine, errors and error motions as crate/examples/bench.rs.
  const tanLim = preset('C/A double turntable on an X table (Tan & Lim)');
  tanLim.errors = { E_C0Y: 0.001, E_B0Z: -0.0008, E_Y0A: 0.005 };
  tanLim.motions = {
    E_XX: { poly: [0, 1e-5, 2e-9] },
    E_BX: { position: [-400, -200, 0, 200, 400], value: [-0.0003, 0.0001, 0, 0.0002, -0.0001] },
    E_YY: { poly: [0.001, -8e-6] },
    E_AY: 0.0002,
    E_ZZ: { poly: [0, 5e-6] },
    E_XZ: { position: [-300, 0, 300], value: [0.002, 0, 0.003] },
    E_XC: { position: [0, 90, 180, 270, 360], value: [0, 0.002, 0, -0.002, 0] },
    E_CC: 0.001,
    E_ZA: 0.003,
  };
  wasm['volumetric: 10^6 poses exact (1001 x 1001 plane) + budget'] = time(
    3,
    () => fa.volumetricMap({ machine: tanLim, region: { plane: 'XY', uFrom: -300, uTo: 300, vFrom: -200, vTo: 200, at: 50, k: 30, m: -20, steps: 1001 } }),
    (m) => total(m.norm),
  );

  // Li et al.'s Table 5 in ISO names (E = −ε of the paper), on their machine's preset.
  const li = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
  li.errors = { E_X0B: -0.0146, E_Y0B: 0.0089, E_Z0B: 0.0142, E_A0B: 0.0023, E_B0B: -0.0029, E_C0B: 0.00002, E_A0C: 0.00017, E_X0C: -0.0094 };
  wasm['cubic: height map 961x961 (Table 5)'] = time(3, () => fa.cubicHeightMap({ machine: li, nx: 961, ny: 961 }), (m) => total(m.height));
  // S-shape: the same inputs as crate/examples/bench.rs.
  const chanal = (pivot) => {
    const m = preset('B swivel head, C rotary table, Y under the table');
    m.geometry.pivotLength = pivot;
    m.errors = { E_X0B: 0.0294, E_A0B: (3.2419e-4 * 180) / Math.PI };
    return m;
  };
  wasm['sshape: overcut maps of A and B (eq 6 + exact), 261 x 16'] = time(
    3,
    () => fa.sshapeOvercut({ tool: { rTool: 10, lTool: 35 }, nu: 261, nv: 16 }),
    (o) => total(o.surfaces[0].exact) + total(o.surfaces[1].exact),
  );
  wasm['sshape: eq 14 model (IK along both paths) + defects'] = time(
    3,
    () => fa.sshapeDefects({ machine: chanal(399.889 + 0.001 * ++ssRun) }),
    (d) => total(d.total),
  );
  const ssCsv = readFileSync(new URL('../public/samples/sshape-measured.csv', import.meta.url), 'utf8');
  const paper = ['E_C0Y', 'E_A0Z', 'E_B0Z', 'E_A0C', 'E_B0C', 'E_X0B', 'E_A0B', 'E_C0B'];
  fa.sshapeDefects({ machine: chanal(399.889) }); // builds the model once, as the page does
  const ssInput = { machine: chanal(399.889), csv: ssCsv, parameters: paper }; // as bench.rs: one input
  wasm['sshape: identification of the 100-point sample (parse + SVD fit), 100 times'] = time(
    3,
    () => {
      let fit;
      for (let i = 0; i < 100; i++) fit = fa.sshapeIdentify(ssInput);
      return fit;
    },
    (f) => f.rms,
  );

  wasm['reversal: default test with and without friction (2 simulations)'] = time(3, () => fa.reversalSimulate({}), (r) => total(r.deviation));
  // The cubic test designer and the identification of its export (same inputs as bench.rs: the
  // preset as it is, without Table 5's errors).
  const liPreset = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
  let designedCsv = '';
  wasm['cubic: test designer, B/C table, 2 set-ups (1098 candidate zones)'] = time(3, () => fa.cubicDesign({ machine: liPreset, secondSetup: 100 }), (d) => {
    designedCsv = d.designed.csv;
    return d.designed.smallest;
  });
  const filledCsv = designedCsv.replace(/,,,\n/g, ',1,0.00001,-0.00001\n');
  const cubicInput = { machine: liPreset, csv: filledCsv, decision: { noise: 0.001 } }; // as bench.rs: one input
  wasm['cubic: identification of 18 measured zones, 100 times'] = time(
    3,
    () => {
      let r;
      for (let i = 0; i < 100; i++) r = fa.cubicIdentify(cubicInput);
      return r;
    },
    (r) => r.rms,
  );

  // Reading: the same texts as crate/examples/bench.rs (clsf, iso), target under 0.5 s as wasm.
  function clsf(n) {
    let s = 'TOOL PATH/BENCH,TOOL,T1\nMSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000\n';
    for (let i = 0; i < n - 2; i++) {
      if (i % 200 === 0) s += 'RAPID\n';
      else if (i % 200 === 2) s += 'FEDRAT/MMPM,1500.0000\n';
      else {
        const t = ((30 + 20 * Math.sin(0.003 * i)) * Math.PI) / 180;
        const a = ((0.002 * i) * Math.PI / 180) * 57;
        s += `GOTO/${(100 * Math.sin(0.001 * i)).toFixed(4)},${(100 * Math.cos(0.0013 * i)).toFixed(4)},${(1e-3 * i).toFixed(4)},${(Math.sin(t) * Math.cos(a)).toFixed(7)},${(Math.sin(t) * Math.sin(a)).toFixed(7)},${Math.cos(t).toFixed(7)}\n`;
      }
    }
    return s;
  }
  function iso(n) {
    let s = '%\nO1000\nG90 G21 G17\nG43.4 H1\nG0 X0 Y0 Z50 A0 C0\n';
    for (let i = 0; i < n - 6; i++) {
      if (i % 100 === 50) s += `N${i} G2 X${(100 * Math.sin(0.001 * i) + 1).toFixed(4)} Y${(100 * Math.cos(0.0013 * i)).toFixed(4)} R50.\n`;
      else s += `N${i} G1 X${(100 * Math.sin(0.001 * i)).toFixed(4)} Y${(100 * Math.cos(0.0013 * i)).toFixed(4)} Z${(1e-3 * i).toFixed(4)} A${(-30 - 20 * Math.sin(0.003 * i)).toFixed(4)} C${(0.11 * i).toFixed(4)}\n`;
    }
    return `${s}M30\n%\n`;
  }
  const readSum = (p) => {
    const pts = p.path.points;
    let sum = p.count;
    for (let i = 0; i < p.count; i++) sum += pts[6 * i] + pts[6 * i + 1] + pts[6 * i + 2];
    return sum;
  };
  // The file's bytes, as the page's worker passes them (the engine decodes them).
  const cl = new TextEncoder().encode(clsf(22_000));
  wasm['toolpath read: CLSF, 22000 statements'] = time(10, () => fa.toolpathParse(cl, { format: 'apt' }), readSum);
  const ncBytes = new TextEncoder().encode(iso(16_000));
  wasm['toolpath read: ISO program, 16000 blocks'] = time(10, () => fa.toolpathParse(ncBytes, { format: 'nc', machine: preset('A/C trunnion table') }), readSum);
  // The sphere test: 200 probed poses identified (same JSON as crate/examples/bench.rs).
  const probe = probeInput();
  wasm['probe: identification of 200 probed poses (probeIdentify)'] = time(5, () => fa.probeIdentify(probe), probeCheck);
  return wasm;
}

// A round of the wasm timings, asked for by the parent process below: its results as JSON lines.
if (process.env.BENCH_WASM_ROUND) {
  for (const [name, r] of Object.entries(runWasm())) console.log(JSON.stringify({ name, ...r }));
  process.exit(0);
}

/** Timings by kernel from a process's JSON lines. */
const byName = (out) => Object.fromEntries(out.trim().split('\n').map((l) => JSON.parse(l)).map((r) => [r.name, r]));

/** One round of the native timings (crate/examples/bench.rs), by kernel. */
function runNative(round) {
  const env = { ...process.env, BENCH_ROUND: String(round) }; // its eq 14 pivots, as runWasm's
  return byName(execFileSync('cargo', ['run', '--release', '-q', '-p', 'fiveaxis', '--example', 'bench'], { cwd: root, encoding: 'utf8', env }));
}

/**
 * One round of the wasm timings, in a Node process of its own, as each native round is: a Node
 * process can stay slower than another for its whole life (the S-shape identification ×100 at
 * 18–19 ms in one, 27–33 ms in the next, minutes apart on the same quiet machine), so that
 * rounds run in one process shared its luck.
 */
function runWasmRound(round) {
  const env = { ...process.env, BENCH_ROUND: String(round), BENCH_WASM_ROUND: '1' };
  return byName(execFileSync(process.execPath, [fileURLToPath(import.meta.url)], { cwd: root, encoding: 'utf8', env }));
}

/** The faster of two timings of a kernel. */
const faster = (a, b) => (!a ? b : !b ? a : b.ms < a.ms ? b : a);
const sameCheck = (w, n) => Boolean(w && n) && Math.abs(w.check - n.check) <= 1e-9 * Math.max(1, Math.abs(n.check));

// Native and wasm in alternate rounds, the best of each kept: the machine is shared, and a
// load that comes and goes would otherwise fall on one side only (BENCH_ROUNDS, default 3).
const ROUNDS = Number(process.env.BENCH_ROUNDS ?? 3);
const native = {};
const wasm = {};
const agree = {}; // native and wasm gave the same result in every round
console.error('building the native benchmark (cargo build --release --example bench) ...');
execFileSync('cargo', ['build', '--release', '-q', '-p', 'fiveaxis', '--example', 'bench'], { cwd: root, stdio: 'inherit' });
for (let round = 1; round <= ROUNDS; round++) {
  console.error(`round ${round} of ${ROUNDS}: native, then wasm ...`);
  const n = runNative(round);
  const w = runWasmRound(round);
  for (const k of Object.keys(n)) {
    native[k] = faster(native[k], n[k]);
    wasm[k] = faster(wasm[k], w[k]);
    agree[k] = (agree[k] ?? true) && sameCheck(w[k], n[k]);
  }
}

const rows = Object.keys(native).filter((name) => !name.startsWith('toolpath:')).map((name) => {
  const n = native[name];
  const w = wasm[name];
  return {
    kernel: name,
    'native ms': n.ms.toFixed(1),
    'wasm ms': w ? w.ms.toFixed(1) : '—',
    'wasm/native': w ? (w.ms / n.ms).toFixed(2) : '—',
    'within 1.5×': w && w.ms <= 1.5 * n.ms ? 'yes' : 'NO',
    'same result': agree[name] ? 'yes' : 'NO',
    // Orientation evaluations per move of the exact maximum (native count, same algorithm).
    'evaluations/move': n.evaluations === undefined ? '—' : n.evaluations.toFixed(2),
  };
});
console.table(rows);
const rev = 'reversal: default test with and without friction (2 simulations)';
if (native[rev] && wasm[rev]) {
  console.log(`reversal: one simulation ${(wasm[rev].ms / 2).toFixed(1)} ms as wasm (target <= 50 ms), ${(native[rev].ms / 2).toFixed(1)} ms native`);
}
const probeName = 'probe: identification of 200 probed poses (probeIdentify)';
if (native[probeName] && wasm[probeName]) {
  const ratio = wasm[probeName].ms / native[probeName].ms;
  console.log(`probe: identification of 200 probed poses: ${wasm[probeName].ms.toFixed(1)} ms as wasm, ${native[probeName].ms.toFixed(1)} ms native, ratio ${ratio.toFixed(2)} (budget 1.5×: ${ratio <= 1.5 ? 'within' : 'ABOVE'})`);
}
for (const name of ['toolpath read: CLSF, 22000 statements', 'toolpath read: ISO program, 16000 blocks']) {
  if (wasm[name]) console.log(`${name}: ${wasm[name].ms.toFixed(0)} ms as wasm (target < 500 ms)`);
}

// The toolpath ranking in headless Chromium: the built page's workers (www/src/toolpath/pool.ts),
// one worker and as many as the page uses (navigator.hardwareConcurrency, at most 6), on the same
// path as crate/examples/bench.rs, beside the native time on one thread.
const { startBrowser } = await import('../tests/e2e/harness.mjs');
const b = await startBrowser();
try {
  const page = await (await b.browser.newContext()).newPage();
  await page.goto(b.url);
  await page.waitForFunction(() => window.fiveaxisToolpath);
  const chromium = await page.evaluate(async () => {
    const tp = window.fiveaxisToolpath;
    /** Same formula as bench_path in crate/examples/bench.rs. */
    const path = (n) => {
      const out = new Float64Array(6 * n);
      for (let i = 0; i < n; i++) {
        const tilt = ((35 + 25 * Math.sin(0.0071 * i)) * Math.PI) / 180;
        const az = (170 * Math.sin(0.003 * i) * Math.PI) / 180;
        out.set([100 * Math.sin(0.001 * i), 100 * Math.cos(0.0013 * i), 1e-5 * i, Math.sin(tilt) * Math.cos(az), Math.sin(tilt) * Math.sin(az), Math.cos(tilt)], 6 * i);
      }
      return out;
    };
    const input = { machine: {}, length: 100, tolerance: 0.01 };
    await tp.rankTypes(input, path(1000), undefined, tp.WORKERS); // start the workers and their engines
    const points = path(1_000_000);
    const timed = async (workers) => {
      const t = performance.now();
      const rows = await tp.rankTypes(input, points, undefined, workers);
      return { ms: performance.now() - t, check: rows.reduce((s, r) => s + r.max + r.mean, 0) };
    };
    return { one: await timed(1), all: await timed(tp.WORKERS), workers: tp.WORKERS, cores: navigator.hardwareConcurrency };
  });
  const n = native['toolpath: 10^6 points on the 12 types'];
  const same = (w) => (Math.abs(w.check - n.check) <= 1e-9 * Math.max(1, Math.abs(n.check)) ? 'yes' : 'NO');
  console.table([
    { kernel: 'toolpath: 10^6 points x 12 types, native, one thread', ms: n.ms.toFixed(0), 'vs native': '1.00', 'same result': 'yes', 'evaluations/segment': n.evaluations.toFixed(2) },
    { kernel: 'the same, wasm in Chromium, 1 worker', ms: chromium.one.ms.toFixed(0), 'vs native': (chromium.one.ms / n.ms).toFixed(2), 'same result': same(chromium.one), 'evaluations/segment': '—' },
    { kernel: `the same, wasm in Chromium, ${chromium.workers} worker${chromium.workers === 1 ? "" : "s"} (as the page on ${chromium.cores} cores)`, ms: chromium.all.ms.toFixed(0), 'vs native': (chromium.all.ms / n.ms).toFixed(2), 'same result': same(chromium.all), 'evaluations/segment': '—' },
  ]);
  if (same(chromium.one) !== 'yes' || same(chromium.all) !== 'yes') process.exitCode = 1;
} finally {
  await b.close();
}
if (rows.some((r) => r['same result'] !== 'yes')) {
  console.error('native and wasm results differ: see the checksums');
  process.exitCode = 1;
}
