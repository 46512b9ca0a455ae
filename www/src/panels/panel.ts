import { EngineError } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el } from '../ui/fields';
import type { ShowsError } from '../ui/form';
import { note, stale } from '../ui/plot';

// A study's panel: mounted once, the first time it is shown.
export interface Panel {
  /** Stable id, used in the tab, the URL and the presets file name (public/presets/<id>.json). */
  id: string;
  /** Prefix of every field id of the panel ("nl" for "nl-length"): the page state relies on it. */
  prefix: string;
  /** Tab text. */
  title: string;
  /** The engine exports whose inputs the panel renders (their shown fields, machine aside). */
  exports: string[];
  mount(root: HTMLElement, machine: MachineSection): Promise<void>;
}

/**
 * The layout every panel shares: its heading, a lead paragraph (what it computes, the paper),
 * the input form on the left and the results on the right. Returns the form and the results.
 */
export function panelShell(root: HTMLElement, heading: string, lead: string) {
  root.append(el('h2', {}, heading), el('p', { class: 'lead' }, lead));
  const layout = el('div', { class: 'panel-grid' });
  const form = el('form', { class: 'inputs', novalidate: '' });
  form.addEventListener('submit', (e) => e.preventDefault());
  const results = el('div', { class: 'results' });
  layout.append(form, results);
  root.append(layout);
  return { form, results };
}

/**
 * Shows an engine error at the field its path names (`"start.k: ..."` → the field registered
 * under `"start.k"`, without the path) or at the machine's field for a `machine.` path. Returns
 * the error when no field shows it, for the caller to show.
 */
export function showAtField(err: unknown, fieldsByPath: Record<string, ShowsError>, machine: MachineSection): EngineError | null {
  const e = EngineError.of(err);
  const f = fieldsByPath[e.field];
  if (f) return f.setError(e.text), null;
  return machine.showError(e) ? null : e;
}

/**
 * A handler for an engine error: the message goes to the field its path names
 * ([`showAtField`]), or over the plot `target` when it names none. The plot is greyed: it no
 * longer shows what the inputs ask for.
 */
export function engineErrors(fieldsByPath: Record<string, ShowsError>, machine: MachineSection) {
  return (err: unknown, target: HTMLElement) => {
    const e = showAtField(err, fieldsByPath, machine);
    // A message about the machine as a whole ("machine: ZONE II-1: outside the travel …") goes
    // over the plot without its path.
    if (e) note(target, e.field === 'machine' ? e.text : e.message);
    stale(target, true, e ? 'Showing the last valid result; the engine refused the inputs (see the message).' : undefined);
  };
}
