// What the Node and browser tests share: the engine as a script loads it, the page's machine
// presets, and the papers' numbers in the papers' own terms.
import { readFileSync } from 'node:fs';
import * as fa from '../wasm/pkg/fiveaxis.js';

fa.initSync({ module: readFileSync(new URL('../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
export { fa };

/** The page's machine presets (public/presets/machines.json). */
export const MACHINES = JSON.parse(readFileSync(new URL('../public/presets/machines.json', import.meta.url), 'utf8')).presets;

/** A copy of the machine object of the preset whose name starts with `prefix`. */
export function preset(prefix) {
  const p = MACHINES.find((m) => m.name.startsWith(prefix));
  if (!p) throw new Error(`no machine preset named ${prefix}…`);
  return structuredClone(p.machine);
}

/** Table 5 of Li et al. (2021) in the paper's symbols (mm, degrees). */
export const T5 = { dxBY: 0.0146, dyBY: -0.0089, dzBY: -0.0142, alphaBY: -0.0023, betaBY: 0.0029, gammaBY: -0.00002, alphaCB: -0.00017, dxCB: 0.0094 };
/** The same as ISO 230-1 errors: Li et al.'s matrices are the inverse displacement, E = −ε. */
export const T5_ISO = {
  E_X0B: -T5.dxBY, E_Y0B: -T5.dyBY, E_Z0B: -T5.dzBY, E_A0B: -T5.alphaBY,
  E_B0B: -T5.betaBY, E_C0B: -T5.gammaBY, E_A0C: -T5.alphaCB, E_X0C: -T5.dxCB,
};
