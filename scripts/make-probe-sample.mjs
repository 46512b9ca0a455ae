// Writes public/samples/probe-sphere-measured.csv: the sphere centres a touch probe would measure
// on the B/C tilting table preset with stated location errors, simulated by the engine
// (`probeSimulate`: the exact kinematic chain) at the poses the page designs for that machine
// (`probeDesign`), after the reference pose C = 0, B = 0, with Gaussian noise of 1 µm on each
// coordinate from a fixed seed. Written as a control's export is: `;` separators, a decimal comma,
// explicit signs, units in the header, CRLF line ends. Run after `npm run build:wasm`:
//
//   node scripts/make-probe-sample.mjs
//
// The errors, noise and seed are stated in the file's header; tests/e2e/probe.test.mjs states the
// same errors on its own and checks that the page identifies them.
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const PRESET = 'B/C tilting table, vertical spindle (Li et al. 2021)';
const presets = JSON.parse(readFileSync(new URL('../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const machine = structuredClone(presets.find((p) => p.name === PRESET).machine);
/** The machine's errors the sample is made with (ISO 230-1; mm and degrees). */
const ERRORS = { E_X0B: 0.012, E_Z0B: -0.008, E_A0B: 0.005, E_C0B: -0.003 };
/** The sphere: on the table centre (C's axis), 100 mm above the table surface. */
const SPHERE = { x: 0, y: 0, height: 100 };
const SIGMA = 0.001; // mm, one coordinate
const SEED = 31;

/** mulberry32: a 32-bit generator of uniform numbers in [0, 1) from a seed. */
function mulberry32(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
const uniform = mulberry32(SEED);
/** A standard normal number (Box–Muller, the cosine branch). */
const gauss = () => Math.sqrt(-2 * Math.log(1 - uniform())) * Math.cos(2 * Math.PI * uniform());

// The poses: the reference pose first, then the designed layout for this machine and sphere.
const design = fa.probeDesign({ machine, sphere: SPHERE });
const poses = [{ k: 0, m: 0 }, ...design.designed.poses.map((p) => ({ k: p.k, m: p.m }))];
const sim = fa.probeSimulate({ machine: { ...machine, errors: ERRORS }, sphere: SPHERE, k: poses.map((p) => p.k), m: poses.map((p) => p.m) });

/** `v` with `digits` decimals, an explicit sign and a decimal comma ("+0,0012", "-100,0000"). */
const comma = (v, digits) => {
  const t = Math.abs(v).toFixed(digits);
  return `${v < 0 && Number(t) !== 0 ? '-' : '+'}${t.replace('.', ',')}`;
};
const stated = Object.entries(ERRORS).map(([n, v]) => `${n} = ${comma(v, 3)} ${n.startsWith('E_X') || n.startsWith('E_Y') || n.startsWith('E_Z') ? 'mm' : 'deg'}`).join('; ');
const lines = [
  '# Sphere test of the rotary axes C and B: measured sphere centres, one line per pose',
  `# machine: ${PRESET}`,
  '# sphere: 0 mm, 0 mm, 100 mm above the table centre (on the C axis); probe calibrated, TCPM off',
  '# SIMULATED, not measured: scripts/make-probe-sample.mjs, probeSimulate (the exact kinematic chain)',
  `# known errors (ISO 230-1): ${stated}; every other error 0`,
  `# noise: Gaussian, standard deviation 0,001 mm (1 um) on each coordinate, seed ${SEED} (mulberry32, Box-Muller), then rounded to 0,0001 mm`,
  `# poses: the reference pose C = 0, B = 0, then the ${design.designed.poses.length} poses the page designs for this machine and sphere`,
  '# units: C and B in degrees; X, Y, Z in mm (machine coordinates of the sphere centre)',
  'Pose;C [deg];B [deg];X [mm];Y [mm];Z [mm]',
];
sim.poses.forEach((p, i) => {
  const c = p.measured.map((v) => v + SIGMA * gauss());
  lines.push([i === 0 ? 'REF' : String(i), comma(p.k, 3), comma(p.m, 3), ...c.map((v) => comma(v, 4))].join(';'));
});
const out = new URL('../public/samples/probe-sphere-measured.csv', import.meta.url);
writeFileSync(out, `${lines.join('\r\n')}\r\n`);

// The engine reads it back, and says what it finds.
const text = readFileSync(out, 'utf8');
const read = fa.probeReadCsv({ machine, csv: text });
const f = fa.probeIdentify({ machine, sphere: SPHERE, csv: text });
console.log(`wrote ${out.pathname}: ${read.poses.length} poses (reference ${read.reference}, separator ${read.separator})`);
for (const e of f.estimates) if (e.value !== null) console.log(`  ${e.name}: ${e.value.toPrecision(4)} ${e.unit} [${e.interval?.map((v) => v.toPrecision(4)).join(', ')}] ${e.verdict}`);
console.log(`  spread before: ${(f.before.sigma * 1000).toFixed(2)} µm 1σ, ${(f.before.max * 1000).toFixed(2)} µm max; after: ${(f.after.sigma * 1000).toFixed(2)} µm, ${(f.after.max * 1000).toFixed(2)} µm`);
