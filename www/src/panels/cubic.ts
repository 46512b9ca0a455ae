// The "Cubic-machining test" panel: Li, Sato, Shirase & Sakamoto (2021), a B/C tilting-rotary
// table cutting a 3 × 3-zone face. Which zones come out high or low for given geometric errors.
import type { Annotations, Data, Layout, Shape } from 'plotly.js';
import type { CubicErrorInfo, CubicInput, CubicMapResult, CubicReference, CubicResult } from '@engine';
import { call, channel, SUPERSEDED } from '../engine/client';
import { checkField, el, numberField, selectField, type NumberField } from '../ui/fields';
import { axis, draw, note } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, type Panel } from './panel';

/** A length from the engine (mm) in the small-length unit shown now. */
const D = (mm: number) => toDisplay('errLength', mm);

/** Largest errors the engine accepts: 5 mm, 5°. */
const MAX_ERROR = 5;
/** Most height-map points per side shown; finer maps are averaged in blocks for display. */
const DISPLAY_SIDE = 241;

const REFERENCES: { value: CubicReference; label: string; short: string }[] = [
  { value: 'workpiece', label: 'Workpiece frame (nominal face)', short: 'workpiece frame' },
  { value: 'zone1-height', label: 'ZONE I’s height (Section 5.1)', short: 'relative to ZONE I’s height' },
  { value: 'zone1-plane', label: 'ZONE I’s plane, levelled (Fig 15)', short: 'levelled on ZONE I' },
];

export const cubicPanel: Panel = {
  id: 'cubic',
  prefix: 'cb',
  title: 'Cubic-machining test',
  mount,
};

async function mount(root: HTMLElement) {
  const infos: CubicErrorInfo[] = await call('cubicErrors');
  const { form, results } = panelShell(
    root,
    'Cubic-machining test: 3 × 3 zone heights on a B/C tilting-rotary table',
    'A ball-end mill (Ø6 mm) cuts the nine 16 × 16 mm zones of a 48 × 48 mm face with the rotary axes standing still: ' +
      'ZONE I with the tool vertical, the others tilted 30° towards the centre (Tables 1, 2). The eight geometric errors ' +
      'of the rotary axes (Table 3) make each zone come out higher (material left, positive) or lower than nominal. ' +
      'Li, Sato, Shirase & Sakamoto, Precision Engineering 71 (2021), eqs 1–15.',
  );

  // ---- inputs
  const errorFields: NumberField[] = infos.map((i) =>
    numberField({
      id: `cb-${i.key}`,
      label: `${i.symbol}: ${shortDescription(i)}`,
      quantity: i.unit === 'deg' ? 'errAngle' : 'errLength',
      value: 0,
      min: -MAX_ERROR,
      max: MAX_ERROR,
      hint: `Maps onto ISO 230-1 ${i.iso} = −${i.symbol}.`,
    }),
  );
  const errorSet = el('fieldset');
  errorSet.append(el('legend', {}, 'Geometric errors (Table 3)'), presetPicker('cubic', 'cb'), ...errorFields.map((f) => f.root));

  const transform = checkField(
    'cb-transform',
    'Workpiece transformation M_WC (eqs 10–12)',
    true,
    'On: the workpiece coordinate system is set at B = C = 0, so ZONE I is exact (Fig 12). Off: the workpiece frame is the erroneous table frame (Fig 10).',
  );
  const reference = selectField('cb-reference', 'Heights measured from', REFERENCES, 'workpiece',
    'Section 5.1 sets the measurement frame on ZONE I: shifted to its height, or also parallel to its surface.');
  const modelSet = el('fieldset');
  modelSet.append(el('legend', {}, 'Model'), transform.root, reference.root);

  const L = (id: string, label: string, value: number, min: number, max: number, hint?: string, positive = false) =>
    numberField({ id, label, quantity: 'length', value, min, max, hint, positive });
  const tableAboveB = L('cb-table', 'Table surface above the B axis', 0, -2000, 2000, 'At B = 0; negative: below the axis.');
  const workpieceHeight = L('cb-height', 'Workpiece height (top face above the table)', 50, 0, 2000, undefined, true);
  const cOffset = L('cb-coffset', 'C axis offset from the B axis, along X', 0, -2000, 2000, '0: B and C intersect.');
  const workpieceX = L('cb-wx', 'Face centre from the C axis, X', 0, -2000, 2000);
  const workpieceY = L('cb-wy', 'Face centre from the C axis, Y', 0, -2000, 2000);
  const setupSet = el('fieldset');
  const pairOf = (a: NumberField, b: NumberField) => {
    const d = el('div', { class: 'pair' });
    d.append(a.root, b.root);
    return d;
  };
  setupSet.append(el('legend', {}, 'Set-up geometry'), tableAboveB.root, workpieceHeight.root, cOffset.root, pairOf(workpieceX, workpieceY));

  const zoneSize = L('cb-zone', 'Zone size', 16, 1, 200, 'The face is 3 × 3 zones.');
  const toolRadius = L('cb-radius', 'Ball-end radius r', 3, 0.05, 50);
  const pick = L('cb-pick', 'Pick feed p', 0.1, 0.001, 200);
  const stock = numberField({ id: 'cb-stock', label: 'Stock above the face', quantity: 'errLength', value: 0.1, min: 0, max: 50, positive: true,
    hint: 'Depth of cut: what stays where no pass reaches.' });
  const grid = numberField({ id: 'cb-grid', label: 'Height-map points along X', value: 193, min: 4, max: 2001, integer: true,
    hint: '193 gives 0.25 mm steps over 48 mm. Along Y (across the passes) the map takes 4 points per pass step, so that the scallops are sampled evenly.' });
  const range = numberField({ id: 'cb-range', label: 'Colour scale ± (0: automatic)', quantity: 'errLength', value: 0, min: 0, max: 50,
    hint: 'Fig 16 uses ±0.01 mm.' });
  const pieceSet = el('fieldset');
  pieceSet.append(el('legend', {}, 'Test piece and plots'), zoneSize.root, pairOf(toolRadius, pick), stock.root, grid.root, range.root);
  form.append(errorSet, modelSet, setupSet, pieceSet);

  // ---- outputs
  const summary = el('dl', { class: 'summary', id: 'cb-summary', 'aria-live': 'polite' });
  const plot = (id: string, wide = false, tall = false) => {
    const wrap = el('div', { class: wide ? 'plot-wrap wide' : 'plot-wrap' });
    const p = el('div', { class: tall ? 'plot tall' : 'plot', id });
    wrap.append(p);
    return { wrap, p };
  };
  const zonesPlot = plot('cb-zones', false, true);
  const mapPlot = plot('cb-map', false, true);
  const sensPlot = plot('cb-sens', true, true);
  const plots = el('div', { class: 'plots' });
  plots.append(zonesPlot.wrap, mapPlot.wrap, sensPlot.wrap);
  results.append(summary, plots);

  // ---- computation
  const runTest = channel('cubicTest');
  const runMap = channel('cubicHeightMap');
  const fieldsByPath: Record<string, NumberField> = {
    'setup.tableAboveB': tableAboveB, 'setup.workpieceHeight': workpieceHeight, 'setup.cOffset': cOffset,
    'setup.workpieceX': workpieceX, 'setup.workpieceY': workpieceY, 'setup.zoneSize': zoneSize,
    'setup.toolRadius': toolRadius, 'setup.pick': pick, 'setup.stock': stock, nx: grid, ny: grid,
  };
  infos.forEach((i, n) => (fieldsByPath[`errors.${i.key}`] = errorFields[n]));
  /** Shows an engine error at the field it names (or over the plot when it names none). */
  const engineError = engineErrors(fieldsByPath);

  let lastTest: { r: CubicResult; input: CubicInput } | null = null;
  let lastMap: CubicMapResult | null = null;
  let fixedRange: number | null = null; // mm, or null for automatic

  /** The shared colour range, mm: the chosen one, or 1.25 × the largest zone height. */
  const colourRange = () => {
    if (fixedRange) return fixedRange;
    const hs = lastTest ? lastTest.r.zones.map((z) => Math.abs(z.height)) : [];
    return Math.max(5e-4, 1.25 * Math.max(0, ...hs));
  };

  const update = () => {
    const errs = errorFields.map((f) => f.read());
    const geo = [tableAboveB, workpieceHeight, cOffset, workpieceX, workpieceY, zoneSize, toolRadius, pick, stock].map((f) => f.read());
    const n = grid.read();
    const rng = range.read();
    if (errs.some((v) => v === null) || geo.some((v) => v === null)) return; // messages at the fields; plots keep the last good input
    fixedRange = rng ? rng : null;
    const [tab, wh, co, wx, wy, zs, tr, pk, st] = geo as number[];
    const errors = Object.fromEntries(infos.map((i, k) => [i.key, errs[k] as number]));
    const input: CubicInput = {
      errors,
      setup: { tableAboveB: tab, workpieceHeight: wh, cOffset: co, workpieceX: wx, workpieceY: wy, zoneSize: zs, toolRadius: tr, pick: pk, stock: st },
      transform: transform.input.checked,
      reference: reference.select.value as CubicReference,
    };
    runTest(input).then((r) => {
      if (r === SUPERSEDED) return;
      lastTest = { r, input };
      showTest(r, input);
      if (lastMap) showMap(lastMap);
    }, (e) => engineError(e, zonesPlot.p));
    if (n !== null) {
      // Rows at a quarter of the actual pass step, aligned with the passes (the face starts on
      // a pass): whole scallop periods can then be averaged for display without aliasing.
      const ny = Math.min(12 * Math.ceil(zs / pk - 1e-9) + 1, 4001, Math.floor(4e6 / n));
      runMap({ ...input, nx: n, ny }).then((m) => {
        if (m === SUPERSEDED) return;
        lastMap = m;
        showMap(m);
      }, (e) => engineError(e, mapPlot.p));
    }
  };

  const frameText = (r: CubicResult) =>
    `${r.transform ? 'with M_WC' : 'without M_WC'}, ${REFERENCES.find((x) => x.value === r.reference)?.short ?? r.reference}`;

  const showTest = (r: CubicResult, input: CubicInput) => {
    note(zonesPlot.p, null);
    note(sensPlot.p, null);
    const zs = input.setup?.zoneSize ?? 16;
    const heights = r.zones.map((z) => z.height);
    const lo = Math.min(...heights);
    const hi = Math.max(...heights);
    const worst = Math.max(...r.zones.map((z) => Math.abs(z.height - z.linearHeight)));
    const items: [string, string, string][] = [
      ['cb-span', 'Zone heights', `${show('errLength', lo)} to ${show('errLength', hi)} (spread ${show('errLength', hi - lo)})`],
      ['cb-high', 'Highest / lowest zone', `${r.zones[heights.indexOf(hi)].name} / ${r.zones[heights.indexOf(lo)].name}`],
      ['cb-linear', 'Exact vs first order Σ k·ε', `differ by at most ${show('errLength', worst)}`],
      ['cb-frame', 'Frame', frameText(r)],
    ];
    summary.replaceChildren();
    for (const [id, k, v] of items) summary.append(el('dt', {}, k), el('dd', { id }, v));

    // 3 × 3 map: rows bottom (−Y) to top, columns left (−X) to right, like Fig 2.
    const R = D(colourRange());
    const at = (row: number, col: number) => r.zones.find((z) => z.row === row && z.col === col)!;
    const coords = [-zs, 0, zs];
    const z: number[][] = [-1, 0, 1].map((row) => [-1, 0, 1].map((col) => D(at(row, col).height)));
    const rise = (s: number) => show('errLength', s * zs);
    const text = [-1, 0, 1].map((row) => [-1, 0, 1].map((col) => {
      const q = at(row, col);
      return `ZONE ${q.name}: B = ${fmt.num(q.b, 5)}°, C = ${fmt.num(q.c, 5)}°<br>height ${show('errLength', q.height)}` +
        ` (first order ${show('errLength', q.linearHeight)})<br>tilt: rises ${rise(q.slopeX)} along +X, ${rise(q.slopeY)} along +Y over the zone`;
    }));
    const annotations: Partial<Annotations>[] = r.zones.map((q) => ({
      x: q.col * zs, y: q.row * zs, xref: 'x', yref: 'y', showarrow: false,
      text: `<b>${q.name}</b><br>${show('errLength', q.height, 3)}`,
      font: { size: 12, color: '#1f2328' }, bgcolor: 'rgba(255,255,255,0.8)', borderpad: 2,
    }));
    draw(zonesPlot.p, `Zone heights at the zone centres<br>${frameText(r)}`, [{
      type: 'heatmap', x: coords, y: coords, z, text: text as unknown as string[], hovertemplate: '%{text}<extra></extra>',
      colorscale: 'RdBu', zmin: -R, zmax: R, name: 'zone height',
      colorbar: { title: { text: titled('height', 'errLength') } },
    } as Data], {
      xaxis: axis('X (mm)', { tickvals: coords, constrain: 'domain' }),
      yaxis: axis('Y (mm)', { tickvals: coords, scaleanchor: 'x' }),
      annotations,
    }, 'cubic-zones');

    // Sensitivities: positions (mm per mm) above, angles (per the angle unit shown) below.
    const len = unitDef('errLength');
    const ang = unitDef('errAngle');
    const names = r.zones.map((q) => q.name);
    const colors = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];
    const data: Data[] = infos.map((info, e) => {
      const angular = info.unit === 'deg';
      const scale = angular ? len.factor / ang.factor : 1;
      const k = r.zones.map((_, zi) => r.kHeight[zi * 8 + e] * scale);
      const unit = angular ? `${len.label}/${ang.label}` : `${len.label}/${len.label}`;
      return {
        type: 'bar', x: names, y: k, name: `${info.symbol}${angular ? ' (angle)' : ''}`, marker: { color: colors[e] },
        xaxis: angular ? 'x2' : 'x', yaxis: angular ? 'y2' : 'y',
        hovertemplate: `${info.symbol} on ZONE %{x}: k = %{y:.4g} ${unit}<extra></extra>`,
      } as Data;
    });
    draw(sensPlot.p, `Sensitivity k = E/ε of the zone heights (eq 15; ${r.transform ? 'Fig 12' : 'Fig 10'}: ${frameText(r)})`, data, {
      grid: { rows: 2, columns: 1, pattern: 'independent', roworder: 'top to bottom' },
      barmode: 'group',
      xaxis: axis('zone', { anchor: 'y' }),
      yaxis: axis(`k, positions (${len.label}/${len.label})`),
      xaxis2: axis('zone', { anchor: 'y2' }),
      yaxis2: axis(`k, angles (${len.label}/${ang.label})`),
    } as Partial<Layout>, 'cubic-sensitivity');
  };

  const showMap = (m: CubicMapResult) => {
    note(mapPlot.p, null);
    const R = D(colourRange());
    const passAligned = (m.ny - 1) % 12 === 0 && Math.abs((m.y[1] - m.y[0]) * 4 - m.step) < 1e-9 * m.step;
    const small = downsample(m, DISPLAY_SIDE, passAligned ? 4 : 1);
    const zs = (m.x[m.nx - 1] - m.x[0]) / 3;
    const annotations: Partial<Annotations>[] = m.zoneAverage.map((v, i) => ({
      x: m.zones[i].x, y: m.zones[i].y, xref: 'x', yref: 'y', showarrow: false,
      text: `${m.zones[i].name}: ${show('errLength', v, 3)}`, font: { size: 11, color: '#1f2328' },
      bgcolor: 'rgba(255,255,255,0.8)', borderpad: 2,
    }));
    const shapes: Partial<Shape>[] = [-0.5, 0.5].flatMap((t) => [
      { type: 'line', x0: t * zs, x1: t * zs, y0: -1.5 * zs, y1: 1.5 * zs, line: { color: '#555', width: 1, dash: 'dot' } },
      { type: 'line', y0: t * zs, y1: t * zs, x0: -1.5 * zs, x1: 1.5 * zs, line: { color: '#555', width: 1, dash: 'dot' } },
    ]);
    draw(mapPlot.p, `Simulated machined face, zone averages (Fig 16(b))<br>${m.nx} × ${m.ny} points (shown ${small.x.length} × ${small.y.length}); scallops ${show('errLength', m.scallop, 3)}`, [{
      type: 'heatmap', x: small.x, y: small.y, z: small.z.map((row) => row.map(D)), colorscale: 'RdBu',
      zmin: -R, zmax: R, name: 'height', colorbar: { title: { text: titled('height', 'errLength') } },
      hovertemplate: `X %{x:.2f} mm, Y %{y:.2f} mm<br>height %{z:.4g} ${unitDef('errLength').label}<extra></extra>`,
    } as Data], {
      xaxis: axis('X (mm)', { constrain: 'domain' }),
      yaxis: axis('Y (mm)', { scaleanchor: 'x' }),
      annotations, shapes,
    }, 'cubic-height-map');
  };

  for (const input of form.querySelectorAll('input, select')) input.addEventListener('input', update);
  onUnitsChange(() => {
    if (lastTest) showTest(lastTest.r, lastTest.input);
    if (lastMap) showMap(lastMap);
  });
  update();
}

/** "Positional error of B-axis average line along X-axis direction" → shorter label text. */
function shortDescription(i: CubicErrorInfo): string {
  return i.description
    .replace('Positional error of ', '')
    .replace('Orientation error between ', '')
    .replace(' average line', '')
    .replace(' direction', '')
    .replace(/ \(.*\)$/, '');
}

/**
 * The map as rows for Plotly, averaged over blocks so that neither side exceeds `max`; the
 * rows in blocks of a multiple of `period` (rows per scallop period, so whole periods are
 * averaged).
 */
function downsample(m: CubicMapResult, max: number, period: number): { x: number[]; y: number[]; z: number[][] } {
  const sx = Math.max(1, Math.ceil(m.nx / max));
  const sy = period * Math.max(1, Math.ceil(m.ny / (period * max)));
  const blocks = (n: number, s: number) => Array.from({ length: Math.ceil(n / s) }, (_, b) => [b * s, Math.min(n, (b + 1) * s)]);
  const bx = blocks(m.nx, sx);
  const by = blocks(m.ny, sy);
  const mean = (v: ArrayLike<number>, [a, b]: number[]) => {
    let t = 0;
    for (let i = a; i < b; i++) t += v[i];
    return t / (b - a);
  };
  const z = by.map(([y0, y1]) =>
    bx.map(([x0, x1]) => {
      let t = 0;
      for (let iy = y0; iy < y1; iy++) for (let ix = x0; ix < x1; ix++) t += m.height[iy * m.nx + ix];
      return t / ((y1 - y0) * (x1 - x0));
    }),
  );
  return { x: bx.map((b) => mean(m.x, b)), y: by.map((b) => mean(m.y, b)), z };
}
