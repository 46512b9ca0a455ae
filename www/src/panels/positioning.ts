// The "Laser positioning" panel: a positioning test of one axis evaluated as ISO 230-2 defines it,
// from the runs a laser interferometer (or any instrument) measured, usually 5 each way at each
// target. The engine (`positioningEvaluate`) gives per target the mean deviations each way, the
// estimators s, the reversal value B_i and the repeatability R_i, and for the axis A, E, M, R
// and B each way and bidirectional, checked against the tolerances entered; the panel tabulates
// them, plots the runs with the ±2s bands and judges the axis. "Use as error motion" puts the
// mean bidirectional deviation into the machine as the axis's positioning error motion (E_XX …),
// so that the volumetric map uses it. Nothing is computed here: every number is the engine's.
import type { Data, Layout } from 'plotly.js';
import type { Positioning } from '@engine';
import { channel, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el } from '../ui/fields';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, plotBox, stale } from '../ui/plot';
import * as fmt from '../ui/format';
import { fileSource, sampleAsDefault } from '../ui/source';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { listWords, lowerFirst, verdictBox, type VerdictStatus } from '../ui/verdict';
import { engineErrors, panelShell, type Panel } from './panel';

export const positioningPanel: Panel = {
  id: 'positioning',
  prefix: 'ps',
  title: 'Laser positioning (ISO 230-2)',
  exports: ['positioningEvaluate'],
  mount,
};

const SAMPLE = 'samples/x-laser-runs.csv';
const SAMPLE_NOTE = 'synthetic, made by scripts/make-laser-sample.mjs: X from −300 to 300 mm every 50 mm, 5 runs each way; 10 µm/m of scale error, a 1.5 µm ripple, 3 µm of lost motion and 0.4 µm of noise (its header says so).';
const ROTARY = ['A', 'B', 'C'];

/** The axis's results in words, with what to do when one is above its tolerance. */
const RESULTS: Record<string, { name: string; advice: string }> = {
  A: { name: 'Accuracy A', advice: 'the sum of the systematic error and the scatter; see E and R' },
  E: { name: 'Systematic deviation E', advice: 'pitch-error compensation from these means (“Use as error motion” below puts them into the machine; the control needs them as its compensation table)' },
  M: { name: 'Mean deviation M', advice: 'pitch-error compensation from the mean bidirectional deviation' },
  R: { name: 'Repeatability R', advice: 'look for play, a loose encoder or scale, or thermal drift during the runs' },
  B: { name: 'Reversal B', advice: 'backlash (reversal) compensation on the axis, or the ball screw’s preload and the guideways' },
};

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Laser positioning: a linear or rotary axis by ISO 230-2',
    'A laser interferometer (or an angle encoder for a rotary axis) measures where the axis stops at each target, usually 5 runs each way. ' +
      'From the runs, as ISO 230-2 defines them: the mean deviations each way x̄↑ and x̄↓, the estimators s, the reversal value B_i and the ' +
      'bidirectional repeatability R_i at each target; for the axis the accuracy A, the systematic deviation E, the mean deviation M, the ' +
      'repeatability R and the reversal B, each against its tolerance. The mean bidirectional deviation is the axis’s positioning error ' +
      'motion: one button puts it into the machine, and the Volumetric tab’s map uses it. The panel opens on a synthetic sample of an X axis.',
  );

  // ---- inputs (the engine's fields; the accuracy's tolerance goes beside the verdict)
  const inputs = renderFields(positioningPanel.exports.flatMap((n) => schema.exports[n]), 'ps', form);
  const csvArea = form.querySelector<HTMLTextAreaElement>('#ps-csv');
  if (csvArea) csvArea.placeholder = 'target (mm), up 1 (µm), …, up 5 (µm), down 1 (µm), …, down 5 (µm)\n0, 0.4, …\n…';
  const axisSelect = form.querySelector<HTMLSelectElement>('#ps-axis');
  const linearSet = inputs.groups.get('Tolerances (linear axis)');
  const rotarySet = inputs.groups.get('Tolerances (rotary axis)');
  const aLinear = inputs.field('tolerance.a');
  const aRotary = inputs.field('rotaryTolerance.a');
  if (!axisSelect || !linearSet || !rotarySet || !aLinear || !aRotary) throw new Error('positioningEvaluate lacks a field the panel shows');
  const axisName = () => axisSelect.value || 'X';
  const rotary = () => ROTARY.includes(axisName());

  // The accuracy's tolerance, of the kind of axis chosen, beside the verdict; the others stay in
  // the form. A field of the other kind is hidden, and so not read (nor sent).
  const pair = el('div', { class: 'tolerance-pair' });
  pair.append(aLinear.root, aRotary.root);
  const verdict = verdictBox({
    prefix: 'ps',
    tolerance: { adopt: { root: pair, input: aLinear.input, read: () => (rotary() ? aRotary.read() : aLinear.read()) } },
    onTolerance: () => {},
  });
  pair.addEventListener('input', () => update());
  const showAxisKind = () => {
    const rot = rotary();
    for (const [set, hide] of [[linearSet, rot], [rotarySet, !rot]] as const) {
      set.hidden = hide;
      for (const f of set.querySelectorAll<HTMLElement>(':scope > [data-path]')) f.hidden = hide;
    }
    aLinear.root.hidden = rot;
    aRotary.root.hidden = !rot;
    linearSet.querySelector('legend')!.textContent = 'Tolerances of the axis (0: not judged)';
    rotarySet.querySelector('legend')!.textContent = 'Tolerances of the rotary axis (0: not judged)';
  };
  showAxisKind();

  // ---- outputs
  const summary = el('dl', { class: 'summary', id: 'ps-summary', 'aria-live': 'polite' });
  const runsPlot = plotBox('ps-runs', 'wide', 'tall');
  const plots = el('div', { class: 'plots' });
  plots.append(runsPlot.wrap);
  const axisBox = el('div', { class: 'ident', id: 'ps-axis-results', 'aria-live': 'polite' });
  const targetBox = el('div', { class: 'ident', id: 'ps-targets' });
  const motionBox = el('div', { class: 'motion-use', id: 'ps-motion' });
  const useButton = el('button', { type: 'button', id: 'ps-use-motion', disabled: '' }, 'Use as error motion');
  const motionMsg = el('p', { class: 'field-hint', id: 'ps-motion-msg', 'aria-live': 'polite' });
  motionBox.append(useButton, motionMsg);
  results.append(
    verdict.root, summary, motionBox, plots,
    el('h3', {}, 'The axis (ISO 230-2)'), axisBox,
    el('h3', {}, 'At each target'), targetBox,
  );
  const boxes = [axisBox, targetBox];

  const source = fileSource(form, {
    prefix: 'ps',
    field: 'ps-csv',
    sample: { url: SAMPLE, button: 'Load the sample runs', note: SAMPLE_NOTE },
    expected: 'a table of positioning runs (CSV or text)',
    refused: (message) => {
      run.cancel();
      fresh = false;
      useButton.disabled = true;
      stale(runsPlot.p, true, `${message} Greyed: the result of the runs before it.`);
      for (const b of boxes) stale(b, true, message);
      verdict.none(`No verdict: ${message}`);
    },
  });
  (inputs.groups.get('Positioning (ISO 230-2)') ?? form).querySelector('legend')?.after(source.root);
  // The panel opens on the sample (the field's default), and says so.
  const sampleText = await sampleAsDefault('ps-csv', SAMPLE);
  const sourceName = (csv: string) => source.name() ?? (sampleText && csv === sampleText ? `the sample ${SAMPLE.split('/').pop()} (synthetic)` : 'the text in the field');

  verdict.details('ISO 230-2: the definitions',
    el('pre', { class: 'formula' },
      'x_ij = P_ij − P_i                                  (position reached less the target)\n' +
      'x̄_i↑ = (1/n)·Σ_j x_ij↑,   s_i↑ = √(Σ_j (x_ij↑ − x̄_i↑)² / (n − 1))   (and ↓)\n' +
      'x̄_i = (x̄_i↑ + x̄_i↓)/2,   B_i = x̄_i↑ − x̄_i↓,   R_i↑ = 4·s_i↑\n' +
      'R_i = max(2·s_i↑ + 2·s_i↓ + |B_i|, R_i↑, R_i↓)\n' +
      'B = max|B_i|,  R = max R_i,  E = max(x̄_i↑, x̄_i↓) − min(x̄_i↑, x̄_i↓),  M = max x̄_i − min x̄_i\n' +
      'A = max(x̄_i↑ + 2s_i↑, x̄_i↓ + 2s_i↓) − min(x̄_i↑ − 2s_i↑, x̄_i↓ − 2s_i↓)'),
    el('p', { class: 'field-hint' }, 'The bidirectional R is the largest R_i, not the larger of R↑ and R↓: with a reversal it can exceed both. E covers both directions’ means together. Derivations: crate/src/positioning/mod.rs.'),
  );

  const run = channel('positioningEvaluate');
  const engineError = engineErrors(inputs.byPath, machine);
  let last: { r: Positioning; came: string; file: string; axis: string } | null = null;
  let fresh = false;

  const greyAll = (why?: string) => {
    stale(runsPlot.p, true, why);
    for (const b of boxes) stale(b, true, why);
    useButton.disabled = true;
  };

  /** The quantity of the axis's values: small lengths (mm) or small angles (degrees). */
  const qOf = (r: Positioning): 'errLength' | 'errAngle' => (r.unit === 'deg' ? 'errAngle' : 'errLength');

  const update = () => {
    showAxisKind();
    const own = inputs.read();
    if (!own) {
      run.cancel();
      fresh = false;
      verdict.invalid();
      greyAll();
      return;
    }
    if (String(own.csv ?? '').trim() === '') {
      run.cancel();
      fresh = false;
      useButton.disabled = true;
      inputs.byPath.csv?.setError(null);
      verdict.none('No verdict yet: no runs. Choose or drop the file your laser software exports, paste it into the field, or load the sample runs.');
      if (last) greyAll('No runs in the field: this is the result of the runs before.');
      else for (const b of boxes) b.replaceChildren(el('p', { class: 'field-hint' }, 'The results appear here once runs are loaded.'));
      return;
    }
    fresh = false;
    verdict.pending();
    useButton.disabled = true;
    const file = sourceName(String(own.csv ?? ''));
    const axisNow = axisName();
    run(own as never).then((r) => {
      if (r === SUPERSEDED) return;
      inputs.byPath.csv?.setError(null);
      const came = `${file}: axis ${axisNow}, ${r.targets.length} targets from ${fmt.num(r.targets[0].target)} to ${fmt.num(r.targets[r.targets.length - 1].target)} ${r.unit === 'deg' ? '°' : 'mm'}, ${r.runs} runs each way (file in ${r.units[0]} and ${r.units[1]})`;
      last = { r, came, file, axis: axisNow };
      fresh = true;
      showResult();
    }, (e) => {
      fresh = false;
      engineError(e, runsPlot.p);
      for (const b of boxes) stale(b, true, 'Showing the result of the runs before: these were refused (see the message at the field).');
      useButton.disabled = true;
      verdict.refused(e);
    });
  };

  const judgeNow = () => {
    if (!last || !fresh) return;
    const { r, came } = last;
    const q = qOf(r);
    const s = (v: number) => show(q, v, 3);
    const headline = `A ${s(r.a)}, E ${s(r.e)}, M ${s(r.m)}, R ${s(r.r)}, B ${s(r.b)}`;
    if (!r.checks.length) {
      return verdict.none(`${headline} (${came}). No tolerance entered, so no verdict: enter the accuracy A you accept beside this line (and E, R, B or M under the inputs).`);
    }
    const failing = r.checks.filter((c) => !c.pass);
    const status: Exclude<VerdictStatus, 'none'> = failing.length ? 'fail' : 'pass';
    // The check that decides: the one furthest above (or nearest to) its tolerance.
    const decides = [...r.checks].sort((a, b) => b.value / b.tolerance - a.value / a.tolerance)[0];
    const each = r.checks.map((c) => `${c.name} ${s(c.value)} ${c.pass ? '≤' : '>'} ${s(c.tolerance)}`).join('; ');
    const advice = failing.map((c) => `${RESULTS[c.name].name}: ${RESULTS[c.name].advice}.`);
    verdict.show({
      status, worst: decides.value, tolerance: decides.tolerance, quantity: q, what: RESULTS[decides.name].name, source: came,
      sentence: status === 'pass'
        ? `Axis ${last.axis} passes ISO 230-2’s checks entered: ${each}.`
        : `Axis ${last.axis} fails ${listWords(failing.map((c) => lowerFirst(RESULTS[c.name].name)))}: ${each}.`,
      notes: [`All results: ${headline}.`, ...advice],
    });
  };

  const showResult = () => {
    if (!last) return;
    const { r, came } = last;
    const q = qOf(r);
    const V = (v: number) => toDisplay(q, v);
    const u = unitDef(q).label;
    const s = (v: number) => show(q, v, 4);
    note(runsPlot.p, null);
    summary.replaceChildren();
    const item = (id: string, k: string, v: string) => summary.append(el('dt', {}, k), el('dd', { id }, v));
    item('ps-sum-came', 'Computed from', came);
    item('ps-sum-motion', 'Error motion it gives', `${r.motion.name}: the mean bidirectional deviation x̄_i at the ${r.motion.position.length} targets`);

    // ---- the axis
    const checks = new Map(r.checks.map((c) => [c.name, c]));
    const at = el('table', { class: 'ident-table plain', id: 'ps-axis-table' });
    const ah = el('tr');
    for (const h of ['result', '↑', '↓', 'bidirectional', 'tolerance']) ah.append(el('th', { scope: 'col' }, h));
    at.append(el('thead'), el('tbody'));
    at.tHead!.append(ah);
    const rows: [string, string, number | null, number | null, number, string?][] = [
      ['A', 'Accuracy A', r.aUp, r.aDown, r.a],
      ['E', 'Systematic deviation E', r.eUp, r.eDown, r.e],
      ['M', 'Mean deviation M', null, null, r.m],
      ['R', 'Repeatability R', r.rUp, r.rDown, r.r],
      ['B', 'Reversal B', null, null, r.b, `mean reversal B̄ = ${s(r.bMean)}`],
    ];
    for (const [key, name, up, down, both, extra] of rows) {
      const tr = el('tr');
      tr.dataset.name = key;
      tr.dataset.value = String(both);
      const c = checks.get(key);
      const tol = el('td', {}, c ? `${s(c.tolerance)}: ${c.pass ? 'pass' : 'FAIL'}` : '—');
      if (c) tr.classList.add(c.pass ? 'pass' : 'fail');
      const bothCell = el('td', {}, s(both));
      if (extra) bothCell.append(el('br'), el('span', { class: 'field-hint' }, extra));
      tr.append(el('th', { scope: 'row' }, name), el('td', {}, up === null ? '—' : s(up)), el('td', {}, down === null ? '—' : s(down)), bothCell, tol);
      at.tBodies[0].append(tr);
    }
    const scroll = (t: HTMLElement) => {
      const w = el('div', { class: 'table-scroll' });
      w.append(t);
      return w;
    };
    axisBox.replaceChildren(el('p', { class: 'field-hint' }, '↑: each target approached in the positive direction; ↓: in the negative direction; bidirectional: both (ISO 230-2). B = max |B_i|.'), scroll(at));

    // ---- each target
    const tt = el('table', { class: 'ident-table plain', id: 'ps-targets-table' });
    const th = el('tr');
    const tu = r.unit === 'deg' ? '°' : 'mm';
    for (const h of [`target (${tu})`, `x̄↑ (${u})`, `x̄↓ (${u})`, `s↑ (${u})`, `s↓ (${u})`, `B_i (${u})`, `R_i (${u})`, `x̄_i (${u})`]) th.append(el('th', { scope: 'col' }, h));
    tt.append(el('thead'), el('tbody'));
    tt.tHead!.append(th);
    const n = (v: number) => fmt.num(V(v), 4);
    for (const t of r.targets) {
      const tr = el('tr');
      tr.dataset.target = String(t.target);
      tr.append(el('th', { scope: 'row' }, fmt.num(t.target)), ...[t.meanUp, t.meanDown, t.sUp, t.sDown, t.b, t.r, t.mean].map((v) => el('td', {}, n(v))));
      tt.tBodies[0].append(tr);
    }
    targetBox.replaceChildren(el('p', { class: 'field-hint' }, `The ${r.runs} runs each way at each target: means, estimators s (n − 1), reversal B_i = x̄↑ − x̄↓, bidirectional repeatability R_i and the mean bidirectional deviation x̄_i (the error motion).`), scroll(tt));
    for (const b of boxes) stale(b, false);

    // ---- the runs with the ±2s bands
    const x = r.targets.map((t) => t.target);
    const data: Data[] = [];
    const band = (lo: number[], hi: number[], name: string, fill: string) => {
      data.push(
        { x, y: lo.map(V), type: 'scatter', mode: 'lines', line: { width: 0 }, hoverinfo: 'skip', showlegend: false, legendgroup: name, name: `${name} (low)` } as Data,
        { x, y: hi.map(V), type: 'scatter', mode: 'lines', line: { width: 0 }, fill: 'tonexty', fillcolor: fill, name, legendgroup: name, hoverinfo: 'skip' } as Data,
      );
    };
    band(r.targets.map((t) => t.bandUp[0]), r.targets.map((t) => t.bandUp[1]), 'x̄↑ ± 2s↑', 'rgba(31,119,180,0.16)');
    band(r.targets.map((t) => t.bandDown[0]), r.targets.map((t) => t.bandDown[1]), 'x̄↓ ± 2s↓', 'rgba(214,39,40,0.14)');
    const runs = (all: number[][], name: string, colour: string, symbol: string) => all.forEach((runJ, j) => data.push({
      x, y: runJ.map(V), type: 'scatter', mode: 'markers', name, legendgroup: name, showlegend: j === 0,
      marker: { color: colour, symbol, size: 6, opacity: 0.8 },
      hovertemplate: `${name}, run ${j + 1}<br>%{x} ${tu}: %{y:.4g} ${u}<extra></extra>`,
    } as Data));
    runs(r.up, 'runs ↑', '#1f77b4', 'triangle-up');
    runs(r.down, 'runs ↓', '#d62728', 'triangle-down');
    data.push(
      { x, y: r.targets.map((t) => V(t.meanUp)), type: 'scatter', mode: 'lines', name: 'x̄↑', line: { color: '#1f77b4', width: 1.3 } } as Data,
      { x, y: r.targets.map((t) => V(t.meanDown)), type: 'scatter', mode: 'lines', name: 'x̄↓', line: { color: '#d62728', width: 1.3 } } as Data,
      { x, y: r.targets.map((t) => V(t.mean)), type: 'scatter', mode: 'lines+markers', name: `x̄ (${r.motion.name})`, line: { color: '#1f2328', width: 2 }, marker: { size: 4 } } as Data,
    );
    void draw(runsPlot.p, `Axis ${last.axis}: the runs and the ±2s bands<br>A ${show(q, r.a, 3)}, E ${show(q, r.e, 3)}, R ${show(q, r.r, 3)}, B ${show(q, r.b, 3)}`, data, {
      xaxis: axis(`target ${last.axis} (${tu})`),
      yaxis: axis(titled('positional deviation x', q)),
      legend: { orientation: 'h', x: 0, y: -0.18, yanchor: 'top' },
      margin: { b: 110 },
    } as Partial<Layout>, 'positioning-runs');
    useButton.disabled = false;
    useButton.textContent = `Use as error motion (${r.motion.name})`;
    judgeNow();
  };

  /** The table entered last (its name and values): its message goes once the machine no longer
   *  holds it (cleared or replaced on the Volumetric tab, another machine loaded). */
  let entered: { name: string; value: string } | null = null;
  const checkEntered = () => {
    if (!entered) return;
    const fn = machine.motionFunction(entered.name);
    if (!fn || 'poly' in fn || JSON.stringify(fn.value) !== entered.value) {
      entered = null;
      motionMsg.textContent = '';
    }
  };
  machine.onChange(checkEntered);

  useButton.addEventListener('click', () => {
    if (!last || !fresh) return;
    const { r, file } = last;
    const m = r.motion;
    machine.setMotion(m.name, { position: [...m.position], value: [...m.value], file, units: [r.units[0], r.units[1]] });
    entered = { name: m.name, value: JSON.stringify([...m.value]) };
    const axisLetter = m.name.slice(-1);
    const ctx = machine.context();
    const onMachine = !ROTARY.includes(axisLetter) || axisLetter === ctx.k || axisLetter === ctx.m;
    const tu = r.unit === 'deg' ? '°' : 'mm';
    motionMsg.textContent = `Entered ${m.name} into the machine: the mean bidirectional deviation x̄_i of ${file} at ${m.position.length} points, ${axisLetter} from ${fmt.num(m.position[0])} to ${fmt.num(m.position[m.position.length - 1])} ${tu}, ` +
      `interpolated linearly (not extrapolated: the Volumetric tab’s map must lie within it). ` +
      (onMachine ? 'The volumetric map and every study that uses error motions now include it; the Volumetric tab shows it and clears it.' : `This machine has no ${axisLetter} axis: it is kept but not used.`);
  });

  form.addEventListener('input', (e) => {
    if ((e.target as HTMLElement).id === 'ps-file') return;
    update();
  });
  onUnitsChange(() => {
    if (last && fresh) showResult();
  });
  update();
}
