// `node scripts/make-ballbar-rotary-sample.mjs [file]`: writes public/samples/ballbar-rotary.csv
// (or `file`), the traces of three ball-bar tests with a rotary axis moving, SYNTHETIC: the tests
// of the sample preset (public/presets/ballbar-rotary.json) simulated by the engine
// (`ballbarRotarySimulate`: the exact kinematic chain) on the page's default machine (a B/C
// tilting table) with the location errors below, then what a real bar adds and the model
// fits as set-up: a bar length off by a few µm per test, a constant lag of the clockwise run,
// and Gaussian noise from a fixed seed. Run after `npm run build:wasm`. The errors are in the
// file's header; tests/e2e/ballbar-rotary.test.mjs states them on its own (ERRORS is exported
// for the check that the sample is what this script writes).
import { readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import * as fa from '../wasm/pkg/fiveaxis.js';
import { rng } from './make-ballbar-sample.mjs';

fa.initSync({ module: readFileSync(new URL('../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

/** The machine's location errors (ISO 230-1; mm and degrees). */
export const ERRORS = { E_X0C: 0.012, E_X0B: 0.005, E_Z0B: -0.008, E_A0C: 0.004 };
/** What the bar adds: its length off the nominal per test (µm), the clockwise run's constant lag
 *  (µm), the noise (µm rms) and its seed. */
export const BAR = { length: [2, -3, 1.5], lagCw: 1.5, noise: 0.5, seed: 32 };

/** The sample preset's tests, as the engine takes them (a list). */
export function sampleTests() {
  const presets = JSON.parse(readFileSync(new URL('../public/presets/ballbar-rotary.json', import.meta.url), 'utf8')).presets;
  const p = presets.find((x) => x.name.startsWith('Sample file'));
  return Array.from({ length: p.input.count }, (_, i) => p.input.tests[String(i)]);
}

/** The file's text. */
export function rotarySample() {
  const tests = sampleTests();
  const sim = fa.ballbarRotarySimulate({ machine: { errors: ERRORS }, tests });
  const next = rng(BAR.seed);
  const gauss = () => Math.sqrt(-2 * Math.log(Math.max(next(), 1e-300))) * Math.cos(2 * Math.PI * next());
  const stated = Object.entries(ERRORS).map(([n, v]) => `${n} = ${v > 0 ? '+' : ''}${v} ${/^E_[XYZ]/.test(n) ? 'mm' : 'deg'}`).join(', ');
  const lines = [
    '# Ball-bar tests with a rotary axis moving (ISO 10791-6 style). SYNTHETIC: made by scripts/make-ballbar-rotary-sample.mjs, not a real machine\'s data.',
    '# Machine: the page\'s default (a B/C tilting table, type CBZ, vertical spindle), simulated through the exact kinematic chain (ballbarRotarySimulate).',
    `# Location errors (ISO 230-1): ${stated}; every other error 0.`,
    `# The bar: its length off the nominal by ${BAR.length.join(', ')} µm in the three tests; the CW run ${BAR.lagCw} µm longer throughout (a constant lag);`,
    `#   noise ${BAR.noise} µm rms, Gaussian (mulberry32 seed ${BAR.seed}, Box–Muller).`,
    ...sim.tests.map((t) => `# test ${t.name}: ${t.axis} from ${+t.angle[0].toFixed(6)}° to ${+Math.max(...t.angle).toFixed(6)}° with ${t.held} at ${+t.hold.toFixed(6)}°, ${t.direction} bar of ${t.length} mm, table ball at ${t.ball.map((v) => +v.toFixed(3)).join(', ')} mm`),
    '# angle: the moving axis\'s command; deviation: the bar\'s length change, + longer; direction: ccw = command increasing.',
    'test, angle (deg), deviation (µm), direction',
  ];
  sim.tests.forEach((t, i) => {
    for (let j = 0; j < t.angle.length; j++) {
      const cw = t.run[j] < 0;
      const v = t.deviation[j] * 1000 + BAR.length[i] + (cw ? BAR.lagCw : 0) + BAR.noise * gauss();
      lines.push(`${t.name}, ${+t.angle[j].toFixed(6)}, ${v.toFixed(3)}, ${cw ? 'cw' : 'ccw'}`);
    }
  });
  return lines.join('\n') + '\n';
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const out = process.argv[2] ?? fileURLToPath(new URL('../public/samples/ballbar-rotary.csv', import.meta.url));
  const text = rotarySample();
  writeFileSync(out, text);
  const r = fa.ballbarRotaryIdentify({ tests: sampleTests(), csv: text });
  console.log(`wrote ${out}`);
  for (const e of r.identification.estimates) if (e.value !== null && !e.name.startsWith('offset')) console.log(`  ${e.name}: ${e.value.toPrecision(4)} ${e.unit} [${e.interval?.map((v) => v.toPrecision(4)).join(', ')}] ${e.verdict}`);
  console.log('  ranges:', r.tests.map((t) => `${t.name} ${(t.range * 1000).toFixed(2)} µm → ${(t.rangeAfter * 1000).toFixed(2)} µm`).join('; '));
  console.log(r.summary.join('\n'));
}
