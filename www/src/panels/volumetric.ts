// The "Volumetric error" panel: the tool tip's deviation over a plane of the working volume for
// the machine's location errors and its position-dependent error motions (ISO 230-1 E_XX … E_CC),
// the worst point and the error budget; Tan & Lim's RRTTT model beside it on their machine.
import type { Annotations, Data } from 'plotly.js';
import type { ErrorDef, Machine, VolumetricInput, VolumetricMap, PaperComparison } from '@engine';
import { call, channel, EngineError, SUPERSEDED } from '../engine/client';
import { debounced } from '../engine/idle';
import type { MachineSection, MotionFunction } from '../machine/section';
import { download } from '../ui/export';
import { el, selectField, type NumberField } from '../ui/fields';
import { FileRefused, readTextFile, WINDOWS_1252_NOTE } from '../ui/files';
import { displayQuantity, loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, plotBox, rows, stale } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { fromDisplay, onUnitsChange, ROUND_OFF, show, titled, toDisplay, unitDef, type Quantity } from '../ui/units';
import { engineErrors, panelShell, type Panel } from './panel';
import { extent } from '../ui/arrays';
import { errorWords, lowerFirst, judge, unseenOf, verdictBox } from '../ui/verdict';

export const volumetricPanel: Panel = {
  id: 'volumetric',
  prefix: 'vm',
  title: 'Volumetric error',
  exports: ['volumetricMap'],
  mount,
};

/** Draws a plot with its title broken into lines that fit its width (a phone is narrow). */
function drawFit(p: HTMLElement, title: string, ...rest: Parameters<typeof draw> extends [unknown, unknown, ...infer R] ? R : never) {
  const chars = Math.max(28, Math.floor((p.clientWidth || 600) / 7));
  const lines = title.split('<br>').flatMap((line) => {
    const out: string[] = [];
    let cur = '';
    for (const w of line.split(' ')) {
      if (cur && `${cur} ${w}`.length > chars) {
        out.push(cur);
        cur = w;
      } else cur = cur ? `${cur} ${w}` : w;
    }
    return [...out, cur];
  });
  return draw(p, lines.join('<br>'), ...rest);
}

/**
 * The top of a colour scale that starts at 0 (or runs from −top to top) for `values`, in the
 * display unit of `q`: their largest magnitude, or, when that is round-off (no error entered), a
 * tenth of a micrometre or 1e-4° (a scale still, the map at 0). Both ends are given: with one
 * only, Plotly stretches a near-constant map's scale over its round-off, and its ticks read
 * 164.70423213582998.
 */
function scaleTop(values: number[], q: 'errLength' | 'errAngle'): number {
  const [lo, hi] = extent(values);
  const top = Math.max(-lo, hi, 0);
  return top > toDisplay(q, ROUND_OFF) ? top : toDisplay(q, 1e-4);
}

/** A length from the engine (mm) in the unit shown now; an angle shown back to degrees. */
const D = (mm: number) => toDisplay('errLength', mm);
const fromAngle = (shown: number) => fromDisplay('errAngle', shown);
/** Arrows drawn per side of the map at most. */
const ARROWS = 11;
const COMPONENTS = [
  { value: 'dx', label: 'Δx: along X of the workpiece' },
  { value: 'dy', label: 'Δy: along Y of the workpiece' },
  { value: 'dz', label: 'Δz: along Z of the workpiece' },
] as const;

/** One error motion's row: its constant field, its CSV loader, its message and its plot. */
interface MotionRow {
  def: ErrorDef;
  field: NumberField;
  root: HTMLElement;
  msg: HTMLElement;
  clear: HTMLButtonElement;
  plot: HTMLElement;
  /** The key of what the plot shows (redrawn only when it changes). */
  shown: string;
  /** The name of the last file loaded here when it was read as Windows-1252. */
  windows1252?: string;
}

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Volumetric error: how far off the tool is over the working volume',
    'Every error of the machine at once: the location errors of its axes (Machine section above) and the error ' +
      'motions of each axis as measured along its travel (positioning, straightness, roll, pitch and yaw of X, Y, Z; ' +
      'radial, axial, tilt and angular errors of the rotary axes), each a constant or a table from the measuring ' +
      'software (laser interferometer, straightness optics, ball bar). The deviation of the tool tip from where the ' +
      'control believes it is computed exactly over a plane of the working volume, with the worst point and each ' +
      'error’s share; the verdict compares the worst point with your tolerance. After Tan & Lim, Modeling the Volumetric ' +
      'Errors in Calibration of Five-axis CNC Machine, on any machine.',
  );

  // ---- inputs: the region (from the schema), then the error motions per axis
  form.append(presetPicker('volumetric', 'vm', machine));
  const inputs = renderFields(volumetricPanel.exports.flatMap((n) => schema.exports[n]), 'vm', form, machine.context());
  const motionBox = el('div', { class: 'motions', id: 'vm-motions' });
  motionBox.append(
    el('h3', {}, 'Error motions of the axes (ISO 230-1)'),
    el('p', { class: 'field-hint' },
      'Each is a constant (in the small-length or small-angle unit chosen above) or a table against the axis ' +
        'position read from a CSV file: a header line “X (mm), E_XX (µm)”, then one position, value per line; ' +
        'values between the table’s points are interpolated linearly, and a position outside the table is refused. ' +
        'They belong to the machine: every study uses them.'),
  );
  form.append(motionBox);
  const axisSets = new Map<string, HTMLFieldSetElement>();
  const motionRows = new Map<string, MotionRow>();
  for (const { def, field } of machine.motions()) {
    let set = axisSets.get(def.axis);
    if (!set) {
      set = el('fieldset', { class: 'motion-set' });
      set.dataset.axis = def.axis;
      set.append(el('legend', {}, `${def.axis} axis`));
      axisSets.set(def.axis, set);
      motionBox.append(set);
    }
    motionRows.set(def.name, motionRow(def, field, set));
  }

  // ---- outputs
  const words = errorWords(schema);
  const verdict = verdictBox({
    prefix: 'vm',
    tolerance: { label: 'Tolerance on the tool tip’s position', value: 0.02, hint: 'The largest deviation of the tool tip you accept anywhere on the plane.' },
    onTolerance: () => judgeMap(),
  });
  const sentence = el('p', { class: 'result-sentence', id: 'vm-sentence', 'aria-live': 'polite' });
  verdict.root.querySelector('.verdict-head')?.after(sentence);
  const summary = el('dl', { class: 'summary', id: 'vm-summary', 'aria-live': 'polite' });
  const mapPlot = plotBox('vm-map', 'wide', 'tall');
  const compPlot = plotBox('vm-component');
  const component = selectField('vm-component-choice', 'Component shown', COMPONENTS.map((c) => ({ ...c })), 'dx');
  compPlot.wrap.prepend(component.root);
  const tiltPlot = plotBox('vm-tilt');
  const budgetPlot = plotBox('vm-budget', 'wide');
  const budgetTable = el('div', { class: 'table-wrap', id: 'vm-budget-table' });
  const exportButton = el('button', { type: 'button', id: 'vm-export', disabled: '' }, 'Download the map (CSV)');
  const exportRow = el('div', { class: 'file-row' });
  exportRow.append(exportButton, el('span', { class: 'field-hint' }, 'u, v, X, Y, Z, Δx, Δy, Δz, |Δ| and the tilt error at every point of the map.'));
  const plots = el('div', { class: 'plots' });
  plots.append(mapPlot.wrap, compPlot.wrap, tiltPlot.wrap, budgetPlot.wrap);
  const paper = el('details', { class: 'paper', id: 'vm-paper' });
  const paperBody = el('div', { id: 'vm-paper-body', 'aria-live': 'polite' });
  paper.append(el('summary', {}, 'Tan & Lim’s model (paper)'), paperBody);
  results.append(verdict.root, summary, exportRow, plots, el('h3', {}, 'Error budget'), budgetTable, paper);
  const allPlots = [mapPlot.p, compPlot.p, tiltPlot.p, budgetPlot.p];

  // ---- computation
  const runMap = channel('volumetricMap');
  const runPaper = channel('volumetricPaper');
  const fieldErrors = engineErrors(inputs.byPath, machine);
  let last: { r: VolumetricMap; input: VolumetricInput } | null = null;

  /** The verdict: the engine's worst point against the tolerance, the budget ranked. */
  const judgeMap = () => {
    const tol = verdict.tolerance();
    if (tol === null) return verdict.invalid();
    if (!last || !fresh) return;
    const { r } = last;
    const w = r.worst;
    const t = show('errLength', tol);
    // The errors entered that move the tool tip nowhere on this plane (the engine's budget leaves
    // out those whose first-order part is zero at every point).
    const unseen = unseenOf('the volumetric map on this plane', last.input.machine ?? {}, schema, (name) => r.budget.some((b) => b.name === name && b.max > 0));
    if (w.norm === 0) {
      return verdict.show({ status: 'pass', worst: 0, tolerance: tol, unseen,
        sentence: r.budget.length ? `The errors entered do not move the tool tip on this plane (within the ${t} tolerance).` : `No errors entered: the tool tip is where the control puts it everywhere on the plane (within the ${t} tolerance).` });
    }
    const status = judge(w.norm, tol);
    const top = r.budget.find((b) => b.share > 0);
    const at = `X ${fmt.num(w.position[0])}, Y ${fmt.num(w.position[1])}, Z ${fmt.num(w.position[2])} mm`;
    verdict.show({
      status, worst: w.norm, tolerance: tol, unseen,
      sentence: `Worst point ${show('errLength', w.norm)} off (at ${at}), ${status === 'pass' ? 'within' : 'above'} the ${t} tolerance` +
        (top ? `; the largest share, ${fmt.percent(top.share, 2)}, is ${top.name}, the ${lowerFirst(words.get(top.name)?.label ?? top.label)}.` : '.'),
      contributors: r.budget.filter((b) => b.share > 0).slice(0, 8).map((b) => ({
        name: b.name, label: words.get(b.name)?.label ?? b.label, title: words.get(b.name)?.title, share: b.share,
        amount: `up to ${show('errLength', b.max)} alone`,
      })),
      contributorsOf: 'share of the squared deviation over the plane, the error budget',
    });
  };

  /** Whether `last` answers the inputs as they are (a verdict may be drawn from it). */
  let fresh = false;
  const greyAll = () => {
    fresh = false;
    verdict.invalid();
    for (const p of allPlots) stale(p, true);
    budgetTable.classList.add('stale');
    sentence.classList.add('stale');
    paperBody.classList.add('stale');
  };
  /** An engine error: at the error motion it names (a table that does not cover the map), at the
   *  field, or over the map; every result greyed. */
  const engineError = (err: unknown) => {
    const e = EngineError.of(err);
    const name = e.field.startsWith('machine.motions.') ? e.field.slice('machine.motions.'.length) : '';
    const row = motionRows.get(name);
    if (row) {
      row.msg.classList.remove('ok');
      row.msg.textContent = e.text;
      note(mapPlot.p, e.message);
      stale(mapPlot.p, true);
    } else fieldErrors(err, mapPlot.p);
    greyAll();
    // A motion's table at fault is named by its row (not a field): the engine's words then.
    if (row) verdict.error(e.message);
    else verdict.refused(err);
  };

  const update = () => {
    const ctx = machine.context();
    inputs.setContext(ctx);
    syncAxes();
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) {
      greyAll();
      runMap.cancel(); // a late result would look current
      runPaper.cancel();
      return;
    }
    const input = { ...own, machine: m as Machine } as VolumetricInput;
    verdict.pending();
    fresh = false;
    runMap(input).then((r) => {
      if (r === SUPERSEDED) return;
      for (const row of motionRows.values()) if (!row.msg.dataset.csv) describe(row);
      last = { r, input };
      fresh = true;
      showMap(r);
      judgeMap();
      comparePaper(r, input);
    }, engineError);
  };

  /** Shows the rotary axes of this machine (K and M) besides X, Y, Z, and each table's plot. */
  const syncAxes = () => {
    const ctx = machine.context();
    for (const [a, set] of axisSets) {
      const linear = ['X', 'Y', 'Z'].includes(a);
      set.hidden = !linear && a !== ctx.k && a !== ctx.m;
      const role = a === ctx.k ? ' (K, nearer the workpiece)' : a === ctx.m ? ' (M, nearer the tool)' : '';
      set.querySelector('legend')!.textContent = `${a} axis${role}`;
    }
    for (const row of motionRows.values()) showFunction(row);
  };

  /** Where the spindle axis's 0 is, in words and mm from the rotary axes, and where the map is. */
  const zeroText = (r: VolumetricMap) => {
    const ctx = machine.context();
    const kind = machine.current()?.kind ?? 'table-table';
    const sp = r.spindleAxis;
    const origin = kind === 'head-head' ? 'the machine origin (where the workpiece is set)' : `the rotary centre, on the ${kind === 'table-table' ? ctx.m : ctx.k} axis`;
    const atZero = kind === 'table-table' ? 'the spindle nose' : `the head’s ${ctx.m} axis`;
    const tip = kind === 'table-table' ? 'the tool length' : 'the pivot length plus the tool length';
    const th = r.tableHeight;
    const [, , wa] = r.axes;
    const onSurface = wa === sp && Math.abs(r.at - r.surfaceAt) < 1e-9;
    return `${sp} 0 puts ${atZero} at ${origin}; the tool tip is then ${fmt.num(r.tipOffset)} mm from it against the spindle (${tip}). ` +
      `The table surface is ${fmt.num(Math.abs(th))} mm ${th >= 0 ? 'above' : 'below'} ${kind === 'head-head' ? 'the machine origin' : 'the rotary centre'}: the tool tip touches it at ${sp} ${fmt.num(r.surfaceAt)} mm. ` +
      `This map: ${wa} ${fmt.num(r.at)} mm${onSurface ? ', on the table surface' : ''}.`;
  };

  const showMap = (r: VolumetricMap) => {
    const [ua, va, wa] = r.axes;
    const nu = r.u.length;
    const nv = r.v.length;
    const comp = { X: r.deviation[0], Y: r.deviation[1], Z: r.deviation[2] } as Record<string, Float64Array>;
    const w = r.worst;
    note(mapPlot.p, null);
    sentence.textContent = r.summary;
    sentence.classList.remove('stale');
    budgetTable.classList.remove('stale');
    const top = r.budget.filter((b) => b.share > 0).slice(0, 3);
    const items: [string, string, string][] = [
      ['vm-worst', 'Worst point', `|Δ| = ${show('errLength', w.norm)} at X ${fmt.num(w.position[0])}, Y ${fmt.num(w.position[1])}, Z ${fmt.num(w.position[2])} mm`],
      ['vm-worst-dev', 'There', `Δx ${show('errLength', w.deviation[0])}, Δy ${show('errLength', w.deviation[1])}, Δz ${show('errLength', w.deviation[2])}; tool tilted by ${show('errAngle', w.tilt)}`],
      ['vm-zero', 'Where the plane is', zeroText(r)],
      ['vm-rms', 'rms of |Δ| over the plane', show('errLength', r.rms)],
      ['vm-top', 'Largest contributors', top.length ? top.map((b) => `${b.name} (${b.label}) ${fmt.percent(b.share, 2)}`).join(', ') : 'none: no error entered'],
      ['vm-functions', 'Error motions as tables or polynomials', functionsText()],
      ['vm-linear', 'Exact vs first order', `the first-order (linear) deviation differs from the exact one by at most ${show('errLength', r.firstOrderGap)}, where the first-order |Δ| reaches ${show('errLength', r.firstOrderMax)} (${r.budgetSide[0]} × ${r.budgetSide[1]} points)`],
    ];
    summary.replaceChildren();
    const atInput = form.querySelector<HTMLInputElement>('#vm-region-at');
    if (atInput) atInput.placeholder = r.axes[2] === r.spindleAxis ? `empty: the table surface, ${r.spindleAxis} ${fmt.num(r.surfaceAt)}` : 'empty: 0, the rotary centre';
    const tips: Record<string, string> = {
      'vm-worst': '|Δ|: the distance of the tool tip from where the control believes it is (the volumetric error; Tan & Lim’s ΔX, ΔY, ΔZ combined).',
      'vm-worst-dev': 'Δx, Δy, Δz: the tool tip’s deviation along X, Y and Z (workpiece coordinates); the tilt: the angle between the actual and the commanded tool axis.',
      'vm-linear': 'First order: the sum of each error’s own effect, as the paper’s small-angle formulas give it; exact: the chain of the machine’s axes computed without approximation.',
    };
    for (const [id, k, v] of items) summary.append(el('dt', tips[id] ? { title: tips[id] } : {}, k), el('dd', { id }, v));
    exportButton.removeAttribute('disabled');

    // |Δ| with the in-plane deviation as arrows, scaled so that the longest is 7 % of the plane.
    const span = Math.max(r.u[nu - 1] - r.u[0], r.v[nv - 1] - r.v[0]);
    const cu = comp[ua];
    const cv = comp[va];
    let longest = 0;
    for (let i = 0; i < nu * nv; i++) longest = Math.max(longest, Math.hypot(cu[i], cv[i]));
    const scale = longest > 0 ? (0.07 * span) / longest : 0;
    const pick = (n: number) => Array.from(new Set(Array.from({ length: Math.min(n, ARROWS) }, (_, k) => Math.round((k * (n - 1)) / Math.max(1, Math.min(n, ARROWS) - 1)))));
    const arrows: Partial<Annotations>[] = [];
    if (scale > 0) {
      for (const j of pick(nv)) {
        for (const i of pick(nu)) {
          const k = j * nu + i;
          if (Math.hypot(cu[k], cv[k]) < 1e-3 * longest) continue;
          arrows.push({
            x: r.u[i] + scale * cu[k], y: r.v[j] + scale * cv[k], ax: r.u[i], ay: r.v[j], xref: 'x', yref: 'y', axref: 'x', ayref: 'y',
            showarrow: true, arrowhead: 2, arrowsize: 1, arrowwidth: 1.3, arrowcolor: '#1f2328', text: '',
          });
        }
      }
    }
    const [wu, wv] = [w.position['XYZ'.indexOf(ua)], w.position['XYZ'.indexOf(va)]];
    const norm = Array.from(r.norm, D);
    const unit = unitDef('errLength').label;
    const arrowText = scale > 0
      ? `arrows: the deviation in the ${ua}${va} plane, 1 ${unit} drawn as ${fmt.num(scale / unitDef('errLength').factor, 3)} mm`
      : 'no deviation in the plane: no arrows';
    drawFit(mapPlot.p, `Tool-tip deviation |Δ| over the ${ua}–${va} plane at ${wa} = ${fmt.num(w.position['XYZ'.indexOf(wa)])} mm<br>${arrowText}; ✕ the worst point`, [
      {
        type: 'heatmap', x: Array.from(r.u), y: Array.from(r.v), z: rows(norm, nu, nv), colorscale: 'YlOrRd', reversescale: true,
        zmin: 0, zmax: scaleTop(norm, 'errLength'),
        name: '|Δ|', colorbar: { title: { text: titled('|Δ|', 'errLength') }, exponentformat: 'none' },
        hovertemplate: `${ua} %{x:.4g} mm, ${va} %{y:.4g} mm<br>|Δ| %{z:.4g} ${unit}<extra></extra>`,
      } as Data,
      {
        type: 'scatter', mode: 'markers', x: [wu], y: [wv], name: 'worst point', showlegend: false,
        marker: { symbol: 'x', size: 13, color: '#0b5cad', line: { width: 2, color: '#0b5cad' } },
        hovertemplate: `worst point<br>|Δ| ${show('errLength', w.norm)}<extra></extra>`,
      } as Data,
    ], {
      xaxis: axis(`${ua} (mm)`, { constrain: 'domain' }),
      yaxis: axis(`${va} (mm)`, { scaleanchor: 'x' }),
      // The worst point's label inside the plane, on a white ground over the arrows.
      annotations: [...arrows, {
        x: wu, y: wv, xref: 'x', yref: 'y', text: `worst ${show('errLength', w.norm, 3)}`, showarrow: true, arrowhead: 0, arrowcolor: '#0b5cad',
        ax: wu > (r.u[0] + r.u[nu - 1]) / 2 ? -50 : 50, ay: wv > (r.v[0] + r.v[nv - 1]) / 2 ? 30 : -30,
        font: { color: '#0b5cad', size: 12 }, bgcolor: 'rgba(255,255,255,0.9)', bordercolor: '#0b5cad', borderpad: 2,
      }],
    }, 'volumetric-map');

    showComponent();
    // The tilt error: from 0 (a constant tilt, as constant angular errors give, still has a scale).
    const tilt = Array.from(r.tilt, (t) => toDisplay('errAngle', t));
    const [tLo, tHi] = extent(tilt);
    const tiltRange = tHi - tLo < 1e-6 * Math.max(tHi, 1e-30) ? `the same everywhere: ${show('errAngle', r.worst.tilt)}` : `from ${show('errAngle', fromAngle(tLo))} to ${show('errAngle', fromAngle(tHi))}`;
    drawFit(tiltPlot.p, `Tilt error of the tool axis over the ${ua}–${va} plane<br>actual vs commanded tool axis, ${tiltRange}`, [{
      type: 'heatmap', x: Array.from(r.u), y: Array.from(r.v), z: rows(tilt, nu, nv),
      colorscale: 'Viridis', zmin: 0, zmax: scaleTop(tilt, 'errAngle'), name: 'tilt error', colorbar: { title: { text: titled('tilt', 'errAngle') }, exponentformat: 'none' },
      hovertemplate: `${ua} %{x:.4g} mm, ${va} %{y:.4g} mm<br>tilt %{z:.4g} ${unitDef('errAngle').label}<extra></extra>`,
    } as Data], { xaxis: axis(`${ua} (mm)`, { constrain: 'domain' }), yaxis: axis(`${va} (mm)`, { scaleanchor: 'x' }) }, 'volumetric-tilt');

    // The budget: the largest shares as bars (largest on top), every error in the table.
    const shown = r.budget.slice(0, 12).reverse();
    budgetPlot.p.style.height = `${Math.max(200, 110 + 26 * shown.length)}px`;
    drawFit(budgetPlot.p, `Error budget: each error’s share of the squared deviation over the plane<br>${r.budget.length ? `largest: ${top.map((b) => b.name).join(', ')}` : 'no error entered'}`, [{
      type: 'bar', orientation: 'h', y: shown.map((b) => b.name), x: shown.map((b) => 100 * b.share), name: 'share',
      text: shown.map((b) => fmt.percent(b.share, 2)), textposition: 'auto', marker: { color: '#0b5cad' },
      hovertemplate: '%{y}: %{x:.3g} %<extra></extra>',
    } as Data], {
      xaxis: axis('share of the squared deviation (%)', { rangemode: 'tozero' }),
      yaxis: axis('error (ISO 230-1)', { type: 'category' }),
    }, 'volumetric-budget');
    budget(r);
  };


  const showComponent = () => {
    if (!last) return;
    const { r } = last;
    const key = component.select.value as 'dx' | 'dy' | 'dz';
    const label = COMPONENTS.find((c) => c.value === key)?.label ?? key;
    const data = Array.from(r.deviation[(['dx', 'dy', 'dz'] as const).indexOf(key)], D);
    const R = scaleTop(data, 'errLength');
    const [ua, va] = r.axes;
    drawFit(compPlot.p, `${label.split(':')[0]} over the ${ua}–${va} plane<br>${label.split(': ')[1]} (red +, blue −)`, [{
      type: 'heatmap', x: Array.from(r.u), y: Array.from(r.v), z: rows(data, r.u.length, r.v.length), colorscale: 'RdBu',
      zmin: -R, zmax: R, name: label.split(':')[0], colorbar: { title: { text: titled(label.split(':')[0], 'errLength') }, exponentformat: 'none' },
      hovertemplate: `${ua} %{x:.4g} mm, ${va} %{y:.4g} mm<br>%{z:.4g} ${unitDef('errLength').label}<extra></extra>`,
    } as Data], { xaxis: axis(`${ua} (mm)`, { constrain: 'domain' }), yaxis: axis(`${va} (mm)`, { scaleanchor: 'x' }) }, `volumetric-${key}`);
  };

  const budget = (r: VolumetricMap) => {
    if (!r.budget.length) {
      budgetTable.replaceChildren(el('p', { class: 'field-hint' }, 'No error is entered: nothing to share out.'));
      return;
    }
    const table = el('table', { class: 'ranking budget' });
    const against = r.budget.some((b) => b.share < 0) ? '; a negative share: the error partly cancels the others' : '';
    table.append(el('caption', {}, `Each error alone over the plane (first order, ${r.budgetSide[0]} × ${r.budgetSide[1]} points), largest share first${against}`));
    const head = el('tr');
    for (const h of ['error', 'what it is', 'share', `rms (${unitDef('errLength').label})`, `max (${unitDef('errLength').label})`]) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'));
    table.tHead?.append(head);
    const body = el('tbody');
    for (const b of r.budget) {
      const tr = el('tr');
      for (const c of [b.name, `${b.label}${b.kind === 'motion' ? '' : ' (location)'}`, fmt.percent(b.share, 3), fmt.num(D(b.rms)), fmt.num(D(b.max))]) tr.append(el('td', {}, c));
      body.append(tr);
    }
    table.append(body);
    budgetTable.replaceChildren(table);
  };

  // ---- Tan & Lim's model at the worst point (their machine only; the engine says when not)
  const comparePaper = (r: VolumetricMap, input: VolumetricInput) => {
    const [x, y, z] = r.worst.position;
    const region = input.region ?? {};
    runPaper({ machine: input.machine, x, y, z, ...(region.k === undefined ? {} : { k: region.k }), ...(region.m === undefined ? {} : { m: region.m }) }).then((p) => {
      if (p === SUPERSEDED) return;
      paperBody.classList.remove('stale');
      showPaper(p, r);
    }, (err) => {
      const e = EngineError.of(err);
      paperBody.classList.remove('stale');
      paperBody.replaceChildren(el('p', { class: 'field-hint', id: 'vm-paper-note' }, `Not shown for this machine: ${e.field === 'machine' ? e.text : e.message}`));
    });
  };

  const showPaper = (p: PaperComparison, r: VolumetricMap) => {
    const [x, y, z] = r.worst.position;
    const vec = (v: [number, number, number]) => v.map((c) => show('errLength', c)).join(', ');
    const table = el('table', { class: 'ranking', id: 'vm-paper-table' });
    table.append(el('caption', {}, `At the worst point of the map (X ${fmt.num(x)}, Y ${fmt.num(y)}, Z ${fmt.num(z)} mm): ΔX, ΔY, ΔZ`));
    const body = el('tbody');
    const rowsOf: [string, string][] = [
      ['Their loop, solved exactly (machine axes)', vec(p.paperLoop)],
      ['Their printed first-order ΔX, ΔY, ΔZ (Section VI)', vec(p.paperPrinted)],
      ['This machine, exact, along the machine axes', vec(p.machineAxes)],
      ['This machine, exact, on the workpiece (the map)', vec(p.machine)],
    ];
    for (const [k, v] of rowsOf) {
      const tr = el('tr');
      tr.append(el('th', { scope: 'row' }, k), el('td', {}, v));
      body.append(tr);
    }
    table.append(body);
    const symbols = p.symbols.filter((s) => s.value !== 0).map((s) => `${s.symbol} = ${s.unit === 'deg' ? show('errAngle', s.value) : show('errLength', s.value)}`);
    paperBody.replaceChildren(
      el('p', {}, 'Their loop (Section VI), X carrying A and C on the table, Y and Z the tool:'),
      el('pre', { class: 'formula' }, 'R_x·[R_A·[R_C·P_a + T_C] + T_A] + T_x = R_y·[R_z·P_t + T_z] + T_y,   ΔP = P_a − (P + P_t)'),
      el('p', { class: 'field-hint' }, 'Each R is the printed small-angle matrix of the axis’s three error angles; R_C and R_A hold only the errors (the table does not turn in the loop), so the loop’s ΔX, ΔY, ΔZ are along the machine axes and the map’s along the workpiece’s; with the rotary axes at 0 they agree but for squareness. The paper writes it as α on X and β1, β2 as straightness of Z; ISO 230-1 (X the reference) as the orientations E_C0Y, E_B0Z, E_A0Z of Y and Z: for the same angles the two differ by a turn of the whole workpiece about Z by α (which setting the workpiece up by its edge removes), and the machine’s tilted Z also tilts the tool, a term β·(tool length) the paper does not have.'),
      table,
      el('p', { class: 'field-hint' }, symbols.length ? `Their symbols at this point: ${symbols.join('; ')}.` : 'All their symbols are 0 at this point.'),
      ...(p.notInPaper.length ? [el('p', { class: 'field-hint' }, `Errors of this machine their loop does not have: ${p.notInPaper.join(', ')}.`)] : []),
    );
  };

  // ---- one error motion's row
  function motionRow(def: ErrorDef, field: NumberField, set: HTMLElement): MotionRow {
    const row = el('div', { class: 'motion' });
    row.dataset.motion = def.name;
    const fileId = `vm-csv-${def.name}`;
    const file = el('input', { type: 'file', id: fileId, class: 'visually-hidden', accept: '.csv,.txt,text/csv,text/plain' });
    const load = el('label', { for: fileId, class: 'file-button' }, 'Load CSV…');
    load.title = `A table of ${def.name} against the ${def.axis} position, from the measuring software`;
    const clear = el('button', { type: 'button', class: 'file-button', id: `vm-clear-${def.name}` }, 'Clear table');
    clear.hidden = true;
    const tools = el('div', { class: 'file-row' });
    tools.append(load, file, clear);
    const msg = el('div', { class: 'field-msg', id: `vm-csv-msg-${def.name}`, 'aria-live': 'polite' });
    const plot = el('div', { class: 'plot small', id: `vm-table-${def.name}` });
    const plotWrap = el('div', { class: 'plot-wrap motion-plot' });
    plotWrap.append(plot);
    plotWrap.hidden = true;
    row.append(field.root, tools, msg, plotWrap);
    set.append(row);
    const r: MotionRow = { def, field, root: row, msg, clear, plot, shown: '' };
    file.addEventListener('change', async () => {
      const f = file.files?.[0];
      file.value = '';
      if (!f) return;
      try {
        const read = await readTextFile(f);
        const t = await call('volumetricReadTable', { name: def.name, text: read.text });
        delete msg.dataset.csv;
        r.windows1252 = read.windows1252 ? f.name : undefined;
        machine.setMotion(def.name, { position: t.position, value: t.value, file: f.name, units: t.units });
      } catch (err) {
        // The machine keeps what it had: the results stay, greyed, with the reason.
        const refused = err instanceof FileRefused;
        const e = refused ? null : EngineError.of(err);
        msg.classList.remove('ok');
        msg.dataset.csv = 'bad';
        msg.textContent = e ? `${f.name} was not loaded: ${e.message}` : (err as Error).message;
        runMap.cancel();
        runPaper.cancel();
        note(mapPlot.p, `${def.name}: ${e ? `${f.name} was not loaded (${e.message})` : (err as Error).message.replace(/\.$/, '')}; the results are still those of the errors before it.`);
        greyAll();
      }
    });
    clear.addEventListener('click', () => {
      delete msg.dataset.csv;
      machine.setMotion(def.name, null);
    });
    return r;
  }

  /** The error motions given as functions of the position, for the key numbers (and the print). */
  function functionsText(): string {
    const list = [...motionRows.values()].flatMap(({ def }) => {
      const fn = machine.motionFunction(def.name);
      if (!fn || !machine.current()?.motions?.[def.name]) return [];
      return [`${def.name} (${'poly' in fn ? `polynomial of degree ${fn.poly.length - 1}` : `${fn.file ?? 'table'}, ${fn.position.length} points`})`];
    });
    return list.length ? list.join(', ') : 'none (constants only)';
  }

  /** What a row's table is (its file, points and range), under its field. */
  function describe(row: MotionRow) {
    const fn = machine.motionFunction(row.def.name);
    const unit = ['X', 'Y', 'Z'].includes(row.def.axis) ? 'mm' : '°';
    row.msg.classList.add('ok');
    row.msg.textContent = fn && !('poly' in fn)
      ? `${fn.file ?? 'Table'}${fn.file && fn.file === row.windows1252 ? ` (${WINDOWS_1252_NOTE})` : ''}: ${fn.position.length} points, ${row.def.axis} from ${fmt.num(fn.position[0])} to ${fmt.num(fn.position[fn.position.length - 1])} ${unit}, interpolated linearly.`
      : '';
  }

  /** A row's table or polynomial plotted beside its field (or nothing for a constant). */
  function showFunction(row: MotionRow) {
    const fn = machine.motionFunction(row.def.name);
    // (A message of the engine or of a bad file stays until the next map or file.)
    if (!row.msg.dataset.csv && (!row.msg.textContent || row.msg.classList.contains('ok'))) describe(row);
    const q: Quantity = displayQuantity(row.def.quantity);
    const key = fn ? `${JSON.stringify(fn)}|${unitDef(q).label}` : '';
    row.field.input.disabled = !!fn;
    row.clear.hidden = !fn;
    row.clear.textContent = fn && 'poly' in fn ? 'Clear polynomial' : 'Clear table';
    row.plot.parentElement!.hidden = !fn;
    if (key === row.shown) return;
    row.shown = key;
    if (!fn) return;
    const linear = ['X', 'Y', 'Z'].includes(row.def.axis);
    const pos = positions(fn, row.def.axis, linear);
    const val = 'poly' in fn ? pos.map((p) => fn.poly.reduceRight((acc, c) => acc * p + c, 0)) : fn.value;
    const title = 'poly' in fn ? `${row.def.name}: polynomial in ${row.def.axis}` : `${row.def.name} from ${fn.file ?? 'a table'}${fn.units ? ` (file in ${fn.units[0]}, ${fn.units[1]})` : ''}`;
    void drawFit(row.plot, title, [{
      type: 'scatter', mode: 'poly' in fn ? 'lines' : 'lines+markers', x: pos, y: val.map((v) => toDisplay(q, v)), name: row.def.name,
      marker: { size: 4 }, line: { width: 1.5, color: '#0b5cad' }, hovertemplate: `${row.def.axis} %{x:.4g}<br>${row.def.name} %{y:.4g}<extra></extra>`,
    } as Data], {
      xaxis: axis(`${row.def.axis} (${linear ? 'mm' : '°'})`),
      yaxis: axis(titled(row.def.name, q)),
      margin: { l: 56, r: 8, b: 40 },
      showlegend: false,
    }, `${row.def.name}-table`);
  }

  /** Where to draw a polynomial: over the map's range of a linear axis (±500 mm when the map does
   *  not move it), over a turn of a rotary axis; a table over its own positions. */
  function positions(fn: MotionFunction, axisName: string, linear: boolean): number[] {
    if (!('poly' in fn)) return fn.position;
    let [a, b] = linear ? [-500, 500] : [-180, 180];
    const along = last ? [last.r.u, last.r.v][last.r.axes.indexOf(axisName)] : undefined;
    if (along && along.length > 1) [a, b] = [along[0], along[along.length - 1]];
    const n = 61;
    return Array.from({ length: n }, (_, i) => a + ((b - a) * i) / (n - 1));
  }

  exportButton.addEventListener('click', () => {
    if (!last) return;
    download('volumetric-map.csv', mapCsv(last.r), 'text/csv');
  });
  component.select.addEventListener('change', showComponent);
  form.addEventListener('input', (e) => {
    // The error motions' fields and tables are the machine's: the machine tells every panel.
    const id = (e.target as HTMLElement).id;
    if (id.startsWith('m-') || id.startsWith('vm-csv-')) return;
    update();
  });
  machine.onChange(update);
  onUnitsChange(() => {
    for (const row of motionRows.values()) showFunction(row);
    if (last) showMap(last.r);
    judgeMap();
  });
  // The titles are broken to the plots' width: drawn again when the width changes.
  let width = root.clientWidth;
  const redrawLater = debounced(() => {
    if (root.hidden || root.clientWidth === width) return;
    width = root.clientWidth;
    if (last) showMap(last.r);
  }, 200);
  window.addEventListener('resize', redrawLater);
  update();
}

/** The map as CSV: one row per point, units in the header (the units shown now). */
export function mapCsv(r: VolumetricMap): string {
  const [ua, va, wa] = r.axes;
  const len = unitDef('errLength');
  const ang = unitDef('errAngle');
  const at = r.at;
  const lines = [
    `# Volumetric error map over the ${ua}-${va} plane at ${wa} = ${at} mm; Δ = actual minus commanded tool tip in workpiece coordinates; tilt = angle between actual and commanded tool axis`,
    [`u: ${ua} (mm)`, `v: ${va} (mm)`, 'X (mm)', 'Y (mm)', 'Z (mm)', `dx (${len.label})`, `dy (${len.label})`, `dz (${len.label})`, `|Δ| (${len.label})`, `tilt (${ang.label})`].join(','),
  ];
  const nu = r.u.length;
  for (let j = 0; j < r.v.length; j++) {
    for (let i = 0; i < nu; i++) {
      const k = j * nu + i;
      const p: Record<string, number> = { [ua]: r.u[i], [va]: r.v[j], [wa]: at };
      lines.push([r.u[i], r.v[j], p.X, p.Y, p.Z, r.deviation[0][k] * len.factor, r.deviation[1][k] * len.factor, r.deviation[2][k] * len.factor, r.norm[k] * len.factor, r.tilt[k] * ang.factor]
        .map((v) => String(Number(v.toPrecision(10)))).join(','));
    }
  }
  return lines.join('\n') + '\n';
}
