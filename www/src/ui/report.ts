// The printed report's header: who measured what for whom (company, customer, machine, serial
// number, operator, date), entered once in the toolbar's *Report header* and kept with the page
// state (fields `rp-…`: saved inputs, saved cases and share links carry them). In print: the
// header as a table (no tolerance: each study's is printed beside its verdict), where the inputs
// come from, the studies' verdicts side by side (reportSummary) and, at the end, a line to sign.
import { el, fields } from './fields';
import { show } from './units';
import { listWords } from './verdict';

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
  // What the printed report covers: every study of the machine, or the open one.
  const scopeLabel = el('label', { for: 'rp-scope' }, 'The report covers');
  const scope = el('select', { id: 'rp-scope', name: 'rp-scope' });
  scope.append(el('option', { value: 'machine' }, 'Every study of the machine'), el('option', { value: 'study' }, 'The open study only'));
  body.append(scopeLabel, scope);
  fields.set('rp-scope', {
    id: 'rp-scope',
    control: scope,
    text: () => scope.value,
    defaultText: () => 'machine',
    setText: (t) => {
      scope.value = t === 'study' ? 'study' : 'machine';
      scope.dispatchEvent(new Event('input', { bubbles: true }));
    },
    setBase: (v) => {
      scope.value = v === 'study' ? 'study' : 'machine';
      scope.dispatchEvent(new Event('input', { bubbles: true }));
    },
  });
  scope.addEventListener('change', () => scope.dispatchEvent(new Event('input', { bubbles: true })));
  details.append(summary, body);
  return details;
}

/** What the printed report covers (the *Report header* menu's choice). */
export function reportScope(): 'machine' | 'study' {
  return fields.get('rp-scope')?.text() === 'study' ? 'study' : 'machine';
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

/** A study the report can print: its panel's id, title, field prefix and section. */
export interface Study {
  id: string;
  title: string;
  prefix: string;
  section: HTMLElement;
}

/** Where the inputs come from, in words. */
function provenance(): string {
  const machine = document.getElementById('machine-summary')?.textContent?.trim();
  const from = document.body.dataset.link === 'opened' ? 'opened from a shared link' : 'entered on this page';
  return `Inputs: ${machine ? `${machine}; ` : ''}${from}, as the page showed them when printed (${new Date().toLocaleString()}, ${location.href.split('#')[0]}).`;
}

/** The report's header: the title, who and what (no tolerance: each is beside its verdict),
 *  where the inputs come from. */
export function reportHeader(title: string): HTMLElement {
  const box = el('div', { class: 'report-header' });
  box.append(el('h2', { class: 'report-title' }, title));
  const table = el('table', { class: 'report-table' });
  const rows: [string, string][] = REPORT_FIELDS.map((f) => [f.label, f.id === 'rp-date' ? reportDate() : (fields.get(f.id)?.text() ?? '')]);
  for (let i = 0; i < rows.length; i += 2) {
    const tr = el('tr');
    for (const [k, v] of rows.slice(i, i + 2)) {
      const td = el('td');
      td.append(value(v));
      tr.append(el('th', { scope: 'row' }, k), td);
    }
    table.append(tr);
  }
  box.append(table, el('p', { class: 'report-provenance' }, provenance()));
  return box;
}

interface Judged {
  study: Study;
  status: 'pass' | 'fail';
  worst: number;
  tolerance: number;
  /** What worst and tolerance are (a small length, or a small angle for a rotary axis). */
  quantity: 'errLength' | 'errAngle';
  what: string;
  /** The sentence naming the errors entered this study cannot see, or null. */
  unseen: string | null;
  /** The names of the errors entered it cannot see. */
  hidden: string[];
  /** Whether the study says which errors it sees ("all", "some") or not (undefined). */
  sees?: string;
  /** The errors this study blames (its contributors). */
  blamed: string[];
}

function judgedOf(study: Study): Judged | null {
  const v = study.section.querySelector<HTMLElement>('.results > .verdict');
  const status = v?.dataset.verdict;
  if (!v || (status !== 'pass' && status !== 'fail')) return null;
  return {
    study,
    status,
    worst: Number(v.dataset.worst),
    tolerance: Number(v.dataset.tolerance),
    quantity: v.dataset.quantity === 'errAngle' ? 'errAngle' : 'errLength',
    what: v.dataset.what ?? ((v.querySelector('.verdict-tolerance label')?.textContent?.trim() ?? '').replace(/^Tolerance on\s+/, '') || 'its result'),
    hidden: (v.dataset.unseen ?? '').split(' ').filter(Boolean),
    sees: v.dataset.sees,
    unseen: v.querySelector('.verdict-unseen')?.textContent?.trim() ?? null,
    blamed: [...v.querySelectorAll<HTMLElement>('.verdict-contrib li[data-name]')].map((li) => li.dataset.name ?? ''),
  };
}

/** The studies' verdicts side by side (each with its own tolerance), the overall verdict (the
 *  worst) and, where some pass and others fail, why. */
export function reportSummary(studies: Study[]): HTMLElement {
  const box = el('section', { class: 'report-summary' });
  const judged = studies.map(judgedOf).filter((j): j is Judged => j !== null);
  box.append(el('h3', {}, 'Verdicts'));
  const table = el('table', { class: 'report-verdicts' });
  const head = el('tr');
  for (const h of ['Study', 'What is judged', 'Value', 'Tolerance', 'Verdict']) head.append(el('th', { scope: 'col' }, h));
  table.append(el('thead'), el('tbody'));
  table.tHead!.append(head);
  for (const j of judged) {
    const tr = el('tr', { 'data-study': j.study.id, 'data-verdict': j.status });
    const badge = el('span', { class: 'verdict-badge' }, j.status === 'pass' ? 'PASS' : 'FAIL');
    const cell = el('td', { class: 'report-badge' });
    cell.append(badge);
    tr.append(el('th', { scope: 'row' }, j.study.title), el('td', {}, j.what), el('td', {}, show(j.quantity, j.worst)), el('td', {}, show(j.quantity, j.tolerance)), cell);
    table.tBodies[0].append(tr);
  }
  box.append(table);
  const failing = judged.filter((j) => j.status === 'fail');
  const passing = judged.filter((j) => j.status === 'pass');
  const overall = !judged.length ? 'none' : failing.length ? 'fail' : 'pass';
  const verdict = el('div', { class: 'report-overall verdict', 'data-verdict': overall });
  const badge = el('span', { class: 'verdict-badge' }, overall === 'pass' ? 'PASS' : overall === 'fail' ? 'FAIL' : 'NO VERDICT');
  const names = (js: Judged[]) => listWords(js.map((j) => j.study.title));
  const sentence = !judged.length
    ? 'No study gives a verdict for these inputs.'
    : failing.length
      ? `Overall: the machine fails ${names(failing)} (${failing.length} of ${judged.length} studies), the worst of its verdicts.`
      : `Overall: the machine passes every study that gives a verdict (${judged.length}).`;
  verdict.append(badge, el('p', { class: 'verdict-sentence' }, sentence));
  box.append(verdict);
  // Where studies disagree: what the passing ones cannot see.
  if (failing.length && passing.length) {
    const ul = el('ul', { class: 'report-disagree' });
    for (const p of passing) {
      let why: string;
      if (p.unseen) {
        // The failing studies that blame what this one cannot see.
        const counted = failing.map((f) => [f, p.hidden.filter((n) => f.blamed.includes(n))] as const).filter(([, c]) => c.length);
        why = `${p.unseen}${counted.map(([f, c]) => ` ${f.study.title} counts ${listWords(c)}.`).join('')}`;
      } else if (p.sees === 'all') {
        why = `It sees every error entered; it judges another quantity (${p.what}) against its own tolerance.`;
      } else {
        why = `It judges another quantity (${p.what}) against its own tolerance.`;
      }
      ul.append(el('li', {}, `${p.study.title} passes while ${names(failing)} fail${failing.length === 1 ? 's' : ''}. ${why}`));
    }
    box.append(ul);
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
