// The printed report (the browser's print, or "Save as PDF"), of the whole machine or of the open
// study (the *Report header* menu's choice):
// - the machine's report: the header (who, what, when, where the inputs come from; no tolerance
//   of its own), a table of every study that gives a verdict (its tolerance, its value, its
//   badge), the overall verdict (the worst), why studies that disagree do so, the machine, then
//   each study's section;
// - one study's report: the header, a line saying which other studies exist, the machine and
//   the study's section.
// A study's section holds its verdict with its tolerance beside the badge, a compact table of
// its inputs in place of the form (entered values only: no empty field, no internal name, the
// verdict's tolerance not repeated), its key numbers and its plots at the width of the page;
// headings with nothing under them are left out. The report ends with a line to sign.
import { el, fields } from './fields';
import { reportHeader, reportSummary, signatureBlock, type Study } from './report';
import type { Layout } from 'plotly.js';
import { drawWaiting, loadPlotly } from './plot';
import { idle } from '../engine/idle';

/** Width and height of a plot on an A4 or Letter page (CSS pixels, inside default margins). */
const PRINT_WIDTH = 680;
const PRINT_HEIGHT = 330;

interface Graph extends HTMLElement {
  layout?: { width?: number; height?: number };
}

export type PrintScope = 'machine' | 'study';

export interface PrintHooks {
  /** The open study. */
  active(): Study | null;
  /** Every study, each mounted (its panel computed) before this resolves. */
  all(): Promise<Study[]>;
  /** What the report covers. */
  scope(): PrintScope;
}

let printing = false;
/** What was added for print, removed afterwards. */
const added: HTMLElement[] = [];
let printedSections: HTMLElement[] = [];

/** The label of a field as printed, or null when it has none a reader would understand. */
function fieldLabel(root: HTMLElement, id: string, control: HTMLElement): string | null {
  const label = root.querySelector(`label[for="${id}"]`)?.textContent?.trim();
  // A field of one item of a list (a ball-bar test) is named with its item ("Test 2: Bar length").
  const item = control.closest('.test-card')?.querySelector('legend')?.textContent?.trim();
  if (label) return item ? `${item}: ${label}` : label;
  const aria = control.getAttribute('aria-label')?.trim();
  if (aria) return aria;
  // A group of choices (the errors to fit): its legend.
  const legend = control.closest('fieldset')?.querySelector(':scope > legend')?.textContent?.trim();
  return legend || null;
}

/** Whether the group holding `control` waits for data the user has not given (an identification
 *  without a measurement): its settings are then not printed. */
function waitsForData(control: HTMLElement): boolean {
  const group = control.closest('fieldset');
  if (!group) return false;
  const areas = [...group.querySelectorAll('textarea')];
  return areas.length > 0 && areas.every((a) => a.value.trim() === '');
}

/** One row per input entered in `root`: its label, its value as shown, its unit. */
export function inputRows(root: HTMLElement, prefix: string): [string, string][] {
  const rows: [string, string][] = [];
  const seen = new Set<string>();
  for (const f of fields.values()) {
    // The machine's error motions are entered on the Volumetric panel: printed with its inputs.
    const motion = f.id.startsWith('m-motions-');
    if (!(f.id.startsWith(`${prefix}-`) || motion) || !root.contains(f.control)) continue;
    // Hidden inside the study (a field that does not apply); the study's own section may be
    // hidden on screen when the machine's report prints it.
    const hidden = f.control.closest('[hidden]');
    if (hidden && hidden !== root) continue;
    // A verdict's tolerance is printed beside its verdict, nowhere else.
    if (f.control.closest('.verdict')) continue;
    if (waitsForData(f.control)) continue;
    // Of the machine's errors and error motions only those entered.
    if ((f.id.startsWith('m-errors-') || motion) && Number(f.text()) === 0) continue;
    const label = fieldLabel(root, f.id, f.control);
    if (!label) continue;
    const c = f.control;
    let value: string;
    if (c instanceof HTMLSelectElement) value = c.selectedOptions[0]?.textContent ?? c.value;
    else if (c instanceof HTMLInputElement && c.type === 'checkbox') value = c.checked ? 'yes' : 'no';
    else if (c instanceof HTMLTextAreaElement) {
      const lines = c.value.split('\n').filter((l) => l.trim() !== '').length;
      if (!lines) continue;
      // A one-line field (a name) prints its text; a file's text, how much there is.
      value = c.rows === 1 ? c.value.trim() : `${lines} line${lines === 1 ? '' : 's'} of data`;
    } else if (c.closest('fieldset.names')) {
      // A group of names to choose from (the errors to fit): empty is all of them.
      value = c.value.trim() === '' ? 'all' : c.value.split(',').join(', ');
    } else {
      const unit = c.closest('.field-row')?.querySelector('.unit')?.textContent ?? '';
      // An empty optional field prints what it stands for (its placeholder says so); an empty
      // field that stands for nothing is not printed.
      if (c.value.trim() === '') {
        if (!c.placeholder) continue;
        value = `(${c.placeholder})`;
      } else value = `${c.value}${unit ? ` ${unit}` : ''}`;
    }
    if (seen.has(label + value)) continue;
    seen.add(label + value);
    rows.push([label, value]);
  }
  return rows;
}

/** The machine: its summary and its inputs (the errors entered among them). */
function machineBlock(): HTMLElement {
  const box = el('section', { class: 'report-machine', 'aria-hidden': 'true' });
  const root = document.getElementById('machine');
  const dl = el('dl');
  if (root) for (const [k, v] of inputRows(root, 'm')) dl.append(el('dt', {}, k), el('dd', {}, v));
  const summary = document.getElementById('machine-summary')?.textContent ?? 'Machine';
  box.append(el('h3', {}, summary), dl);
  return box;
}

/** Hides, for print, headings with nothing under them and plots never drawn. */
function markEmpty(section: HTMLElement) {
  for (const wrap of section.querySelectorAll<HTMLElement>('.plot-wrap')) {
    const plot = wrap.querySelector('.plot');
    if (plot && !plot.hasAttribute('data-plotted')) wrap.classList.add('print-empty');
  }
  for (const h of section.querySelectorAll<HTMLElement>('.results > h3')) {
    let empty = true;
    for (let n = h.nextElementSibling as HTMLElement | null; n && !/^H[1-3]$/.test(n.tagName); n = n.nextElementSibling as HTMLElement | null) {
      if (n.hidden || n.classList.contains('print-empty') || n.tagName === 'DETAILS') continue;
      const drawn = n.querySelector('.plot[data-plotted]') || (n.classList.contains('plot') && n.hasAttribute('data-plotted'));
      // Hints for the user on screen ("paste a measurement file") are not results.
      const copy = n.cloneNode(true) as HTMLElement;
      for (const hint of copy.querySelectorAll('.field-hint, [hidden]')) hint.remove();
      const text = copy.classList.contains('field-hint') ? '' : (copy.textContent ?? '').trim();
      if (drawn || text !== '') {
        empty = false;
        break;
      }
    }
    if (empty) h.classList.add('print-empty');
  }
}

/** The study's own inputs, above its results. */
function studyInputs(study: Study, withMachine: boolean): HTMLElement {
  const box = el('section', { class: 'print-inputs', 'aria-hidden': 'true' });
  if (withMachine) box.append(machineBlock());
  const rows = inputRows(study.section, study.prefix);
  if (rows.length) {
    const dl = el('dl');
    for (const [k, v] of rows) dl.append(el('dt', {}, k), el('dd', {}, v));
    box.append(el('h3', {}, 'Inputs'), dl);
  }
  return box;
}

/** Waits until the page has computed and drawn everything it was asked (at most `ms`). */
async function settled(ms = 60_000) {
  const end = performance.now() + ms;
  // Two idle looks a frame apart: a result's callbacks may start a plot just after a call ends.
  let calm = 0;
  while (calm < 2 && performance.now() < end) {
    await new Promise((r) => setTimeout(r, 50));
    calm = idle() ? calm + 1 : 0;
  }
}

function add(parent: Element, child: HTMLElement, where: 'prepend' | 'append' | 'before' = 'append') {
  if (where === 'prepend') parent.prepend(child);
  else if (where === 'before') parent.before(child);
  else parent.append(child);
  added.push(child);
}

async function enter(hooks: PrintHooks) {
  if (printing) return;
  printing = true;
  document.body.dataset.report = 'preparing';
  const scope = hooks.scope();
  const open = hooks.active();
  const studies = scope === 'machine' ? await hooks.all() : open ? [open] : [];
  await settled();
  if (!printing) return;
  const judged = studies.filter((s) => /^(pass|fail)$/.test(s.section.querySelector<HTMLElement>('.results > .verdict')?.dataset.verdict ?? ''));
  const printed = scope === 'machine' ? judged : studies;
  const panels = document.getElementById('panels');
  if (!panels) return;
  const front = el('div', { class: 'report-front', 'aria-hidden': 'true' });
  const title = scope === 'machine' ? 'Machine accuracy report' : `Machine accuracy report: ${open?.title ?? ''}`;
  front.append(reportHeader(title));
  if (scope === 'machine') {
    front.append(reportSummary(judged), machineBlock());
  } else if (open) {
    front.append(el('p', { class: 'report-scope' }, `This report covers one study, ${open.title}. The machine’s report (Report header → “Every study”) gives every study’s verdict side by side.`));
  }
  add(panels, front, 'before');
  document.body.classList.add('printing', `print-${scope}`);
  printedSections = printed.map((s) => s.section);
  for (const s of printed) s.section.classList.add('report-study');
  // The plots of the studies on other tabs, kept until shown (ui/plot.ts), drawn for the page
  // before a plot never drawn is marked empty.
  await Promise.all(printed.map((s) => drawWaiting(s.section)));
  // Printing ended meanwhile (`leave` has run): nothing more to add.
  if (!printing) return;
  for (const s of printed) {
    add(s.section, studyInputs(s, scope === 'study'), 'before');
    // The inputs go under the study's heading and lead.
    const grid = s.section.querySelector('.panel-grid');
    if (grid) grid.before(added[added.length - 1]);
    markEmpty(s.section);
  }
  const sign = signatureBlock();
  sign.setAttribute('aria-hidden', 'true');
  add(panels, sign, 'append');
  const P = await loadPlotly();
  const graphs = printed.flatMap((s) => [...s.section.querySelectorAll<Graph>('.js-plotly-plot')]);
  // At the page's width; as tall as the panel made its box (a budget of three bars is short),
  // else the default: a plot taller than its box would run over what follows.
  await Promise.all(graphs.map((g) => P.relayout(g, { width: PRINT_WIDTH, height: parseFloat(g.style.height) || PRINT_HEIGHT })));
  document.body.dataset.report = 'ready';
}

async function leave() {
  if (!printing) return;
  printing = false;
  for (const a of added.splice(0)) a.remove();
  document.body.classList.remove('printing', 'print-machine', 'print-study');
  delete document.body.dataset.report;
  const sections = printedSections;
  printedSections = [];
  for (const s of sections) {
    s.classList.remove('report-study');
    for (const e of s.querySelectorAll('.print-empty')) e.classList.remove('print-empty');
  }
  const P = await loadPlotly();
  const graphs = sections.flatMap((s) => [...s.querySelectorAll<Graph>('.js-plotly-plot')]);
  // Back to the size of the container (null removes the fixed size).
  await Promise.all(graphs.map((g) => P.relayout(g, { width: null, height: null } as unknown as Partial<Layout>)));
}

/**
 * Prepares the report around the browser's print (window.print, Ctrl+P, or a headless PDF
 * export that switches the media to print).
 */
export function setupPrint(hooks: PrintHooks) {
  window.addEventListener('beforeprint', () => void enter(hooks));
  window.addEventListener('afterprint', () => void leave());
  window.matchMedia('print').addEventListener('change', (e) => void (e.matches ? enter(hooks) : leave()));
}

/** Prepares the report and opens the browser's print dialog. */
export async function printReport(hooks: PrintHooks) {
  await enter(hooks);
  window.print();
}
