// What a measurement of the machine found, as the page gives it back (the probe-and-sphere and the
// rotary ball-bar panels): the corrections to enter in the control, with the sign convention, and
// "Use these errors", which puts the errors found into the one machine model. The numbers and
// words are the engine's (`Correction`, `crate::identify::correct`).
import type { Correction, Estimate, Schema } from '@engine';
import type { MachineSection } from '../machine/section';
import { el } from './fields';
import { quantityOf } from './identify';
import { show } from './units';
import { listWords, type Contributor } from './verdict';


/** The table of corrections (`<prefix>-corrections-table`), in a box that scrolls on a phone, and
 *  the signs below it (`<prefix>-signs`). */
export function correctionsView(prefix: string, corrections: Correction[], words: Map<string, { label: string; title: string }>): HTMLElement[] {
  const table = el('table', { class: 'ident-table', id: `${prefix}-corrections-table` });
  const head = el('tr');
  for (const h of ['error', 'what it means', 'value', 'what to enter in the control']) head.append(el('th', { scope: 'col' }, h));
  table.append(el('thead'), el('tbody'));
  table.tHead!.append(head);
  for (const c of corrections) {
    const tr = el('tr');
    tr.dataset.name = c.name;
    tr.dataset.value = String(c.value);
    tr.append(el('th', { scope: 'row', title: words.get(c.name)?.title ?? '' }, c.name), el('td', {}, c.words), el('td', {}, show(quantityOf(c.unit), c.value)), el('td', { class: 'enter' }, c.enter));
    table.tBodies[0].append(tr);
  }
  const scroll = el('div', { class: 'table-scroll' });
  scroll.append(table);
  const signs = el('p', { class: 'field-hint', id: `${prefix}-signs` }, 'Signs (ISO 230-1): an error is where the axis really is minus where the control believes it is. ' +
    'A position is added to the control’s value of the axis line’s position (mm); a tilt turns the control’s axis direction by the angle (degrees, right-hand rule about the named axis); ' +
    'a zero error is corrected by shifting the axis’s zero by minus the error. Enter them where your control keeps its kinematics (Heidenhain: the kinematics table; Siemens: the TRAORI data set), or let its own cycle do it.');
  return [scroll, signs];
}

/**
 * "Use these errors": the errors found present (`found`, ISO name → mm or degrees) into the
 * machine; the errors the measurement determines and finds indistinguishable from zero become 0
 * (the machine as measured); those it cannot tell apart keep the values entered. `estimates`
 * are the errors' own (the set-up's unknowns left out). Returns what was done, in words.
 */
export function useFound(machine: MachineSection, schema: Schema, found: Record<string, number>, estimates: Estimate[], from: string, by: string): string {
  const zero = estimates.filter((e) => e.verdict === 'not-distinguishable').map((e) => e.name);
  const kept = estimates.filter((e) => e.verdict === 'not-identifiable').map((e) => e.name);
  machine.apply({ errors: { ...Object.fromEntries(zero.map((n) => [n, 0])), ...found } }, false);
  const def = (n: string) => schema.errors.find((d) => d.name === n);
  const entered = Object.entries(found).map(([n, v]) => `${n} = ${show(def(n)?.quantity === 'smallAngle' ? 'errAngle' : 'errLength', v)}`);
  return `Entered in the Machine section from ${from}: ${entered.length ? listWords(entered) : 'no error found present'}` +
    `${zero.length ? `; set to 0 (measured, not distinguishable from zero): ${listWords(zero)}` : ''}` +
    `${kept.length ? `; kept as they were (${by} cannot tell them apart): ${listWords(kept)}` : ''}. ` +
    'The volumetric map, the cubic test, the S-shape part and every other study now run on the machine as measured; the machine’s other values are unchanged.';
}

/** Each error found (a correction), by its largest effect (its estimate's `effect`) as a share of
 *  their sum, largest first: the verdict's contributors. None when no error has an effect. */
export function contributorsOf(corrections: Correction[], estimates: Estimate[], words: Map<string, { label: string; title: string }>): Contributor[] {
  const effects = corrections.map((c) => [c, estimates.find((e) => e.name === c.name)?.effect ?? 0] as const);
  const sum = effects.reduce((s, [, e]) => s + Math.abs(e), 0);
  if (!(sum > 0)) return [];
  return effects.map(([c, e]) => ({
    name: c.name,
    label: words.get(c.name)?.label,
    title: words.get(c.name)?.title,
    share: Math.abs(e) / sum,
    amount: show(quantityOf(c.unit), c.value),
  })).sort((a, b) => b.share - a.share);
}
