// The "Cubic-machining test" panel: Li, Sato, Shirase & Sakamoto (2021) on the machine of the
// Machine section. A ball-end mill cuts a 3 × 3-zone face square to the spindle; which zones come
// out high or low for the machine's errors, and which errors the test cannot see.
import type { Annotations, Data, Layout, Shape } from 'plotly.js';
import type { CubicDesignResult, CubicIdentifyResult, CubicInput, CubicLayoutReport, CubicResult, HeightMap, Machine } from '@engine';
import { channel, EngineError, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el, fields, numberField } from '../ui/fields';
import { encodingNote, readOrRefuse } from '../ui/files';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, stale } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, ROUND_OFF, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';
import { clearPlot, identificationView, sourceText, type Source } from '../ui/identify';
import { download } from '../ui/export';
import { errorWords, lowerFirst, rankParts, judge, unseenOf, verdictBox } from '../ui/verdict';

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
  exports: ['cubicTest', 'cubicHeightMap', 'cubicIdentify', 'cubicDesign'],
  mount,
};

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Cubic-machining test: 3 × 3 zone heights',
    'A ball-end mill (Ø6 mm) cuts the nine 16 × 16 mm zones of a 48 × 48 mm face square to the spindle, with the ' +
      'rotary axes standing still in each zone: ZONE I with the tool along the spindle, the others tilted 30° towards ' +
      'the centre. The machine’s geometric errors (above) make each zone come out higher (material left, ' +
      'positive) or lower than nominal; the verdict compares the worst zone with your tolerance and names the errors behind it. ' +
      'After Li, Sato, Shirase & Sakamoto, Precision Engineering 71 (2021), on any machine.',
  );

  // ---- inputs: the shown fields of the cubic exports; the colour scale is the page's own
  form.append(presetPicker('cubic', 'cb', machine));
  const inputs = renderFields(cubicPanel.exports.flatMap((n) => schema.exports[n]), 'cb', form, machine.context());
  const range = numberField({ id: 'cb-range', label: 'Colour scale ± (0: automatic)', quantity: 'errLength', value: 0, min: 0, max: 50,
    hint: 'The paper’s Fig 16 uses ±0.01 mm.' });
  (inputs.groups.get('Height map') ?? form).append(range.root);
  const fileLabel = el('label', { class: 'import', for: 'cb-file' }, 'Choose a file ');
  const file = el('input', { id: 'cb-file', type: 'file', accept: '.csv,text/csv,text/plain' });
  fileLabel.append(file);
  const fileRow = el('div', { class: 'file-row' });
  fileRow.append(fileLabel);
  const fileMsg = el('p', { class: 'field-hint', id: 'cb-file-msg', 'aria-live': 'polite' });
  inputs.groups.get('Identification')?.querySelector('legend')?.after(fileRow, fileMsg);
  const csvArea = form.querySelector<HTMLTextAreaElement>('#cb-csv');
  if (csvArea) csvArea.placeholder = 'zone,height_um,slope_x,slope_y\nI,0,,\nII-1,-5.4,0.00002,0\n…';

  // ---- outputs
  const words = errorWords(schema);
  const verdict = verdictBox({
    prefix: 'cb',
    tolerance: { label: 'Tolerance on a zone’s height', value: 0.01, hint: 'The largest height error of a zone you accept (material left or missing, from nominal).' },
    onTolerance: () => judgeTest(),
  });
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
  // A failed measurement file is said at the top, where it cannot be missed.
  const alert = el('p', { class: 'alert', id: 'cb-alert', role: 'alert' });
  alert.hidden = true;
  const ident = el('div', { class: 'ident', id: 'cb-ident', 'aria-live': 'polite' });
  const fitPlot = plot('cb-fit', true);
  const identPlots = el('div', { class: 'plots' });
  identPlots.append(fitPlot.wrap);
  const designOut = el('div', { class: 'ident', id: 'cb-design', 'aria-live': 'polite' });
  const svPlot = plot('cb-design-sv', true);
  const designPlots = el('div', { class: 'plots' });
  designPlots.append(svPlot.wrap);
  results.append(verdict.root, alert, summary, plots,
    el('h3', {}, 'Identification from measured zones'), ident, identPlots,
    el('h3', {}, 'Test designer: a test that can tell the errors apart'), designOut, designPlots);

  // ---- computation
  const runTest = channel('cubicTest');
  const runMap = channel('cubicHeightMap');
  const runIdentify = channel('cubicIdentify');
  const runDesign = channel('cubicDesign');
  let source: Source = { name: 'text typed or pasted in the field', at: new Date() };
  let sourceCsv = '';
  let lastDesign: CubicDesignResult | null = null;
  let lastIdent: { r: CubicIdentifyResult; from: Source } | null = null;
  /** Shows an engine error at the field it names (or over the plot when it names none). */
  const engineError = engineErrors({ ...inputs.byPath, range }, machine);

  let lastTest: { r: CubicResult; input: CubicInput } | null = null;
  /** Whether `lastTest` answers the inputs as they are (a verdict may be drawn from it). */
  let fresh = false;
  let lastMap: HeightMap | null = null;
  let fixedRange: number | null = null; // mm, or null for automatic

  /** The shared colour range, mm: the chosen one, or 1.25 × the largest zone height. */
  const colourRange = () => {
    if (fixedRange) return fixedRange;
    const hs = lastTest ? lastTest.r.zones.map((z) => Math.abs(z.height)) : [];
    return Math.max(5e-4, 1.25 * Math.max(0, ...hs));
  };

  const update = () => {
    inputs.setContext(machine.context());
    inputs.setNames(machine.errorOptions());
    const m = machine.current();
    const own = inputs.read();
    const rng = range.read();
    if (!m || !own || rng === null) {
      fresh = false;
      verdict.invalid();
      for (const p of [zonesPlot, mapPlot, sensPlot, fitPlot, svPlot]) stale(p.p, true);
      stale(ident, true);
      stale(designOut, true);
      for (const run of [runTest, runMap, runIdentify, runDesign]) run.cancel(); // a late result would look current
      return;
    }
    fixedRange = rng ? rng : null;
    const { nx, ny, csv, parameters, rtol, decision, grid, maxTilt, slopes, secondSetup, noise, ...test } = own as Record<string, unknown>;
    const input = { ...test, machine: m as Machine } as CubicInput;
    verdict.pending();
    fresh = false; // the verdict waits for the zones of these inputs
    runTest(input).then((r) => {
      if (r === SUPERSEDED) return;
      lastTest = { r, input };
      fresh = true;
      showTest(r, input);
      judgeTest();
      if (lastMap) showMap(lastMap);
    }, (e) => {
      fresh = false;
      engineError(e, zonesPlot.p);
      verdict.refused(e);
      stale(sensPlot.p, true); // fed by the same computation
    });
    runMap({ ...input, nx: nx as number, ...(ny === undefined ? {} : { ny: ny as number }) }).then((map) => {
      if (map === SUPERSEDED) return;
      lastMap = map;
      showMap(map);
    }, (e) => engineError(e, mapPlot.p));
    identify({ ...input, csv: csv as string, parameters, rtol, decision } as never);
    runDesign({ ...input, parameters, grid, maxTilt, slopes, secondSetup, noise } as never).then((d) => {
      if (d === SUPERSEDED) return;
      lastDesign = d;
      showDesign(d);
    }, (e) => {
      engineError(e, svPlot.p);
      stale(designOut, true);
    });
  };

  // ---- identification
  const setAlert = (text: string | null) => {
    alert.textContent = text ?? '';
    alert.hidden = !text;
    // Brought into view: the user is down at the file field when a file fails.
    if (text) alert.scrollIntoView({ block: 'nearest' });
  };
  /** Drops the last identification at once: its numbers belong to another file or inputs. */
  const clearIdentification = (message: Node) => {
    lastIdent = null;
    ident.replaceChildren(message);
    stale(ident, false);
    void clearPlot(fitPlot.p);
  };
  const identify = (input: CubicInput & { csv: string }) => {
    if (!input.csv || input.csv.trim() === '') {
      inputs.byPath.csv?.setError(null);
      setAlert(null);
      runIdentify.cancel();
      clearIdentification(el('p', { class: 'field-hint' }, 'Paste or choose a file of measured zone heights (and slopes) to identify the machine’s errors: the paper’s zones by name, or the rows of a designed test as exported below with their heights filled in.'));
      return;
    }
    if (input.csv !== sourceCsv) {
      source = { name: 'text typed or pasted in the field', at: new Date() };
      sourceCsv = input.csv;
    }
    const from = source;
    runIdentify(input as never).then((r) => {
      if (r === SUPERSEDED) return;
      inputs.byPath.csv?.setError(null);
      setAlert(null);
      lastIdent = { r, from };
      showIdentification(r, from);
    }, (e) => {
      const err = EngineError.of(e);
      setAlert(`No identification from ${from.name}: ${err.text} The previous results were removed.`);
      clearIdentification(el('p', { class: 'warn', id: 'cb-ident-failed' }, `No identification: ${from.name} could not be used (${err.text}).`));
      showAtField(e, inputs.byPath, machine);
    });
  };

  const showIdentification = (r: CubicIdentifyResult, from: Source) => {
    ident.replaceChildren(...identificationView('cb', r, sourceText(from, r.zones.length, 'zones')));
    stale(ident, false);
    const labels = r.rowZone.map((z, i) => `${r.zones[z].name} ${r.rowKind[i] === 'height' ? 'height' : r.rowKind[i] === 'slopeX' ? `tilt along ${machine.context().u}` : `tilt along ${machine.context().v}`}`);
    const x = labels.map((_, i) => i + 1);
    draw(fitPlot.p, `Measured and fitted per zone<br>a tilt as the height it makes over half a zone<br>${from.name}<br>residual RMS ${show('errLength', r.rms)}`, [
      { x, y: Array.from(r.measured, D), type: 'bar', name: 'measured', marker: { color: '#9fb7d0' }, hovertext: labels, hovertemplate: `%{hovertext}<br>measured %{y:.4g} ${unitDef('errLength').label}<extra></extra>` },
      { x, y: Array.from(r.fitted, D), type: 'scatter', mode: 'markers', name: 'identified errors', marker: { color: '#d62728', size: 8, symbol: 'diamond' }, text: labels, hovertemplate: `%{text}<br>model %{y:.4g} ${unitDef('errLength').label}<extra></extra>` },
    ], {
      xaxis: axis('measured value (zone, then its tilts)', { tickvals: x, ticktext: r.rowZone.map((z, i) => (r.rowKind[i] === 'height' ? r.zones[z].name : '')), tickangle: -60 }),
      yaxis: axis(titled('height', 'errLength')),
      legend: { orientation: 'h', x: 0, y: -0.45, xanchor: 'left', yanchor: 'top' },
      margin: { b: 110 },
    } as Partial<Layout>, 'cubic-identification');
  };

  // ---- designer
  const showDesign = (d: CubicDesignResult) => {
    const ctx = machine.context();
    note(svPlot.p, null);
    const paper = d.paper;
    const dz = d.designed;
    const cond = (r: CubicLayoutReport) => (r.condition === null ? 'infinite (rank short)' : fmt.num(r.condition, 3));
    const seen = (r: CubicLayoutReport) => r.identifiable.join(', ') || 'none';
    const apart = (r: CubicLayoutReport) => r.groups.map((g) => g.combinations.length ? `only ${g.combinations.join(', ')}` : `not ${g.members.join(', ')}`).join('; ') || '—';
    const noPaper = `cannot be cut: ${d.paperMessage ?? ''}`;
    const rowsData: [string, string, string][] = [
      ['Rank (independent combinations the test determines)', paper ? `${paper.rank} of ${d.reachableRank} possible` : noPaper, `${dz.rank} of ${d.reachableRank} possible`],
      ['Condition number σ₁/σᵣ', paper ? cond(paper) : '—', cond(dz)],
      ['Weakest combination of typical errors, in noise standard deviations', paper ? fmt.num(paper.smallest, 3) : '—', fmt.num(dz.smallest, 3)],
      ['Errors it identifies on their own', paper ? seen(paper) : '—', seen(dz)],
      ['Combinations only, or nothing', paper ? apart(paper) : '—', apart(dz)],
      ['Zones', paper ? `${paper.zones.length}` : '—', `${dz.zones.length}${dz.zones.some((z) => z.setup === 2) ? ' (two set-ups)' : ''}`],
    ];
    const t = el('table', { class: 'ident-table', id: 'cb-design-compare' });
    const h = el('tr');
    for (const c of ['', 'paper’s layout (Table 1)', 'designed test']) h.append(el('th', { scope: 'col' }, c));
    t.append(el('thead'), el('tbody'));
    t.tHead!.append(h);
    for (const [k, a, b] of rowsData) {
      const tr = el('tr');
      tr.append(el('th', { scope: 'row' }, k), el('td', {}, a), el('td', {}, b));
      t.tBodies[0].append(tr);
    }
    const unseen = el('p', { id: 'cb-design-unseen' }, `What no test of this kind can see on this machine (all ${d.candidates} reachable zones together, rank ${d.reachableRank} of ${d.errorNames.length}): ` +
      (d.unseen.map((g) => (g.combinations.length ? `${g.members.join(' and ')} only as ${g.combinations.join(', ')}` : g.members.join(', '))).join('; ') || 'nothing') +
      '. An offset along an axis’s own line moves no point; an error the set-up at zero absorbs changes nothing; a table axis’s offset across its line moves the piece within the face.');
    const zt = el('table', { class: 'ident-table', id: 'cb-design-zones' });
    const zh = el('tr');
    for (const c of ['zone', 'set-up', `face centre off the table, along ${ctx.u} (mm)`, `centre ${ctx.u}, ${ctx.v} (mm)`, 'tilt (°)', 'azimuth (°)', 'tool vector (i, j, k)', `${ctx.k}, ${ctx.m} (°)`]) zh.append(el('th', { scope: 'col' }, c));
    zt.append(el('thead'), el('tbody'));
    zt.tHead!.append(zh);
    for (const z of dz.zones) {
      const tr = el('tr');
      tr.append(el('th', { scope: 'row' }, z.name), el('td', {}, String(z.setup)), el('td', {}, fmt.num(z.pieceX, 4)), el('td', {}, `${fmt.num(z.x, 4)}, ${fmt.num(z.y, 4)}`),
        el('td', {}, fmt.num(z.tilt, 4)), el('td', {}, fmt.num(z.azimuth, 4)), el('td', {}, fmt.vector(z.toolVector, 4)), el('td', {}, `${fmt.num(z.k, 5)}, ${fmt.num(z.m, 5)}`));
      zt.tBodies[0].append(tr);
    }
    const scroll = el('div', { class: 'table-scroll' });
    scroll.append(zt);
    const exportButton = el('button', { type: 'button', id: 'cb-design-export' }, 'Download the zone table (CSV)');
    exportButton.addEventListener('click', () => download('cubic-designed-test.csv', dz.csv, 'text/csv'));
    const compareScroll = el('div', { class: 'table-scroll' });
    compareScroll.append(t);
    designOut.replaceChildren(compareScroll, unseen, el('p', { class: 'field-hint' }, `Scaling: ${d.scaling}`), el('h4', {}, 'The designed test: zones to machine'), scroll, exportButton);
    stale(designOut, false);
    const idx = Array.from({ length: d.reachableRank }, (_, i) => i + 1);
    const data: Data[] = [
      { x: idx, y: dz.singularValues.slice(0, d.reachableRank), type: 'bar', name: 'designed test', marker: { color: '#2ca02c' }, hovertemplate: 'σ%{x} = %{y:.3g}<extra>designed</extra>' } as Data,
    ];
    if (paper) data.unshift({ x: idx, y: paper.singularValues.slice(0, d.reachableRank).map((v) => Math.max(v, 1e-3)), type: 'bar', name: 'paper’s layout', marker: { color: '#9fb7d0' }, hovertemplate: 'σ%{x} = %{y:.3g}<extra>paper</extra>' } as Data);
    draw(svPlot.p, `Singular values of the scaled sensitivities<br>(noise std. dev. per typical error; 10⁻³ = zero)<br>the smallest decides what the test tells apart`, data, {
      barmode: 'group',
      xaxis: axis('singular value number', { tickvals: idx }),
      yaxis: axis('σ (noise std. dev.)', { type: 'log' }),
      legend: { orientation: 'h', x: 0, y: -0.3, xanchor: 'left', yanchor: 'top' },
    } as Partial<Layout>, 'cubic-design-singular-values');
  };

  const frameText = (r: CubicResult) =>
    `${r.transform ? 'workpiece set with every axis at zero' : 'workpiece frame = table frame'}, ${REFERENCE_SHORT[r.reference] ?? r.reference}`;

  /** The zones judged: all but ZONE I when it is the reference (its height 0 by definition). */
  const judged = (r: CubicResult) => r.zones.filter((z) => !(z.name === 'I' && (r.reference !== 'workpiece' || Math.abs(z.height) < ROUND_OFF)));

  /** The verdict: the worst zone's height (the engine's) against the tolerance, the errors behind it. */
  const judgeTest = () => {
    const tol = verdict.tolerance();
    if (tol === null) return verdict.invalid();
    if (!lastTest || !fresh) return;
    const { r } = lastTest;
    const n = r.errorNames.length;
    // The errors entered that no zone height changes with (the engine's sensitivities).
    const unseen = unseenOf('the cubic test', lastTest.input.machine ?? {}, schema, (name) => !r.visibility.invisible.includes(name));
    const zones = judged(r);
    const worst = zones.reduce((a, z) => (Math.abs(z.height) > Math.abs(a.height) ? z : a), zones[0]);
    const zi = r.zones.indexOf(worst);
    const parts: [string, number][] = r.errorNames.map((name, e) => [name, r.single[zi * n + e]]);
    const anyError = Array.from(r.single).some((v) => v !== 0);
    const status = judge(worst.height, tol);
    const t = show('errLength', tol);
    if (!anyError && Math.abs(worst.height) < ROUND_OFF) {
      return verdict.show({ status: 'pass', worst: 0, tolerance: tol, unseen, sentence: `No errors entered: every zone at 0 (within the ${t} tolerance). Enter the machine’s errors above, or choose a preset.` });
    }
    if (Math.abs(worst.height) < ROUND_OFF) {
      return verdict.show({ status: 'pass', worst: 0, tolerance: tol, unseen,
        sentence: `Every zone at 0: the errors entered change no zone’s height (${r.visibility.invisible.join(', ') || 'they cancel'}), within the ${t} tolerance.` });
    }
    const ranked = rankParts(parts, (v) => show('errLength', v), words);
    const top = ranked[0];
    const side = worst.height < 0 ? 'low' : 'high';
    const because = top ? `; ${fmt.percent(top.share, 2)} of it comes from ${top.name}, the ${lowerFirst(top.label ?? top.name)}` : '';
    verdict.show({
      status, worst: Math.abs(worst.height), tolerance: tol, unseen,
      sentence: `Worst zone ${worst.name} is ${show('errLength', Math.abs(worst.height))} ${side}, ${status === 'pass' ? 'within' : 'above'} the ${t} tolerance${because}.`,
      contributors: ranked,
      contributorsOf: `each error alone on zone ${worst.name}, as a share of the sum of their sizes`,
    });
  };

  const showTest = (r: CubicResult, input: CubicInput) => {
    const ctx = machine.context();
    note(zonesPlot.p, null);
    note(sensPlot.p, null);
    const zs = input.setup?.zoneSize ?? 16;
    const heights = r.zones.map((z) => z.height);
    const lo = Math.min(...heights);
    const hi = Math.max(...heights);
    // ZONE I is left out of "highest / lowest" when it is the reference (0 by definition).
    const others = judged(r);
    const oh = others.map((z) => z.height);
    const highest = others[oh.indexOf(Math.max(...oh))];
    const lowest = others[oh.indexOf(Math.min(...oh))];
    const worst = Math.max(...r.zones.map((z) => Math.abs(z.height - z.linearHeight)));
    const v = r.visibility;
    const alike = v.alike.map((g) => g.map((x) => x.name).join(' ~ ')).join('; ');
    const items: [string, string, string][] = [
      ['cb-span', 'Zone heights', `${show('errLength', lo)} to ${show('errLength', hi)} (spread ${show('errLength', hi - lo)})`],
      ['cb-high', 'Highest / lowest zone', hi - lo < ROUND_OFF ? 'all zones at the same height' : `${highest.name} / ${lowest.name}`],
      ['cb-linear', 'Exact vs first-order estimate (sensitivity × error, summed)', `differ by at most ${show('errLength', worst)}`],
      ['cb-blind', 'Errors this test cannot see', v.invisible.length ? `${v.invisible.join(', ')} (no zone height changes${v.tiltOnly.length ? `; ${v.tiltOnly.join(', ')} only tilt zones` : ''})` : 'none'],
      ['cb-alike', 'Errors it cannot tell apart', alike ? `${alike} (their height changes are proportional)` : 'none'],
      ['cb-rank', 'Independent combinations the heights give', `${v.rank} of ${r.errorNames.length} errors`],
      ['cb-frame', 'Frame', frameText(r)],
    ];
    summary.replaceChildren();
    const tips: Record<string, string> = {
      'cb-linear': 'The first-order estimate adds each error times its sensitivity k = E/ε (the height change per unit of error, Li et al. eq 15); the exact heights come from the machine’s chain without approximation.',
      'cb-high': 'ZONE I, cut with the tool along the spindle where the workpiece was set, is the reference and is left out.',
      'cb-frame': 'Set with every axis at zero: the workpiece coordinate system is probed with the axes at zero (Li et al.’s M_WC, eqs 10–12).',
      'cb-rank': 'How many independent combinations of the errors the nine zone heights determine.',
    };
    for (const [id, k, val] of items) summary.append(el('dt', tips[id] ? { title: tips[id] } : {}, k), el('dd', { id }, val));

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

  const showMap = (m: HeightMap) => {
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

  file.addEventListener('change', async () => {
    const f = file.files?.[0];
    if (!f) return;
    file.value = '';
    if (f.size > 1_000_000) {
      fileMsg.textContent = `${f.name} is larger than 1 MB: not a file of measured zones.`;
      setAlert(`${f.name} is larger than 1 MB: not a file of measured zones. The previous results were removed.`);
      clearIdentification(el('p', { class: 'warn' }, `No identification: ${f.name} is not a file of measured zones.`));
      return;
    }
    const read = await readOrRefuse(f, (message) => {
      fileMsg.textContent = message;
      setAlert(`${message} The previous results were removed.`);
      clearIdentification(el('p', { class: 'warn' }, `No identification: ${message}`));
    });
    if (!read) return;
    const { text } = read;
    fileMsg.textContent = `Read ${f.name}${encodingNote(read)}.`;
    source = { name: f.name, at: new Date() };
    sourceCsv = text;
    clearIdentification(el('p', { class: 'field-hint' }, `Identifying ${f.name}…`));
    fields.get('cb-csv')?.setText(text);
  });
  form.addEventListener('input', (e) => {
    if ((e.target as HTMLElement).id !== 'cb-file') update();
  });
  machine.onChange(update);
  onUnitsChange(() => {
    if (lastTest) showTest(lastTest.r, lastTest.input);
    judgeTest();
    if (lastMap) showMap(lastMap);
    if (lastIdent) showIdentification(lastIdent.r, lastIdent.from);
    if (lastDesign) showDesign(lastDesign);
  });
  update();
}

/**
 * The map as rows for Plotly, averaged over blocks so that neither side exceeds `max`; the
 * rows in blocks of a multiple of `period` (rows per scallop period, so whole periods are
 * averaged).
 */
function downsample(m: HeightMap, max: number, period: number): { x: number[]; y: number[]; z: number[][] } {
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
