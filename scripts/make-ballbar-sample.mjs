// `node scripts/make-ballbar-sample.mjs [file]`: writes public/samples/ballbar-xy.csv (or `file`),
// a ball-bar circular test (ISO 230-4) of the XY plane synthesised from stated faults, each
// moving the tool exactly as the fault models of crate/src/ballbar/mod.rs describe it (the exact
// geometry, not the fit's first-order terms), with Gaussian noise from a fixed seed. The faults
// are written in the file's header; tests/e2e/ballbar.test.mjs checks the page's diagnostics
// against them (FAULTS below, exported).
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

/** The faults, in the units the header states them in. */
export const FAULTS = {
  /** Ball-bar length, mm. */
  radius: 100,
  /** Feed, mm/min. */
  feed: 1000,
  /** Lost motion of X, µm: X stops half of it short in its direction of travel. */
  backlashX: 8,
  /** Out-of-squareness, µm/m: Y leans towards +X (X and Y closer than 90°). */
  squareness: 30,
  /** Scale mismatch, ppm: X reads this much long, Y exact. */
  scaleMismatch: 20,
  /** Where the circle's centre is from the ball-bar's pivot (set-up), µm: [X, Y]. */
  centre: [4, -3],
  /** Noise, µm rms. */
  noise: 0.5,
  /** Seed of the noise (mulberry32, Box–Muller). */
  seed: 20240611,
};

/** mulberry32: a small seeded generator in [0, 1). */
export function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** The file's text. */
export function ballbarSample(f = FAULTS) {
  const R = f.radius;
  const next = rng(f.seed);
  const gauss = () => Math.sqrt(-2 * Math.log(Math.max(next(), 1e-300))) * Math.cos(2 * Math.PI * next());
  const eu = f.scaleMismatch * 1e-6; // X's scale error (Y's is 0)
  const alpha = f.squareness * 1e-6; // rad
  const bu = f.backlashX / 1000; // mm
  const [cu, cv] = f.centre.map((c) => c / 1000);
  const sign = (x) => (x > 0 ? 1 : x < 0 ? -1 : 0);
  /** Δr (µm) at θ (degrees) moving CCW (d = +1) or CW (d = −1): the commanded point, then each
   *  fault's exact effect on where the tool is, then its distance from the pivot less R. */
  const dr = (deg, d) => {
    const th = (deg * Math.PI) / 180;
    const u = R * Math.cos(th);
    const v = R * Math.sin(th);
    const du = -d * Math.sin(th); // X's direction of travel
    const ua = u * (1 + eu) + alpha * v - 0.5 * bu * sign(du);
    const va = v;
    return (Math.hypot(ua + cu, va + cv) - R) * 1000 + f.noise * gauss();
  };
  const lines = [
    '# Ball-bar circular test of the XY plane (G17), 360° each way. SYNTHETIC: made by scripts/make-ballbar-sample.mjs, not a real machine\'s data.',
    '# The faults, each moving the tool exactly (not to first order) as crate/src/ballbar/mod.rs models it:',
    `#   X backlash (lost motion) ${f.backlashX} µm: X stops ${f.backlashX / 2} µm short in its direction of travel; Y none;`,
    `#   out-of-squareness ${f.squareness} µm/m: Y leans towards +X (X and Y closer than 90°);`,
    `#   scale mismatch ${f.scaleMismatch} ppm: X reads ${f.scaleMismatch} µm/m long, Y exact;`,
    `#   set-up: the circle's centre ${f.centre[0]} µm along X and ${f.centre[1]} µm along Y from the ball-bar's pivot; no servo mismatch, no cyclic error;`,
    `#   noise ${f.noise} µm rms, Gaussian (mulberry32 seed ${f.seed}, Box–Muller), CCW column first at each angle.`,
    '# Angle from +X towards +Y; deviation = measured length − nominal radius, positive outwards.',
    `# radius: ${R} mm`,
    `# feed: ${f.feed} mm/min`,
    'angle (deg), ccw (µm), cw (µm)',
  ];
  for (let k = 0; k < 360; k++) {
    const deg = k + 0.5;
    const ccw = dr(deg, 1);
    const cw = dr(deg, -1);
    const f = (v) => v.toFixed(3).replace(/^-(0\.0+)$/, '$1');
    lines.push(`${deg.toFixed(1)}, ${f(ccw)}, ${f(cw)}`);
  }
  return lines.join('\n') + '\n';
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const out = process.argv[2] ?? fileURLToPath(new URL('../public/samples/ballbar-xy.csv', import.meta.url));
  writeFileSync(out, ballbarSample());
  console.log(`wrote ${out}`);
}
