// What an identification found, as a machine-tool engineer reads it: the verdicts first (the
// engine's words), then a table of every error (value, 95 % interval in the chosen units, the
// decision, its meaning), the groups the test cannot separate and the goodness of fit, and the
// file it came from. Shared by the S-shape and the cubic-machining panels (`Identification`,
// the engine's `fiveaxis::identify`).
import type { Identification } from '@engine';
import { el } from './fields';
import { forgetDrawing, loadPlotly } from './plot';
import * as fmt from './format';
import { show } from './units';

/** Where a measurement came from: shown with every result. */
export interface Source {
  /** File name, or "pasted text". */
  name: string;
  /** When it was read. */
  at: Date;
}

const VERDICT: Record<string, string> = {
  present: 'present',
  'below-tolerance': 'present, below the tolerance',
  'not-distinguishable': 'not distinguishable from zero',
  'not-identifiable': 'not identifiable alone',
};

/** The display quantity of an error in the engine's unit ("deg" or "mm"). */
export const quantityOf = (unit: string) => (unit === 'deg' ? 'errAngle' : 'errLength');

/** "From sample.csv (100 measurements), read at 16:31:02." */
export function sourceText(s: Source, count: number, what: string): string {
  return `From ${s.name} (${count} ${what}), read at ${s.at.toLocaleTimeString()}.`;
}

/** The identification's elements (ids prefixed by `prefix`): source, verdicts, table, groups. */
export function identificationView(prefix: string, f: Identification, source: string, paramLabel = (n: string) => n): HTMLElement[] {
  const src = el('p', { class: 'source', id: `${prefix}-source` }, source);
  const verdicts = el('ul', { class: 'verdicts', id: `${prefix}-verdicts` });
  for (const s of f.summary) {
    const li = el('li', {}, s);
    if (f.goodness.explains === false && s === f.goodness.words) li.className = 'warn';
    verdicts.append(li);
  }
  const table = el('table', { class: 'ident-table', id: `${prefix}-ident-table` });
  const head = el('tr');
  for (const h of ['error', 'identified value', '95 % interval ±', 'decision', 'what it means']) head.append(el('th', { scope: 'col' }, h));
  table.append(el('thead'), el('tbody'));
  table.tHead!.append(head);
  for (const e of f.estimates) {
    const q = quantityOf(e.unit);
    const tr = el('tr');
    tr.dataset.name = e.name;
    tr.dataset.verdict = e.verdict;
    const half = e.interval ? (e.interval[1] - e.interval[0]) / 2 : null;
    const decision = e.verdict === 'not-identifiable' ? `${VERDICT[e.verdict]} (group ${(e.group ?? 0) + 1})` : VERDICT[e.verdict];
    const meaning = e.verdict === 'not-identifiable' ? `minimum-norm split ${show(q, e.minNorm)} (a convention, not a value)` : e.words.replace(/^[^:]*: /, '');
    tr.append(
      el('th', { scope: 'row' }, paramLabel(e.name)),
      el('td', {}, e.value === null ? '—' : show(q, e.value)),
      el('td', {}, half === null ? '—' : show(q, half, 2)),
      el('td', {}, decision),
      el('td', {}, meaning),
    );
    table.tBodies[0].append(tr);
  }
  const groups = el('ul', { id: `${prefix}-groups` });
  // The names in a combination's text as the table shows them (longest first: none is then
  // replaced inside a longer one).
  const names = f.estimates.map((e) => e.name).sort((a, b) => b.length - a.length);
  const labelled = (text: string) => names.reduce((t, n) => (paramLabel(n) === n ? t : t.split(n).join(paramLabel(n))), text);
  f.groups.forEach((g, i) => {
    const members = g.members.map(paramLabel).join(', ');
    if (!g.combinations.length) {
      groups.append(el('li', {}, `Group ${i + 1} (${members}): the test cannot see ${g.members.length > 1 ? 'them' : 'it'} at all.`));
    }
    for (const c of g.combinations) {
      const lead = f.estimates.find((e) => e.name === c.terms[0][0]);
      const q = quantityOf(lead?.unit ?? 'mm');
      const half = (c.interval[1] - c.interval[0]) / 2;
      groups.append(el('li', {}, `Group ${i + 1} (${members}): only this combination is measurable: ${labelled(c.text)} = ${show(q, c.value)} ± ${show(q, half, 2)} (${VERDICT[c.verdict]})`));
    }
  });
  const svs = f.singularValues.map((s) => fmt.num(s, 2)).join(', ');
  const rank = el('p', { id: `${prefix}-rank` },
    `Rank ${f.rank} of ${f.estimates.length} (relative singular values ${svs}; threshold ${fmt.num(f.rtol)}). ` +
      `Decisions hold a ${fmt.num(100 * f.alpha, 3)} % chance of reporting any error that is not there (Holm’s step-down on the t statistics)` +
      `${f.tolerance === null ? '' : `; tolerance ${show('errLength', f.tolerance)}`}.`);
  const scroll = el('div', { class: 'table-scroll' });
  scroll.append(table);
  return [src, verdicts, scroll, ...(f.groups.length ? [groups] : []), rank];
}

/** Removes a plot entirely (a result that belongs to other inputs must not stay on screen). */
export async function clearPlot(target: HTMLElement) {
  forgetDrawing(target);
  const P = await loadPlotly();
  P.purge(target);
  target.parentElement?.querySelector(':scope > .plot-tools')?.remove();
  target.parentElement?.querySelector(':scope > .plot-note')?.remove();
  target.closest('.plot-wrap')?.classList.remove('stale');
  // Not a figure any more: no role, no label (an unlabelled div may not carry aria-label).
  target.removeAttribute('role');
  target.removeAttribute('aria-label');
}
