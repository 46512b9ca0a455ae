// The "Nonlinear error" panel: Geng, Wu & Qiu (2018), on the machine of the Machine section (its
// rotary-axis type and pivot).
import type { Data } from 'plotly.js';
import type { Orientations, Machine, MoveAnalysis } from '@engine';
import { channel, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el } from '../ui/fields';
import { fill, loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, rows, stale } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';
import { judge, unseenOf, verdictBox } from '../ui/verdict';

/** A length from the engine (mm) in the unit shown now. */
const D = (mm: number) => toDisplay('errLength', mm);

export const nonlinearPanel: Panel = {
  id: 'nonlinear',
  prefix: 'nl',
  title: 'Nonlinear error',
  exports: ['nonlinearMove', 'nonlinearSweepM', 'nonlinearGrid', 'machineInverse'],
  mount,
};

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Nonlinear error of rotary-axis interpolation',
    'When both rotary axes move together, the control interpolates their angles in a straight line, so the tool ' +
      'does not turn in the plane of its start and end directions. The nonlinear error δ is the largest distance of ' +
      'the tool point (at length L from the pivot) from that plane; splitting the move into shorter steps reduces ' +
      'it. The machine (its rotary-axis type and pivot) is the one above. ' +
      'After Geng, Wu & Qiu, Math. Problems in Engineering 2018.',
  );

  // ---- inputs: the shown fields of the panel's exports (the machine is the Machine section's)
  form.append(presetPicker('nonlinear', 'nl', machine));
  const fieldsOf = nonlinearPanel.exports.flatMap((name) => schema.exports[name]);
  const inputs = renderFields(fieldsOf, 'nl', form, machine.context());
  const ikSet = inputs.groups.get('Tool vector → axis angles');
  const ikOut = el('div', { class: 'ik-out', id: 'nl-ik-out', 'aria-live': 'polite' });
  ikSet?.append(el('p', { class: 'field-hint' }, 'Workpiece coordinates; the solution nearest the start pose is marked, within the machine\'s travel.'), ikOut);

  // ---- outputs
  const tolField = inputs.field('tolerance');
  if (!tolField) throw new Error('the engine declares no tolerance for nonlinearMove');
  const verdict = verdictBox({ prefix: 'nl', tolerance: { adopt: tolField }, onTolerance: () => update() });
  const summary = el('dl', { class: 'summary', id: 'nl-summary', 'aria-live': 'polite' });
  const paperSummary = el('dl', { class: 'summary', id: 'nl-paper-summary' });
  const plot = (id: string, wide = false) => {
    const wrap = el('div', { class: wide ? 'plot-wrap wide' : 'plot-wrap' });
    const p = el('div', { class: 'plot', id });
    wrap.append(p);
    return { wrap, p };
  };
  const curve = plot('nl-curve', true);
  const sweepK = plot('nl-sweep-k');
  const sweepM = plot('nl-sweep-m');
  const mapMax = plot('nl-map-max');
  const mapU = plot('nl-map-u');
  const compare = plot('nl-compare', true);
  const plots = el('div', { class: 'plots' });
  plots.append(curve.wrap, sweepK.wrap, sweepM.wrap, mapMax.wrap, mapU.wrap, compare.wrap);
  results.append(verdict.root, summary, plots);

  // ---- computation, one channel per output so that bursts of edits coalesce
  const runMove = channel('nonlinearMove');
  const runSweepK = channel('nonlinearSweepK');
  const runSweepM = channel('nonlinearSweepM');
  const runGrid = channel('nonlinearGrid');
  const runGridU = channel('nonlinearGrid');
  const runCompare = channel('nonlinearCompareTypes');
  const runIk = channel('machineInverse');

  /** Shows an engine error at the field it names (or over the plot when it names none). */
  const engineError = engineErrors(inputs.byPath, machine);
  const allPlots = [curve, sweepK, sweepM, mapMax, mapU, compare];

  const lengthInput = form.querySelector<HTMLInputElement>('#nl-length');
  const update = () => {
    const ctx = machine.context();
    inputs.setContext(ctx);
    const swing = machine.swingLength();
    if (lengthInput) lengthInput.placeholder = swing === null ? 'enter L (this machine gives none)' : `empty: the machine's ${fmt.num(swing)}`;
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) {
      verdict.invalid();
      // Messages are at the fields; the plots no longer show what the inputs ask for.
      for (const p of allPlots) stale(p.p, true);
      stale(ikOut, true);
      // A result still on its way would look current: drop it.
      for (const run of [runMove, runSweepK, runSweepM, runGrid, runGridU, runCompare, runIk]) run.cancel();
      return;
    }
    const t = String(m.type ?? 'CBZ');
    const start = own.start as { k: number; m: number };
    const end = own.end as { k: number; m: number };
    const length = own.length as number | undefined;
    const ratioList = own.ratios as number[];
    const n = own.nx as number;
    const dK = end.k - start.k;
    const dM = end.m - start.m;
    const base = { machine: m as Machine, ...(length === undefined ? {} : { length }) };

    verdict.pending();
    runMove({ ...base, start, end, tolerance: own.tolerance as number }).then((r) => {
      if (r === SUPERSEDED) return;
      showMove(r, t, start, end);
    }, (e) => {
      engineError(e, curve.p);
      verdict.refused(e);
    });

    runSweepK({ ...base, thetaM: start.m, dK, dM, from: -180, to: 180, n: 73 }).then((r) => {
      if (r === SUPERSEDED) return;
      note(sweepK.p, null);
      draw(sweepK.p, fill(`δ against the start angle of {K} (Fig 4)<br>Δ{K} = ${fmt.num(dK)}°, Δ{M} = ${fmt.num(dM)}°, {M} from ${fmt.num(start.m)}°`, ctx), [
        { x: Array.from(r.k), y: Array.from(r.max, D), type: 'scatter', mode: 'lines+markers', name: 'exact δ', marker: { size: 4 } },
      ], { xaxis: axis(fill('start angle of {K} (°)', ctx), { dtick: 60 }), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }) }, 'nonlinear-fig4');
    }, (e) => engineError(e, sweepK.p));

    if (dM !== 0) {
      runSweepM({ ...base, dM, ratios: ratioList, from: -180, to: 180, n: 181 }).then((r) => {
        if (r === SUPERSEDED) return;
        note(sweepM.p, null);
        const colors = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];
        const data: Data[] = [];
        r.curves.forEach((c, i) => {
          const color = colors[i % colors.length];
          const group = `K${i}`;
          data.push({ x: Array.from(r.m), y: Array.from(c.exact, D), type: 'scatter', mode: 'lines', name: `ratio ${c.ratio}`, legendgroup: group, line: { color } });
          data.push({ x: Array.from(r.m), y: c.approx.map((v) => (v === null ? null : D(v))), type: 'scatter', mode: 'lines', name: `ratio ${c.ratio}, u = 0.5`, legendgroup: group, showlegend: false, line: { color, dash: 'dot' } });
        });
        draw(sweepM.p, fill(`δ against the start angle of {M} (Fig 7)<br>Δ{M} = ${fmt.num(dM)}°, Δ{K} = ratio·Δ{M} (dotted: u = 0.5)`, ctx), data,
          { xaxis: axis(fill('start angle of {M} (°)', ctx), { dtick: 45 }), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }) }, 'nonlinear-fig7');
      }, (e) => engineError(e, sweepM.p));
    } else {
      note(sweepM.p, fill('Δ{M} = 0: the ratio Δ{K}/Δ{M} is undefined, so this sweep needs a move of {M}.', ctx));
    }

    runGrid({ ...base, thetaM: start.m, dK: { from: -90, to: 90 }, dM: { from: -90, to: 90 }, nx: n, ny: n }).then((g) => {
      if (g === SUPERSEDED) return;
      draw(mapMax.p, fill(`Maximum δ over the increments (Fig 5)<br>moves from {M} = ${fmt.num(start.m)}°`, ctx), [{
        type: 'heatmap', x: Array.from(g.dK), y: Array.from(g.dM), z: rows(Array.from(g.max, D), g.nx, g.ny), colorscale: 'Viridis',
        colorbar: { title: { text: titled('δ', 'errLength') } }, hovertemplate: fill(`Δ{K} %{x}°<br>Δ{M} %{y}°<br>δ %{z:.4g} ${unitDef('errLength').label}<extra></extra>`, ctx),
      }], { xaxis: axis(fill('Δ{K} (°)', ctx)), yaxis: axis(fill('Δ{M} (°)', ctx)) }, 'nonlinear-fig5');
    }, (e) => engineError(e, mapMax.p));
    runGridU({ ...base, thetaM: start.m, dK: { from: 1, to: 90 }, dM: { from: 1, to: 90 }, nx: n, ny: n }).then((g) => {
      if (g === SUPERSEDED) return;
      const u = g.uAtMax;
      let lo = Infinity;
      let hi = -Infinity;
      for (const x of u) if (x !== null) (lo = Math.min(lo, x)), (hi = Math.max(hi, x));
      draw(mapU.p, fill(`Where along the move the error is largest (0 start, 1 end; the paper’s u*, Figs 3, 8)<br>from {M} = ${fmt.num(start.m)}°: from ${fmt.num(lo)} to ${fmt.num(hi)}`, ctx), [{
        type: 'heatmap', x: Array.from(g.dK), y: Array.from(g.dM), z: rows(u, g.nx, g.ny), colorscale: 'RdBu', zmid: 0.5,
        colorbar: { title: { text: 'where (0–1)' } }, hovertemplate: fill('Δ{K} %{x}°<br>Δ{M} %{y}°<br>largest at %{z:.4f} of the move<extra></extra>', ctx),
      } as Data], { xaxis: axis(fill('Δ{K} (°)', ctx)), yaxis: axis(fill('Δ{M} (°)', ctx)) }, 'nonlinear-fig3-8');
    }, (e) => engineError(e, mapU.p));

    runCompare({ ...base, start, end }).then((rowsOut) => {
      if (rowsOut === SUPERSEDED) return;
      const colors = rowsOut.map((r) => (r.type === t ? '#d62728' : r.group === 'I' ? '#1f77b4' : '#7fb3d5'));
      const pose = (p: number[] | null) => (p ? `${fmt.degrees(p[0])}, ${fmt.degrees(p[1])}` : '');
      const out = rowsOut.filter((r) => r.max === null).map((r) => r.type);
      const note = out.length ? `<br>out of this machine's travel: ${out.join(', ')}` : '';
      draw(compare.p, `The same tool path (start and end tool vectors of this move) on all 12 types; this machine: ${t}${note}`, [{
        type: 'bar', x: rowsOut.map((r) => r.type), y: rowsOut.map((r) => (r.max === null ? null : D(r.max))), marker: { color: colors },
        customdata: rowsOut.map((r) => [r.uAtMax === null ? '' : fmt.num(r.uAtMax), r.group, pose(r.start), pose(r.end)]),
        hovertemplate: '%{x} (the paper’s Group %{customdata[1]})<br>δ %{y:.4g}, largest at %{customdata[0]} of the move<br>axes (%{customdata[2]}) → (%{customdata[3]})<extra></extra>',
        name: 'exact δ',
      } as Data], { xaxis: axis('rotary-axis type (left: tool along K at zero; right: tool across K; the paper’s Groups I, II)'), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }), showlegend: false }, 'nonlinear-types');
    }, (e) => engineError(e, compare.p));

    updateIk(m as Machine, own.vector as number[], start);
  };

  const updateIk = (m: Machine, vector: number[], start: { k: number; m: number }) => {
    const ctx = machine.context();
    runIk({ machine: m, vector, previous: start }).then((r) => {
      if (r === SUPERSEDED) return;
      const res = r as Orientations;
      ikOut.replaceChildren();
      stale(ikOut, false);
      const list = el('ul');
      for (const [i, s] of res.solutions.entries()) {
        const travel = s.inTravel ? '' : ' (outside the travel)';
        list.append(el('li', {}, `${ctx.k} = ${fmt.degrees(s.k)}, ${ctx.m} = ${fmt.degrees(s.m)}${travel}${i === res.chosen ? '  ← nearest the start pose' : ''}`));
      }
      ikOut.append(list);
      if (res.unreachable) ikOut.append(el('p', { class: 'warn' }, res.unreachable));
      if (res.singular) {
        ikOut.append(el('p', { class: 'warn' }, `Singular: the tool lies along the ${ctx.k} axis, so ${ctx.k} is arbitrary (kept at the start value).`));
      } else if (res.poleAngle < 1) {
        ikOut.append(el('p', { class: 'warn' }, `Near the singularity: ${fmt.degrees(res.poleAngle, 3)} from the ${ctx.k} axis; ${ctx.k} turns fast here.`));
      }
    }, (e) => {
      // The angles shown were for other inputs: clear them, and say where the message is.
      const err = showAtField(e, inputs.byPath, machine);
      ikOut.replaceChildren(el('p', { class: 'warn' }, err ? err.message : 'No angles: see the message at the field.'));
    });
  };

  const showMove = (r: MoveAnalysis, t: string, start: { k: number; m: number }, end: { k: number; m: number }) => {
    const ctx = machine.context();
    const L = r.length;
    note(curve.p, null);
    const eq = r.group === 'I' ? 'eq 25' : 'eq 30';
    const items: [string, string, string][] = [
      ['nl-max', 'Largest deviation δ of the tool point', `${show('errLength', r.max)} at u = ${fmt.num(r.uAtMax, 5)} (${fmt.percent(r.uAtMax)} of the way)`],
      ['nl-used-length', 'L (tool point from its pivot)', `${fmt.num(L)} mm`],
      ['nl-sweep', 'Angle between start and end tool', fmt.degrees(r.sweepAngle, 5)],
      ['nl-split', 'Steps that keep within the tolerance', splitText(r, ctx)],
    ];
    const paperItems: [string, string, string][] = [
      ['nl-approx', `u = 0.5 approximation (${eq}, type Group ${r.group})`, r.approx === null ? 'undefined (no unique plane)' : show('errLength', r.approx)],
      ['nl-shortfall', 'Approximation falls short by', r.approxShortfall === null ? '—' : `${fmt.percent(r.approxShortfall)} (${show('errLength', r.max - (r.approx ?? 0))})`],
      ['nl-eq26', 'Closed form at the pole (eq 26)', r.closedForm === null
        ? `not applicable: the move does not start at θm = ${r.group === 'I' ? '0°' : '±90°'}`
        : show('errLength', r.closedForm)],
      ['nl-ref', 'Reference', referenceText(r)],
      ['nl-v0', 'Start tool vector V0', fmt.vector(r.startVector)],
      ['nl-v1', 'End tool vector V1', fmt.vector(r.endVector)],
    ];
    summary.replaceChildren();
    for (const [id, k, v] of items) summary.append(el('dt', TIPS[id] ? { title: TIPS[id] } : {}, k), el('dd', { id }, v));
    paperSummary.replaceChildren();
    for (const [id, k, v] of paperItems) paperSummary.append(el('dt', {}, k), el('dd', { id }, v));
    verdict.details('From the paper: approximations, symbols and vectors (Geng, Wu & Qiu 2018)',
      el('p', { class: 'field-hint' }, 'u runs from 0 at the start of the move to 1 at its end (eq 10); u* is where δ is largest. ' +
        'The paper estimates δ at u = 0.5 (eq 25 for Group I types, whose tool is along K at M = 0; eq 30 for Group II) and gives a closed form ' +
        'for moves starting at the pole (eq 26). V0 and V1 are the start and end tool directions; their plane is the reference (eqs 19–21).'),
      paperSummary);
    judgeMove(r, ctx);
    const data: Data[] = [
      { x: Array.from(r.u), y: Array.from(r.delta, D), type: 'scatter', mode: 'lines', name: 'δ(u)', line: { color: '#1f77b4', width: 2 } },
      { x: [r.uAtMax], y: [D(r.max)], type: 'scatter', mode: 'markers', name: `maximum ${show('errLength', r.max)} at u = ${fmt.num(r.uAtMax)}`, marker: { color: '#d62728', size: 10, symbol: 'diamond' } },
    ];
    if (r.approx !== null) {
      data.push({ x: [0.5], y: [D(r.approx)], type: 'scatter', mode: 'markers', name: `u = 0.5 approximation (${eq})`, marker: { color: '#ff7f0e', size: 9, symbol: 'circle-open', line: { width: 2 } } });
    }
    if (r.closedForm !== null) {
      data.push({ x: [0.5], y: [D(r.closedForm)], type: 'scatter', mode: 'markers', name: 'eq 26', marker: { color: '#2ca02c', size: 7, symbol: 'x' } });
    }
    draw(curve.p, `δ(u) along the move: ${t}, L = ${fmt.num(L)} mm, (${ctx.k}, ${ctx.m}) from (${fmt.num(start.k)}°, ${fmt.num(start.m)}°) to (${fmt.num(end.k)}°, ${fmt.num(end.m)}°)`, data,
      { xaxis: axis('interpolation parameter u', { range: [0, 1] }), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }) }, 'nonlinear-curve');
  };

  /** The verdict: the engine's δ and split against the tolerance. */
  const judgeMove = (r: MoveAnalysis, ctx: { k: string; m: string }) => {
    const sp = r.split;
    if (!sp) return verdict.none('No verdict: no tolerance was given.');
    const head = `Nonlinear error ${show('errLength', r.max)} at L = ${fmt.num(r.length)} mm`;
    // δ is the interpolation's own: the engine computes it from the type and L alone (the
    // Node test nonlinear_errors proves the machine's errors do not change it).
    const m = machine.current();
    const unseen = m ? unseenOf('the nonlinear error', m, schema, () => false, 'it comes from how the control interpolates the rotary axes, whatever the machine’s errors') : undefined;
    const tol = show('errLength', sp.tolerance);
    if (judge(r.max, sp.tolerance) === 'pass') {
      verdict.show({
        status: 'pass', worst: r.max, tolerance: sp.tolerance, unseen,
        sentence: r.max < 1e-12
          ? `No nonlinear error: the tool turns in the plane of its start and end directions (within the ${tol} tolerance).`
          : `${head}: within the ${tol} tolerance as one move.`,
      });
      return;
    }
    const steps = (n: number) => stepWords(sp.stepK, sp.stepM, ctx, n);
    verdict.show({
      status: 'fail', worst: r.max, tolerance: sp.tolerance, unseen,
      sentence: sp.steps === null
        ? `${head}, above the ${tol} tolerance: even ${sp.maxSteps} equal steps leave ${show('errLength', sp.max)}; shorten the move or choose another path.`
        : `${head}, above the ${tol} tolerance: split the move into ${sp.steps} equal steps ${steps(sp.steps)} to stay under it.`,
      notes: sp.steps === null ? [] : [`With ${sp.steps} steps the largest error of a step is ${show('errLength', sp.max)}.`],
    });
  };

  // 'input' fires on every edit of a text field and on every choice in a select.
  form.addEventListener('input', update);
  machine.onChange(update);
  onUnitsChange(update);
  update();
}

/** Tooltips of the summary's symbols: the plain meaning and the paper's symbol. */
const TIPS: Record<string, string> = {
  'nl-max': 'δ: the nonlinear error, the largest distance of the tool point from the plane of its start and end directions during the move (Geng et al. eqs 19–21). u: how far along the move, 0 at the start, 1 at the end (eq 10).',
  'nl-used-length': 'L: the distance of the tool point from the axis it swings about (tool length, or the pivot distance).',
  'nl-split': 'The move programmed as this many equal blocks of both axes, each interpolated by the control on its own.',
};

/** "of at most 1.6° on C and 0.79° on B" for steps of both axes, else of the one that moves. */
function stepWords(stepK: number, stepM: number, ctx: { k: string; m: string }, n: number): string {
  const parts: string[] = [];
  if (stepK > 0) parts.push(`${fmt.num(stepK, 3)}° on ${ctx.k}`);
  if (stepM > 0) parts.push(`${fmt.num(stepM, 3)}° on ${ctx.m}`);
  return parts.length ? `of ${parts.join(' and ')}${n > 1 ? ' each' : ''}` : '';
}

function splitText(r: MoveAnalysis, ctx: { k: string; m: string }): string {
  const sp = r.split;
  if (!sp) return '—';
  if (sp.steps === null) return `more than ${sp.maxSteps}`;
  if (sp.steps === 1) return '1: the move as it is';
  return `${sp.steps} ${stepWords(sp.stepK, sp.stepM, ctx, sp.steps)} (largest error of a step ${show('errLength', sp.max)})`;
}

function referenceText(r: MoveAnalysis): string {
  switch (r.reference) {
    case 'coincident':
      return 'start and end orientations coincide: δ is the chord |P(u) − V0| (eq 19)';
    case 'opposite':
      return 'start and end orientations are opposite: least-squares plane through ±V0';
    default:
      return r.planeSine < 1e-3
        ? `plane of V0 and V1 (nearly parallel, |V0×V1| = ${fmt.num(r.planeSine, 3)}: the plane is ill-conditioned)`
        : 'plane of V0 and V1';
  }
}
