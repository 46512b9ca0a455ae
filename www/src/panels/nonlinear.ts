// The "Nonlinear error" panel: Geng, Wu & Qiu (2018), for the 12 rotary-axis types.
import type { Data } from 'plotly.js';
import type { NonlinearMoveResult, RotaryTypeInfo, MachineLayout, InverseResult } from '@engine';
import { call, channel, EngineError, SUPERSEDED } from '../engine/client';
import { el, listField, numberField, selectField, type NumberField } from '../ui/fields';
import { axis, draw, note, rows } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';

/** A length from the engine (mm) in the unit shown now. */
const D = (mm: number) => toDisplay('errLength', mm);
import { engineErrors, panelShell, type Panel } from './panel';

const ANGLE = 3600; // largest accepted angle, degrees (the engine's limit)

const MACHINES = [
  { value: 'table-table', label: 'Table-table' },
  { value: 'head-head', label: 'Head-head' },
  { value: 'head-table', label: 'Head-table' },
];

export const nonlinearPanel: Panel = {
  id: 'nonlinear',
  prefix: 'nl',
  title: 'Nonlinear error',
  mount,
};

async function mount(root: HTMLElement) {
  const types = await call('rotaryTypes');
  const { form, results } = panelShell(
    root,
    'Nonlinear error of rotary-axis interpolation',
    'When both rotary axes move together with linearly interpolated angles, the tool does not stay in the plane ' +
      'through its start and end orientations. δ is the largest distance of the tool point (at length L from the ' +
      'pivot) from that plane. Geng, Wu & Qiu, Math. Problems in Engineering 2018, eqs 4–31.',
  );

  // ---- inputs
  const machine = selectField('nl-machine', 'Machine type', MACHINES, 'table-table');
  const typeOptions = types.map((t: RotaryTypeInfo) => ({
    value: t.name,
    label: `${t.name} (${t.k}, ${t.m}; tool ${t.home})`,
    group: t.group === 'I' ? 'Group I (tool along K at zero)' : 'Group II (tool along the third axis)',
  }));
  const rtype = selectField('nl-type', 'Rotary-axis type (KMH)', typeOptions, 'CAZ');
  const roles = el('p', { class: 'roles', id: 'nl-roles' });
  const length = numberField({
    id: 'nl-length', label: 'Tool length / pivot distance L', quantity: 'length', value: 100, min: 0, max: 100000, positive: true,
    hint: 'Head: pivot to tool point. Table: rotary centre to tool point.',
  });
  const k0 = numberField({ id: 'nl-k0', quantity: 'angle', label: 'Start θk', value: 0, min: -ANGLE, max: ANGLE });
  const m0 = numberField({ id: 'nl-m0', quantity: 'angle', label: 'Start θm', value: 10, min: -ANGLE, max: ANGLE });
  const k1 = numberField({ id: 'nl-k1', quantity: 'angle', label: 'End θk', value: 30, min: -ANGLE, max: ANGLE });
  const m1 = numberField({ id: 'nl-m1', quantity: 'angle', label: 'End θm', value: 25, min: -ANGLE, max: ANGLE });
  const ratios = listField('nl-ratios', 'Increment ratios K = Δθk/Δθm (Fig 7)', [0.5, 2, 3, 5], -100, 100, 'Comma separated.');
  const grid = numberField({
    id: 'nl-grid', label: 'Grid points per side (maps)', value: 61, min: 5, max: 361, integer: true,
    hint: '361 gives 0.5° steps over ±90°.',
  });

  const machineSet = el('fieldset', {}, '');
  machineSet.append(el('legend', {}, 'Machine'), presetPicker('nonlinear', 'nl'), machine.root, rtype.root, roles);
  const moveSet = el('fieldset');
  const pair = (a: NumberField, b: NumberField) => {
    const d = el('div', { class: 'pair' });
    d.append(a.root, b.root);
    return d;
  };
  moveSet.append(el('legend', {}, 'Move'), length.root, pair(k0, m0), pair(k1, m1));
  const sweepSet = el('fieldset');
  sweepSet.append(el('legend', {}, 'Sweeps'), ratios.root, grid.root);

  // Inverse kinematics: which angles give a tool vector.
  const ikSet = el('fieldset');
  const ix = numberField({ id: 'nl-ix', label: 'i', value: 0.5, min: -1e6, max: 1e6 });
  const iy = numberField({ id: 'nl-iy', label: 'j', value: 0, min: -1e6, max: 1e6 });
  const iz = numberField({ id: 'nl-iz', label: 'k', value: 0.8660254, min: -1e6, max: 1e6 });
  const ikOut = el('div', { class: 'ik-out', id: 'nl-ik-out', 'aria-live': 'polite' });
  const triple = el('div', { class: 'triple' });
  triple.append(ix.root, iy.root, iz.root);
  ikSet.append(
    el('legend', {}, 'Tool vector → axis angles'),
    el('p', { class: 'field-hint' }, 'Workpiece coordinates; the choice nearest the start pose is marked.'),
    triple,
    ikOut,
  );
  form.append(machineSet, moveSet, sweepSet, ikSet);

  // ---- outputs
  const summary = el('dl', { class: 'summary', id: 'nl-summary', 'aria-live': 'polite' });
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
  results.append(summary, plots);

  // ---- computation, one channel per output so that bursts of edits coalesce
  const runMove = channel('nonlinearMove');
  const runLayout = channel('machineLayout');
  const runSweepK = channel('nonlinearSweepK');
  const runSweepM = channel('nonlinearSweepM');
  const runGrid = channel('nonlinearGrid');
  const runGridU = channel('nonlinearGrid');
  const runCompare = channel('nonlinearCompareTypes');
  const runIk = channel('inverseKinematics');

  const fieldsByPath: Record<string, NumberField> = {
    length, 'start.k': k0, 'start.m': m0, 'end.k': k1, 'end.m': m1,
  };
  /** Shows an engine error at the field it names (or over the plot when it names none). */
  const engineError = engineErrors(fieldsByPath);

  const update = () => {
    const t = rtype.select.value;
    const info = types.find((x: RotaryTypeInfo) => x.name === t);
    if (info) {
      k0.label.textContent = `Start θk (${info.k})`;
      m0.label.textContent = `Start θm (${info.m})`;
      k1.label.textContent = `End θk (${info.k})`;
      m1.label.textContent = `End θm (${info.m})`;
    }
    runLayout(t, machine.select.value).then((l) => {
      if (l === SUPERSEDED) return;
      const lay = l as MachineLayout;
      roles.textContent = `Group ${lay.group}. K = ${lay.kRole}. M = ${lay.mRole}. Tool along ${lay.home} at zero angles.`;
    }, (e) => (roles.textContent = String(e)));

    const values = [length.read(), k0.read(), m0.read(), k1.read(), m1.read()];
    const ratioList = ratios.read();
    const n = grid.read();
    if (values.some((v) => v === null)) return; // messages are at the fields; plots keep the last good input
    const [L, a0, b0, a1, b1] = values as number[];
    const start = { k: a0, m: b0 };
    const end = { k: a1, m: b1 };
    const dK = a1 - a0;
    const dM = b1 - b0;

    runMove({ type: t, length: L, start, end, samples: 201 }).then((r) => {
      if (r === SUPERSEDED) return;
      showMove(r, t, L, start, end);
    }, (e) => engineError(e, curve.p));

    runSweepK({ type: t, length: L, thetaM: b0, dK, dM, from: -180, to: 180, n: 73 }).then((r) => {
      if (r === SUPERSEDED) return;
      note(sweepK.p, null);
      draw(sweepK.p, `δ against the start angle θk (Fig 4)<br>Δθk = ${fmt.num(dK)}°, Δθm = ${fmt.num(dM)}°, θm = ${fmt.num(b0)}°`, [
        { x: Array.from(r.k), y: Array.from(r.max, D), type: 'scatter', mode: 'lines+markers', name: 'exact δ', marker: { size: 4 } },
      ], { xaxis: axis('start angle θk (°)', { dtick: 60 }), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }) }, 'nonlinear-fig4');
    }, (e) => engineError(e, sweepK.p));

    if (ratioList && dM !== 0) {
      runSweepM({ type: t, length: L, dM, ratios: ratioList, from: -180, to: 180, n: 181 }).then((r) => {
        if (r === SUPERSEDED) return;
        note(sweepM.p, null);
        const colors = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];
        const data: Data[] = [];
        r.curves.forEach((c, i) => {
          const color = colors[i % colors.length];
          const group = `K${i}`;
          data.push({ x: Array.from(r.m), y: Array.from(c.exact, D), type: 'scatter', mode: 'lines', name: `K = ${c.ratio}`, legendgroup: group, line: { color } });
          data.push({ x: Array.from(r.m), y: c.approx.map((v) => (v === null ? null : D(v))), type: 'scatter', mode: 'lines', name: `K = ${c.ratio}, u = 0.5`, legendgroup: group, showlegend: false, line: { color, dash: 'dot' } });
        });
        draw(sweepM.p, `δ against the start angle θm (Fig 7)<br>Δθm = ${fmt.num(dM)}°, Δθk = K·Δθm (dotted: u = 0.5)`, data,
          { xaxis: axis('start angle θm (°)', { dtick: 45 }), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }) }, 'nonlinear-fig7');
      }, (e) => engineError(e, sweepM.p));
    } else if (ratioList) {
      note(sweepM.p, 'Δθm = 0: the ratio Δθk/Δθm is undefined, so this sweep needs a move of M.');
    }

    if (n !== null) {
      runGrid({ type: t, length: L, thetaM: b0, dK: { from: -90, to: 90 }, dM: { from: -90, to: 90 }, nx: n, ny: n }).then((g) => {
        if (g === SUPERSEDED) return;
        draw(mapMax.p, `Maximum δ over the increments (Fig 5)<br>moves from θm = ${fmt.num(b0)}°`, [{
          type: 'heatmap', x: Array.from(g.dK), y: Array.from(g.dM), z: rows(Array.from(g.max, D), g.nx, g.ny), colorscale: 'Viridis',
          colorbar: { title: { text: titled('δ', 'errLength') } }, hovertemplate: `Δθk %{x}°<br>Δθm %{y}°<br>δ %{z:.4g} ${unitDef('errLength').label}<extra></extra>`,
        }], { xaxis: axis('Δθk (°)'), yaxis: axis('Δθm (°)') }, 'nonlinear-fig5');
      }, (e) => engineError(e, mapMax.p));
      runGridU({ type: t, length: L, thetaM: b0, dK: { from: 1, to: 90 }, dM: { from: 1, to: 90 }, nx: n, ny: n }).then((g) => {
        if (g === SUPERSEDED) return;
        const u = g.uAtMax;
        let lo = Infinity;
        let hi = -Infinity;
        for (const x of u) if (x !== null) (lo = Math.min(lo, x)), (hi = Math.max(hi, x));
        draw(mapU.p, `Where the maximum lies, u* (Figs 3, 8)<br>from θm = ${fmt.num(b0)}°: u* from ${fmt.num(lo)} to ${fmt.num(hi)}`, [{
          type: 'heatmap', x: Array.from(g.dK), y: Array.from(g.dM), z: rows(u, g.nx, g.ny), colorscale: 'RdBu', zmid: 0.5,
          colorbar: { title: { text: 'u*' } }, hovertemplate: 'Δθk %{x}°<br>Δθm %{y}°<br>u* %{z:.4f}<extra></extra>',
        } as Data], { xaxis: axis('Δθk (°)'), yaxis: axis('Δθm (°)') }, 'nonlinear-fig3-8');
      }, (e) => engineError(e, mapU.p));
    }

    runCompare({ length: L, start, end }).then((rowsOut) => {
      if (rowsOut === SUPERSEDED) return;
      const colors = rowsOut.map((r) => (r.type === t ? '#d62728' : r.group === 'I' ? '#1f77b4' : '#7fb3d5'));
      draw(compare.p, `The same move of K and M on all 12 types (selected: ${t})`, [{
        type: 'bar', x: rowsOut.map((r) => r.type), y: rowsOut.map((r) => D(r.max)), marker: { color: colors },
        customdata: rowsOut.map((r) => [fmt.num(r.uAtMax), r.approx === null ? 'undefined' : show('errLength', r.approx), r.group]),
        hovertemplate: '%{x} (Group %{customdata[2]})<br>δ %{y:.4g} at u = %{customdata[0]}<br>u = 0.5 approximation %{customdata[1]}<extra></extra>',
        name: 'exact δ',
      }], { xaxis: axis('rotary-axis type (Group I left, Group II right)'), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }), showlegend: false }, 'nonlinear-types');
    }, (e) => engineError(e, compare.p));

    updateIk(start);
  };

  const updateIk = (start: { k: number; m: number }) => {
    const v = [ix.read(), iy.read(), iz.read()];
    if (v.some((x) => x === null)) return;
    runIk({ type: rtype.select.value, vector: v as number[], previous: start }).then((r) => {
      if (r === SUPERSEDED) return;
      const res = r as InverseResult;
      ikOut.replaceChildren();
      const list = el('ul');
      for (const s of res.solutions) {
        const chosen = Math.abs(((s.k - res.chosen.k) % 360 + 540) % 360 - 180) < 1e-9 && Math.abs(((s.m - res.chosen.m) % 360 + 540) % 360 - 180) < 1e-9;
        list.append(el('li', {}, `θk = ${fmt.degrees(s.k)}, θm = ${fmt.degrees(s.m)}${chosen ? '  ← nearest the start pose' : ''}`));
      }
      ikOut.append(list);
      if (res.singular) {
        ikOut.append(el('p', { class: 'warn' }, 'Singular: the tool lies along the K axis, so θk is arbitrary (kept at the start value).'));
      } else if (res.poleAngle < 1) {
        ikOut.append(el('p', { class: 'warn' }, `Near the singularity: ${fmt.degrees(res.poleAngle, 3)} from the K axis; θk changes fast here.`));
      }
    }, (e) => {
      const err = e instanceof EngineError ? e : new EngineError(String(e));
      ikOut.replaceChildren(el('p', { class: 'warn' }, err.message));
    });
  };

  const showMove = (r: NonlinearMoveResult, t: string, L: number, start: { k: number; m: number }, end: { k: number; m: number }) => {
    note(curve.p, null);
    const group = types.find((x: RotaryTypeInfo) => x.name === t)?.group ?? 'I';
    const eq = group === 'I' ? 'eq 25' : 'eq 30';
    const items: [string, string, string][] = [
      ['nl-max', 'Exact maximum δ', `${show('errLength', r.max)} at u = ${fmt.num(r.uAtMax, 5)}`],
      ['nl-approx', `u = 0.5 approximation (${eq})`, r.approx === null ? 'undefined (no unique plane)' : show('errLength', r.approx)],
      ['nl-shortfall', 'Approximation falls short by', r.approxShortfall === null ? '—' : `${fmt.percent(r.approxShortfall)} (${show('errLength', r.max - (r.approx ?? 0))})`],
      ['nl-eq26', 'Closed form at the pole (eq 26)', r.closedForm === null
        ? `not applicable: the move does not start at θm = ${group === 'I' ? '0°' : '±90°'}`
        : show('errLength', r.closedForm)],
      ['nl-sweep', 'Angle between start and end tool', fmt.degrees(r.sweepAngle, 5)],
      ['nl-ref', 'Reference', referenceText(r)],
      ['nl-v0', 'Start tool vector V0', fmt.vector(r.startVector)],
      ['nl-v1', 'End tool vector V1', fmt.vector(r.endVector)],
    ];
    summary.replaceChildren();
    for (const [id, k, v] of items) {
      summary.append(el('dt', {}, k), el('dd', { id }, v));
    }
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
    draw(curve.p, `δ(u) along the move: ${t}, L = ${fmt.num(L)} mm, (θk, θm) from (${fmt.num(start.k)}°, ${fmt.num(start.m)}°) to (${fmt.num(end.k)}°, ${fmt.num(end.m)}°)`, data,
      { xaxis: axis('interpolation parameter u', { range: [0, 1] }), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero' }) }, 'nonlinear-curve');
  };

  // 'input' fires on every edit of a text field and on every choice in a select.
  for (const input of form.querySelectorAll('input, select')) input.addEventListener('input', update);
  onUnitsChange(update);
  update();
}

function referenceText(r: NonlinearMoveResult): string {
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
