// Plotting through Plotly.js, loaded lazily on first use (it is the page's heaviest part): its
// core with the 2D trace types first, the 3D types (a further bundle) only once a 3D plot is
// about to be shown. Until a plot is drawn its box shows a spinner (style.css, `.plot`).
import type { Config, Data, Layout } from 'plotly.js';
import { download, graphCsv } from './export';
import { drawStarted } from '../engine/idle';
import { blockedBy, invalidFields } from './status';

type PlotlyModule = typeof import('plotly.js');
let plotly: Promise<PlotlyModule> | null = null;
let plotly3d: Promise<PlotlyModule> | null = null;

/** Plotly with the 2D trace types (scatter, bar, heatmap, scatterpolar). */
export function loadPlotly(): Promise<PlotlyModule> {
  plotly ??= import('./plotly-2d').then((m) => m.default as unknown as PlotlyModule);
  return plotly;
}

/** Plotly with the 3D trace types too (scatter3d, surface, mesh3d, cone). */
export function loadPlotly3d(): Promise<PlotlyModule> {
  // The core first (the 2D plots wait for it), then the 3D types.
  plotly3d ??= loadPlotly().then(async (core) => {
    const three = await import('./plotly-3d');
    (core as unknown as { register(m: unknown[]): void }).register(three.traces3d);
    return core;
  });
  return plotly3d;
}

const TYPES_3D = new Set(['scatter3d', 'surface', 'mesh3d', 'cone']);
const is3d = (data: Data[]) => data.some((t) => TYPES_3D.has(String((t as { type?: string }).type)));

const baseLayout: Partial<Layout> = {
  font: { family: 'system-ui, -apple-system, "Segoe UI", Roboto, sans-serif', size: 12, color: '#1f2328' },
  margin: { l: 64, r: 20, t: 24, b: 52 },
  paper_bgcolor: '#ffffff',
  plot_bgcolor: '#ffffff',
  hovermode: 'closest',
  legend: { orientation: 'v', x: 1.02, xanchor: 'left', y: 1, yanchor: 'top', font: { size: 11 } },
};

/** Axis with a title (every plot must say what and in which unit). */
export function axis(title: string, extra: Partial<Layout['xaxis']> = {}): Partial<Layout['xaxis']> {
  return { title: { text: title }, zeroline: false, gridcolor: '#e6e8eb', automargin: true, ...extra };
}

/**
 * A "nice" scale per division (1, 2 or 5 × 10^k, in the unit of `span`) that puts `span` in at
 * most three divisions: a polar plot of a deviation magnified about a nominal circle drawn at a
 * radius of 4 divisions (a ball-bar trace) keeps the deviation between 1 and 7 divisions.
 */
export function perDivision(span: number): number {
  const raw = Math.max(span, 1e-12) / 3;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * p).find((v) => v >= raw) ?? 10 * p;
}

/** Height of Plotly's mode bar, kept clear above every title. */
const MODEBAR = 26;

/**
 * `title` (lines separated by `<br>`) with every line longer than a `width`-px box can show at
 * the title's size broken at spaces (Plotly does not wrap titles; it cuts them).
 */
export function wrapTitle(title: string, width: number): string {
  if (!width) return title;
  const max = Math.max(24, Math.floor((width - 16) / 6.8));
  const out: string[] = [];
  for (const line of title.split('<br>')) {
    let current = '';
    for (const word of line.split(' ')) {
      const plain = (s: string) => s.replace(/<[^>]+>/g, '');
      if (current && plain(`${current} ${word}`).length > max) {
        out.push(current);
        current = word;
      } else current = current ? `${current} ${word}` : word;
    }
    out.push(current);
  }
  return out.join('<br>');
}

/** Narrower than this (px), a plot is laid out for a phone. */
const COMPACT = 520;

type AnyAxis = Record<string, unknown> & { domain?: number[]; anchor?: string };

/**
 * The layout adjusted to the plot's box. Everywhere: axis and colour-bar values are written out
 * (Plotly's default shortens 150000 µm to "150k" µm, which reads as kilo-micrometres). In a box
 * narrower than COMPACT px (a phone): two plots side by side (x and x2) are stacked, the box made
 * taller for them; legends go under the plot, horizontally; 3D axes get fewer ticks.
 */
function fitToBox(layout: Partial<Layout>, el: HTMLElement): Partial<Layout> {
  const out = { ...layout } as Record<string, unknown>;
  const plain = (a: unknown) => ({ exponentformat: 'none', separatethousands: true, ...(a as object) });
  for (const key of Object.keys(out)) {
    if (/^[xy]axis\d*$/.test(key)) out[key] = plain(out[key]);
    if (key === 'coloraxis' || /^coloraxis\d+$/.test(key)) {
      const c = out[key] as { colorbar?: object };
      out[key] = { ...c, colorbar: plain(c?.colorbar) };
    }
  }
  // 3D axes: at most 5 ticks (the default crowds a short axis's labels into its neighbours').
  if (out.scene) {
    const sc = out.scene as Record<string, AnyAxis>;
    out.scene = { ...sc, xaxis: { nticks: 5, ...sc.xaxis }, yaxis: { nticks: 5, ...sc.yaxis }, zaxis: { nticks: 5, ...sc.zaxis } };
  }
  const compact = el.clientWidth > 0 && el.clientWidth < COMPACT;
  const x = out.xaxis as AnyAxis | undefined;
  const x2 = out.xaxis2 as AnyAxis | undefined;
  const sideBySide = !!(x?.domain && x2?.domain && x2.domain[0] >= x.domain[1]);
  el.classList.toggle('stacked', compact && sideBySide);
  if (!compact) return out as Partial<Layout>;
  if (sideBySide) {
    out.xaxis = { ...x, domain: [0, 1], anchor: 'y' };
    out.yaxis = { ...(out.yaxis as AnyAxis), domain: [0.6, 1], anchor: 'x' };
    out.xaxis2 = { ...x2, domain: [0, 1], anchor: 'y2' };
    out.yaxis2 = { ...(out.yaxis2 as AnyAxis), domain: [0, 0.4], anchor: 'x2' };
  }
  out.legend = { ...(out.legend as object), orientation: 'h', x: 0, xanchor: 'left', xref: 'container', y: 0, yanchor: 'bottom', yref: 'container' };
  const margin = out.margin as Partial<Layout['margin']>;
  // A polar plot's angle labels (180° on the left) need room on both sides.
  const side = out.polar ? 40 : 0;
  out.margin = { ...margin, r: Math.max(side, Math.min(margin?.r ?? 20, 10)), l: Math.max(side, Math.min(margin?.l ?? 64, 56)) };
  // Labels in the plot (a zone's name and value) on two lines and smaller, so that neighbours
  // do not run into each other.
  if (Array.isArray(out.annotations)) {
    out.annotations = (out.annotations as { text?: string; font?: { size?: number } }[]).map((a) => ({
      ...a, text: a.text?.replace(': ', ':<br>'), font: { ...a.font, size: Math.min(a.font?.size ?? 12, 10) },
    }));
  }
  if (out.scene) {
    const sc = out.scene as Record<string, AnyAxis>;
    // The camera a little further out, so that the axes' titles stay in the narrow box.
    const cam = sc.camera as { eye?: { x: number; y: number; z: number } } | undefined;
    const eye = cam?.eye ? { camera: { ...cam, eye: { x: cam.eye.x * 1.2, y: cam.eye.y * 1.2, z: cam.eye.z * 1.2 } } } : {};
    out.scene = { ...sc, ...eye, xaxis: { ...sc.xaxis, nticks: 4 }, yaxis: { ...sc.yaxis, nticks: 4 }, zaxis: { ...sc.zaxis, nticks: 4 } };
  }
  return out as Partial<Layout>;
}

/** Lengths in µm from this size on are labelled in mm (150 mm, not "150,000 µm" or "150k µm"). */
const MM_FROM = 10_000;

/** About five round tick values over [lo, hi] (mm), in mm. */
function niceTicks(lo: number, hi: number): number[] {
  const raw = (hi - lo) / 5 || 1;
  const p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw) ?? 10 * p;
  const out: number[] = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) out.push(Number(v.toPrecision(12)));
  return out;
}

/** The title and ticks of an axis or colour bar in µm whose values reach MM_FROM µm, in mm. */
function inMm<T extends { title?: unknown }>(target: T | undefined, values: number[]): T | undefined {
  const t = target?.title as { text?: string } | string | undefined;
  const text = typeof t === 'string' ? t : t?.text;
  if (!target || !text || !text.includes('(µm)') || (target as { tickvals?: unknown }).tickvals) return target;
  const finite = values.filter(Number.isFinite);
  if (!finite.length) return target;
  // A loop, not a spread: a plot may hold 10^6 values, more than a call takes as arguments.
  let lo = 0;
  let hi = 0;
  for (const v of finite) {
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  lo /= 1000;
  hi /= 1000;
  if (Math.max(-lo, hi) * 1000 < MM_FROM) return target;
  const title = typeof t === 'string' ? t.replace('(µm)', '(mm)') : { ...t, text: text.replace('(µm)', '(mm)') };
  if ((target as { type?: string }).type === 'log') {
    // A log axis: a tick at each power of ten the values span (linear ticks would crowd its top).
    let least = Infinity;
    for (const v of finite) if (v > 0 && v < least) least = v;
    if (!Number.isFinite(least)) return target;
    const tickvals: number[] = [];
    for (let e = Math.floor(Math.log10(least)); e <= Math.ceil(Math.log10(hi * 1000)); e++) tickvals.push(10 ** e);
    const mm = (v: number) => (v >= 1e-3 && v < 1e6 ? String(Number(v.toPrecision(6))) : v.toExponential(0));
    return { ...target, title, tickmode: 'array', tickvals, ticktext: tickvals.map((v) => mm(v / 1000)) };
  }
  const ticks = niceTicks(lo, hi);
  return { ...target, title, tickmode: 'array', tickvals: ticks.map((v) => v * 1000), ticktext: ticks.map((v) => String(v)) };
}

const flat = (v: unknown): number[] =>
  Array.isArray(v) || ArrayBuffer.isView(v) ? Array.from(v as ArrayLike<unknown>).flatMap(flat) : typeof v === 'number' ? [v] : [];

/**
 * Axes and colour bars in µm whose values reach MM_FROM µm labelled in mm instead (the data, its
 * hover text and its CSV stay in µm: only the ticks' text and the title change).
 */
function millimetres(layout: Partial<Layout>, traces: Data[]): Partial<Layout> {
  const out = { ...layout } as Record<string, unknown>;
  for (const key of Object.keys(out)) {
    const m = /^([xy])axis(\d*)$/.exec(key);
    if (!m) continue;
    const ref = `${m[1]}${m[2]}`;
    const values = traces
      .filter((t) => ((t as Record<string, unknown>)[`${m[1]}axis`] ?? m[1]) === ref)
      .flatMap((t) => flat((t as Record<string, unknown>)[m[1]]));
    out[key] = inMm(out[key] as { title?: unknown }, values);
  }
  for (let i = 0; i < traces.length; i++) {
    const t = traces[i] as { z?: unknown; colorbar?: { title?: unknown } };
    if (t.colorbar && t.z) traces[i] = { ...t, colorbar: inMm(t.colorbar, flat(t.z)) } as Data;
  }
  return out as Partial<Layout>;
}

/** A trace whose colour bar (its own or its markers') writes its values out, as fitToBox's axes. */
function plainColorbar(t: Data): Data {
  const c = t as { type?: string; colorbar?: object; marker?: { colorbar?: object; showscale?: boolean } };
  // (and the line's, a 3D line coloured without markers)
  const plain = (a?: object) => ({ exponentformat: 'none', separatethousands: true, ...a });
  let out = t;
  if (c.colorbar || ['heatmap', 'surface', 'contour'].includes(c.type ?? '')) out = { ...out, colorbar: plain(c.colorbar) } as Data;
  if (c.marker?.colorbar || c.marker?.showscale) out = { ...out, marker: { ...c.marker, colorbar: plain(c.marker.colorbar) } } as Data;
  const line = (t as { line?: { colorbar?: object; showscale?: boolean } }).line;
  if (line?.colorbar || line?.showscale) out = { ...out, line: { ...line, colorbar: plain(line.colorbar) } as object } as Data;
  return out;
}

/**
 * The drawings asked for plots of a panel that is not shown (another tab), by plot: each the
 * latest asked for, drawn when its panel is shown (`drawWaiting`). A hidden panel still computes
 * (its verdict and key numbers are current, for the machine's report), but Plotly draws only
 * what can be seen: a change of the machine redraws the open panel, not the ten behind it.
 */
const waiting = new Map<HTMLElement, () => Promise<void>>();

/** Whether `el` is a plot of a panel on another tab (hidden, and not being printed). The
 *  machine's drawing is in no panel. */
function behindTab(el: HTMLElement): boolean {
  const panel = el.closest<HTMLElement>('section.panel');
  return !!panel?.hidden && !panel.classList.contains('report-study');
}

/**
 * Draws or redraws `el` in place (Plotly.react keeps zoom state out of the way of new data), or,
 * for a plot of a panel on another tab, greys it and keeps the drawing until the panel is shown.
 */
export async function draw(el: HTMLElement, title: string, data: Data[], layout: Partial<Layout>, filename: string) {
  const box = el.closest<HTMLElement>('.plot-wrap') ?? el;
  if (behindTab(el)) {
    // What it shows no longer answers the inputs: greyed until it is drawn. Greyed again later
    // (the machine turned invalid meanwhile), it stays greyed when drawn (`drawNow`).
    stale(el, true, 'Drawing the result of the current inputs…');
    const greyed = greyedAt.get(box);
    waiting.set(el, () => drawCounted(el, title, data, layout, filename, greyed));
    return;
  }
  waiting.delete(el);
  await drawCounted(el, title, data, layout, filename, greyedAt.get(box));
}

/** Draws the plots inside `root` whose drawing waited while their panel was hidden. */
export async function drawWaiting(root: HTMLElement): Promise<void> {
  const due = [...waiting].filter(([el]) => root.contains(el));
  for (const [el] of due) waiting.delete(el);
  await Promise.all(due.map(([, drawIt]) => drawIt()));
}

/**
 * The plots inside `root` drawn at another width than their box's, resized to it: a study on
 * another tab when the machine's report was printed is given back its size while hidden, which
 * Plotly cannot measure.
 */
export async function fitWidths(root: HTMLElement): Promise<void> {
  const off = [...root.querySelectorAll<HTMLElement>('.js-plotly-plot')].filter((gd) => {
    const drawn = Number(gd.querySelector('svg.main-svg')?.getAttribute('width'));
    return drawn > 0 && gd.clientWidth > 0 && Math.abs(drawn - gd.clientWidth) > 1;
  });
  if (!off.length) return;
  const end = drawStarted();
  try {
    const P = await loadPlotly();
    for (const gd of off) P.Plots.resize(gd);
  } finally {
    end();
  }
}

/** Whether `el` shows a drawing or has one waiting behind its tab (`draw`). */
export function drawnOrWaiting(el: HTMLElement): boolean {
  return Number(el.dataset.plotted ?? 0) > 0 || waiting.has(el);
}

/** Forgets the drawing waiting for `el` (a plot removed: its data belongs to other inputs). */
export function forgetDrawing(el: HTMLElement) {
  waiting.delete(el);
}

async function drawCounted(el: HTMLElement, title: string, data: Data[], layout: Partial<Layout>, filename: string, greyedBefore: number | undefined) {
  const end = drawStarted();
  try {
    await drawNow(el, title, data, layout, filename, greyedBefore);
  } finally {
    end();
  }
}

/** Draws `el`; it stays greyed if it was greyed after `greyedBefore` (when the drawing was asked). */
async function drawNow(el: HTMLElement, title: string, data: Data[], layout: Partial<Layout>, filename: string, greyedBefore: number | undefined) {
  const P = is3d(data) ? await loadPlotly3d() : await loadPlotly();
  const config: Partial<Config> = {
    responsive: true,
    displaylogo: false,
    toImageButtonOptions: { format: 'png', filename, scale: 2 },
    modeBarButtonsToRemove: ['select2d', 'lasso2d'],
    // The 3D views (WebGL) at the screen's own pixel ratio, antialiased by the browser, instead of
    // Plotly's fixed 2: on a screen of ratio 1 that is a quarter of the pixels to shade at every
    // redraw (on a software renderer, as in the headless test browser, WebGL was about a quarter
    // of the browser's work), and on a phone of ratio 3 the views are as sharp as the screen.
    plotGlPixelRatio: Math.min(4, Math.max(1, window.devicePixelRatio || 1)),
  };
  el.setAttribute('role', 'figure');
  el.setAttribute('aria-label', title);
  // The title sits just above the plot area, in a top margin made for its lines. Plotly puts the
  // first line's baseline at the anchor and the others below it, so the anchor is raised by the
  // lines after the first. (Anchored to the container's top, Plotly cuts the first line of a
  // two-line title; with the margin grown by Plotly's automargin instead, the first drawing places
  // the traces before the margin grows, so that they sit above their axes until the next redraw.)
  // Above the title, a strip of MODEBAR px is left for Plotly's mode bar (top right), so that the
  // bar never covers the title. A title longer than the box is wrapped onto further lines.
  const text = wrapTitle(title, el.clientWidth);
  const lines = text.split('<br>').length;
  const titleLayout = { text, font: { size: 13 }, yref: 'paper', y: 1, yanchor: 'bottom', pad: { b: 8 + 17 * (lines - 1) } } as Partial<Layout['title']>;
  const margin = { ...baseLayout.margin, ...layout.margin, t: (layout.margin?.t ?? 0) + 14 + 17 * lines + MODEBAR };
  const traces = data.map(plainColorbar);
  // The axes' titles as drawn, with the data's units: a CSV names its columns from these, not
  // from titles relabelled in mm for the ticks (the data stays in µm).
  const titles: Record<string, string> = {};
  for (const [key, a] of Object.entries(layout)) {
    const t = /^[xy]axis\d*$/.test(key) ? (a as { title?: string | { text?: string } } | undefined)?.title : undefined;
    const text = typeof t === 'string' ? t : t?.text;
    if (text) titles[key] = text;
  }
  const meta = { titles, ...((layout as { meta?: object }).meta) };
  const fitted = fitToBox(millimetres({ ...baseLayout, title: titleLayout, ...layout, margin, meta } as Partial<Layout>, traces), el);
  // Each drawing a task of its own: two plots drawn from one result (the toolpath's δ plot and
  // its 3D path) would otherwise hold the main thread as one long task.
  const box = el.closest<HTMLElement>('.plot-wrap') ?? el;
  await new Promise((resolve) => setTimeout(resolve, 0));
  await P.react(el, traces, fitted, config);
  toolbar(el, title, filename);
  // Greyed after the drawing was asked (an input turned invalid meanwhile): it stays greyed,
  // since what it shows no longer answers the inputs.
  const current = greyedAt.get(box) === greyedBefore;
  if (current) {
    stale(el, false);
    el.closest('.results')?.querySelector(':scope > dl.summary')?.classList.remove('stale');
  }
  el.dataset.plotted = String(Number(el.dataset.plotted ?? '0') + 1);
  // Greyed before it showed anything (its first drawing waited behind its tab), it had no line
  // saying why: it has now. (Not counted as a new greying: a later drawing already under way,
  // asked after that greying, must still clear it.)
  if (!current && !box.querySelector(':scope > .stale-label')) {
    const at = greyedAt.get(box);
    stale(el, true, greyedWhy.get(box));
    if (at !== undefined) greyedAt.set(box, at);
  }
}


/** When each box was last greyed (a count): a drawing started before it leaves it greyed. */
const greyedAt = new WeakMap<HTMLElement, number>();
/** Why each box was last greyed (`stale`'s `why`; none for the default line). */
const greyedWhy = new WeakMap<HTMLElement, string | undefined>();
let greyings = 0;

/**
 * Greys what no longer shows what the inputs ask for: a plot (its wrapper), or any other output
 * element, and with it the panel's summary of key numbers; a line above it says that it shows
 * the last valid result (`why`, by default: which fields to fix and where, ui/status.ts), when it
 * shows one.
 * `on = false` clears the element only: the summary is cleared by a successful drawing (`draw`).
 */
export function stale(target: HTMLElement, on: boolean, why?: string) {
  const box = target.closest<HTMLElement>('.plot-wrap') ?? target;
  box.classList.toggle('stale', on);
  if (on) {
    greyedAt.set(box, ++greyings);
    greyedWhy.set(box, why);
  }
  // The label sits in the plot's frame (not greyed with the plot), or just before the element.
  const isPlot = box !== target;
  let label = isPlot ? box.querySelector<HTMLElement>(':scope > .stale-label') : box.previousElementSibling?.classList.contains('stale-label') ? (box.previousElementSibling as HTMLElement) : null;
  const showsSomething = isPlot ? Number(target.dataset.plotted ?? 0) > 0 : (target.textContent ?? '').trim() !== '';
  if (!on || !showsSomething) {
    label?.remove();
  } else {
    if (!label) {
      label = document.createElement('p');
      label.className = 'stale-label';
      label.setAttribute('role', 'status');
      if (isPlot) box.prepend(label);
      else box.before(label);
    }
    label.textContent = why ?? `Showing the last valid result; ${blockedBy(invalidFields(target), 'the inputs changed')}.`;
  }
  if (on) target.closest('.results')?.querySelector(':scope > dl.summary')?.classList.add('stale');
}

/** PNG and CSV buttons under a plot (added once). */
function toolbar(el: HTMLElement, title: string, filename: string) {
  const plainTitle = title.replace(/<br>/g, ' ');
  let bar = el.parentElement?.querySelector<HTMLElement>(':scope > .plot-tools');
  if (!bar) {
    bar = document.createElement('div');
    bar.className = 'plot-tools';
    const png = Object.assign(document.createElement('button'), { type: 'button', textContent: 'PNG' });
    png.dataset.export = 'png';
    png.addEventListener('click', async () => {
      const P = await loadPlotly();
      await P.downloadImage(el, { format: 'png', filename: bar?.dataset.filename ?? 'plot', width: el.clientWidth, height: el.clientHeight, scale: 2 } as Parameters<typeof P.downloadImage>[1]);
    });
    const csv = Object.assign(document.createElement('button'), { type: 'button', textContent: 'CSV' });
    csv.dataset.export = 'csv';
    csv.addEventListener('click', () => download(`${bar?.dataset.filename ?? 'plot'}.csv`, graphCsv(el), 'text/csv'));
    bar.append(png, csv);
    el.after(bar);
  }
  bar.dataset.filename = filename;
  for (const b of bar.querySelectorAll('button')) b.setAttribute('aria-label', `Download “${plainTitle}” as ${b.textContent}`);
}

/** Shows a note over a plot's area without removing the last good plot. */
export function note(el: HTMLElement, text: string | null) {
  let n = el.parentElement?.querySelector<HTMLElement>(':scope > .plot-note');
  if (!text) {
    n?.remove();
    return;
  }
  if (!n) {
    n = document.createElement('div');
    n.className = 'plot-note';
    n.setAttribute('role', 'status');
    el.before(n);
  }
  n.textContent = text;
}

/** Row-major flat data (`[iy·nx + ix]`) to the rows Plotly's heat maps and surfaces expect. */
export function rows<T>(flat: ArrayLike<T>, nx: number, ny: number): T[][] {
  const out: T[][] = [];
  for (let iy = 0; iy < ny; iy++) out.push(Array.from({ length: nx }, (_, ix) => flat[iy * nx + ix]));
  return out;
}

/** A plot's element in its frame (`.plot-wrap`, which greys it when stale); `wide` spans the
 *  row of plots, `tall` is higher. */
export function plotBox(id: string, ...options: ('wide' | 'tall')[]): { wrap: HTMLElement; p: HTMLElement } {
  const wrap = document.createElement('div');
  wrap.className = options.includes('wide') ? 'plot-wrap wide' : 'plot-wrap';
  const p = document.createElement('div');
  p.className = options.includes('tall') ? 'plot tall' : 'plot';
  p.id = id;
  wrap.append(p);
  return { wrap, p };
}
