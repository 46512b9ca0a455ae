// The page shell: one tab per study (each panel is mounted when first opened, and drawn only
// while shown: a plot asked for behind another tab waits for its tab, ui/plot.ts), the unit
// preferences, and the page state: share link, inputs kept across reloads, reset, named cases.
import './style.css';
import type { Panel } from './panels/panel';
import { nonlinearPanel } from './panels/nonlinear';
import { cubicPanel } from './panels/cubic';
import { sshapePanel } from './panels/sshape';
import { toolpathPanel } from './panels/toolpath';
import { volumetricPanel } from './panels/volumetric';
import { reversalPanel } from './panels/reversal';
import { probePanel } from './panels/probe';
// ball-bar and laser
import { ballbarPanel } from './panels/ballbar';
import { ballbarRotaryPanel } from './panels/ballbar-rotary';
import { positioningPanel } from './panels/positioning';
import { el } from './ui/fields';
import { encodingNote, FileRefused, readTextFile } from './ui/files';
import { keepOnScreen } from './ui/popup';
import { download } from './ui/export';
import { ANGLE_UNITS, LENGTH_UNITS, onUnitsChange, setUnits, units, type AngleUnit, type LengthUnit } from './ui/units';
import * as state from './ui/state';
import { DEFAULT_UNITS } from './ui/units';
import { debounced, track } from './engine/idle';
import { excerpt } from './ui/format';
import { printReport, setupPrint } from './ui/print';
import { drawWaiting, fitWidths } from './ui/plot';
import { reportMenu, reportScope, type Study } from './ui/report';
import { DRAWING_PREFIX, MACHINE_PREFIX, mountMachine, type MachineSection } from './machine/section';

const panels: Panel[] = [
  nonlinearPanel, cubicPanel, sshapePanel, toolpathPanel, volumetricPanel, reversalPanel, probePanel,
  // ball-bar and laser
  ballbarPanel, ballbarRotaryPanel, positioningPanel,
];
let machine: MachineSection | null = null;

const mounted = new Map<string, HTMLElement>();
let active = panels[0].id;
let restoring = false;

interface BannerAction {
  label: string;
  run: () => void | Promise<void>;
}
/** The message at the top of the page (and its one button), or none. */
let shown: { text: string; action?: BannerAction } | null = null;
function banner(text: string | null, action?: BannerAction) {
  shown = text ? { text, action } : null;
  const b = document.getElementById('banner');
  if (!b) return;
  b.hidden = !text;
  b.querySelector('.banner-text')!.textContent = text ?? '';
  const button = document.getElementById('banner-action');
  if (button) {
    button.hidden = !action;
    button.textContent = action?.label ?? '';
  }
}

/** Settings of the state last restored that this version does not know: the machine's and each
 *  panel's (applied when it mounts), named together, after the message about the link. */
const ignored: string[] = [];
let linkMessage: { text: string; action?: BannerAction } | null = null;
function ignoredSettings(ids: string[]) {
  if (!ids.length) return;
  ignored.push(...ids);
  const lead = linkMessage ? `${linkMessage.text} ` : '';
  banner(`${lead}This link has settings this version does not know; they were ignored: ${ignored.map((i) => excerpt(i)).join(', ')}.`, linkMessage?.action);
}

// ---- saving the state (URL fragment and local storage), a moment after the last change
const saveLater = debounced(() => void track(saveNow()), 250);
function scheduleSave() {
  if (restoring) return;
  saveLater();
}
/** The fragment the page itself last wrote: a change to another one is a link opened. */
let written = '';
async function saveNow() {
  saveLater.cancel();
  const s = state.capture(active);
  state.saveLocal(s);
  const fragment = await state.encode(s);
  written = `#${fragment}`;
  history.replaceState(null, '', written);
  document.body.dataset.saved = String(Number(document.body.dataset.saved ?? 0) + 1);
}

// ---- opening a link: never over the user's own inputs
/** Whether two states hold the same inputs and units (the open panel aside). */
function sameInputs(a: state.PageState, b: state.PageState): boolean {
  const key = (s: state.PageState) => JSON.stringify([s.u.length, s.u.angle, Object.entries(s.f).sort(([x], [y]) => x.localeCompare(y))]);
  return key(a) === key(b);
}
/** Whether a state holds anything the user entered (inputs or units other than the defaults). */
function hasWork(s: state.PageState): boolean {
  return Object.keys(s.f).length > 0 || s.u.length !== DEFAULT_UNITS.length || s.u.angle !== DEFAULT_UNITS.angle;
}

/**
 * Opens the link `fragment` over the user's state `own` (the inputs kept in this browser, or
 * those on the page). A link that cannot be read changes nothing and says so. A readable one
 * whose inputs differ from the user's first keeps the user's as a saved case, named in the
 * message at the top, whose button brings them back.
 */
async function openLink(fragment: string, own: state.PageState | null, atStart: boolean) {
  let linked: state.PageState | null;
  try {
    linked = await state.decode(fragment);
    if (linked && !panels.some((p) => p.id === linked?.p)) {
      throw new state.StateError(`names a panel this version does not have (“${excerpt(linked.p)}”)`);
    }
  } catch (e) {
    const why = e instanceof state.StateError ? e.message : 'cannot be read';
    if (atStart) {
      if (own) await restore(own);
      else await show(panels[0].id);
    }
    await saveNow();
    linkMessage = null;
    banner(`This link could not be read: it ${why}. Nothing was changed: your inputs, units and open panel are as they were.`);
    document.body.dataset.link = 'refused';
    return;
  }
  if (!linked) {
    if (own) await restore(own);
    else await show(panels[0].id);
    return;
  }
  // Reloading the page's own address: not a link opened.
  if (own && sameInputs(own, linked) && own.p === linked.p) {
    await restore(own);
    return;
  }
  let kept: string | null = null;
  if (own && hasWork(own) && !sameInputs(own, linked)) {
    const all = state.loadCases();
    const base = `My inputs before opening a link, ${new Date().toLocaleString()}`;
    kept = base;
    for (let i = 2; kept in all; i++) kept = `${base} (${i})`;
    all[kept] = own;
    try {
      state.storeCases(all);
    } catch {
      // Storage refused: the link is not opened, the user's inputs stay on the page.
      if (atStart) await restore(own);
      await saveNow();
      banner('This link was not opened: this browser refused to keep your own inputs as a case (storage full or disabled), and opening it would replace them.');
      document.body.dataset.link = 'refused';
      return;
    }
  }
  const name = kept;
  linkMessage = name
    ? {
        text: `Opened a shared link. Your own inputs are kept as case “${name}”.`,
        action: {
          label: 'Back to my inputs',
          run: async () => {
            const c = state.loadCases()[name];
            if (!c) return banner(`The case “${name}” is no longer saved in this browser.`);
            linkMessage = null;
            await restore(c);
            banner(`Your own inputs are back (also kept as case “${name}” under Saved cases).`);
          },
        },
      }
    : { text: 'Opened a shared link.' };
  banner(linkMessage.text, linkMessage.action);
  await restore(linked);
  document.body.dataset.link = 'opened';
}

// ---- panels
async function show(id: string) {
  const panel = panels.find((p) => p.id === id) ?? panels[0];
  active = panel.id;
  const tabs = document.getElementById('tabs')!;
  for (const b of tabs.querySelectorAll<HTMLButtonElement>('button[role=tab]')) {
    const on = b.dataset.panel === panel.id;
    b.setAttribute('aria-selected', String(on));
    b.tabIndex = on ? 0 : -1;
    if (on) revealTab(tabs, b);
  }
  for (const [pid, section] of mounted) section.hidden = pid !== panel.id;
  // Its plots asked for while it was hidden, drawn now that it is shown (and any laid out at
  // another width while hidden, resized).
  const section = mounted.get(panel.id);
  if (section) void drawWaiting(section).then(() => fitWidths(section));
  await mount(panel);
  scheduleSave();
}

/** Mounts a panel once (hidden unless it is the open one); later calls wait for the first. */
const mounting = new Map<string, Promise<void>>();
function mount(panel: Panel): Promise<void> {
  let p = mounting.get(panel.id);
  if (p) return p;
  const section = el('section', { id: `panel-${panel.id}`, class: 'panel', role: 'tabpanel', 'aria-labelledby': `tab-${panel.id}` });
  section.hidden = panel.id !== active;
  // In the tabs' order, whatever order they are mounted in.
  const host = document.getElementById('panels')!;
  const after = panels.slice(panels.indexOf(panel) + 1).map((q) => mounted.get(q.id)).find((s) => s);
  host.insertBefore(section, after ?? null);
  mounted.set(panel.id, section);
  p = (async () => {
    try {
      if (!machine) throw new Error('the machine section is not ready');
      await panel.mount(section, machine);
      ignoredSettings(state.applyPending(panel.prefix));
      section.dataset.ready = 'true';
      keepFetched();
    } catch (err) {
      section.append(el('p', { class: 'warn' }, `This panel failed to load: ${String(err)}`));
      throw err;
    }
  })();
  mounting.set(panel.id, p);
  return p;
}

/** Every study, each mounted and computing (for the machine's report). */
async function allStudies(): Promise<Study[]> {
  await Promise.allSettled(panels.map((p) => mount(p)));
  return panels.filter((p) => mounted.get(p.id)?.dataset.ready === 'true')
    .map((p) => ({ id: p.id, title: p.title, prefix: p.prefix, section: mounted.get(p.id)! }));
}

/** Scrolls the tab strip (only it, never the page) so that `tab` is wholly in view. */
function revealTab(bar: HTMLElement, tab: HTMLElement) {
  const b = bar.getBoundingClientRect();
  const t = tab.getBoundingClientRect();
  // The strip's own padding kept beside the tab.
  const pad = parseFloat(getComputedStyle(bar).paddingLeft) || 0;
  if (t.left < b.left + pad) bar.scrollLeft -= b.left + pad - t.left;
  else if (t.right > b.right - pad) bar.scrollLeft += t.right - (b.right - pad);
}

function tabs() {
  const bar = document.getElementById('tabs')!;
  for (const p of panels) {
    const b = el('button', { type: 'button', id: `tab-${p.id}`, role: 'tab', 'aria-controls': `panel-${p.id}` }, p.title);
    b.dataset.panel = p.id;
    b.addEventListener('click', () => void show(p.id));
    bar.append(b);
  }
  bar.addEventListener('keydown', (e) => {
    const list = [...bar.querySelectorAll<HTMLButtonElement>('button[role=tab]')];
    const i = list.findIndex((b) => b.getAttribute('aria-selected') === 'true');
    const j = e.key === 'ArrowRight' ? (i + 1) % list.length : e.key === 'ArrowLeft' ? (i - 1 + list.length) % list.length : -1;
    if (j >= 0) {
      list[j].focus();
      void show(list[j].dataset.panel ?? '');
    }
  });
}

// ---- toolbar: units, link, reset, cases, print
function toolbar() {
  const bar = document.getElementById('toolbar')!;
  const unitSelect = (id: string, label: string, defs: Record<string, { name: string }>, value: string, onChange: (v: string) => void) => {
    const wrap = el('label', { class: 'tool', for: id }, `${label} `);
    const s = el('select', { id });
    for (const [k, d] of Object.entries(defs)) s.append(el('option', { value: k }, d.name));
    s.value = value;
    s.addEventListener('change', () => onChange(s.value));
    wrap.append(s);
    return { wrap, s };
  };
  const len = unitSelect('units-length', 'Small lengths', LENGTH_UNITS, units().length, (v) => setUnits({ length: v as LengthUnit }));
  const ang = unitSelect('units-angle', 'Small angles', ANGLE_UNITS, units().angle, (v) => setUnits({ angle: v as AngleUnit }));
  onUnitsChange((u) => {
    len.s.value = u.length;
    ang.s.value = u.angle;
    scheduleSave();
  });

  const button = (id: string, text: string, onClick: () => void, title?: string) => {
    const b = el('button', { type: 'button', id, class: 'tool' }, text);
    if (title) b.title = title;
    b.addEventListener('click', onClick);
    return b;
  };
  const linkOut = el('input', { id: 'share-link', class: 'share-link', readonly: '', 'aria-label': 'Link to this view' });
  linkOut.hidden = true;
  const copy = button('copy-link', 'Copy link', async () => {
    await saveNow();
    linkOut.value = location.href;
    linkOut.hidden = false;
    linkOut.select();
    try {
      await navigator.clipboard.writeText(location.href);
      copy.textContent = 'Link copied';
    } catch {
      copy.textContent = 'Copy the link shown';
    }
    setTimeout(() => (copy.textContent = 'Copy link'), 2500);
  }, 'A link that opens this exact view (inputs, units, panel). It is made here and sent nowhere.');
  const reset = button('reset', 'Reset to defaults', () => {
    const p = panels.find((x) => x.id === active);
    if (p) state.resetPanel(p.prefix);
    scheduleSave();
  }, 'Restore the default inputs of this panel');
  const print = button('print', 'Print report', () => void printReport(printHooks), 'The machine’s report (every study’s verdict, inputs, key numbers and plots) or the open study’s (Report header), for print or PDF');

  bar.append(len.wrap, ang.wrap, copy, reset, casesMenu(), reportMenu(), print, linkOut);
  for (const d of bar.querySelectorAll('details')) keepOnScreen(d);
}

function casesMenu(): HTMLElement {
  const details = el('details', { class: 'cases tool' });
  const summary = el('summary', {}, 'Saved cases');
  const name = el('input', { id: 'case-name', placeholder: 'Case name', 'aria-label': 'Case name', maxlength: '80' });
  const save = el('button', { type: 'button', id: 'case-save' }, 'Save');
  const list = el('ul', { id: 'case-list' });
  const msg = el('p', { class: 'field-hint', 'aria-live': 'polite' });
  const exp = el('button', { type: 'button', id: 'case-export' }, 'Export all (JSON)');
  const impLabel = el('label', { class: 'import', for: 'case-import' }, 'Import JSON ');
  const imp = el('input', { id: 'case-import', type: 'file', accept: 'application/json,.json' });
  impLabel.append(imp);

  const render = () => {
    list.replaceChildren();
    const cases = state.loadCases();
    const names = Object.keys(cases).sort((a, b) => a.localeCompare(b));
    if (!names.length) list.append(el('li', { class: 'field-hint' }, 'No saved cases yet.'));
    for (const n of names) {
      const li = el('li');
      const load = el('button', { type: 'button', 'aria-label': `Load case ${n}` }, 'Load');
      const del = el('button', { type: 'button', 'aria-label': `Delete case ${n}` }, 'Delete');
      load.addEventListener('click', async () => {
        await restore(cases[n]);
        msg.textContent = `Loaded “${n}”.`;
      });
      del.addEventListener('click', () => {
        const all = state.loadCases();
        delete all[n];
        state.storeCases(all);
        render();
        msg.textContent = `Deleted “${n}”.`;
      });
      li.append(el('span', { class: 'case-name' }, n), load, del);
      list.append(li);
    }
  };
  save.addEventListener('click', () => {
    const n = name.value.trim();
    if (!n) return void (msg.textContent = 'Give the case a name first.');
    const all = state.loadCases();
    all[n] = state.capture(active);
    try {
      state.storeCases(all);
      msg.textContent = `Saved “${n}” in this browser.`;
    } catch {
      msg.textContent = 'This browser refused to store the case (storage full or disabled).';
    }
    render();
  });
  exp.addEventListener('click', () => download('fiveaxis-cases.json', JSON.stringify(state.loadCases(), null, 2), 'application/json'));
  imp.addEventListener('change', async () => {
    const file = imp.files?.[0];
    if (!file) return;
    try {
      const read = await readTextFile(file, 'a file of saved cases (JSON)');
      const incoming = state.parseCases(read.text);
      state.storeCases({ ...state.loadCases(), ...incoming });
      msg.textContent = `Imported ${Object.keys(incoming).length} case(s)${encodingNote(read)}.`;
      render();
    } catch (e) {
      if (e instanceof FileRefused) msg.textContent = e.message;
      else msg.textContent = `Could not import ${file.name}: the file ${e instanceof Error ? e.message : String(e)}.`;
    }
    imp.value = '';
  });
  details.addEventListener('toggle', render);
  details.append(summary, el('div', { class: 'cases-body' }));
  details.lastElementChild!.append(name, save, list, exp, impLabel, msg);
  return details;
}

async function restore(s: state.PageState) {
  restoring = true;
  try {
    state.apply(s);
    ignored.length = 0;
    ignoredSettings([...state.applyPending(MACHINE_PREFIX), ...state.applyPending(DRAWING_PREFIX)]);
    await show(panels.some((p) => p.id === s.p) ? s.p : panels[0].id);
  } finally {
    restoring = false;
  }
  await saveNow();
}

/** The open study (for the printed report). */
function activeStudy(): Study | null {
  const section = mounted.get(active);
  const panel = panels.find((p) => p.id === active);
  return section && panel ? { id: panel.id, title: panel.title, prefix: panel.prefix, section } : null;
}
const printHooks = { active: activeStudy, all: allStudies, scope: reportScope };

async function start() {
  const machineRoot = document.getElementById('machine')!;
  machine = await mountMachine(machineRoot);
  machineRoot.dataset.ready = 'true';
  tabs();
  setupPrint(printHooks);
  toolbar();
  document.getElementById('banner-close')?.addEventListener('click', () => banner(null));
  // On a phone the privacy note and the panels' lead paragraphs show two lines; a tap, all.
  document.addEventListener('click', (e) => {
    const p = (e.target as HTMLElement | null)?.closest?.('p.privacy, p.lead');
    if (p) p.classList.toggle('expanded');
  });
  document.getElementById('banner-action')?.addEventListener('click', () => void shown?.action?.run());
  // Any edit anywhere in a panel, the machine or the report's header is saved (URL and local storage).
  document.getElementById('panels')!.addEventListener('input', scheduleSave);
  document.getElementById('report-menu')?.addEventListener('input', scheduleSave);
  machineRoot.addEventListener('input', scheduleSave);

  await openLink(location.hash, state.loadLocal(), true);
  // A link pasted into the address bar of this tab changes only the fragment.
  window.addEventListener('hashchange', () => {
    if (location.hash === written) return;
    void track(openLink(location.hash, state.capture(active), false));
  });
}

// The same engine on the main thread, for the browser console: `fiveaxis.nonlinearMove({...})`.
// The page itself computes in a Web Worker. Loaded once the first panel has drawn, so that it
// reuses the engine file the worker fetched (the browser's cache) and compiles it when the page
// has nothing more urgent to do.
async function consoleEngine() {
  for (let t = 0; t < 100 && !document.querySelector('.plot[data-plotted]'); t++) await new Promise((r) => setTimeout(r, 100));
  await new Promise((r) => ('requestIdleCallback' in window ? requestIdleCallback(r, { timeout: 2000 }) : setTimeout(r, 0)));
  const engine = await import('@engine');
  await engine.default();
  (window as unknown as { fiveaxis: typeof engine }).fiveaxis = engine;
}

/** Asks the service worker to keep the files this visit fetched before it took control. */
function keepFetched() {
  if ('serviceWorker' in navigator) navigator.serviceWorker.controller?.postMessage('sweep');
}

void start().finally(() => {
  void consoleEngine().finally(keepFetched);
});

// Offline use after the first visit (the built page only; the dev server has no sw.js).
if ('serviceWorker' in navigator && import.meta.env.PROD) {
  window.addEventListener('load', () => {
    navigator.serviceWorker.register('./sw.js').catch((err) => banner(`Offline use is unavailable: ${String(err)}`));
    navigator.serviceWorker.addEventListener('controllerchange', keepFetched);
  });
}
