// The printed report's header: who measured what for whom (company, customer, machine, serial
// number, operator, date), entered once in the toolbar's *Report header* and kept with the page
// state (fields `rp-…`: saved inputs, saved cases and share links carry them). In print: the
// header as a table with the panel's tolerance (its field whose id ends in `-tolerance`), the
// panel's verdict (its `.verdict` section) and, at the end, a line to sign.
import { el, fields } from './fields';

/** The header's fields: id, label, input type. */
export const REPORT_FIELDS: { id: string; label: string; type: 'text' | 'date' }[] = [
  { id: 'rp-company', label: 'Company', type: 'text' },
  { id: 'rp-customer', label: 'Customer', type: 'text' },
  { id: 'rp-machine', label: 'Machine', type: 'text' },
  { id: 'rp-serial', label: 'Serial number', type: 'text' },
  { id: 'rp-operator', label: 'Operator', type: 'text' },
  { id: 'rp-date', label: 'Date', type: 'date' },
];

/** The toolbar's *Report header* menu; its fields register with the page state. */
export function reportMenu(): HTMLElement {
  const details = el('details', { class: 'report-menu tool', id: 'report-menu' });
  const summary = el('summary', {}, 'Report header');
  const body = el('div', { class: 'report-body' });
  body.append(el('p', { class: 'field-hint' }, 'Printed at the top of the report; kept with saved cases and share links.'));
  for (const f of REPORT_FIELDS) {
    const label = el('label', { for: f.id }, f.label);
    const input = el('input', { id: f.id, name: f.id, type: f.type, autocomplete: 'off', maxlength: '120' });
    body.append(label, input);
    fields.set(f.id, {
      id: f.id,
      control: input,
      text: () => input.value,
      defaultText: () => '',
      setText: (t) => {
        input.value = t;
        input.dispatchEvent(new Event('input', { bubbles: true }));
      },
      setBase: (v) => {
        input.value = String(v);
        input.dispatchEvent(new Event('input', { bubbles: true }));
      },
    });
  }
  details.append(summary, body);
  return details;
}

/** A value as printed: the text, or a line to fill in by hand when empty. */
function value(text: string): HTMLElement {
  return text.trim() ? el('span', {}, text.trim()) : el('span', { class: 'blank' }, '');
}

/** The date as printed: the one entered, else today's (YYYY-MM-DD, as a date field gives it). */
function reportDate(): string {
  const entered = fields.get('rp-date')?.text().trim();
  if (entered) return entered;
  const d = new Date();
  return `${d.getFullYear()}-${String(d.getMonth() + 1).padStart(2, '0')}-${String(d.getDate()).padStart(2, '0')}`;
}

/** The panel's tolerance as shown (value and unit), from its field whose id ends in `-tolerance`. */
function tolerance(section: HTMLElement, prefix: string): string | null {
  for (const f of fields.values()) {
    if (!f.id.startsWith(`${prefix}-`) || !f.id.endsWith('-tolerance') || !section.contains(f.control)) continue;
    if (f.control.closest('[hidden]')) continue;
    const unit = f.control.closest('.field-row')?.querySelector('.unit')?.textContent ?? '';
    const text = f.text().trim();
    return text ? `${text}${unit ? ` ${unit}` : ''}` : null;
  }
  return null;
}

/** The report's header for the open panel: the title, the header table, the verdict. */
export function reportHeader(section: HTMLElement, prefix: string, study: string): HTMLElement {
  const box = el('div', { class: 'report-header' });
  box.append(el('h2', { class: 'report-title' }, `Machine accuracy report: ${study}`));
  const table = el('table', { class: 'report-table' });
  const rows: [string, string][] = REPORT_FIELDS.map((f) => [f.label, f.id === 'rp-date' ? reportDate() : (fields.get(f.id)?.text() ?? '')]);
  const tol = tolerance(section, prefix);
  if (tol !== null) rows.push(['Tolerance', tol]);
  for (let i = 0; i < rows.length; i += 2) {
    const tr = el('tr');
    for (const [k, v] of rows.slice(i, i + 2)) {
      const td = el('td');
      td.append(value(v));
      tr.append(el('th', { scope: 'row' }, k), td);
    }
    table.append(tr);
  }
  box.append(table);
  // The verdict the panel gives (its `.verdict` section), copied to the top without its ids.
  const verdict = section.querySelector<HTMLElement>('.results .verdict');
  if (verdict) {
    const copy = verdict.cloneNode(true) as HTMLElement;
    for (const e of [copy, ...copy.querySelectorAll<HTMLElement>('[id]')]) e.removeAttribute('id');
    // Its tolerance field is in the table above (a cloned input would show its default).
    for (const e of copy.querySelectorAll('.verdict-tolerance')) e.remove();
    copy.classList.add('report-verdict');
    box.append(el('h3', {}, 'Verdict'), copy);
  }
  return box;
}

/** The line to sign at the end of the report. */
export function signatureBlock(): HTMLElement {
  const box = el('div', { class: 'report-signature' });
  for (const k of ['Checked by', 'Date', 'Signature']) {
    const cell = el('div', { class: 'sign-cell' });
    cell.append(el('div', { class: 'sign-line' }), el('div', { class: 'sign-label' }, k));
    box.append(cell);
  }
  return box;
}
