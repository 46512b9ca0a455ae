// What stops a result: the fields whose text is not acceptable now, named with where they are
// (this panel, or the Machine section above it), and a way to reach each one. A verdict or a
// greyed plot never says "fix the field marked in red" without saying which field that is; when
// no field is marked, it does not say that at all.
import { el } from './fields';

/** A field whose text is not acceptable now. */
export interface Invalid {
  /** The control's element id. */
  id: string;
  /** Its label as shown ("L", "Tolerance"). */
  label: string;
  /** Where it is: "Machine section" or "<tab> tab". */
  where: string;
  /** The message at the field. */
  message: string;
}

/** The label of a field's control, as shown, without its unit's decoration. */
function labelOf(control: HTMLElement): string {
  const byFor = control.id ? document.querySelector<HTMLLabelElement>(`label[for="${CSS.escape(control.id)}"]`) : null;
  const label = byFor ?? control.closest('.field')?.querySelector('label') ?? control.closest('label');
  return (label?.textContent ?? control.getAttribute('aria-label') ?? control.id).trim().replace(/\s+/g, ' ');
}

/**
 * The invalid fields the results of the panel holding `from` depend on: those of that panel and
 * of the Machine section (those in a part of the section hidden for this machine aside).
 */
export function invalidFields(from: HTMLElement): Invalid[] {
  const panel = from.closest<HTMLElement>('.panel');
  const roots: [HTMLElement, string][] = [];
  if (panel) roots.push([panel, `${document.getElementById(`tab-${panel.id.replace(/^panel-/, '')}`)?.textContent?.trim() ?? 'this'} tab`]);
  const machine = document.getElementById('machine');
  if (machine) roots.push([machine, 'Machine section']);
  const out: Invalid[] = [];
  for (const [root, where] of roots) {
    for (const control of root.querySelectorAll<HTMLElement>('[aria-invalid="true"]')) {
      const hidden = control.closest('[hidden]');
      if (hidden && hidden !== root && root.contains(hidden)) continue;
      const message = control.closest('.field')?.querySelector('.field-msg')?.textContent?.trim() ?? '';
      out.push({ id: control.id, label: labelOf(control), where, message });
    }
  }
  return out;
}

/** "L (Machine section): must be greater than 0" for each, joined; "" for none. */
export function invalidWords(list: Invalid[]): string {
  const words = (m: string) => (/^[A-Z][a-z]/.test(m) ? m[0].toLowerCase() + m.slice(1) : m).replace(/\.$/, '');
  return list.map((f) => `${f.label} (${f.where})${f.message ? `: ${words(f.message)}` : ''}`).join('; ');
}

/** What a result that cannot be computed says: the fields to fix, or `otherwise` when none is
 *  marked (an input still missing, say). */
export function blockedBy(list: Invalid[], otherwise: string): string {
  return list.length ? `fix ${invalidWords(list)}` : otherwise;
}

/**
 * Brings the field `id` into view and focus: its panel's tab selected, every folded section
 * around it opened.
 */
export function goTo(id: string) {
  const control = document.getElementById(id);
  if (!control) return;
  const panel = control.closest<HTMLElement>('.panel');
  if (panel?.hidden) document.getElementById(`tab-${panel.id.replace(/^panel-/, '')}`)?.click();
  for (let d = control.closest('details'); d; d = d.parentElement?.closest('details') ?? null) d.open = true;
  control.scrollIntoView({ block: 'center' });
  control.focus({ preventScroll: true });
}

/** A line of buttons, one per invalid field, each going to its field ("Go to: L · Tolerance"). */
export function fieldLinks(list: Invalid[]): HTMLElement {
  const p = el('p', { class: 'field-links' }, list.length ? 'Go to: ' : '');
  list.forEach((f, i) => {
    const b = el('button', { type: 'button', class: 'link', 'data-go': f.id, title: `${f.where}: ${f.message}` }, f.label);
    b.addEventListener('click', () => goTo(f.id));
    p.append(...(i ? [' · ', b] : [b]));
  });
  return p;
}
