// The "S-shape test piece" panel: ISO 10791-7:2020's five-axis test part after Chanal, Duc &
// Chevalier (Precision Engineering 75, 2022) on the machine of the Machine section: the part, the
// flank-milling overcut (eq 6 and the exact gouge), the machining defect of the machine's errors
// (eq 14, Fig 19) and their identification from measured deviations (Table 4, Fig 21).
import type { Data, Layout } from 'plotly.js';
import type { Machine, SShapeDefectsResult, SShapeIdentifyResult, SShapeOvercutResult, SShapeOvercutSurface, SShapePartResult } from '@engine';
import { call, channel, EngineError, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el, fields } from '../ui/fields';
import { encodingNote, readOrRefuse } from '../ui/files';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, rows, stale } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';
import { clearPlot, identificationView, sourceText as sourceText_, type Source } from '../ui/identify';
import { extent } from '../ui/arrays';
import { errorWords, lowerFirst, rankParts, judge, unseenOf, verdictBox } from '../ui/verdict';

export const sshapePanel: Panel = {
  id: 'sshape',
  prefix: 'ss',
  title: 'S-shape test piece',
  exports: ['sshapeDefects', 'sshapeOvercut', 'sshapeIdentify'],
  mount,
};

const SAMPLE = 'samples/sshape-measured.csv';
const COLORS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f', '#aec7e8', '#ffbb78', '#98df8a', '#ff9896', '#c5b0d5'];

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'S-shape test piece (ISO 10791-7)',
    'The five-axis acceptance part: two ruled surfaces between cubic B-splines, flank milled with a Ø20 mm end mill, ' +
      'its base on the table square to the spindle. How much of the 0.12 mm tolerance the geometry itself takes (overcut ' +
      'of a non-developable ruled surface), what the machine’s errors (above) do at the 100 measurement points, and ' +
      'which of them a measured part gives back; the verdict compares the machine’s worst point with your tolerance. ' +
      'After Chanal, Duc & Chevalier, Precision Engineering 75 (2022), on any machine.',
  );

  // ---- inputs: the shown fields of the S-shape exports; loading a file is the page's own
  form.append(presetPicker('sshape', 'ss', machine));
  const inputs = renderFields(sshapePanel.exports.flatMap((n) => schema.exports[n]), 'ss', form, machine.context());
  const sampleButton = el('button', { type: 'button', id: 'ss-load-sample' }, 'Load the sample file');
  const fileLabel = el('label', { class: 'import', for: 'ss-file' }, 'Choose a file ');
  const file = el('input', { id: 'ss-file', type: 'file', accept: '.csv,text/csv,text/plain' });
  fileLabel.append(file);
  const fileMsg = el('p', { class: 'field-hint', id: 'ss-file-msg', 'aria-live': 'polite' });
  const buttons = el('div', { class: 'file-row' });
  buttons.append(sampleButton, fileLabel);
  const identSet = inputs.groups.get('Identification');
  identSet?.querySelector('legend')?.after(buttons, fileMsg);
  const csvArea = form.querySelector<HTMLTextAreaElement>('#ss-csv');
  if (csvArea) csvArea.placeholder = 'curve,point,deviation_mm\ntop,1,0.0123\n…';

  // ---- outputs
  const words = errorWords(schema);
  const verdict = verdictBox({
    prefix: 'ss',
    tolerance: { label: 'Tolerance on the part’s surface', value: 0.02, hint: 'The largest deviation of a measured point from the nominal surface that you accept from the machine’s errors.' },
    onTolerance: () => judgeDefects(),
  });
  const summary = el('dl', { class: 'summary', id: 'ss-summary', 'aria-live': 'polite' });
  // A failed measurement file is said here, at the top, where it cannot be missed.
  const alert = el('p', { class: 'alert', id: 'ss-alert', role: 'alert' });
  alert.hidden = true;
  const plot = (id: string, wide = false, tall = false) => {
    const wrap = el('div', { class: wide ? 'plot-wrap wide' : 'plot-wrap' });
    const p = el('div', { class: 'plot', id });
    if (tall) p.style.height = '460px';
    wrap.append(p);
    return { wrap, p };
  };
  const part3d = plot('ss-part', true, true);
  const mapA = plot('ss-overcut-a', true);
  const mapB = plot('ss-overcut-b', true);
  const defects = plot('ss-defects', true, true);
  const fitPlot = plot('ss-fit', true);
  const residualPlot = plot('ss-residuals', true);
  const ident = el('div', { class: 'ident', id: 'ss-ident', 'aria-live': 'polite' });
  const plots = el('div', { class: 'plots' });
  plots.append(part3d.wrap, mapA.wrap, mapB.wrap, defects.wrap);
  const identPlots = el('div', { class: 'plots' });
  identPlots.append(fitPlot.wrap, residualPlot.wrap);
  results.append(verdict.root, alert, summary, plots, el('h3', {}, 'Identification from measured deviations'), ident, identPlots);

  // ---- state shared between the outputs
  const part = (await call('sshapePart', { nu: 131, nv: 7 })) as SShapePartResult;
  const labels = part.points.map((p) => `${p.curve} ${p.number} (${p.surface})`);
  let lastDefects: SShapeDefectsResult | null = null;
  let lastOvercut: SShapeOvercutResult | null = null;
  const summaryItems = new Map<string, [string, string]>();
  // The overcut by the paper's equation and its vectors: one level down, in the verdict's details.
  const paperSummary = el('dl', { class: 'summary', id: 'ss-paper-summary' });
  const PAPER_ROWS = new Set(['ss-max-a', 'ss-max-b', 'ss-max-b-inner']);
  const setSummary = (id: string, label: string, value: string) => {
    summaryItems.set(id, [label, value]);
    summary.replaceChildren();
    paperSummary.replaceChildren();
    for (const [key, [k, v]] of summaryItems) (PAPER_ROWS.has(key) ? paperSummary : summary).append(el('dt', {}, k), el('dd', { id: key }, v));
    verdict.details('From the paper: the overcut by its eq 6 and the exact gouge (Chanal et al. 2022)',
      el('p', { class: 'field-hint' }, 'Eq 6 estimates the overcut of flank milling a ruled surface from the tool radius R and the surface’s twist (its tangent T; the paper’s T, or T⊥ square to the rulings); the exact gouge is computed from the tool’s swept surface. N = R × T is the paper’s side of the tool.'),
      paperSummary);
  };

  /** Where the text in the measurement field came from. */
  let source: Source = { name: 'pasted text', at: new Date() };
  let sourceText = '';
  const setSource = (name: string, text: string) => {
    source = { name, at: new Date() };
    sourceText = text;
  };

  const runOvercut = channel('sshapeOvercut');
  const runDefects = channel('sshapeDefects');
  const runIdentify = channel('sshapeIdentify');

  /** Shows an engine error at the field it names (or over the plot when it names none). */
  const engineError = engineErrors(inputs.byPath, machine);

  /** The inputs, split per export. */
  const read = () => {
    inputs.setContext(machine.context());
    inputs.setNames(machine.errorOptions());
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) return null;
    const { tool, model, dR, nu, nv, csv, parameters, radiusTerm, rtol, decision } = own as Record<string, unknown>;
    return { machine: m as Machine, tool, model, dR, nu, nv, csv: csv as string, parameters, radiusTerm, rtol, decision };
  };

  /** Whether `lastDefects` answers the inputs as they are (a verdict may be drawn from it). */
  let fresh = false;
  /** The verdict: the engine's defect at its worst point against the tolerance, the errors behind it. */
  const judgeDefects = () => {
    const tol = verdict.tolerance();
    if (tol === null) return verdict.invalid();
    const d = lastDefects;
    if (!d || !fresh) return;
    const n = d.names.length;
    // The errors entered that move no measured point (the engine's sensitivities, eq 14).
    const m = machine.current();
    const sees = (name: string) => {
      const j = d.names.indexOf(name);
      if (j < 0) return true;
      for (let i = 0; i * n + j < d.sensitivity.length; i++) if (Math.abs(d.sensitivity[i * n + j]) > 1e-9) return true;
      return false;
    };
    const unseen = m ? unseenOf('the S-shape part', m, schema, sees) : undefined;
    let k = 0;
    for (let i = 1; i < d.total.length; i++) if (Math.abs(d.total[i]) > Math.abs(d.total[k])) k = i;
    const worst = Math.abs(d.total[k]);
    const t = show('errLength', tol);
    const overcut = lastOvercut ? Math.max(...lastOvercut.surfaces.map((x) => x.maxGouge)) : null;
    const notes = overcut === null ? [] : [`Apart from the machine, flank milling this non-developable surface with a Ø20 mm tool overcuts it by up to ${show('errLength', overcut)} (the part’s geometry, shown below).`];
    if (worst < 1e-9) {
      const any = Array.from(d.contributions).some((v) => v !== 0) || Array.from(d.radius).some((v) => v !== 0);
      return verdict.show({ status: 'pass', worst: 0, tolerance: tol, notes, unseen,
        sentence: any ? `The errors entered move no measured point off the surface (within the ${t} tolerance).` : `No errors entered: every measured point on the nominal surface (within the ${t} tolerance). Enter the machine’s errors above, or choose a preset.` });
    }
    const parts: [string, number][] = d.names.map((name, j) => [name, d.contributions[n * k + j]]);
    if (d.radius[k] !== 0) parts.push(['tool radius', d.radius[k]]);
    const ranked = rankParts(parts, (v) => show('errLength', v), words);
    for (const c of ranked) if (c.name === 'tool radius') (c.label = 'tool radius R′ − R'), (c.title = 'The tool’s actual radius minus its nominal radius (the paper’s dR).');
    const top = ranked[0];
    const p = part.points[k];
    const status = judge(worst, tol);
    const side = d.total[k] > 0 ? 'outside' : 'inside';
    verdict.show({
      status, worst, tolerance: tol, notes, unseen,
      sentence: `Worst point ${p.curve.toUpperCase()} ${p.number} (surface ${p.surface}) is ${show('errLength', worst)} ${side} the nominal surface, ${status === 'pass' ? 'within' : 'above'} the ${t} tolerance` +
        (top ? `; ${fmt.percent(top.share, 2)} of it comes from ${top.name === 'tool radius' ? 'the tool radius' : `${top.name}, the ${lowerFirst(top.label ?? top.name)}`}.` : '.'),
      contributors: ranked,
      contributorsOf: `each error’s part at ${p.curve.toUpperCase()} ${p.number}, as a share of the sum of their sizes`,
    });
  };

  const update = () => {
    const i = read();
    if (!i) {
      fresh = false;
      verdict.invalid();
      for (const p of [part3d, mapA, mapB, defects, fitPlot, residualPlot]) stale(p.p, true);
      stale(ident, true);
      for (const run of [runOvercut, runDefects, runIdentify]) run.cancel(); // a late result would look current
      return;
    }
    runOvercut({ tool: i.tool, nu: i.nu, nv: i.nv } as never).then((o) => {
      if (o === SUPERSEDED) return;
      lastOvercut = o;
      showOvercut(o);
      judgeDefects();
    }, (e) => engineError(e, mapA.p));
    fresh = false;
    verdict.pending();
    runDefects({ machine: i.machine, tool: i.tool, model: i.model, dR: i.dR } as never).then((d) => {
      if (d === SUPERSEDED) return;
      lastDefects = d;
      fresh = true;
      showDefects(d);
      showPart();
      judgeDefects();
    }, (e) => {
      engineError(e, defects.p);
      verdict.refused(e);
      stale(part3d.p, true); // coloured by the same defects
    });
    identify(i);
  };

  /** Drops the last identification at once: its numbers belong to another file or inputs. */
  const clearIdentification = (message: Node) => {
    ident.replaceChildren(message);
    stale(ident, false);
    void clearPlot(fitPlot.p);
    void clearPlot(residualPlot.p);
  };
  const setAlert = (text: string | null) => {
    alert.textContent = text ?? '';
    alert.hidden = !text;
    // Brought into view: the user is down at the file field when a file fails.
    if (text) alert.scrollIntoView({ block: 'nearest' });
  };

  const identify = (i: NonNullable<ReturnType<typeof read>>) => {
    const text = i.csv;
    if (text.trim() === '') {
      inputs.byPath.csv?.setError(null);
      setAlert(null);
      runIdentify.cancel();
      clearIdentification(el('p', { class: 'field-hint' }, 'Paste a measurement file, choose one, or load the sample file (a part simulated on Chanal et al.’s machine with Table 4’s errors) to identify the errors.'));
      return;
    }
    if (text !== sourceText) setSource('text typed or pasted in the field', text);
    const from = source;
    runIdentify({ machine: i.machine, tool: i.tool, model: i.model, csv: text, parameters: i.parameters, radiusTerm: i.radiusTerm, rtol: i.rtol, decision: i.decision } as never).then((f) => {
      if (f === SUPERSEDED) return;
      inputs.byPath.csv?.setError(null);
      setAlert(null);
      showIdentification(f, from);
    }, (e) => {
      // A failed identification clears the previous one at once: its numbers belong to another
      // file; the reason is said at the top of the panel and at the field.
      const err = EngineError.of(e);
      setAlert(`No identification from ${from.name}: ${err.text} The previous results were removed.`);
      clearIdentification(el('p', { class: 'warn', id: 'ss-ident-failed' }, `No identification: ${from.name} could not be used (${err.text}).`));
      showAtField(e, inputs.byPath, machine);
    });
  };

  // ---- drawing
  const D = (mm: number) => toDisplay('errLength', mm);
  const lu = () => unitDef('errLength').label;

  const showPart = () => {
    const surface = (i: number, color: string): Data => {
      const s = part.surfaces[i];
      const grid = (a: Float64Array) => rows(Array.from(a), s.nu, s.nv);
      return {
        type: 'surface', x: grid(s.x), y: grid(s.y), z: grid(s.z), name: `surface ${s.id}`, showscale: false,
        colorscale: [[0, color], [1, color]], opacity: 0.75, hoverinfo: 'name', showlegend: true,
      } as Data;
    };
    const total = lastDefects ? Array.from(lastDefects.total, D) : null;
    const pts: Data = {
      type: 'scatter3d', mode: 'markers', name: 'measurement points',
      x: part.points.map((p) => p.point[0]), y: part.points.map((p) => p.point[1]), z: part.points.map((p) => p.point[2]),
      text: labels,
      marker: total
        ? { size: 4, color: total, colorscale: 'RdBu', cmid: 0, colorbar: { title: { text: titled('defect', 'errLength') }, len: 0.6 } }
        : { size: 4, color: '#111' },
      hovertemplate: total ? `%{text}<br>defect %{marker.color:.4g} ${lu()}<extra></extra>` : '%{text}<extra></extra>',
    } as Data;
    draw(part3d.p, 'The part: surfaces A and B (Fig 3) and the 100 measurement points, coloured by the defect of the entered errors', [surface(0, '#b8c7d6'), surface(1, '#d4d4c4'), pts], {
      scene: {
        xaxis: { title: { text: 'x (mm)' } }, yaxis: { title: { text: 'y (mm)' } }, zaxis: { title: { text: 'z (mm)' } },
        aspectmode: 'manual', aspectratio: { x: 1.3, y: 1, z: 0.45 }, camera: { eye: { x: -0.95, y: -1.65, z: 1.05 }, center: { x: 0, y: 0, z: -0.08 } },
      },
      margin: { l: 0, r: 0, b: 0 },
      legend: { x: 0, y: 1, xanchor: 'left', bgcolor: 'rgba(255,255,255,0.7)' },
    } as Partial<Layout>, 'sshape-part');
  };

  const showOvercut = (o: SShapeOvercutResult) => {
    note(mapA.p, null);
    const u = Array.from(o.u);
    const z = Array.from(o.z);
    const one = (s: SShapeOvercutSurface, target: HTMLElement) => {
      const eq6 = rows(Array.from(s.eq6, D), o.nu, o.nv);
      const gouge = rows(Array.from(s.exact, (d) => D(Math.max(0, -d))), o.nu, o.nv);
      const hover = (what: string) => `u %{x:.4f}<br>z %{y:.2f} mm<br>${what} %{z:.4g} ${lu()}<extra></extra>`;
      const data: Data[] = [
        { type: 'heatmap', x: u, y: z, z: eq6, name: `eq 6 overcut, surface ${s.id}`, coloraxis: 'coloraxis', hovertemplate: hover('eq 6') } as Data,
        { type: 'heatmap', x: u, y: z, z: gouge, xaxis: 'x2', yaxis: 'y2', name: `exact gouge, surface ${s.id}`, coloraxis: 'coloraxis', hovertemplate: hover('gouge') } as Data,
      ];
      // Each map's name is in its own x-axis title, which stays under its map when a phone
      // stacks the two (no "left"/"right" in the title).
      draw(target, `Overcut on surface ${s.id}: eq 6 and the exact gouge<br>paper: ${show('errLength', s.id === 'A' ? o.paper.a : o.paper.b)} by eq 6`, data, {
        xaxis: axis(`eq 6 (max ${show('errLength', s.maxEq6)})<br>u along the S (0 at y = −95.5)`, { domain: [0, 0.45], range: [0, 1] }),
        yaxis: axis('z (mm)', { range: [0, 30] }),
        xaxis2: axis(`exact gouge (max ${show('errLength', s.maxGouge)})<br>u along the S`, { domain: [0.55, 1], range: [0, 1] }),
        yaxis2: axis('z (mm)', { anchor: 'x2', range: [0, 30] }),
        coloraxis: { colorscale: 'Viridis', cmin: 0, colorbar: { title: { text: titled('overcut', 'errLength') } } },
      } as Partial<Layout>, `sshape-overcut-${s.id}`);
    };
    one(o.surfaces[0], mapA.p);
    one(o.surfaces[1], mapB.p);
    const [a, b] = o.surfaces;
    setSummary('ss-max-a', 'Overcut, surface A', `eq 6 ${show('errLength', a.maxEq6)} (paper’s T: ${show('errLength', a.maxEq6Paper)}); exact gouge ${show('errLength', a.maxGouge)}; paper ${show('errLength', o.paper.a)}`);
    setSummary('ss-max-b', 'Overcut, surface B', `eq 6 ${show('errLength', b.maxEq6)} (paper’s T: ${show('errLength', b.maxEq6Paper)}); exact gouge ${show('errLength', b.maxGouge)}; paper ${show('errLength', o.paper.b)}`);
    setSummary('ss-max-b-inner', 'Surface B with the paper’s N = R × T', `eq 6 ${show('errLength', o.bPaperSide[0])}: the tool on the side facing A reproduces the paper’s ${show('errLength', o.paper.b)}`);
  };

  const showDefects = (d: SShapeDefectsResult) => {
    note(defects.p, null);
    const x = part.points.map((_, i) => i + 1);
    const data: Data[] = [];
    const n = d.names.length;
    d.names.forEach((name, j) => {
      const y = Array.from({ length: 100 }, (_, k) => D(d.contributions[n * k + j]));
      if (y.every((v) => v === 0)) return;
      data.push({ x, y, type: 'scatter', mode: 'lines', name, line: { color: COLORS[j % COLORS.length], width: 1.5 }, text: labels, hovertemplate: `%{text}<br>${name}: %{y:.4g} ${lu()}<extra></extra>` });
    });
    if (Array.from(d.radius).some((v) => v !== 0)) {
      data.push({ x, y: Array.from(d.radius, D), type: 'scatter', mode: 'lines', name: 'tool radius', line: { color: '#555', width: 1.5, dash: 'dot' }, text: labels, hovertemplate: `%{text}<br>tool radius: %{y:.4g} ${lu()}<extra></extra>` });
    }
    data.push({ x, y: Array.from(d.total, D), type: 'scatter', mode: 'lines+markers', name: 'total', line: { color: '#111', width: 2.5 }, marker: { size: 4 }, text: labels, hovertemplate: `%{text}<br>total: %{y:.4g} ${lu()}<extra></extra>` });
    const ctx = machine.context();
    const singular = d.poses.map((p, i) => (p.singular ? i : -1)).filter((i) => i >= 0);
    if (singular.length) {
      data.push({ x: singular.map((i) => i + 1), y: singular.map((i) => D(d.total[i])), type: 'scatter', mode: 'markers', name: `tool along ${ctx.k}: ${ctx.k} undefined, kept`, marker: { symbol: 'x', size: 10, color: '#d62728' }, text: singular.map((i) => labels[i]), hovertemplate: `%{text}<br>tool along the ${ctx.k} axis: ${ctx.k} kept from before<extra></extra>` });
    }
    const band = (x0: number, x1: number, text: string) => ({ type: 'rect', xref: 'x', yref: 'paper', x0, x1, y0: 0, y1: 1, fillcolor: text.includes('B') ? '#f6f8fa' : 'rgba(0,0,0,0)', line: { width: 0 }, layer: 'below' });
    draw(defects.p, `Machining defect at the measurement points (eq 14, Fig 19), one line per non-zero error<br>${referenceText(fields.get('ss-model-reference')?.text() ?? '')}; ${fields.get('ss-model-point')?.text() === 'contact' ? 'axis point at the measured height moved' : 'tool tip moved'}`, data, {
      xaxis: pointAxis(' (shaded)'),
      yaxis: axis(titled('deviation along the outward normal', 'errLength')),
      shapes: [band(25.5, 50.5, 'B'), band(75.5, 100.5, 'B'), { type: 'line', xref: 'x', yref: 'paper', x0: 50.5, x1: 50.5, y0: 0, y1: 1, line: { color: '#8c959f', width: 1, dash: 'dot' } }],
    } as Partial<Layout>, 'sshape-defects');
    const pairs = d.alike.slice(0, 4).map((p) => `${p.a} / ${p.b} ${fmt.num(p.cosine, 4)}`).join('; ');
    setSummary('ss-pairs', 'Errors the part can hardly tell apart', pairs ? `${pairs} (cosine of their effects; ±1: alike, not separable)` : 'none (no pair above 0.95)');
    setSummary('ss-singular', `Tool along ${ctx.k} (${ctx.k} undefined)`, `${singular.length} of 100 points: ${singular.map((i) => labels[i]).join(', ') || 'none'}`);
    const [lo, hi] = extent(d.total);
    setSummary('ss-range', 'Defect of the entered errors', `${show('errLength', lo)} to ${show('errLength', hi)}`);
  };

  const showIdentification = (f: SShapeIdentifyResult, from: Source) => {
    note(fitPlot.p, null);
    ident.replaceChildren(...identificationView('ss', f, sourceText_(from, f.measured.length, 'points'), (n) => (n === 'dR' ? 'tool radius R′ − R' : n)));
    stale(ident, false);
    const x = Array.from({ length: 100 }, (_, i) => i + 1);
    const xaxis = pointAxis('');
    draw(fitPlot.p, `Measured and fitted deviation (Fig 21a)<br>${from.name}`, [
      { x, y: Array.from(f.measured, D), type: 'scatter', mode: 'markers', name: 'measured', marker: { size: 5, color: '#1f77b4' }, text: labels, hovertemplate: `%{text}<br>measured %{y:.4g} ${lu()}<extra></extra>` },
      { x, y: Array.from(f.fitted, D), type: 'scatter', mode: 'lines', name: 'identified model', line: { color: '#d62728' }, text: labels, hovertemplate: `%{text}<br>model %{y:.4g} ${lu()}<extra></extra>` },
    ], { xaxis, yaxis: axis(titled('deviation', 'errLength')) }, 'sshape-fit');
    draw(residualPlot.p, `Residuals after the identification (Fig 21b): RMS ${show('errLength', f.rms)}`, [
      { x, y: Array.from(f.residuals, D), type: 'bar', name: 'measured − model', marker: { color: '#6e7781' }, text: labels, hovertemplate: `%{text}<br>residual %{y:.4g} ${lu()}<extra></extra>` },
    ], { xaxis, yaxis: axis(titled('residual', 'errLength')), showlegend: false }, 'sshape-residuals');
  };

  // ---- loading measurement files
  sampleButton.addEventListener('click', async () => {
    try {
      const res = await fetch(SAMPLE);
      if (!res.ok) throw new Error(`${res.status} ${res.statusText}`);
      const text = await res.text();
      setSource('the sample file sshape-measured.csv', text);
      fields.get('ss-csv')?.setText(text);
      fileMsg.textContent = 'Read the sample file (simulated: Table 4’s E_X0B and E_A0B, a tool 0.02 mm small, 2 µm noise).';
    } catch (e) {
      fileMsg.textContent = `Could not load the sample file: ${String(e)}`;
    }
  });
  file.addEventListener('change', async () => {
    const f = file.files?.[0];
    if (!f) return;
    if (f.size > 1_000_000) {
      fileMsg.textContent = `${f.name} is larger than 1 MB: not a measurement file of 100 points.`;
      setAlert(`${f.name} is larger than 1 MB: not a measurement file of 100 points. The previous results were removed.`);
      clearIdentification(el('p', { class: 'warn' }, `No identification: ${f.name} is not a measurement file.`));
      return;
    }
    file.value = '';
    const read = await readOrRefuse(f, (message) => {
      fileMsg.textContent = message;
      setAlert(`${message} The previous results were removed.`);
      clearIdentification(el('p', { class: 'warn' }, `No identification: ${message}`));
    });
    if (!read) return;
    const { text } = read;
    setSource(f.name, text);
    // The last identification goes at once: it belongs to the previous file.
    clearIdentification(el('p', { class: 'field-hint' }, `Identifying ${f.name}…`));
    fields.get('ss-csv')?.setText(text);
    fileMsg.textContent = `Read ${f.name}${encodingNote(read)} (${text.split(/\r?\n/).length} lines); the result below says whether it could be used.`;
  });

  form.addEventListener('input', (e) => {
    if ((e.target as HTMLElement).id !== 'ss-file') update();
  });
  machine.onChange(update);
  onUnitsChange(() => {
    update();
    if (lastOvercut) showOvercut(lastOvercut);
  });
  showPart();
  update();
}

/** The x axis of the per-point plots: list index 1..100, labelled with each curve's numbers. */
function pointAxis(extra: string) {
  const top = [1, 10, 20, 30, 40];
  const bottom = [1, 10, 20, 30, 40, 50];
  return axis(`point: T = TOP curve (z = 25 mm), B = BOTTOM (z = 11 mm); 1–25 on surface A, 26–50 on B${extra}`, {
    range: [0.5, 100.5], tickvals: [...top, ...bottom.map((v) => v + 50)], ticktext: [...top.map((v) => `T${v}`), ...bottom.map((v) => `B${v}`)],
  });
}

function referenceText(r: string): string {
  return r === 'axesZero' ? 'defect at all axes zero subtracted (eq 14 as printed)' : 'defect with the tool tip at the workpiece origin subtracted';
}
