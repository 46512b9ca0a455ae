// The "Cubic-machining test" panel: Li, Sato, Shirase & Sakamoto (2021) on the machine of the
// Machine section. A ball-end mill cuts a 3 × 3-zone face square to the spindle; which zones come
// out high or low for the machine's errors, and which errors the test cannot see.
import type { Annotations, Data, Layout, Shape } from 'plotly.js';
import type { CubicInput, CubicMapResult, CubicResult, Machine } from '@engine';
import { channel, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el, numberField } from '../ui/fields';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, stale } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, ROUND_OFF, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, type Panel } from './panel';

/** A length from the engine (mm) in the small-length unit shown now. */
const D = (mm: number) => toDisplay('errLength', mm);

/** Most height-map points per side shown; finer maps are averaged in blocks for display. */
const DISPLAY_SIDE = 241;

const REFERENCE_SHORT: Record<string, string> = {
  workpiece: 'workpiece frame',
  'zone1-height': 'relative to ZONE I’s height',
  'zone1-plane': 'levelled on ZONE I',
};

export const cubicPanel: Panel = {
  id: 'cubic',
  prefix: 'cb',
  title: 'Cubic-machining test',
  exports: ['cubicTest', 'cubicHeightMap'],
  mount,
};

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Cubic-machining test: 3 × 3 zone heights',
    'A ball-end mill (Ø6 mm) cuts the nine 16 × 16 mm zones of a 48 × 48 mm face square to the spindle, with the ' +
      'rotary axes standing still in each zone: ZONE I with the tool along the spindle, the others tilted 30° towards ' +
      'the centre (Tables 1, 2). The machine’s geometric errors (above) make each zone come out higher (material left, ' +
      'positive) or lower than nominal. Li, Sato, Shirase & Sakamoto, Precision Engineering 71 (2021), eqs 1–15, on ' +
      'any machine.',
  );

  // ---- inputs: the shown fields of the cubic exports; the colour scale is the page's own
  form.append(presetPicker('cubic', 'cb', machine));
  const inputs = renderFields(cubicPanel.exports.flatMap((n) => schema.exports[n]), 'cb', form, machine.context());
  const range = numberField({ id: 'cb-range', label: 'Colour scale ± (0: automatic)', quantity: 'errLength', value: 0, min: 0, max: 50,
    hint: 'Fig 16 uses ±0.01 mm.' });
  (inputs.groups.get('Height map') ?? form).append(range.root);

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
  /** Shows an engine error at the field it names (or over the plot when it names none). */
  const engineError = engineErrors({ ...inputs.byPath, range }, machine);

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
    inputs.setContext(machine.context());
    const m = machine.current();
    const own = inputs.read();
    const rng = range.read();
    if (!m || !own || rng === null) {
      for (const p of [zonesPlot, mapPlot, sensPlot]) stale(p.p, true);
      for (const run of [runTest, runMap]) run.cancel(); // a late result would look current
      return;
    }
    fixedRange = rng ? rng : null;
    const { nx, ny, ...test } = own as Record<string, unknown>;
    const input = { ...test, machine: m as Machine } as CubicInput;
    runTest(input).then((r) => {
      if (r === SUPERSEDED) return;
      lastTest = { r, input };
      showTest(r, input);
      if (lastMap) showMap(lastMap);
    }, (e) => {
      engineError(e, zonesPlot.p);
      stale(sensPlot.p, true); // fed by the same computation
    });
    runMap({ ...input, nx: nx as number, ...(ny === undefined ? {} : { ny: ny as number }) }).then((map) => {
      if (map === SUPERSEDED) return;
      lastMap = map;
      showMap(map);
    }, (e) => engineError(e, mapPlot.p));
  };

  const frameText = (r: CubicResult) =>
    `${r.transform ? 'workpiece set at zero (M_WC)' : 'workpiece frame = table frame'}, ${REFERENCE_SHORT[r.reference] ?? r.reference}`;

  const showTest = (r: CubicResult, input: CubicInput) => {
    const ctx = machine.context();
    note(zonesPlot.p, null);
    note(sensPlot.p, null);
    const zs = input.setup?.zoneSize ?? 16;
    const heights = r.zones.map((z) => z.height);
    const lo = Math.min(...heights);
    const hi = Math.max(...heights);
    const worst = Math.max(...r.zones.map((z) => Math.abs(z.height - z.linearHeight)));
    const v = r.visibility;
    const alike = v.alike.map((g) => g.map((x) => x.name).join(' ~ ')).join('; ');
    const items: [string, string, string][] = [
      ['cb-span', 'Zone heights', `${show('errLength', lo)} to ${show('errLength', hi)} (spread ${show('errLength', hi - lo)})`],
      ['cb-high', 'Highest / lowest zone', hi - lo < ROUND_OFF ? 'all zones at the same height' : `${r.zones[heights.indexOf(hi)].name} / ${r.zones[heights.indexOf(lo)].name}`],
      ['cb-linear', 'Exact vs first order Σ k·ε', `differ by at most ${show('errLength', worst)}`],
      ['cb-blind', 'Errors this test cannot see', v.invisible.length ? `${v.invisible.join(', ')} (no zone height changes${v.tiltOnly.length ? `; ${v.tiltOnly.join(', ')} only tilt zones` : ''})` : 'none'],
      ['cb-alike', 'Errors it cannot tell apart', alike ? `${alike} (their height changes are proportional)` : 'none'],
      ['cb-rank', 'Independent combinations the heights give', `${v.rank} of ${r.errorNames.length} errors`],
      ['cb-frame', 'Frame', frameText(r)],
    ];
    summary.replaceChildren();
    for (const [id, k, val] of items) summary.append(el('dt', {}, k), el('dd', { id }, val));

    // 3 × 3 map: rows bottom (−v) to top, columns left (−u) to right, like Fig 2.
    const R = D(colourRange());
    const at = (row: number, col: number) => r.zones.find((z) => z.row === row && z.col === col)!;
    const coords = [-zs, 0, zs];
    const z: number[][] = [-1, 0, 1].map((row) => [-1, 0, 1].map((col) => D(at(row, col).height)));
    const rise = (s: number) => show('errLength', s * zs);
    const text = [-1, 0, 1].map((row) => [-1, 0, 1].map((col) => {
      const q = at(row, col);
      return `ZONE ${q.name}: ${ctx.k} = ${fmt.num(q.k, 5)}°, ${ctx.m} = ${fmt.num(q.m, 5)}°<br>height ${show('errLength', q.height)}` +
        ` (first order ${show('errLength', q.linearHeight)})<br>tilt: rises ${rise(q.slopeX)} along +${ctx.u}, ${rise(q.slopeY)} along +${ctx.v} over the zone`;
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
      xaxis: axis(`${ctx.u} (mm)`, { tickvals: coords, constrain: 'domain' }),
      yaxis: axis(`${ctx.v} (mm)`, { tickvals: coords, scaleanchor: 'x' }),
      annotations,
    }, 'cubic-zones');

    // Sensitivities: positions (per length unit) above, angles (per angle unit) below; only the
    // errors the heights see.
    const len = unitDef('errLength');
    const ang = unitDef('errAngle');
    const names = r.zones.map((q) => q.name);
    const colors = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f', '#aec7e8', '#ff9896', '#98df8a', '#c5b0d5', '#c49c94'];
    const n = r.errorNames.length;
    const data: Data[] = [];
    r.errorNames.forEach((name, e) => {
      if (v.invisible.includes(name)) return;
      const angular = r.errorUnits[e] === 'deg';
      const scale = angular ? len.factor / ang.factor : 1;
      const k = r.zones.map((_, zi) => r.kHeight[zi * n + e] * scale);
      const unit = angular ? `${len.label}/${ang.label}` : `${len.label}/${len.label}`;
      data.push({
        type: 'bar', x: names, y: k, name: `${name}${angular ? ' (angle)' : ''}`, marker: { color: colors[e % colors.length] },
        xaxis: angular ? 'x2' : 'x', yaxis: angular ? 'y2' : 'y',
        hovertemplate: `${name} on ZONE %{x}: k = %{y:.4g} ${unit}<extra></extra>`,
      } as Data);
    });
    draw(sensPlot.p, `Sensitivity k = E/ε of the zone heights to each error the test sees (eq 15)<br>${frameText(r)}`, data, {
      grid: { rows: 2, columns: 1, pattern: 'independent', roworder: 'top to bottom' },
      barmode: 'group',
      xaxis: axis('zone', { anchor: 'y' }),
      yaxis: axis(`k, positions (${len.label}/${len.label})`),
      xaxis2: axis('zone', { anchor: 'y2' }),
      yaxis2: axis(`k, angles (${len.label}/${ang.label})`),
    } as Partial<Layout>, 'cubic-sensitivity');
  };

  const showMap = (m: CubicMapResult) => {
    const ctx = machine.context();
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
      hovertemplate: `${ctx.u} %{x:.2f} mm, ${ctx.v} %{y:.2f} mm<br>height %{z:.4g} ${unitDef('errLength').label}<extra></extra>`,
    } as Data], {
      xaxis: axis(`${ctx.u} (mm)`, { constrain: 'domain' }),
      yaxis: axis(`${ctx.v} (mm)`, { scaleanchor: 'x' }),
      annotations, shapes,
    }, 'cubic-height-map');
  };

  form.addEventListener('input', update);
  machine.onChange(update);
  onUnitsChange(() => {
    if (lastTest) showTest(lastTest.r, lastTest.input);
    if (lastMap) showMap(lastMap);
  });
  update();
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
