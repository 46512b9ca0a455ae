// `node scripts/make-laser-sample.mjs [file]`: writes public/samples/x-laser-runs.csv (or `file`),
// a positioning test of the X axis (ISO 230-2: 5 runs each way at 13 targets) synthesised from
// stated errors with Gaussian noise from a fixed seed, in the layout laser software exports (one
// line per target, the runs in columns). The errors are written in the file's header.
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

export const LASER = {
  /** Targets, mm. */
  from: -300,
  to: 300,
  step: 50,
  /** Runs each way. */
  runs: 5,
  /** Scale error, µm/m. */
  scale: 10,
  /** Ripple amplitude, µm, and period, mm (the pitch of the ball screw's lead error). */
  ripple: 1.5,
  period: 400,
  /** Lost motion, µm: approached upwards the axis stops half of it short, downwards half past. */
  lostMotion: 3,
  /** Repeatability noise, µm rms. */
  noise: 0.4,
  seed: 20240612,
};

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

export function laserSample(s = LASER) {
  const next = rng(s.seed);
  const gauss = () => Math.sqrt(-2 * Math.log(Math.max(next(), 1e-300))) * Math.cos(2 * Math.PI * next());
  const systematic = (x) => s.scale * 1e-3 * x + s.ripple * Math.sin((2 * Math.PI * x) / s.period);
  const cols = [...Array.from({ length: s.runs }, (_, j) => `up ${j + 1} (µm)`), ...Array.from({ length: s.runs }, (_, j) => `down ${j + 1} (µm)`)];
  const lines = [
    '# Laser positioning test of the X axis (ISO 230-2), 5 runs each way. SYNTHETIC: made by scripts/make-laser-sample.mjs, not a real machine\'s data.',
    `# Deviation = position reached − target (µm): ${s.scale} µm/m of scale error plus a ${s.ripple} µm ripple of period ${s.period} mm,`,
    `# ${s.lostMotion} µm of lost motion (approached upwards X stops ${s.lostMotion / 2} µm short, downwards ${s.lostMotion / 2} µm past: B_i = −${s.lostMotion} µm),`,
    `# and ${s.noise} µm rms of noise at each approach (Gaussian; mulberry32 seed ${s.seed}, Box–Muller).`,
    ['target (mm)', ...cols].join(','),
  ];
  for (let x = s.from; x <= s.to + 1e-9; x += s.step) {
    const up = Array.from({ length: s.runs }, () => systematic(x) - s.lostMotion / 2 + s.noise * gauss());
    const down = Array.from({ length: s.runs }, () => systematic(x) + s.lostMotion / 2 + s.noise * gauss());
    lines.push([x, ...[...up, ...down].map((v) => v.toFixed(2).replace(/^-(0\.0+)$/, '$1'))].join(','));
  }
  return lines.join('\n') + '\n';
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const out = process.argv[2] ?? fileURLToPath(new URL('../public/samples/x-laser-runs.csv', import.meta.url));
  writeFileSync(out, laserSample());
  console.log(`wrote ${out}`);
}
