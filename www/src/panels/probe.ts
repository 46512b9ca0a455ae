// The "Probe and sphere" panel (issue 31): a maintenance engineer checks the rotary axes with a
// touch probe and a calibration sphere, as Heidenhain's KinematicsOpt, Siemens' CYCLE996 or
// Renishaw's AxiSet do, on the machine of the Machine section. The engine designs the poses to
// probe (`probeDesign`: the designed layout beside the simple one, what the sphere cannot see,
// what a second sphere would add, CSV and NC blocks), reads the measured centres and identifies
// the rotary axes' location errors (`probeIdentify`). The verdict is on the centres as measured:
// how far the sphere's centre strays from a fixed sphere while the rotary axes turn, against the
// tolerance; the corrections are the numbers to enter, and "Use these errors" puts them into the
// one machine model, so that every other study runs on the machine as measured.
import type { Data, Layout } from 'plotly.js';
import type { Estimate, Layout as PoseLayout, Machine, ProbeDesign, ProbeIdentification } from '@engine';
import { channel, EngineError, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el, fields } from '../ui/fields';
import { encodingNote, readOrRefuse } from '../ui/files';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, stale } from '../ui/plot';
import { applyPreset, loadPresets, presetPicker } from '../ui/presets';
import { download } from '../ui/export';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';
import { clearPlot, quantityOf, sourceText, type Source } from '../ui/identify';
import { contributorsOf, correctionsView, useFound } from '../ui/found';
import { measured } from '../ui/measured';
import { errorWords, judge, listWords, verdictBox } from '../ui/verdict';

export const probePanel: Panel = {
  id: 'probe',
  prefix: 'pb',
  title: 'Probe and sphere',
  exports: ['probeDesign', 'probeIdentify'],
  mount,
};

const SAMPLE = 'samples/probe-sphere-measured.csv';
const SAMPLE_NAME = 'the sample file probe-sphere-measured.csv';
/** The study preset (public/presets/probe.json) the sample was made on: its machine and sphere. */
const SAMPLE_PRESET = 'Sample file';
const SAMPLE_WORDS = 'simulated on the B/C tilting table preset with the sphere 100 mm above the table centre, ' +
  'E_X0B = +12 µm, E_Z0B = −8 µm, E_A0B = +0.005°, E_C0B = −0.003° and 1 µm of noise';
/** The layout keys that must agree for a file to be read on this machine. */
const LAYOUT = ['kind', 'type', 'linear'] as const;

const DECISION: Record<string, string> = {
  present: 'present',
  'below-tolerance': 'present, below the tolerance',
  'not-distinguishable': 'not distinguishable from zero',
  'not-identifiable': 'not identifiable alone',
};

/** "sphere_X" → "sphere position, X"; an error keeps its ISO name. */
const paramName = (n: string) => (n.startsWith('sphere_') ? `sphere position, ${n.slice(7)}` : n);
/** Shows or hides `e` (and marks it `hidden` for tests and assistive technology): the page's
 *  boxes with a display of their own (`.plots`, `.file-row`, `dl.summary`) ignore the attribute. */
const setShown = (e: HTMLElement, on: boolean) => {
  e.hidden = !on;
  e.style.display = on ? '' : 'none';
};

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const words = errorWords(schema);
  const { form, results } = panelShell(
    root,
    'Probe and sphere: the rotary axes checked with a touch probe',
    'A calibration sphere sits on the table; the spindle’s touch probe measures its centre at poses of the two rotary axes, ' +
      'each with the control’s own probing cycle (Heidenhain KinematicsOpt, Siemens CYCLE996, Renishaw AxiSet). If the axes ' +
      'were where the control believes, every centre would fall on one fixed sphere; how far they stray, and how, gives back the ' +
      'location errors of the rotary axes (ISO 230-1) with their 95 % intervals, the numbers to enter in the control, and what ' +
      'a sphere in this place cannot see. The page designs the poses for the machine above and exports them as a table and as NC blocks.',
  );

  // ---- inputs: the shown fields of the two exports (the machine's come from the Machine section)
  form.append(presetPicker('probe', 'pb', machine));
  const inputs = renderFields(probePanel.exports.flatMap((n) => schema.exports[n]), 'pb', form, machine.context());
  const sampleButton = el('button', { type: 'button', id: 'pb-load-sample' }, 'Load the sample file');
  const fileLabel = el('label', { class: 'import', for: 'pb-file' }, 'Choose a file ');
  const file = el('input', { id: 'pb-file', type: 'file', accept: '.csv,.txt,text/csv,text/plain' });
  fileLabel.append(file);
  const fileMsg = el('p', { class: 'field-hint', id: 'pb-file-msg', 'aria-live': 'polite' });
  const sampleOffer = el('div', { class: 'file-row', id: 'pb-sample-offer' });
  setShown(sampleOffer, false);
  const buttons = el('div', { class: 'file-row' });
  buttons.append(sampleButton, fileLabel);
  const identSet = inputs.groups.get('Identification');
  identSet?.querySelector('legend')?.after(buttons, el('p', { class: 'field-hint' }, 'Or drop the file on this box, or paste its text below.'), fileMsg, sampleOffer);
  const csvArea = form.querySelector<HTMLTextAreaElement>('#pb-csv');
  if (csvArea) csvArea.placeholder = 'Pose;C [deg];B [deg];X [mm];Y [mm];Z [mm]\nREF;+0,000;+0,000;+0,0012;-0,0008;+100,0003\n…';

  // ---- outputs
  const verdict = verdictBox({
    prefix: 'pb',
    tolerance: {
      label: 'Tolerance on the centre’s wander',
      value: 0.01,
      hint: 'The largest distance you accept between a measured centre and one fixed sphere while the rotary axes turn: how far the tool tip strays from where the control puts it.',
    },
    onTolerance: () => {
      judgeNow();
      // The bar plot's tolerance line.
      const shown = measurement.shown;
      if (shown && measurement.state.s === 'ok' && verdict.tolerance() !== null) showIdentification(shown.r, shown.from);
    },
  });
  // A measurement file that cannot be used is said here, at the top, where it cannot be missed.
  const alert = el('p', { class: 'alert', id: 'pb-alert', role: 'alert' });
  alert.hidden = true;
  // The identification's key numbers, in a box of their own: the page's plots clear the greying of
  // a summary that sits directly in the results (ui/plot.ts), and the design's plot is redrawn
  // while a failed file keeps these greyed.
  const summary = el('dl', { class: 'summary', id: 'pb-summary', 'aria-live': 'polite' });
  const summaryBox = el('div', { class: 'ident-summary' });
  summaryBox.append(summary);
  const corrections = el('div', { class: 'ident', id: 'pb-corrections', 'aria-live': 'polite' });
  const useButton = el('button', { type: 'button', id: 'pb-use-errors', class: 'primary' }, 'Use these errors');
  useButton.title = 'Puts the errors this measurement found into the Machine section, so that the volumetric map, the cubic test and the toolpath run on the machine as measured.';
  const useMsg = el('p', { class: 'field-hint', id: 'pb-use-msg', 'aria-live': 'polite' });
  const useRow = el('div', { class: 'file-row use-row' });
  useRow.append(useButton);
  const ident = el('div', { class: 'ident', id: 'pb-ident', 'aria-live': 'polite' });
  const plotBox = (id: string, tall = false) => {
    const wrap = el('div', { class: 'plot-wrap wide' });
    const p = el('div', { class: 'plot', id });
    if (tall) p.style.height = '460px';
    wrap.append(p);
    return { wrap, p };
  };
  const centresPlot = plotBox('pb-centres');
  const componentsPlot = plotBox('pb-components', true);
  const identPlots = el('div', { class: 'plots' });
  identPlots.append(centresPlot.wrap, componentsPlot.wrap);
  const design = el('div', { class: 'ident', id: 'pb-design', 'aria-live': 'polite' });
  const svPlot = plotBox('pb-design-sv');
  const designPlots = el('div', { class: 'plots' });
  designPlots.append(svPlot.wrap);
  results.append(
    verdict.root, alert, summaryBox,
    el('h3', {}, 'The numbers to enter'), corrections, useRow, useMsg,
    el('h3', {}, 'What the measurement identifies'), ident, identPlots,
    el('h3', {}, 'The poses to probe'), design, designPlots,
  );

  const summaryItems = new Map<string, [string, string]>();
  const setSummary = (id: string, label: string, value: string | null) => {
    if (value === null) summaryItems.delete(id);
    else summaryItems.set(id, [label, value]);
    summary.replaceChildren();
    for (const [key, [k, v]] of summaryItems) summary.append(el('dt', {}, k), el('dd', { id: key }, v));
    setShown(summary, summaryItems.size > 0);
  };
  setShown(summary, false);

  const runDesign = channel('probeDesign');
  const runIdentify = channel('probeIdentify');
  const engineError = engineErrors(inputs.byPath, machine);

  /** Where the text in the measurement field came from. */
  let source: Source = { name: 'text typed or pasted in the field', at: new Date() };
  let sourceCsv = '';
  /** The text as the field holds it (a text area keeps line ends as LF). */
  const plain = (text: string) => text.replace(/\r\n?/g, '\n');
  const setSource = (name: string, text: string) => {
    source = { name, at: new Date() };
    sourceCsv = plain(text);
  };
  let lastDesign: ProbeDesign | null = null;

  const letters = () => {
    const c = machine.context();
    return { k: c.k || 'K', m: c.m || 'M' };
  };

  /** The inputs of each export, or null when a field is invalid (its message shown). */
  const read = () => {
    inputs.setContext(machine.context());
    // The errors to choose from: the rotary axes' (all ticked: the engine's default, the twelve
    // location errors of the two rotary axes).
    const { k, m: mm } = machine.context();
    const axisOf = (name: string) => schema.errors.find((d) => d.name === name)?.axis;
    inputs.setNames(machine.errorOptions().filter((o) => [k, mm].includes(axisOf(o.name) ?? '')));
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) return null;
    const { sphere, fitSphere, parameters, maxTilt, noise, step, count, second, csv, rtol, decision } = own as Record<string, unknown>;
    const common = { machine: m as Machine, sphere, fitSphere, parameters, maxTilt, noise };
    return { design: { ...common, step, count, second }, identify: { ...common, csv: (csv as string) ?? '', rtol, decision } };
  };

  // ---- the verdict: on the measured centres
  const judgeNow = () => {
    const tol = verdict.tolerance();
    if (tol === null) return verdict.invalid();
    const st = measurement.toJudge(verdict, 'No verdict yet: load the measured sphere centres (choose or drop a file, paste it, or load the sample file). The poses to probe are designed below.');
    if (!st) return;
    const f = st.r;
    const { k, m } = letters();
    const t = show('errLength', tol);
    const before = f.before.max;
    const after = f.after.max;
    const status = judge(before, tol);
    const n = f.corrections.length;
    const fix = n
      ? ` Entering the ${n === 1 ? 'correction' : `${n} corrections`} below would bring it to ${show('errLength', after)} at most (predicted by the model), ${after <= tol ? 'within' : 'still above'} the tolerance.`
      : status === 'fail'
        ? ' No location error of the rotary axes is found present: the wander is not one the errors identified explain (see the model-fit check below).'
        : ' No error found present: nothing to correct.';
    const sentence = `As ${k} and ${m} turn, the sphere’s measured centre strays up to ${show('errLength', before)} from one fixed sphere ` +
      `(${show('errLength', f.before.sigma)} 1σ per coordinate, ${f.poses.length} poses): ${status === 'pass' ? 'within' : 'above'} the ${t} tolerance.${fix}`;
    const notes = [
      'Judged: the largest 3-D distance of a measured centre from the best-fitting fixed sphere, before any correction: how far the tool tip strays from where the control puts it when the rotary axes turn.',
      f.goodness.words,
    ];
    // Each error found, by its largest effect on a measured centre.
    const contributors = contributorsOf(f.corrections, f.estimates, words);
    // Errors entered on the machine that a sphere here cannot see at all.
    const invisible = lastDesign?.visibility.invisible.map((u) => u.name) ?? [];
    const entered = Object.entries(machine.current()?.errors ?? {}).filter(([name, v]) => typeof v === 'number' && v !== 0 && invisible.includes(name));
    verdict.show({
      status, worst: before, tolerance: tol, sentence, notes, contributors,
      contributorsOf: 'each error found, by its largest effect on a measured centre, as a share of their sum',
      source: st.from.name,
      unseen: lastDesign
        ? { by: 'the sphere test', errors: entered.map(([name, v]) => ({ name, value: show(schema.errors.find((d) => d.name === name)?.quantity === 'smallAngle' ? 'errAngle' : 'errLength', v as number) })), why: 'a sphere in this place moves with them nowhere (see “The poses to probe”)' }
        : undefined,
    });
  };

  // ---- computing
  const update = () => {
    const i = read();
    if (!i) {
      verdict.invalid();
      stale(design, true);
      stale(svPlot.p, true);
      runDesign.cancel();
      measurement.invalid();
      return;
    }
    runDesign(i.design as never).then((d) => {
      if (d === SUPERSEDED) return;
      lastDesign = d;
      showDesign(d);
      if (measurement.state.s === 'ok') judgeNow();
    }, (e) => {
      engineError(e, svPlot.p);
      stale(design, true, `Showing the last design; the engine refused these inputs: ${EngineError.of(e).text}`);
    });
    const input = i.identify;
    if (input.csv.trim() !== '' && plain(input.csv) !== sourceCsv) setSource('text typed or pasted in the field', input.csv);
    measurement.identify(input as never, source);
  };

  /** Greys every output of the identification (it no longer answers the inputs), with `why`. */
  const greyIdentification = (why?: string) => {
    for (const box of [corrections, ident]) stale(box, true, why);
    for (const p of [centresPlot, componentsPlot]) stale(p.p, true, why);
    summary.classList.toggle('stale', summaryItems.size > 0);
  };
  /** No measurement: the identification's outputs say how to give one. */
  const clearIdentification = () => {
    corrections.replaceChildren(el('p', { class: 'field-hint' }, 'The errors found, the numbers to enter in the control and the button that puts them into the machine above appear here once a measurement is loaded.'));
    ident.replaceChildren(el('p', { class: 'field-hint' }, 'Paste the measured centres, choose or drop a file, or load the sample file (' + SAMPLE_WORDS + ').'));
    for (const box of [corrections, ident]) stale(box, false);
    void clearPlot(centresPlot.p);
    void clearPlot(componentsPlot.p);
    setShown(identPlots, false);
    for (const id of ['pb-sum-source', 'pb-sum-before', 'pb-sum-after', 'pb-sum-sphere', 'pb-sum-fit']) setSummary(id, '', null);
    summary.classList.remove('stale');
  };

  const measurement = measured(runIdentify, {
    name: (from: Source) => from.name,
    before: 'the file before it',
    alert, useButton, useMsg,
    grey: greyIdentification,
    clear: clearIdentification,
    show: (r, from) => showIdentification(r, from),
    judge: () => judgeNow(),
    fieldOk: () => inputs.byPath.csv?.setError(null),
    fieldError: (e) => showAtField(e, inputs.byPath, machine),
  });

  // ---- drawing
  const D = (mm: number) => toDisplay('errLength', mm);
  const lu = () => unitDef('errLength').label;
  const norm = (v: number[]) => Math.hypot(v[0], v[1], v[2]);

  const showIdentification = (f: ProbeIdentification, from: Source) => {
    const { k, m } = letters();
    setSummary('pb-sum-source', 'Measured centres', `${sourceText(from, f.poses.length, 'poses')}${f.measurements.reference === null ? '' : ' The first line is the reference pose.'}`);
    setSummary('pb-sum-before', 'Wander before correction', `${show('errLength', f.before.sigma)} 1σ per coordinate, ${show('errLength', f.before.max)} at most (3-D, from the best-fitting fixed sphere)`);
    setSummary('pb-sum-after', 'After correction (predicted)', `${show('errLength', f.after.sigma)} 1σ per coordinate, ${show('errLength', f.after.max)} at most: what is left once the errors found are entered`);
    const mm4 = (v: number) => (Math.abs(v) < 5e-5 ? 0 : v).toFixed(4);
    setSummary('pb-sum-sphere', 'Sphere found at', `${f.sphere.map(mm4).join(', ')} mm (workpiece frame, all axes at zero)`);
    setSummary('pb-sum-fit', 'Model fit', f.goodness.words);
    summary.classList.remove('stale');

    // The corrections: plain words, the number to enter, the sign convention.
    if (f.corrections.length) {
      corrections.replaceChildren(
        el('p', {}, `The errors of ${k} and ${m} this measurement finds present (Holm’s decisions below), in the machine’s frame with every axis at zero:`),
        ...correctionsView('pb', f.corrections, words),
      );
    } else {
      corrections.replaceChildren(el('p', { id: 'pb-no-corrections' }, `No location error of ${k} or ${m} is found present in ${from.name}: nothing to enter.`));
    }
    stale(corrections, false);

    // The identification: every unknown, its interval and decision.
    const table = el('table', { class: 'ident-table', id: 'pb-ident-table' });
    const head = el('tr');
    for (const h of ['error', 'identified value', '95 % interval ±', 'decision', 'what it means']) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'), el('tbody'));
    table.tHead!.append(head);
    const row = (e: Estimate) => {
      const q = quantityOf(e.unit);
      const tr = el('tr');
      tr.dataset.name = e.name;
      tr.dataset.verdict = e.verdict;
      const half = e.interval ? (e.interval[1] - e.interval[0]) / 2 : null;
      const decision = e.verdict === 'not-identifiable' && e.group !== null ? `${DECISION[e.verdict]} (group ${e.group + 1})` : DECISION[e.verdict];
      tr.append(
        el('th', { scope: 'row', title: words.get(e.name)?.title ?? '' }, paramName(e.name)),
        el('td', {}, e.value === null ? '—' : show(q, e.value)),
        el('td', {}, half === null ? '—' : show(q, half, 2)),
        el('td', {}, decision),
        el('td', {}, e.words.replace(/^[^:]*: /, '')),
      );
      return tr;
    };
    for (const e of f.estimates) table.tBodies[0].append(row(e));
    const scroll = el('div', { class: 'table-scroll' });
    scroll.append(table);
    const verdicts = el('ul', { class: 'verdicts', id: 'pb-verdicts' });
    for (const s of f.summary) {
      const li = el('li', {}, s);
      if (f.goodness.explains === false && s === f.goodness.words) li.className = 'warn';
      verdicts.append(li);
    }
    const groups = el('ul', { id: 'pb-groups' });
    f.groups.forEach((g, i) => groups.append(el('li', {}, `Group ${i + 1} (${g.members.map(paramName).join(', ')}): ${g.words.join(' ') || 'not measured'}`)));
    const rank = el('p', { id: 'pb-rank' }, `Rank ${f.rank} of ${f.estimates.length} (relative singular values ${f.singularValues.map((s) => fmt.num(s, 2)).join(', ')}).` +
      (f.estimates.some((e) => e.name.startsWith('sphere_')) ? ' The sphere’s own position is fitted with the errors (its exact place on the table need not be known).' : ''));
    ident.replaceChildren(el('p', { class: 'source', id: 'pb-source' }, sourceText(from, f.poses.length, 'poses')), verdicts, scroll, ...(f.groups.length ? [groups] : []), rank);
    stale(ident, false);

    // The plots: per pose, before and after.
    setShown(identPlots, true);
    const labels = f.poses.map((p) => `pose ${p.label}: ${k} ${fmt.num(p.k, 6)}°, ${m} ${fmt.num(p.m, 6)}°`);
    const x = f.poses.map((_, i) => i + 1);
    // Upright labels while they fit (about 28 px each), else turned.
    const crowded = f.poses.length * 28 > Math.max(centresPlot.p.clientWidth - 80, 200);
    const xaxis = axis(`pose (${k}, ${m} in the hover text)`, { tickvals: x, ticktext: f.poses.map((p) => p.label), tickangle: crowded ? -90 : 0 });
    const tol = verdict.tolerance();
    draw(centresPlot.p, `How far each measured centre lies from one fixed sphere<br>before correction (as measured) and after (predicted)<br>${from.name}`, [
      { x, y: f.poses.map((p) => D(norm(p.before))), type: 'bar', name: 'before correction', marker: { color: '#d62728' }, hovertext: labels, hovertemplate: `%{hovertext}<br>before %{y:.4g} ${lu()}<extra></extra>` },
      { x, y: f.poses.map((p) => D(norm(p.after))), type: 'bar', name: 'after correction (predicted)', marker: { color: '#2ca02c' }, hovertext: labels, hovertemplate: `%{hovertext}<br>after %{y:.4g} ${lu()}<extra></extra>` },
      ...(tol === null ? [] : [{ x: [0.5, f.poses.length + 0.5], y: [D(tol), D(tol)], type: 'scatter', mode: 'lines', name: `tolerance (${show('errLength', tol)})`, line: { color: '#57606a', width: 1.5, dash: 'dash' }, hoverinfo: 'skip' } as Data]),
    ], {
      barmode: 'group',
      xaxis,
      yaxis: axis(titled('distance (3-D)', 'errLength'), { rangemode: 'tozero' }),
      legend: { orientation: 'h', x: 0, y: -0.3, xanchor: 'left', yanchor: 'top' },
      margin: { b: 100 },
    } as Partial<Layout>, 'probe-centres');
    const colors = ['#1f77b4', '#ff7f0e', '#9467bd'];
    const comp: Data[] = [];
    ['X', 'Y', 'Z'].forEach((c, a) => {
      comp.push({ x, y: f.poses.map((p) => D(p.before[a])), type: 'scatter', mode: 'lines+markers', name: `${c} before`, line: { color: colors[a], width: 1.5 }, marker: { size: 6 }, text: labels, hovertemplate: `%{text}<br>${c} before %{y:.4g} ${lu()}<extra></extra>` } as Data);
      comp.push({ x, y: f.poses.map((p) => D(p.after[a])), type: 'scatter', mode: 'lines+markers', name: `${c} after (predicted)`, line: { color: colors[a], width: 1, dash: 'dot' }, marker: { size: 6, symbol: 'circle-open' }, text: labels, hovertemplate: `%{text}<br>${c} after %{y:.4g} ${lu()}<extra></extra>` } as Data);
    });
    draw(componentsPlot.p, `Measured minus expected centre along X, Y, Z (machine axes), less the best-fitting sphere position:<br>before correction and the residual after (predicted)`, comp, {
      xaxis,
      yaxis: axis(titled('deviation', 'errLength')),
      legend: { orientation: 'h', x: 0, y: -0.2, xanchor: 'left', yanchor: 'top' },
      margin: { b: 120 },
    } as Partial<Layout>, 'probe-components');
  };

  const showDesign = (d: ProbeDesign) => {
    const [k, m] = d.axes;
    note(svPlot.p, null);
    const r = d.visibility.reachableRank;
    const compare = el('table', { class: 'ident-table', id: 'pb-design-compare' });
    const head = el('tr');
    for (const h of ['', 'simple layout', 'designed layout']) head.append(el('th', { scope: 'col' }, h));
    compare.append(el('thead'), el('tbody'));
    compare.tHead!.append(head);
    const cond = (l: PoseLayout) => (l.condition === null ? 'infinite (rank short)' : fmt.num(l.condition, 3));
    for (const [label, a, b] of [
      ['Poses', `${d.simple.poses.length} (${k} every 30° at ${m} = 0, ${m} every 30° at ${k} = 0)`, `${d.designed.poses.length} (chosen among ${d.candidates} reachable)`],
      ['Rank (independent combinations measured)', `${d.simple.rank} of ${r} possible`, `${d.designed.rank} of ${r} possible`],
      ['Weakest combination of typical errors (smallest scaled singular value, noise standard deviations)', fmt.num(d.simple.smallest, 3), fmt.num(d.designed.smallest, 3)],
      ['Condition number σ₁/σᵣ', cond(d.simple), cond(d.designed)],
    ]) {
      const tr = el('tr');
      tr.append(el('th', { scope: 'row' }, label), el('td', {}, a), el('td', {}, b));
      compare.tBodies[0].append(tr);
    }
    const compareScroll = el('div', { class: 'table-scroll' });
    compareScroll.append(compare);

    const vis = el('ul', { id: 'pb-visibility' });
    vis.append(el('li', {}, `Identified on their own by a sphere here (${d.candidates} reachable poses together, rank ${r} of ${d.unknowns.length} unknowns): ${listWords(d.visibility.identifiable) || 'none'}.`));
    for (const u of d.visibility.invisible) {
      const li = el('li', {}, `${u.name} cannot be seen at all: ${u.why}`);
      li.dataset.invisible = u.name;
      vis.append(li);
    }
    for (const g of d.visibility.inseparable) vis.append(el('li', {}, g.why));
    const second = el('li', { id: 'pb-second' }, d.secondSphere.words);
    vis.append(second);

    const poseTable = (l: PoseLayout, id: string, title: string, file: string) => {
      const box = el('div', { class: 'pose-layout' });
      const t = el('table', { class: 'ident-table pose-table', id });
      const group = el('tr');
      group.append(el('td', { colspan: '3' }), el('th', { scope: 'colgroup', colspan: '3' }, 'expected centre (mm)'));
      const h = el('tr');
      for (const c of ['pose', `${k} (°)`, `${m} (°)`, 'X', 'Y', 'Z']) h.append(el('th', { scope: 'col' }, c));
      t.append(el('thead'), el('tbody'));
      t.tHead!.append(group, h);
      l.poses.forEach((p, i) => {
        const tr = el('tr');
        tr.dataset.k = String(p.k);
        tr.dataset.m = String(p.m);
        tr.dataset.tilt = String(p.tilt);
        const c = (v: number) => fmt.num(Math.abs(v) < 5e-10 ? 0 : v, 7);
        tr.append(el('th', { scope: 'row' }, String(i + 1)), el('td', {}, fmt.turn(p.k).replace('°', '')), el('td', {}, fmt.turn(p.m).replace('°', '')),
          el('td', {}, c(p.expected[0])), el('td', {}, c(p.expected[1])), el('td', {}, c(p.expected[2])));
        t.tBodies[0].append(tr);
      });
      const scroll = el('div', { class: 'table-scroll' });
      scroll.append(t);
      const csv = el('button', { type: 'button', id: `${id}-csv` }, 'Download the poses (CSV)');
      csv.addEventListener('click', () => download(`${file}.csv`, l.csv, 'text/csv'));
      const nc = el('button', { type: 'button', id: `${id}-nc` }, 'Download NC blocks');
      nc.addEventListener('click', () => download(`${file}.nc`, l.nc, 'text/plain'));
      const row = el('div', { class: 'file-row' });
      row.append(csv, nc);
      box.append(el('h4', {}, `${title}: ${l.poses.length} poses, weakest combination ${fmt.num(l.smallest, 3)}`), scroll, row);
      return box;
    };
    const layouts = el('div', { class: 'pose-layouts' });
    layouts.append(
      poseTable(d.designed, 'pb-poses-designed', 'Designed layout', 'probe-designed-poses'),
      poseTable(d.simple, 'pb-poses-simple', 'Simple layout', 'probe-simple-poses'),
    );
    design.replaceChildren(
      el('p', { id: 'pb-design-lead' }, d.summary[0] ?? ''),
      compareScroll,
      el('h4', {}, 'What a sphere in this place can see'), vis,
      el('p', { class: 'field-hint' }, `Scaling: ${d.scaling} The expected centre is where the control should find the sphere with no error (linear-axis positions, TCPM off). The CSV has empty X_mm, Y_mm, Z_mm columns to fill in: the page reads it back as it is. The NC blocks position ${k} and ${m}; run the control’s own sphere-probing cycle at each.`),
      layouts,
    );
    stale(design, false);
    const idx = Array.from({ length: r }, (_, i) => i + 1);
    draw(svPlot.p, 'Singular values of the scaled sensitivities (noise standard deviations per typical error):<br>the smallest decides what the poses tell apart', [
      { x: idx, y: d.simple.singularValues.slice(0, r).map((v) => Math.max(v, 1e-3)), type: 'bar', name: 'simple layout', marker: { color: '#9fb7d0' }, hovertemplate: 'σ%{x} = %{y:.3g}<extra>simple</extra>' } as Data,
      { x: idx, y: d.designed.singularValues.slice(0, r), type: 'bar', name: 'designed layout', marker: { color: '#2ca02c' }, hovertemplate: 'σ%{x} = %{y:.3g}<extra>designed</extra>' } as Data,
    ], {
      barmode: 'group',
      xaxis: axis('singular value number', { tickvals: idx }),
      yaxis: axis('σ (noise standard deviations)', { type: 'log' }),
      legend: { orientation: 'h', x: 0, y: -0.3, xanchor: 'left', yanchor: 'top' },
    } as Partial<Layout>, 'probe-design-singular-values');
  };

  // ---- "Use these errors": the identified errors into the one machine model
  useButton.addEventListener('click', () => {
    const st = measurement.state;
    if (st.s !== 'ok') return;
    const f = st.r;
    const own = f.estimates.filter((e) => !e.name.startsWith('sphere_'));
    useMsg.textContent = useFound(machine, schema, f.errors as Record<string, number>, own, st.from.name, 'this measurement');
  });

  // ---- measurement files
  /** The sample's preset (machine and sphere) when the machine above is another layout. */
  const offerSampleMachine = async () => {
    sampleOffer.replaceChildren();
    setShown(sampleOffer, false);
    const presets = await loadPresets('probe').catch(() => []);
    const p = presets.find((x) => x.name.startsWith(SAMPLE_PRESET));
    const all = await machine.presets().catch(() => []);
    const base = all.find((x) => p?.machinePreset && x.name.startsWith(p.machinePreset));
    const m = machine.current() as Record<string, unknown> | null;
    if (!p || !base || !m) return;
    const differs = LAYOUT.filter((key) => (base.machine[key] ?? null) !== (m[key] ?? null));
    if (!differs.length) return;
    const button = el('button', { type: 'button', id: 'pb-sample-machine' }, 'Set the sample’s machine and sphere');
    button.addEventListener('click', async () => {
      const text = fields.get('pb-csv')?.text() ?? '';
      await applyPreset('pb', p, machine);
      fields.get('pb-csv')?.setText(text);
      setShown(sampleOffer, false);
      fileMsg.textContent = `The machine above is now “${base.name}”, the sphere where the sample was measured.`;
    });
    sampleOffer.append(el('span', { class: 'warn' }, `The sample was measured on “${base.name}”; the machine above differs (${differs.join(', ')}).`), button);
    setShown(sampleOffer, true);
  };

  sampleButton.addEventListener('click', async () => {
    try {
      const res = await fetch(SAMPLE);
      if (!res.ok) throw new Error(`${res.status} ${res.statusText}`);
      const text = await res.text();
      setSource(SAMPLE_NAME, text);
      useMsg.textContent = '';
      fields.get('pb-csv')?.setText(text);
      fileMsg.textContent = `Loaded the sample file (${SAMPLE_WORDS}).`;
      await offerSampleMachine();
    } catch (e) {
      fileMsg.textContent = `Could not load the sample file: ${String(e)}`;
    }
  });

  const readFile = async (f: File) => {
    if (f.size > 1_000_000) {
      const message = `${f.name} is larger than 1 MB: not a file of measured sphere centres.`;
      fileMsg.textContent = message;
      measurement.refuse({ name: f.name, at: new Date() }, message);
      return;
    }
    const got = await readOrRefuse(f, (message) => {
      fileMsg.textContent = message;
      measurement.refuse({ name: f.name, at: new Date() }, message);
    }, 'a table of measured sphere centres');
    if (!got) return;
    setSource(f.name, got.text);
    useMsg.textContent = '';
    setShown(sampleOffer, false);
    fields.get('pb-csv')?.setText(got.text);
    fileMsg.textContent = `Read ${f.name}${encodingNote(got)}; the result above says whether it could be used.`;
  };
  file.addEventListener('change', async () => {
    const f = file.files?.[0];
    file.value = '';
    if (f) await readFile(f);
  });
  if (identSet) {
    identSet.addEventListener('dragover', (e) => {
      e.preventDefault();
      identSet.classList.add('drop');
    });
    identSet.addEventListener('dragleave', () => identSet.classList.remove('drop'));
    identSet.addEventListener('drop', async (e) => {
      e.preventDefault();
      identSet.classList.remove('drop');
      const f = e.dataTransfer?.files?.[0];
      if (f) await readFile(f);
    });
  }

  form.addEventListener('input', (e) => {
    const id = (e.target as HTMLElement).id;
    if (id === 'pb-file') return;
    update();
  });
  machine.onChange(update);
  onUnitsChange(() => {
    if (lastDesign) showDesign(lastDesign);
    const shown = measurement.shown;
    if (shown && measurement.state.s === 'ok') showIdentification(shown.r, shown.from);
    judgeNow();
  });
  measurement.clear();
  update();
}
