// The printable report of a panel (the browser's print, or "Save as PDF"): the report's header
// (company, customer, machine, serial number, operator, date, the panel's tolerance and verdict;
// see report.ts), a compact table of the panel's inputs in place of the form, the key numbers,
// every plot redrawn at the width of the printed page (Plotly sizes plots for the screen, so
// they would be cut off on paper), and a line to sign.
import { el, fields } from './fields';
import { reportHeader, signatureBlock } from './report';
import type { Layout } from 'plotly.js';
import { loadPlotly } from './plot';

/** Width and height of a plot on an A4 or Letter page (CSS pixels, inside default margins). */
const PRINT_WIDTH = 680;
const PRINT_HEIGHT = 330;

interface Graph extends HTMLElement {
  layout?: { width?: number; height?: number };
}

let printing = false;

/** One row per input of the panel: its label, its value as shown, its unit. */
function inputRows(section: HTMLElement, prefix: string): [string, string][] {
  const rows: [string, string][] = [];
  for (const f of fields.values()) {
    // The machine's error motions are entered on the Volumetric panel: printed with its inputs.
    const motion = f.id.startsWith('m-motions-');
    if (!(f.id.startsWith(`${prefix}-`) || motion) || !section.contains(f.control) || f.control.closest('[hidden]')) continue;
    // Of the machine's errors and error motions only those entered.
    if ((f.id.startsWith('m-errors-') || motion) && Number(f.text()) === 0) continue;
    const label = section.querySelector(`label[for="${f.id}"]`)?.textContent?.trim() ?? f.id;
    const c = f.control;
    let value: string;
    if (c instanceof HTMLSelectElement) value = c.selectedOptions[0]?.textContent ?? c.value;
    else if (c instanceof HTMLInputElement && c.type === 'checkbox') value = c.checked ? 'yes' : 'no';
    else if (c instanceof HTMLTextAreaElement) {
      const lines = c.value.split('\n').filter((l) => l.trim() !== '').length;
      value = `${lines} line${lines === 1 ? '' : 's'} of data`;
    } else {
      const unit = c.closest('.field-row')?.querySelector('.unit')?.textContent ?? '';
      // An empty optional field prints what it stands for (its placeholder says so), not a
      // bare unit.
      if (c.value.trim() === '') value = c.placeholder ? `(${c.placeholder})` : '(empty)';
      else value = `${c.value}${unit ? ` ${unit}` : ''}`;
    }
    rows.push([label, value]);
  }
  return rows;
}

async function enter(section: HTMLElement, prefix: string) {
  if (printing) return;
  printing = true;
  for (const old of section.querySelectorAll(':scope > :is(.print-inputs, .report-header, .report-signature)')) old.remove();
  // The report's header first, above the panel's heading.
  const header = reportHeader(section, prefix, section.querySelector('h2')?.textContent ?? '');
  header.setAttribute('aria-hidden', 'true');
  section.prepend(header);
  const box = el('section', { class: 'print-inputs', 'aria-hidden': 'true' });
  const dl = el('dl');
  for (const [k, v] of inputRows(section, prefix)) dl.append(el('dt', {}, k), el('dd', {}, v));
  // The machine the panel computed for (the Machine section is not printed).
  const machineRoot = document.getElementById('machine');
  const mdl = el('dl');
  if (machineRoot) for (const [k, v] of inputRows(machineRoot, 'm')) mdl.append(el('dt', {}, k), el('dd', {}, v));
  const summary = document.getElementById('machine-summary')?.textContent ?? 'Machine';
  box.append(el('h3', {}, summary), mdl, el('h3', {}, 'Inputs'), dl, el('p', {}, `Printed ${new Date().toLocaleString()} from ${location.href.split('#')[0]}`));
  section.querySelector('.panel-grid')?.before(box);
  const sign = signatureBlock();
  sign.setAttribute('aria-hidden', 'true');
  section.append(sign);
  const P = await loadPlotly();
  const graphs = [...section.querySelectorAll<Graph>('.js-plotly-plot')];
  await Promise.all(graphs.map((g) => P.relayout(g, { width: PRINT_WIDTH, height: PRINT_HEIGHT })));
}

async function leave(section: HTMLElement) {
  if (!printing) return;
  printing = false;
  for (const old of section.querySelectorAll(':scope > :is(.print-inputs, .report-header, .report-signature)')) old.remove();
  const P = await loadPlotly();
  const graphs = [...section.querySelectorAll<Graph>('.js-plotly-plot')];
  // Back to the size of the container (null removes the fixed size).
  await Promise.all(graphs.map((g) => P.relayout(g, { width: null, height: null } as unknown as Partial<Layout>)));
}

/**
 * Prepares the open panel for printing around the browser's print (window.print, Ctrl+P, or a
 * headless PDF export that switches the media to print). `active()` gives the open panel's
 * section and field prefix.
 */
export function setupPrint(active: () => { section: HTMLElement; prefix: string } | null) {
  const on = () => {
    const a = active();
    if (a) return enter(a.section, a.prefix);
  };
  const off = () => {
    const a = active();
    if (a) return leave(a.section);
  };
  window.addEventListener('beforeprint', () => void on());
  window.addEventListener('afterprint', () => void off());
  window.matchMedia('print').addEventListener('change', (e) => void (e.matches ? on() : off()));
}

/** Prepares the open panel for print and opens the browser's print dialog. */
export async function printReport(active: () => { section: HTMLElement; prefix: string } | null) {
  const a = active();
  if (a) await enter(a.section, a.prefix);
  window.print();
}
