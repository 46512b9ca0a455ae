// The "Rotary axes with a ball-bar" panel (issue 32, ISO 10791-6 style): one rotary axis turns
// while the linear axes keep the spindle's ball where the ideal machine keeps it above the table
// ball, so that the bar's length changes only by the machine's errors. The engine simulates the
// tests on the machine of the Machine section (`ballbarRotarySimulate`: what the bar would show,
// what the tests can and cannot see) and identifies the rotary axes' location errors from the
// measured traces (`ballbarRotaryIdentify`: the shared identification, the corrections to enter).
// The verdict is on the traces as measured: the largest range of the bar's length over a test
// against the tolerance. "Use these errors" puts what was found into the one machine model.
// Nothing is computed here: every number is the engine's.
import type { Data, Layout } from 'plotly.js';
import type { BallbarRotaryIdentification, BallbarRotarySimulation, FieldInfo, Machine } from '@engine';
import { channel, EngineError, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el, fields, selectField } from '../ui/fields';
import { fieldId, loadSchema, renderFields, type RenderedForm, type ShowsError } from '../ui/form';
import { axis, draw, note, plotBox, stale } from '../ui/plot';
import { download } from '../ui/export';
import { identificationView, clearPlot } from '../ui/identify';
import { contributorsOf, correctionsView, useFound } from '../ui/found';
import { measured } from '../ui/measured';
import { leaves, loadPresets, presetPicker } from '../ui/presets';
import { fileSource, sampleAsDefault } from '../ui/source';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { errorWords, judge, listWords, verdictBox } from '../ui/verdict';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';

export const ballbarRotaryPanel: Panel = {
  id: 'ballbar-rotary',
  prefix: 'br',
  title: 'Ball-bar: rotary axes',
  exports: ['ballbarRotarySimulate', 'ballbarRotaryIdentify'],
  mount,
};

const SAMPLE = 'samples/ballbar-rotary.csv';
const SAMPLE_NOTE = 'synthetic, made by scripts/make-ballbar-rotary-sample.mjs on the page’s default machine (a B/C tilting table) from E_X0C = +12 µm, E_X0B = +5 µm, E_Z0B = −8 µm, E_A0C = +0.004°, bar lengths a few µm off, a 1.5 µm clockwise lag and 0.5 µm of noise (its header says so). Its three tests are the panel’s defaults.';
/** The most tests (the engine's limit, `MAX_TESTS`). */
const MAX_TESTS = 8;
const COLOURS = { ccw: '#1f77b4', cw: '#d62728', fitCcw: '#0b3d6b', fitCw: '#7f1416' };
const TEST_COLOURS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22'];
/** "offset_C low_cw" → "offset of test C low (CW)" (the bar's length and the balls' set-up in
 *  that test and direction); an error keeps its ISO name. */
const paramName = (n: string) => {
  const m = /^offset_(.*)_(ccw|cw)$/.exec(n);
  return m ? `offset of test ${m[1]} (${m[2].toUpperCase()})` : n;
};

/** One test's form: its fields (paths relative to the test) in a box of its own. */
interface Card {
  root: HTMLElement;
  form: RenderedForm;
}

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const words = errorWords(schema);
  const { form, results } = panelShell(
    root,
    'Ball-bar with a rotary axis moving (ISO 10791-6 style)',
    'One rotary axis turns while the linear axes follow the ball on the table, so that the ideal machine keeps the bar’s length: ' +
      'what the bar records is where the axes really are. From the traces: the rotary axes’ location errors (ISO 230-1) with their 95 % intervals, ' +
      'the numbers to enter in the control, and what these tests cannot see. The tests are simulated on the machine above before you measure, ' +
      'so that you can see what each shows and what a second ball position adds. The panel opens on a synthetic sample: ' +
      'choose or drop your traces (angle of the moving axis, length change, direction, and a test column naming each line’s test), or paste them.',
  );

  // ---- inputs: the tests (one form per test, from the schema's item fields), then the study's
  form.append(presetPicker('ballbar-rotary', 'br', machine));
  const itemFields: FieldInfo[] = (schema.lists.ballbarTests ?? []).filter((f) => f.path !== 'csv');
  const testsSet = el('fieldset', { id: 'br-tests' });
  testsSet.append(el('legend', {}, 'The tests'));
  const countField = selectField('br-count', 'Number of tests', Array.from({ length: MAX_TESTS }, (_, i) => ({ value: String(i + 1), label: String(i + 1) })), '1',
    'Each test moves one rotary axis with the ball-bar in one place; two tests with the ball at different heights, or another bar direction, separate errors one test alone cannot.');
  testsSet.append(countField.root);
  form.append(testsSet);
  const cards: Card[] = [];
  for (let i = 0; i < MAX_TESTS; i++) {
    const box = el('div', { class: 'test-card', id: `br-test-${i}` });
    const rendered = renderFields(itemFields, `br-tests-${i}`, box, machine.context());
    const legend = box.querySelector('legend');
    if (legend) legend.textContent = `Test ${i + 1}`;
    testsSet.append(box);
    cards.push({ root: box, form: rendered });
  }
  const study = renderFields(ballbarRotaryPanel.exports.flatMap((n) => schema.exports[n]).filter((f) => f.path !== 'tests'), 'br', form, machine.context());
  const what = study.groups.get('Ball-bar test')?.querySelector('legend');
  if (what) what.textContent = 'What to identify';
  const csvArea = form.querySelector<HTMLTextAreaElement>('#br-csv');
  if (csvArea) csvArea.placeholder = 'test, angle (deg), deviation (µm), direction\nC low, 0, -14.81, ccw\n…';

  // The sample's tests are the panel's defaults: the panel opens on a result that says what it is.
  const samplePreset = (await loadPresets('ballbar-rotary').catch(() => [])).find((p) => p.name.startsWith('Sample file'));
  const adopt = (id: string, value: number | string) => {
    const h = fields.get(id);
    if (!h) return;
    h.setBase(value);
    const text = h.text();
    fields.set(id, { ...h, defaultText: () => text });
  };
  const sampleInput = (samplePreset?.input ?? {}) as { count?: number; tests?: Record<string, Record<string, unknown>> };
  if (sampleInput.count) adopt('br-count', String(sampleInput.count));
  for (const [i, t] of Object.entries(sampleInput.tests ?? {})) {
    for (const [path, v] of leaves(t)) adopt(fieldId('br', `tests.${i}.${path}`), v as number | string);
  }

  // ---- outputs
  const verdict = verdictBox({
    prefix: 'br',
    tolerance: {
      label: 'Tolerance on the bar’s length change (range per test)',
      value: 0.02,
      hint: 'The largest range (largest − smallest) of the bar’s length over one test that you accept: how far the tool strays from the table as the rotary axis turns.',
    },
    onTolerance: () => judgeNow(),
  });
  const alert = el('p', { class: 'alert', id: 'br-alert', role: 'alert' });
  alert.hidden = true;
  const summary = el('dl', { class: 'summary', id: 'br-summary', 'aria-live': 'polite' });
  const summaryBox = el('div', { class: 'ident-summary' });
  summaryBox.append(summary);
  const corrections = el('div', { class: 'ident', id: 'br-corrections', 'aria-live': 'polite' });
  const useButton = el('button', { type: 'button', id: 'br-use-errors', class: 'primary', disabled: '' }, 'Use these errors');
  useButton.title = 'Puts the errors these traces found into the Machine section, so that the volumetric map, the cubic test and the toolpath run on the machine as measured.';
  const useMsg = el('p', { class: 'field-hint', id: 'br-use-msg', 'aria-live': 'polite' });
  const useRow = el('div', { class: 'file-row use-row' });
  useRow.append(useButton);
  const tracePlots = el('div', { class: 'plots', id: 'br-trace-plots' });
  const ident = el('div', { class: 'ident', id: 'br-ident', 'aria-live': 'polite' });
  const simulated = el('div', { class: 'ident', id: 'br-simulated', 'aria-live': 'polite' });
  const simPlot = plotBox('br-sim-plot', 'wide');
  const simPlots = el('div', { class: 'plots' });
  simPlots.append(simPlot.wrap);
  results.append(
    verdict.root, alert, summaryBox,
    el('h3', {}, 'The numbers to enter'), corrections, useRow, useMsg,
    el('h3', {}, 'The traces, measured and fitted'), tracePlots,
    el('h3', {}, 'What the traces identify'), ident,
    el('h3', {}, 'What the machine above would show (simulated)'), simulated, simPlots,
  );
  const tracePlotBoxes = Array.from({ length: MAX_TESTS }, (_, i) => plotBox(`br-trace-${i}`, 'wide'));

  const identSet = study.groups.get('Identification') ?? form;
  const source = fileSource(form, {
    prefix: 'br',
    field: 'br-csv',
    sample: { url: SAMPLE, button: 'Load the sample traces', note: SAMPLE_NOTE },
    expected: 'ball-bar traces (CSV or text)',
    refused: (message) => measurement.refuse('the file chosen', message),
  });
  identSet.querySelector('legend')?.after(source.root);
  const sampleText = await sampleAsDefault('br-csv', SAMPLE);

  verdict.details('What the bar measures, and what the fit does',
    el('p', {}, 'At each angle θ of the moving axis the control puts the linear axes where the ideal machine keeps the spindle’s ball at t = p + L·b̂ from the table ball p (L the bar’s length, b̂ its direction: radial, tangential or axial to the moving axis). ' +
      'On the real machine the balls sit elsewhere; the bar records its length change ΔL = |tool ball − table ball| − L, exactly, through the machine’s kinematic chain.'),
    el('pre', { class: 'formula' },
      'ΔL(θ) ≈ b̂ · Σ_ε J_ε(θ)·ε  +  o(test, direction)\n' +
      '  J_ε: how error ε moves the tool ball relative to the table (the chain’s Jacobian)\n' +
      '  o:   the bar’s own length and the balls’ set-up, one per test and direction'),
    el('p', { class: 'field-hint' }, 'The errors ε and the offsets o are fitted by least squares (the project’s one identification: rank, groups, Holm’s decisions, 95 % intervals). ' +
      'A turn about the axis’s own line, or a shift along it, moves the ball square to a radial bar and is not seen; an error that changes the length alike at every angle acts as the bar’s length and is fitted with it. The derivations: crate/src/ballbar/rotary/mod.rs.'),
  );
  const sourceName = (csv: string) => source.name() ?? (sampleText && csv === sampleText ? `the sample ${SAMPLE.split('/').pop()} (synthetic)` : 'the text in the field');

  // Every field by the path the engine names (`tests[1].ball.x`, `csv`).
  const byPath: Record<string, ShowsError> = { ...study.byPath };
  cards.forEach((c, i) => {
    for (const [p, h] of Object.entries(c.form.byPath)) byPath[`tests[${i}].${p}`] = h;
  });
  const engineError = engineErrors(byPath, machine);
  const runSim = channel('ballbarRotarySimulate');
  const runIdentify = channel('ballbarRotaryIdentify');

  let lastSim: BallbarRotarySimulation | null = null;

  const count = () => Number(fields.get('br-count')?.text() ?? '1') || 1;
  const showCards = () => cards.forEach((c, i) => {
    c.root.hidden = i >= count();
    c.root.style.display = i >= count() ? 'none' : '';
  });

  /** The inputs of each export, or null when a field is invalid (its message shown). */
  const read = () => {
    const ctx = machine.context();
    for (const c of cards) c.form.setContext(ctx);
    study.setContext(ctx);
    const { k, m: mm } = ctx;
    const axisOf = (name: string) => schema.errors.find((d) => d.name === name)?.axis;
    study.setNames(machine.errorOptions().filter((o) => [k, mm].includes(axisOf(o.name) ?? '')));
    showCards();
    const m = machine.current();
    const own = study.read();
    const tests = cards.slice(0, count()).map((c) => c.form.read());
    if (!m || !own || tests.some((t) => t === null)) return null;
    const { parameters, csv, rtol, decision } = own as Record<string, unknown>;
    const common = { machine: m as Machine, tests, parameters };
    return { simulate: common, identify: { ...common, csv: String(csv ?? ''), rtol, decision } };
  };

  const setSummary = (items: [string, string, string][]) => {
    summary.replaceChildren();
    for (const [id, k, v] of items) summary.append(el('dt', {}, k), el('dd', { id }, v));
    summary.hidden = items.length === 0;
    summary.style.display = items.length ? '' : 'none';
  };

  /** Greys every output of the identification, with `why`. */
  const greyIdentification = (why?: string) => {
    for (const box of [corrections, ident]) stale(box, true, why);
    tracePlotBoxes.forEach((b) => b.p.isConnected && stale(b.p, true, why));
    summary.classList.toggle('stale', summary.childElementCount > 0);
  };
  const clearIdentification = () => {
    corrections.replaceChildren(el('p', { class: 'field-hint' }, 'The errors found, the numbers to enter in the control and the button that puts them into the machine above appear here once traces are loaded.'));
    ident.replaceChildren(el('p', { class: 'field-hint' }, 'Choose or drop the traces your ball-bar software exports, paste them, or load the sample traces.'));
    for (const box of [corrections, ident]) stale(box, false);
    for (const b of tracePlotBoxes) void clearPlot(b.p);
    tracePlots.replaceChildren();
    setSummary([]);
    summary.classList.remove('stale');
  };
  const measurement = measured(runIdentify, {
    name: (from: string) => from,
    before: 'the traces before',
    alert, useButton, useMsg,
    grey: greyIdentification,
    clear: clearIdentification,
    show: (r, from) => showIdentification(r, from),
    judge: () => judgeNow(),
    fieldOk: () => study.byPath.csv?.setError(null),
    fieldError: (e) => showAtField(e, byPath, machine),
  });

  // ---- the verdict: on the traces as measured
  const judgeNow = () => {
    const tol = verdict.tolerance();
    if (tol === null) return verdict.invalid();
    const st = measurement.toJudge(verdict, 'No verdict yet: load the measured traces (choose or drop a file, paste it, or load the sample traces). What the tests would show on the machine above is simulated below.');
    if (!st) return;
    const r = st.r;
    const worst = r.tests.reduce((a, t) => (t.range > a.range ? t : a), r.tests[0]);
    const status = judge(worst.range, tol);
    const afterWorst = Math.max(...r.tests.map((t) => t.rangeAfter));
    const n = r.corrections.length;
    const fix = n
      ? ` Entering the ${n === 1 ? 'correction' : `${n} corrections`} below would bring it to ${show('errLength', afterWorst)} at most (predicted by the model; the bar’s length and set-up stay), ${afterWorst <= tol ? 'within' : 'still above'} the tolerance.`
      : status === 'fail' ? ' No location error is found present: the trace is not one the errors identified explain (see the model fit below).' : ' No error found present: nothing to correct.';
    const sentence = `The bar’s length varies by up to ${show('errLength', worst.range)} over a test (test ${worst.name}, ${worst.axis} moving; largest − smallest, both directions): ${status === 'pass' ? 'within' : 'above'} the ${show('errLength', tol)} tolerance.${fix}`;
    const contributors = contributorsOf(r.corrections, r.identification.estimates, words);
    verdict.show({
      status, worst: worst.range, tolerance: tol, sentence, contributors, source: st.from,
      contributorsOf: 'each error found, by its largest effect on the bar, as a share of their sum',
      notes: [
        'Judged: the range of the bar’s length change over each test as measured (its largest minus its smallest value, both directions), before any correction.',
        ...r.tests.map((t) => `Test ${t.name}: ${show('errLength', t.range)} measured, ${show('errLength', t.rangeAfter)} predicted after correction.`),
      ],
    });
  };

  // ---- computing
  const update = () => {
    const i = read();
    if (!i) {
      runSim.cancel();
      verdict.invalid();
      stale(simulated, true);
      stale(simPlot.p, true);
      measurement.invalid();
      return;
    }
    runSim(i.simulate as never).then((r) => {
      if (r === SUPERSEDED) return;
      lastSim = r;
      note(simPlot.p, null);
      showSimulation(r);
    }, (e) => {
      engineError(e, simPlot.p);
      stale(simulated, true, `Showing the last simulation; the engine refused these inputs: ${EngineError.of(e).text}`);
    });
    measurement.identify(i.identify, sourceName(i.identify.csv));
  };

  // ---- drawing
  const D = (mm: number) => toDisplay('errLength', mm);
  const lu = () => unitDef('errLength').label;

  const showIdentification = (r: BallbarRotaryIdentification, from: string) => {
    const points = r.tests.reduce((s, t) => s + t.points, 0);
    setSummary([
      ['br-sum-came', 'Computed from', `${from}: ${r.tests.length} test${r.tests.length === 1 ? '' : 's'}, ${points} points${r.ignored.length ? `; columns not used: ${r.ignored.join(', ')}` : ''}`],
      ...r.tests.map((t, i): [string, string, string] => [`br-sum-test-${i}`, `Test ${t.name} (${t.axis} moving)`,
        `${show('errLength', t.range)} range measured, ${show('errLength', t.before)} rms about its mean; after correction (predicted) ${show('errLength', t.rangeAfter)} range, ${show('errLength', t.after)} rms`]),
      ['br-sum-fit', 'Model fit', r.identification.goodness.words],
    ]);
    summary.classList.remove('stale');

    if (r.corrections.length) {
      corrections.replaceChildren(
        el('p', {}, 'The location errors these traces find present (Holm’s decisions below), in the machine’s frame with every axis at zero:'),
        ...correctionsView('br', r.corrections, words),
      );
    } else {
      corrections.replaceChildren(el('p', { id: 'br-no-corrections' }, `No location error is found present in ${from}: nothing to enter.`));
    }
    stale(corrections, false);

    const visibility = el('ul', { id: 'br-visibility' });
    for (const u of r.visibility.invisible) visibility.append(el('li', {}, `${u.name} cannot be seen by these tests: ${u.why}`));
    for (const g of r.visibility.inseparable) visibility.append(el('li', {}, g.why));
    visibility.append(el('li', { id: 'br-together' }, r.together.words));
    ident.replaceChildren(
      ...identificationView('br', r.identification, `From ${from}.`, paramName),
      el('h4', {}, 'What these tests cannot see or tell apart'), visibility,
    );
    stale(ident, false);

    // One plot per test: the measured trace each way and the fitted model.
    tracePlots.replaceChildren(...r.tests.map((_, i) => tracePlotBoxes[i].wrap));
    r.tests.forEach((t, i) => {
      const box = tracePlotBoxes[i];
      const angle = Array.from(t.angle);
      const run = Array.from(t.run);
      const data: Data[] = [];
      for (const [d, name, colour, fitColour] of [[1, 'CCW', COLOURS.ccw, COLOURS.fitCcw], [-1, 'CW', COLOURS.cw, COLOURS.fitCw]] as const) {
        const idx = run.flatMap((v, j) => (v === d ? [j] : []));
        if (!idx.length) continue;
        data.push(
          { x: idx.map((j) => angle[j]), y: idx.map((j) => D(t.measured[j])), type: 'scatter', mode: 'markers', name: `${name} measured`, marker: { color: colour, size: 4 } } as Data,
          { x: idx.map((j) => angle[j]), y: idx.map((j) => D(t.fitted[j])), type: 'scatter', mode: 'lines', name: `${name} fitted`, line: { color: fitColour, width: 2 } } as Data,
        );
      }
      stale(box.p, false);
      void draw(box.p, `Test ${t.name}: the bar’s length change as ${t.axis} turns,<br>measured and fitted (errors found and the bar’s offsets)`, data, {
        xaxis: axis(`${t.axis} command (°)`),
        yaxis: axis(titled('length change', 'errLength')),
        legend: { orientation: 'h', x: 0, y: -0.25, yanchor: 'top' },
        margin: { b: 90 },
      } as Partial<Layout>, `ballbar-rotary-${t.name}`);
    });
  };

  const showSimulation = (s: BallbarRotarySimulation) => {
    const list = el('ul', { id: 'br-sim-summary' });
    for (const line of s.summary) list.append(el('li', {}, line));
    const dl = el('button', { type: 'button', id: 'br-sim-csv' }, 'Download the simulated traces (CSV)');
    dl.addEventListener('click', () => download('ballbar-rotary-simulated.csv', s.csv, 'text/csv'));
    const row = el('div', { class: 'file-row' });
    row.append(dl);
    const identifiable = s.visibility.identifiable;
    simulated.replaceChildren(
      el('p', { class: 'field-hint' }, `From the errors in the Machine section, through the exact kinematic chain: what a bar set up as the tests above would record (the axes where commanded; no servo lag or backlash). ${identifiable.length ? `The tests together identify on their own: ${listWords(identifiable)}.` : 'The tests together identify no error on its own.'}`),
      list, row,
    );
    stale(simulated, false);
    const data: Data[] = s.tests.map((t, i) => {
      const idx = Array.from(t.run).flatMap((v, j) => (v > 0 ? [j] : []));
      return { x: idx.map((j) => t.angle[j]), y: idx.map((j) => (t.spread < 1e-9 ? 0 : D(t.deviation[j]))), type: 'scatter', mode: 'lines', name: `test ${t.name} (${t.axis})`, line: { color: TEST_COLOURS[i % TEST_COLOURS.length], width: 1.6 } } as Data;
    });
    stale(simPlot.p, false);
    // A machine without errors: the traces are the chain's rounding (picometres), drawn flat on a
    // micrometre scale rather than magnified into noise.
    const flat = s.tests.every((t) => t.spread < 1e-9);
    void draw(simPlot.p, `Simulated on the machine above: the bar’s length change<br>as the moving axis turns (${lu()}; the same both ways)`, data, {
      xaxis: axis('moving axis command (°)'),
      yaxis: axis(titled('length change', 'errLength'), flat ? { range: [-D(0.001), D(0.001)] } : {}),
      legend: { orientation: 'h', x: 0, y: -0.25, yanchor: 'top' },
      margin: { b: 90 },
    } as Partial<Layout>, 'ballbar-rotary-simulated');
  };

  // ---- "Use these errors": the identified errors into the one machine model
  useButton.addEventListener('click', () => {
    const st = measurement.state;
    if (st.s !== 'ok') return;
    const r = st.r;
    const own = r.identification.estimates.filter((e) => !e.name.startsWith('offset_'));
    useMsg.textContent = useFound(machine, schema, r.errors as Record<string, number>, own, st.from, 'these tests');
  });

  form.addEventListener('input', (e) => {
    if ((e.target as HTMLElement).id === 'br-file') return;
    update();
  });
  machine.onChange(update);
  onUnitsChange(() => {
    if (lastSim) showSimulation(lastSim);
    const shown = measurement.shown;
    if (shown && measurement.state.s === 'ok') showIdentification(shown.r, shown.from);
    judgeNow();
  });
  measurement.clear();
  update();
}
