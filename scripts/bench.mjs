// `npm run bench`: times the engine's heavy kernels natively (crate/examples/bench.rs, release
// build) and as WebAssembly in Node (the release package wasm/pkg) on the same inputs, and
// prints both times and their ratio (and, for the nonlinear maxima, the orientation evaluations
// per move, counted natively). Each kernel is timed natively, then as wasm, seconds apart, in
// rounds of new processes (runRound; BENCH_ROUNDS, default 3); the best time over the rounds is
// kept on each side.
import { execFileSync, spawn } from 'node:child_process';
import { once } from 'node:events';
import { readFileSync } from 'node:fs';
import { createInterface } from 'node:readline';
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

/** How long each kernel runs untimed, then timed, at least (milliseconds; `time`), both sides. */
const SETTLE_MS = 1000;
/** In a round driven by the parent process (below): the lines it sends on stdin. */
const stepped = Boolean(process.env.BENCH_WASM_ROUND);
const words = stepped ? createInterface({ input: process.stdin })[Symbol.asyncIterator]() : null;
/** Says which kernel is next (`ready <name>`) and waits for the driver's word to go. */
async function step(name) {
  console.log(`ready ${name}`);
  if ((await words.next()).done) process.exit(1); // the driver has gone: stop
}

/**
 * Best of at least `repeat` timed runs and at least `ms` of them, after at least `warmRuns`
 * untimed runs and at least `ms` of them (`ms` 0: exactly `warmRuns`, then exactly `repeat`).
 * The steady state, as natively (crate/examples/bench.rs times the same way). Node runs
 * WebAssembly first as baseline code and compiles the hot functions again, optimised, in the
 * background: a short kernel timed cold measures the compiler (the S-shape identification ×100, 20 ms, took 40-60 ms a run for its
 * first 4-8 runs, then 17-21 ms). And the machine has slow spells of a fraction of a second to
 * seconds (the same identification at 17 ms, then 25-76 ms for a few runs, with nothing else
 * running): three runs of a short kernel could all fall in one.
 */
async function time(name, repeat, f, check, { ms = SETTLE_MS, warmRuns = 1 } = {}) {
  await step(name);
  const warm = performance.now();
  for (let i = 0; i < warmRuns || performance.now() - warm < ms; i++) f();
  let best = Infinity;
  let sum = 0;
  const timed = performance.now();
  for (let i = 0; i < repeat || performance.now() - timed < ms; i++) {
    const t = performance.now();
    const r = f();
    best = Math.min(best, performance.now() - t);
    sum = check(r);
  }
  console.log(JSON.stringify({ name, ms: best, check: sum }));
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

/** One round of the WebAssembly timings, kernel by kernel as the driver says (runRound). */
async function runWasm() {
  // In the order of crate/examples/bench.rs, so that a driven round times each kernel natively,
  // then as wasm, seconds apart.
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
  await time('toolpath read: CLSF, 22000 statements', 10, () => fa.toolpathParse(cl, { format: 'apt' }), readSum);
  const ncBytes = new TextEncoder().encode(iso(16_000));
  await time('toolpath read: ISO program, 16000 blocks', 10, () => fa.toolpathParse(ncBytes, { format: 'nc', machine: preset('A/C trunnion table') }), readSum);
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
  await time('volumetric: 10^6 poses exact (1001 x 1001 plane) + budget',
    3,
    () => fa.volumetricMap({ machine: tanLim, region: { plane: 'XY', uFrom: -300, uTo: 300, vFrom: -200, vTo: 200, at: 50, k: 30, m: -20, steps: 1001 } }),
    (m) => total(m.norm),
  );

  const mv = moves(1_000_000);
  await time('nonlinear: exact max of 10^6 moves', 3, () => fa.nonlinearMaxErrors('CAZ', 1, mv), total);
  const short = shortMoves(1_000_000);
  await time('nonlinear: exact max of 10^6 short moves (< 5°)', 3, () => fa.nonlinearMaxErrors('CAZ', 1, short), total);
  await time('nonlinear: 361x361 increment grid',
    3,
    () => fa.nonlinearGrid({ machine: { type: 'CAZ' }, length: 1, thetaM: 10, dK: { from: -90, to: 90 }, dM: { from: -90, to: 90 }, nx: 361, ny: 361 }),
    (g) => total(g.max),
  );

  // Li et al.'s Table 5 in ISO names (E = −ε of the paper), on their machine's preset.
  const li = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
  li.errors = { E_X0B: -0.0146, E_Y0B: 0.0089, E_Z0B: 0.0142, E_A0B: 0.0023, E_B0B: -0.0029, E_C0B: 0.00002, E_A0C: 0.00017, E_X0C: -0.0094 };
  await time('cubic: height map 961x961 (Table 5)', 3, () => fa.cubicHeightMap({ machine: li, nx: 961, ny: 961 }), (m) => total(m.height));
  // S-shape: the same inputs as crate/examples/bench.rs.
  const chanal = (pivot) => {
    const m = preset('B swivel head, C rotary table, Y under the table');
    m.geometry.pivotLength = pivot;
    m.errors = { E_X0B: 0.0294, E_A0B: (3.2419e-4 * 180) / Math.PI };
    return m;
  };
  await time('sshape: overcut maps of A and B (eq 6 + exact), 261 x 16',
    3,
    () => fa.sshapeOvercut({ tool: { rTool: 10, lTool: 35 }, nu: 261, nv: 16 }),
    (o) => total(o.surfaces[0].exact) + total(o.surfaces[1].exact),
  );
  // A new pivot per run (the engine keeps designs in a cache): a count of runs, not a time, the
  // same as natively, so that the last run's pivot, and so its result, is the same.
  let ssRun = 0;
  await time('sshape: eq 14 model (IK along both paths) + defects',
    10,
    () => fa.sshapeDefects({ machine: chanal(399.889 + 0.001 * ++ssRun) }),
    (d) => total(d.total),
    { ms: 0, warmRuns: 30 },
  );
  const ssCsv = readFileSync(new URL('../public/samples/sshape-measured.csv', import.meta.url), 'utf8');
  const paper = ['E_C0Y', 'E_A0Z', 'E_B0Z', 'E_A0C', 'E_B0C', 'E_X0B', 'E_A0B', 'E_C0B'];
  fa.sshapeDefects({ machine: chanal(399.889) }); // builds the model once, as the page does
  const ssInput = { machine: chanal(399.889), csv: ssCsv, parameters: paper }; // as bench.rs: one input
  await time('sshape: identification of the 100-point sample (parse + SVD fit), 100 times',
    3,
    () => {
      let fit;
      for (let i = 0; i < 100; i++) fit = fa.sshapeIdentify(ssInput);
      return fit;
    },
    (f) => f.rms,
  );

  await time('reversal: default test with and without friction (2 simulations)', 3, () => fa.reversalSimulate({}), (r) => total(r.deviation));
  // The cubic test designer and the identification of its export (same inputs as bench.rs: the
  // preset as it is, without Table 5's errors).
  const liPreset = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
  let designedCsv = '';
  await time('cubic: test designer, B/C table, 2 set-ups (1098 candidate zones)', 3, () => fa.cubicDesign({ machine: liPreset, secondSetup: 100 }), (d) => {
    designedCsv = d.designed.csv;
    return d.designed.smallest;
  });
  const filledCsv = designedCsv.replace(/,,,\n/g, ',1,0.00001,-0.00001\n');
  const cubicInput = { machine: liPreset, csv: filledCsv, decision: { noise: 0.001 } }; // as bench.rs: one input
  await time('cubic: identification of 18 measured zones, 100 times',
    3,
    () => {
      let r;
      for (let i = 0; i < 100; i++) r = fa.cubicIdentify(cubicInput);
      return r;
    },
    (r) => r.rms,
  );

  // The sphere test: 200 probed poses identified (same JSON as crate/examples/bench.rs).
  const probe = probeInput();
  await time('probe: identification of 200 probed poses (probeIdentify)', 5, () => fa.probeIdentify(probe), probeCheck);
}

// A round of the wasm timings, driven by the parent process below (runRound). After the last
// kernel the process ends once its output is written (the parent reads that end as the wasm
// side's last line), without running the parent's part below.
if (stepped) {
  await runWasm();
  await new Promise((written) => process.stdout.write('', written));
  process.exit(0);
}

/** The next line a child process writes (null at its end). */
const lineReader = (stream) => {
  const lines = createInterface({ input: stream })[Symbol.asyncIterator]();
  return async () => {
    const next = await lines.next();
    return next.done ? null : next.value;
  };
};

/**
 * One round: the native benchmark (crate/examples/bench.rs) and the wasm one (this file, in a
 * Node process of its own) started side by side, each stopping before every kernel (`ready`)
 * until told to go. Each kernel is timed natively, then as wasm, while the other side waits:
 * the two timings of a kernel are seconds apart, and nothing else of the benchmark runs during
 * either. (The machine has slow spells of minutes: the native S-shape identification ×100 took
 * 10.4–11.8 ms, then 18.5–20 ms a few minutes later, a plain arithmetic loop the same all along.
 * Timed a whole suite apart, one side could fall in a spell and the other not.) A kernel only
 * one side has (the native toolpath ranking: its wasm side is timed in Chromium below) is timed
 * alone. Each round's processes are new: a process can also stay slower than the next.
 */
async function runRound() {
  const start = (cmd, args, more) => {
    const child = spawn(cmd, args, { cwd: root, env: { ...process.env, ...more }, stdio: ['pipe', 'pipe', 'inherit'] });
    const exited = once(child, 'exit');
    const next = lineReader(child.stdout);
    /** The next line; at the child's end (it died, or the kernels differ), an error that says so. */
    const line = async (what) => {
      const l = await next();
      if (l !== null) return l;
      await exited;
      throw new Error(`bench: ${cmd === 'cargo' ? 'the native benchmark' : 'the wasm benchmark'} ended (exit ${child.exitCode}) where ${what} was expected`);
    };
    return { child, exited, next, line, go: () => child.stdin.write('go\n') };
  };
  const nat = start('cargo', ['run', '--release', '-q', '-p', 'fiveaxis', '--example', 'bench'], { BENCH_STEP: '1' });
  const was = start(process.execPath, [fileURLToPath(import.meta.url)], { BENCH_WASM_ROUND: '1' });
  const n = {};
  const w = {};
  try {
    let natReady = await nat.next();
    let wasReady = await was.line('its first kernel');
    while (natReady === 'ready') {
      nat.go();
      const r = JSON.parse(await nat.line('a result'));
      n[r.name] = r;
      natReady = await nat.next(); // the next kernel's inputs made before the wasm side runs
      if (wasReady === `ready ${r.name}`) {
        was.go();
        const rw = JSON.parse(await was.line(`the result of ${r.name}`));
        w[rw.name] = rw;
        wasReady = await was.next();
      }
    }
    if (natReady !== null || wasReady !== null) {
      throw new Error(`bench: the two sides' kernels differ in name or order (native: ${natReady}, wasm: ${wasReady})`);
    }
    for (const side of [nat, was]) {
      side.child.stdin.end();
      await side.exited;
      if (side.child.exitCode !== 0) throw new Error(`bench: ${side.child.spawnfile} exited with ${side.child.exitCode}`);
    }
  } finally {
    // On an error, neither side is left running (the end of its input stops each side).
    for (const { child } of [nat, was]) if (child.exitCode === null && child.signalCode === null) child.kill();
  }
  return [n, w];
}

/** The faster of two timings of a kernel. */
const faster = (a, b) => (!a ? b : !b ? a : b.ms < a.ms ? b : a);
const sameCheck = (w, n) => Boolean(w && n) && Math.abs(w.check - n.check) <= 1e-9 * Math.max(1, Math.abs(n.check));

// Rounds of both sides (runRound), the best of each kept (BENCH_ROUNDS, default 3).
const ROUNDS = Number(process.env.BENCH_ROUNDS ?? 3);
const native = {};
const wasm = {};
const agree = {}; // native and wasm gave the same result in every round
console.error('building the native benchmark (cargo build --release --example bench) ...');
execFileSync('cargo', ['build', '--release', '-q', '-p', 'fiveaxis', '--example', 'bench'], { cwd: root, stdio: 'inherit' });
for (let round = 1; round <= ROUNDS; round++) {
  console.error(`round ${round} of ${ROUNDS}: each kernel native, then wasm ...`);
  const [n, w] = await runRound();
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
