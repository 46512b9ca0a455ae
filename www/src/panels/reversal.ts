// The "Rotary-axis reversal" panel: Nishiguchi, Hasegawa, Sato & Shirase (2017) on the machine of
// the Machine section. C reciprocates 0° → 90° → 0° while X and Y keep the tool on a circle in
// table coordinates; the simulated ball-bar trace with and without C's friction (eq 2), the axes
// against time, the dent for Table 1's feeds and radii, and friction fitted from a measured trace.
// With a measured trace loaded the verdict is on the trace: the engine's depth and width of its
// dent (`reversalTrace`, measured from the trace itself), and the fitted friction in a drive's
// terms; a trace file that names its machine (`# machine: <preset>`) is checked against the
// machine above, with an offer to switch to it.
import type { Data, Layout } from 'plotly.js';
import type { DentRow, FrictionFit, Machine, MeasuredTrace, ReversalSimulation } from '@engine';
import { channel, EngineError, SUPERSEDED } from '../engine/client';
import type { MachinePreset, MachineSection } from '../machine/section';
import { el, fields } from '../ui/fields';
import { encodingNote, readOrRefuse } from '../ui/files';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, perDivision, stale } from '../ui/plot';
import { presetPicker } from '../ui/presets';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { engineErrors, panelShell, type Panel } from './panel';
import { extent } from '../ui/arrays';
import { judge, verdictBox } from '../ui/verdict';

export const reversalPanel: Panel = {
  id: 'reversal',
  prefix: 'rv',
  title: 'Rotary-axis reversal',
  exports: ['reversalSimulate', 'reversalFit'],
  mount,
};

const SAMPLE = 'samples/reversal-measured.csv';

/** What the reversal test sees of a machine: its layout and the axes' directions (travel
 *  limits, heights and lengths do not change the circle the test draws with B or A at 0). */
const LAYOUT = ['kind', 'type', 'linear', 'rotary.kReversed', 'rotary.mReversed'];

/** The layout keys in which `m` differs from `preset`'s machine (schema defaults for keys the
 *  preset leaves out: false for the directions). */
function layoutDifferences(preset: MachinePreset, m: Machine | null): string[] {
  if (!m) return [];
  const at = (o: unknown, path: string) => path.split('.').reduce<unknown>((v, k) => (v && typeof v === 'object' ? (v as Record<string, unknown>)[k] : undefined), o);
  return LAYOUT.filter((k) => (at(preset.machine, k) ?? false) !== (at(m, k) ?? false));
}

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Rotary-axis reversal: the C table’s direction change on a ball bar',
    'C turns from 0° to 90° and back while X and Y keep the tool on a circle fixed to the table, so X and Y do not ' +
      'reverse when C does: what happens at 180° of the trace is C’s own reversal, copied onto the circle in proportion ' +
      'to the distance r of the circle’s centre from C’s axis. Every axis is a servo drive (position loop, velocity loop, ' +
      'inertia); C has the friction of eq 2, which dents the trace just after the reversal. A measured trace gives back ' +
      'the friction a compensator needs. Nishiguchi, Hasegawa, Sato & Shirase (2017), Sections 3–5, on any machine with a C table.',
  );

  // ---- inputs
  form.append(presetPicker('reversal', 'rv', machine));
  const inputs = renderFields(reversalPanel.exports.flatMap((n) => schema.exports[n]), 'rv', form, machine.context());
  const sampleButton = el('button', { type: 'button', id: 'rv-load-sample' }, 'Load the sample trace');
  const fileLabel = el('label', { class: 'import', for: 'rv-file' }, 'Choose a file ');
  const file = el('input', { id: 'rv-file', type: 'file', accept: '.csv,text/csv,text/plain' });
  fileLabel.append(file);
  const fileMsg = el('p', { class: 'field-hint', id: 'rv-file-msg', 'aria-live': 'polite' });
  const buttons = el('div', { class: 'file-row' });
  buttons.append(sampleButton, fileLabel);
  inputs.groups.get('Fit')?.querySelector('legend')?.after(buttons, fileMsg);
  const csvArea = form.querySelector<HTMLTextAreaElement>('#rv-csv');
  if (csvArea) csvArea.placeholder = 'angle_deg,deviation_um\n0.1,-4.9\n…';

  // ---- outputs
  const verdict = verdictBox({
    prefix: 'rv',
    tolerance: { label: 'Tolerance on the dent', value: 0.01, hint: 'The deepest dent you accept in the circle just after C reverses (what a ball bar shows as a spike).' },
    onTolerance: () => judgeSim(),
  });
  const summary = el('dl', { class: 'summary', id: 'rv-summary', 'aria-live': 'polite' });
  /** The machine a loaded trace names, against the machine above (with a switch button). */
  const traceMachine = el('div', { class: 'trace-machine', id: 'rv-trace-machine', 'aria-live': 'polite' });
  traceMachine.hidden = true;
  const plot = (id: string, wide = false, tall = false) => {
    const wrap = el('div', { class: wide ? 'plot-wrap wide' : 'plot-wrap' });
    const p = el('div', { class: 'plot', id });
    if (tall) p.style.height = '560px';
    wrap.append(p);
    return { wrap, p };
  };
  const polar = plot('rv-polar', false, true);
  const radial = plot('rv-radial');
  const timePlot = plot('rv-time', true, true);
  const linearPlot = plot('rv-linear', true);
  const dentsBox = el('div', { class: 'ident', id: 'rv-dents', 'aria-live': 'polite' });
  const fitBox = el('div', { class: 'ident', id: 'rv-fit', 'aria-live': 'polite' });
  const fitPlot = plot('rv-fit-plot', true);
  const residualPlot = plot('rv-residuals', true);
  const plots = el('div', { class: 'plots' });
  plots.append(polar.wrap, radial.wrap, timePlot.wrap, linearPlot.wrap);
  const fitPlots = el('div', { class: 'plots' });
  fitPlots.append(fitPlot.wrap, residualPlot.wrap);
  results.append(
    verdict.root, traceMachine, summary, plots,
    el('h3', {}, 'The dent for Table 1’s feeds and radii'), dentsBox,
    el('h3', {}, 'Friction from a measured trace'), fitBox, fitPlots,
  );

  const summaryItems = new Map<string, [string, string]>();
  const setSummary = (id: string, label: string, value: string) => {
    summaryItems.set(id, [label, value]);
    summary.replaceChildren();
    for (const [key, [k, v]] of summaryItems) summary.append(el('dt', {}, k), el('dd', { id: key }, v));
  };

  const runSim = channel('reversalSimulate');
  const runDents = channel('reversalDents');
  const runFit = channel('reversalFit');
  const runTrace = channel('reversalTrace');
  const engineError = engineErrors(inputs.byPath, machine);
  let last: ReversalSimulation | null = null;
  let lastCase = '';

  const read = () => {
    inputs.setContext(machine.context());
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) return null;
    const { csv, ...rest } = own as Record<string, unknown>;
    return { machine: m as Machine, rest, csv: (csv as string) ?? '' };
  };

  /** What the result came from, in words. */
  const conditions = (i: NonNullable<ReturnType<typeof read>>) => {
    const t = (i.rest.test ?? {}) as Record<string, number>;
    const ff = String(i.rest.feedForward ?? 'none');
    const c = (i.rest.c ?? {}) as Record<string, number>;
    return `${machine.context()?.k ?? 'C'} table on ${String(i.machine.type ?? 'CBZ')}: R ${fmt.num(t.radius ?? 50)} mm, r ${fmt.num(t.offset ?? 25)} mm, F ${fmt.num(t.feed ?? 1000)} mm/min, ` +
      `friction ${fmt.num(c.friction ?? 10)} N·m (slope ${fmt.num(c.frictionSlope ?? 500)} 1/rad), feed-forward ${ff}`;
  };

  /** Whether `last` answers the inputs as they are (a verdict may be drawn from it). */
  let fresh = false;
  /** The last fit of a measured trace, while it answers the inputs. */
  let lastFit: FrictionFit | null = null;
  /** The fit: none (no trace), on its way, done, or refused (its message). */
  let fitState: { s: 'none' } | { s: 'pending' } | { s: 'ok' } | { s: 'error'; message: string } = { s: 'none' };
  /** The measured trace: none loaded, being read, read (its dent), or refused (its message). */
  let traceState: { s: 'none' } | { s: 'pending' } | { s: 'ok'; r: MeasuredTrace } | { s: 'error'; message: string } = { s: 'none' };
  /** Where the trace came from, for the verdict ("reversal-measured.csv", "the pasted trace"). */
  let traceName = 'the trace in the field';
  /** The machine preset a trace names and how the machine above differs from it. */
  let traceOn: { name: string; preset: MachinePreset | null; differs: string[] } | null = null;

  /** The fitted friction in a drive's terms, for the verdict's notes. */
  const frictionNotes = (k: string): string[] => {
    if (fitState.s === 'pending') return [`Fitting ${k}’s friction to the trace… (a few dozen simulations)`];
    if (fitState.s === 'error') return [`${k}’s friction could not be fitted: ${fitState.message}`];
    if (!lastFit) return [];
    const f = lastFit;
    return [
      `Fitted friction of ${k} (eq 2): f_c = ${fmt.num(f.friction.value, 4)} N·m (95 % interval ${fmt.num(f.friction.low, 4)} to ${fmt.num(f.friction.high, 4)}), ` +
        `${fmt.percent(f.frictionShare, 4)} of the drive’s rated torque (${fmt.num(f.ratedTorque, 6)} N·m).`,
      `A friction compensator on ${k} needs a torque step of 2·f_c = ${fmt.num(f.torqueStep.value, 4)} N·m at each reversal ` +
        `(${fmt.percent(f.torqueStepShare, 4)} of the rated torque), built up over the first ${fmt.num(f.halfway, 3)}° of travel (half way).`,
    ];
  };

  /** The verdict on the loaded trace: the dent the engine measured from it, and the fit. */
  const judgeTrace = (tol: number) => {
    const k = machine.context()?.k ?? 'C';
    const t = show('errLength', tol);
    const ts = traceState;
    if (ts.s === 'pending' || ts.s === 'none') return verdict.pending();
    if (ts.s === 'error') {
      return verdict.none(`No verdict on the measured trace: it could not be read (${ts.message}). Fix the file or clear the field to judge the simulation.`);
    }
    const d = ts.r.dent;
    const mismatch = traceOn && traceOn.differs.length
      ? [`This trace was made on “${traceOn.name}” (its file says so), not on the machine above: switch to that machine (the button under this verdict) to fit it where it was made.`]
      : [];
    const how = `Measured from the trace itself (${ts.r.points} points): depth = how far it falls below its level before the reversal ` +
      `(the median over 170°–179° of trace angle) within 180°–190°; width = where it lies at least half that deep.`;
    const notes = [...mismatch, ...frictionNotes(k), how];
    if (!(d.depth > 0)) {
      return verdict.show({ status: 'pass', worst: 0, tolerance: tol, notes, sentence: `On the measured trace (${traceName}): it does not fall below its level before ${k}’s reversal, no dent (within the ${t} tolerance).` });
    }
    const status = judge(d.depth, tol);
    const width = d.open
      ? `and stays down to 190° and beyond: a step of ${show('errLength', d.step)} (its level after the reversal) rather than a dent, at least ${fmt.num(d.width, 3)}° wide at half depth`
      : `${fmt.num(d.width, 3)}° wide at half depth (${fmt.num(ts.r.duration * 1e3, 3)} ms at the feed entered)`;
    const advice = status === 'pass' ? '.'
      : d.open
        ? `: ${k}’s following error changes side when it reverses; velocity feed-forward on ${k}, or a smaller offset r, would reduce the step.`
        : `: friction compensation on ${k} (the torque step below) would reduce it.`;
    verdict.show({
      status, worst: d.depth, tolerance: tol, notes,
      sentence: `On the measured trace (${traceName}): after ${k}’s reversal the trace falls ${show('errLength', d.depth)} below its level before it ` +
        `(deepest at ${fmt.num(d.angle, 4)}°), ${width}; ${status === 'pass' ? 'within' : 'above'} the ${t} tolerance${advice}`,
    });
  };

  /** The verdict: on the loaded trace when there is one, else on the simulation (and it says so). */
  const judgeSim = () => {
    const tol = verdict.tolerance();
    if (tol === null) return verdict.invalid();
    if (traceState.s !== 'none') return judgeTrace(tol);
    if (!last || !fresh) return;
    const d = last.dent;
    const t = show('errLength', tol);
    const k = machine.context()?.k ?? 'C';
    const notes = ['No measured trace is loaded: this is the simulation of the inputs entered. Load a ball-bar trace of your machine (below) to judge it and fit its friction.'];
    if (!(d.depth > 0)) {
      return verdict.show({ status: 'pass', worst: 0, tolerance: tol, notes, sentence: `Simulated: no friction dent at ${k}’s reversal (within the ${t} tolerance).` });
    }
    const status = judge(d.depth, tol);
    verdict.show({
      status, worst: d.depth, tolerance: tol, notes,
      sentence: `Simulated (no measured trace loaded): the friction dent at ${k}’s reversal is ${show('errLength', d.depth)} deep (at ${fmt.num(d.angle, 4)}° of the trace, ${fmt.num(d.width, 3)}° wide), ${status === 'pass' ? 'within' : 'above'} the ${t} tolerance` +
        (status === 'fail' ? ': friction compensation on the C axis, or a smaller circle offset from the C axis, would reduce it.' : '.'),
    });
  };

  /** Which machine the loaded trace names, against the machine above; offers to switch. */
  const showTraceMachine = async (r: MeasuredTrace | null) => {
    traceOn = null;
    traceMachine.replaceChildren();
    traceMachine.hidden = true;
    if (!r || !r.machine) return;
    const name = r.machine;
    const presets = await machine.presets().catch(() => [] as MachinePreset[]);
    const preset = presets.find((p) => p.name === name) ?? null;
    const differs = preset ? layoutDifferences(preset, machine.current()) : [];
    traceOn = { name, preset, differs };
    traceMachine.hidden = false;
    traceMachine.classList.toggle('mismatch', differs.length > 0 || !preset);
    if (!preset) {
      traceMachine.append(el('p', {}, `The trace names its machine: “${name}”, not a machine preset of this page. The fit only holds on that machine: check the machine above.`));
    } else if (differs.length) {
      const button = el('button', { type: 'button', id: 'rv-switch-machine' }, `Switch to ${name}`);
      button.addEventListener('click', () => machine.apply(preset.machine));
      traceMachine.append(
        el('p', {}, `This trace was made on “${name}” (its file says so). The machine above is another one (its ${differs.join(', ')} differ${differs.length === 1 ? 's' : ''}): the fit below runs on the machine above, not on the one the trace was made on.`),
        button,
      );
    } else {
      traceMachine.append(el('p', {}, `This trace was made on “${name}”, the layout of the machine above.`));
    }
  };

  const update = () => {
    const i = read();
    if (!i) {
      fresh = false;
      lastFit = null;
      fitState = { s: 'none' };
      traceState = { s: 'none' };
      verdict.invalid();
      for (const p of [polar, radial, timePlot, linearPlot, fitPlot, residualPlot]) stale(p.p, true);
      stale(dentsBox, true);
      stale(fitBox, true);
      for (const run of [runSim, runDents, runFit, runTrace]) run.cancel();
      return;
    }
    const input = { machine: i.machine, ...i.rest };
    const came = conditions(i);
    fresh = false;
    verdict.pending();
    runSim({ ...input, checkStep: true } as never).then((r) => {
      if (r === SUPERSEDED) return;
      last = r;
      lastCase = came;
      fresh = true;
      showSim(r, came);
      judgeSim();
    }, (e) => {
      for (const p of [radial, timePlot, linearPlot]) stale(p.p, true);
      engineError(e, polar.p);
      verdict.refused(e);
    });
    runDents(input as never).then((rows) => {
      if (rows === SUPERSEDED) return;
      showDents(rows, came);
    }, (e) => {
      dentsBox.replaceChildren(el('p', { class: 'warn' }, `No table: ${String((e as Error).message)}`));
      stale(dentsBox, true);
    });
    fit(i, input, came);
  };

  const fit = (i: NonNullable<ReturnType<typeof read>>, input: Record<string, unknown>, came: string) => {
    lastFit = null;
    if (i.csv.trim() === '') {
      fitState = { s: 'none' };
      traceState = { s: 'none' };
      runTrace.cancel();
      void showTraceMachine(null);
      inputs.byPath.csv?.setError(null);
      fitBox.replaceChildren(el('p', { class: 'field-hint' }, 'Paste a measured trace (trace angle, radial deviation), choose a file, or load the sample trace (simulated with f_c = 12 N·m, a = 800 1/rad, C gain 28 1/s and 0.3 µm of noise) to fit C’s friction.'));
      stale(fitBox, false);
      return;
    }
    fitBox.replaceChildren(el('p', { class: 'field-hint' }, 'Fitting… (a few dozen simulations)'));
    traceState = { s: 'pending' };
    fitState = { s: 'pending' };
    // The trace's own dent and the machine it names first (no simulation), then the fit.
    runTrace({ ...input, csv: i.csv } as never).then(async (r) => {
      if (r === SUPERSEDED) return;
      traceState = { s: 'ok', r };
      await showTraceMachine(r);
      judgeSim();
    }, (e) => {
      traceState = { s: 'error', message: EngineError.of(e).text };
      void showTraceMachine(null);
      judgeSim();
    });
    runFit({ ...input, csv: i.csv } as never).then((f) => {
      if (f === SUPERSEDED) return;
      inputs.byPath.csv?.setError(null);
      lastFit = f;
      fitState = { s: 'ok' };
      showFit(f, came);
      judgeSim();
    }, (e) => {
      let err = EngineError.of(e);
      // A trace made on another machine cannot be fitted on this one: say so with the reason.
      if (traceOn && traceOn.differs.length && err.field === 'csv') {
        err = new EngineError(`${err.message} This trace was made on “${traceOn.name}” (its file says so), not on the machine above: switch to that machine, or load a trace made on this one.`);
      }
      fitState = { s: 'error', message: err.text };
      fitBox.replaceChildren(el('p', { class: 'warn', id: 'rv-fit-error' }, traceOn && traceOn.differs.length
        ? `No fit: the trace was made on “${traceOn.name}”, another machine (see the message at the field).`
        : 'No fit: see the message at the field or above the plot.'));
      stale(fitBox, false);
      engineError(err, fitPlot.p);
      stale(residualPlot.p, true);
      judgeSim();
    });
  };

  const D = (mm: number) => toDisplay('errLength', mm);
  const lu = () => unitDef('errLength').label;

  const showSim = (r: ReversalSimulation, came: string) => {
    note(polar.p, null);
    const theta = Array.from(r.theta);
    const dev = Array.from(r.deviation);
    const dry = Array.from(r.withoutFriction);
    const [dLo, dHi] = extent(dev);
    const [yLo, yHi] = extent(dry);
    const span = Math.max(-dLo, dHi, -yLo, yHi);
    const div = perDivision(span);
    const base = 4; // the nominal circle at 4 divisions
    const rp = (d: number[]) => d.map((v) => base + v / div);
    const hover = (what: string) => `${what}<br>θ %{theta:.2f}°<br>%{customdata:.4g} ${lu()}<extra></extra>`;
    draw(polar.p, `Ball-bar trace, deviation magnified:<br>${show('errLength', div, 2)} per division`, [
      { type: 'scatterpolar', r: theta.map(() => base), theta, customdata: theta.map(() => 0), mode: 'lines', name: 'nominal circle', line: { color: '#8c959f', dash: 'dot', width: 1 }, hoverinfo: 'skip' } as Data,
      { type: 'scatterpolar', r: rp(dry), theta, mode: 'lines', name: 'without friction', customdata: dry.map(D), line: { color: '#1f77b4', width: 1.5 }, hovertemplate: hover('without friction') } as Data,
      { type: 'scatterpolar', r: rp(dev), theta, mode: 'lines', name: 'with friction (eq 2)', customdata: dev.map(D), line: { color: '#d62728', width: 1.5 }, hovertemplate: hover('with friction') } as Data,
    ], {
      polar: {
        // Room between the circle and the title for the angle label at 90° (it sat under the title).
        domain: { x: [0, 1], y: [0, 0.92] },
        radialaxis: { range: [0, base + 3], dtick: 1, showticklabels: false, ticks: '', gridcolor: '#e6e8eb' },
        angularaxis: { direction: 'counterclockwise', rotation: 0, dtick: 30, ticksuffix: '°' },
      },
      legend: { orientation: 'h', x: 0, y: -0.08, yanchor: 'top' },
      margin: { l: 30, r: 30, b: 70 },
      meta: { csvX: 'trace angle θ (°)', csvY: titled('radial deviation', 'errLength') },
    } as Partial<Layout>, 'reversal-polar');

    const i0 = theta.findIndex((t) => t > 150);
    const i1 = theta.findIndex((t) => t > 230);
    const cut = <T,>(a: T[]) => a.slice(i0 < 0 ? 0 : i0, i1 < 0 ? undefined : i1);
    draw(radial.p, `Radial deviation near C’s reversal (180°)<br>dent ${show('errLength', r.dent.depth, 3)} at ${fmt.num(r.dent.angle, 4)}°, ${fmt.num(r.dent.width, 3)}° wide`, [
      { x: cut(theta), y: cut(dry).map(D), type: 'scatter', mode: 'lines', name: 'without friction', line: { color: '#1f77b4' } },
      { x: cut(theta), y: cut(dev).map(D), type: 'scatter', mode: 'lines', name: 'with friction', line: { color: '#d62728' } },
    ], {
      xaxis: axis('trace angle θ (°)'),
      yaxis: axis(titled('radial deviation', 'errLength')),
      legend: { orientation: 'h', x: 0, y: -0.25, yanchor: 'top' },
      shapes: [{ type: 'line', xref: 'x', yref: 'paper', x0: 180, x1: 180, y0: 0, y1: 1, line: { color: '#8c959f', width: 1, dash: 'dot' } }],
    } as Partial<Layout>, 'reversal-radial');

    const t = Array.from(r.time);
    const line = (y: Float64Array, name: string, yaxis: string, color: string, scale = 1, dash = 'solid'): Data =>
      ({ x: t, y: Array.from(y, (v) => v * scale), type: 'scatter', mode: 'lines', name, yaxis, line: { color, width: 1.3, dash } }) as Data;
    const asec = 3600;
    draw(timePlot.p, 'C against time: angle (command dotted),<br>velocity, following error, friction (eq 2)', [
      line(r.cCommand, 'C command (°)', 'y', '#8c959f', 1, 'dot'),
      line(r.cActual, 'C actual (°)', 'y', '#1f77b4'),
      line(r.cVelocity, 'C velocity (°/s)', 'y2', '#2ca02c'),
      line(r.cError, 'C following error (″)', 'y3', '#9467bd', asec),
      line(r.cFriction, 'friction torque (N·m)', 'y4', '#d62728'),
    ], {
      xaxis: axis('time (s)', { anchor: 'y4' }),
      yaxis: axis('C (°)', { domain: [0.78, 1] }),
      yaxis2: axis('velocity (°/s)', { domain: [0.53, 0.75] }),
      yaxis3: axis('error (″)', { domain: [0.28, 0.5] }),
      yaxis4: axis('friction (N·m)', { domain: [0, 0.25] }),
      showlegend: false,
      shapes: [{ type: 'line', xref: 'x', yref: 'paper', x0: r.reversalTime, x1: r.reversalTime, y0: 0, y1: 1, line: { color: '#8c959f', width: 1, dash: 'dot' } }],
    } as Partial<Layout>, 'reversal-time');

    const moving = r.linear.filter((l) => Array.from(l.velocity).some((v) => Math.abs(v) > 1e-9));
    const colors = ['#1f77b4', '#ff7f0e', '#2ca02c'];
    draw(linearPlot.p, 'Linear axes’ velocities: no reversal<br>when C reverses (dotted line)', moving.map((l, k) => ({
      x: t, y: Array.from(l.velocity, (v) => v * 60), type: 'scatter', mode: 'lines', name: `${l.name} (mm/min)`, line: { color: colors[k % 3], width: 1.3 },
    }) as Data), {
      xaxis: axis('time (s)'),
      yaxis: axis('velocity (mm/min)'),
      legend: { orientation: 'h', x: 0, y: -0.25, yanchor: 'top' },
      shapes: [
        { type: 'line', xref: 'x', yref: 'paper', x0: r.reversalTime, x1: r.reversalTime, y0: 0, y1: 1, line: { color: '#8c959f', width: 1, dash: 'dot' } },
        { type: 'line', xref: 'paper', yref: 'y', x0: 0, x1: 1, y0: 0, y1: 0, line: { color: '#444', width: 0.8 } },
      ],
    } as Partial<Layout>, 'reversal-linear');

    const mean = (a: number[], from: number, to: number) => {
      const v = a.filter((_, k) => theta[k] > from && theta[k] < to);
      return v.reduce((s, x) => s + x, 0) / Math.max(1, v.length);
    };
    setSummary('rv-sum-came', 'Computed for', came);
    setSummary('rv-sum-dent', 'Friction dent (simulated)', r.dent.depth > 0
      ? `${show('errLength', r.dent.depth)} deep at ${fmt.num(r.dent.angle, 4)}° (C reverses at 180°), ${fmt.num(r.dent.width, 3)}° wide at half depth`
      : 'none');
    setSummary('rv-sum-radius', 'Radius change (servo lag)', `${show('errLength', mean(dry, 30, 150))} before the reversal, ${show('errLength', mean(dry, 210, 330))} after (without friction)`);
    const dirs = r.directions.filter((d) => d.name !== 'Z' || Math.abs(d.before) > 1e-9);
    setSummary('rv-sum-directions', 'X and Y at C’s reversal (±5°)', dirs.map((d) => `${d.name} ${d.reverses || d.actualReverses ? 'REVERSES' : d.stops ? 'stops, keeps its direction' : 'keeps its direction'} (${fmt.num(d.before * 60, 4)} → ${fmt.num(d.after * 60, 4)} mm/min)`).join('; '));
    if (r.stepCheck) setSummary('rv-sum-step', 'Integration step', `${fmt.num(r.stepCheck.step, 3)} ms: halving it changes the trace by ${show('errLength', r.stepCheck.difference, 2)} (${fmt.percent(r.stepCheck.relative, 2)} of the largest deviation)`);
  };

  const showDents = (rows: DentRow[], came: string) => {
    const table = el('table', { class: 'ident-table', id: 'rv-dents-table' });
    const head = el('tr');
    for (const h of ['F (mm/min)', 'r (mm)', `depth (${lu()})`, 'at (°)', 'width (°)']) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'), el('tbody'));
    table.tHead!.append(head);
    for (const row of rows) {
      const tr = el('tr');
      tr.append(el('td', {}, fmt.num(row.feed)), el('td', {}, fmt.num(row.offset)), el('td', {}, fmt.num(D(row.dent.depth), 4)), el('td', {}, fmt.num(row.dent.angle, 4)), el('td', {}, fmt.num(row.dent.width, 3)));
      table.tBodies[0].append(tr);
    }
    dentsBox.replaceChildren(
      el('p', {}, `The other inputs as entered (${came.replace(/, F [^,]+, /, ', ').replace(/r [^,]+, /, '')}). The dent lasts as long as C’s loop needs to take up the friction’s turn: its depth hardly depends on the feed, its width in trace angle grows with it; both scale with r.`),
      table,
    );
    stale(dentsBox, false);
  };

  const showFit = (f: FrictionFit, came: string) => {
    note(fitPlot.p, null);
    const table = el('table', { class: 'ident-table', id: 'rv-fit-table' });
    const head = el('tr');
    for (const h of ['parameter', 'fitted', '95 % interval']) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'), el('tbody'));
    table.tHead!.append(head);
    const row = (name: string, key: string, e: { value: number; low: number; high: number }, unit: string, digits = 4) => {
      const tr = el('tr');
      tr.dataset.name = key;
      tr.append(el('th', { scope: 'row' }, name), el('td', {}, `${fmt.num(e.value, digits)} ${unit}`), el('td', {}, `${fmt.num(e.low, 4)} to ${fmt.num(e.high, 4)} ${unit}`));
      table.tBodies[0].append(tr);
    };
    row('Coulomb friction f_c', 'friction', f.friction, 'N·m');
    row('friction slope a', 'frictionSlope', f.frictionSlope, '1/rad');
    row('C position-loop gain', 'positionGain', f.positionGain, '1/s');
    row(`radius offset (${lu()})`, 'offset', { value: D(f.offset.value), low: D(f.offset.low), high: D(f.offset.high) }, '');
    fitBox.replaceChildren(
      el('p', { id: 'rv-compensator' }, `For a friction compensator: a torque step of 2·f_c = ${fmt.num(f.torqueStep.value, 4)} N·m at each reversal of C ` +
        `(${fmt.percent(f.torqueStepShare, 4)} of the rated torque ${fmt.num(f.ratedTorque, 6)} N·m; 95 % interval ${fmt.num(f.torqueStep.low, 4)} to ${fmt.num(f.torqueStep.high, 4)} N·m), ` +
        `built up over the first ${fmt.num(f.halfway, 3)}° of travel (half way; eq 2 with a = ${fmt.num(f.frictionSlope.value, 4)} 1/rad), C’s position-loop gain ${fmt.num(f.positionGain.value, 4)} 1/s. ` +
        `The friction itself, f_c = ${fmt.num(f.friction.value, 4)} N·m, is ${fmt.percent(f.frictionShare, 4)} of the rated torque.`),
      table,
      el('p', {}, `Residuals: ${show('errLength', f.sigma, 2)} standard deviation, ${f.iterations} iterations. Fitted with ${came}.`),
    );
    if (traceOn && traceOn.differs.length) {
      fitBox.prepend(el('p', { class: 'warn', id: 'rv-fit-machine' }, `Fitted on the machine above, but the trace was made on “${traceOn.name}” (its file says so): switch to that machine to fit it where it was made.`));
    }
    stale(fitBox, false);
    const x = Array.from(f.angle);
    draw(fitPlot.p, 'Measured and fitted trace<br>around the reversal', [
      { x, y: Array.from(f.measured, D), type: 'scatter', mode: 'markers', name: 'measured', marker: { size: 3, color: '#1f77b4' } },
      { x, y: Array.from(f.fitted, D), type: 'scatter', mode: 'lines', name: 'fitted model', line: { color: '#d62728' } },
    ], { xaxis: axis('trace angle θ (°)', { range: [160, 220] }), yaxis: axis(titled('radial deviation', 'errLength')), legend: { orientation: 'h', x: 0, y: -0.25, yanchor: 'top' } } as Partial<Layout>, 'reversal-fit');
    draw(residualPlot.p, `Residuals (measured − fitted)<br>standard deviation ${show('errLength', f.sigma, 2)}`, [
      { x, y: Array.from(f.residuals, D), type: 'scatter', mode: 'markers', name: 'residual', marker: { size: 3, color: '#6e7781' } },
    ], { xaxis: axis('trace angle θ (°)'), yaxis: axis(titled('residual', 'errLength')), showlegend: false }, 'reversal-residuals');
  };

  // ---- measured traces
  sampleButton.addEventListener('click', async () => {
    try {
      const res = await fetch(SAMPLE);
      if (!res.ok) throw new Error(`${res.status} ${res.statusText}`);
      traceName = 'the sample trace';
      fields.get('rv-csv')?.setText(await res.text());
      fileMsg.textContent = 'Loaded the sample trace (simulated on the B/C tilting table preset with the default inputs but f_c = 12 N·m, a = 800 1/rad, C gain 28 1/s; 0.3 µm noise).';
    } catch (e) {
      fileMsg.textContent = `Could not load the sample trace: ${String(e)}`;
    }
  });
  file.addEventListener('change', async () => {
    const f = file.files?.[0];
    if (!f) return;
    if (f.size > 5_000_000) {
      fileMsg.textContent = `${f.name} is larger than 5 MB: not a trace file.`;
      return;
    }
    file.value = '';
    const read = await readOrRefuse(f, (message) => {
      // The fit shown is of another trace: greyed, and no longer in the verdict.
      fileMsg.textContent = message;
      runFit.cancel();
      lastFit = null;
      if (fresh) judgeSim();
      for (const p of [fitPlot, residualPlot]) stale(p.p, true, `${message} Greyed: the fit of the trace before it.`);
      stale(fitBox, true, message);
    });
    if (!read) return;
    traceName = f.name;
    fields.get('rv-csv')?.setText(read.text);
    fileMsg.textContent = `Loaded ${f.name}${encodingNote(read)}.`;
  });

  form.addEventListener('input', (e) => {
    const id = (e.target as HTMLElement).id;
    // Typed or pasted into the field: no longer the file loaded.
    if (id === 'rv-csv' && e.isTrusted) traceName = 'the trace in the field';
    if (id !== 'rv-file') update();
  });
  machine.onChange(update);
  onUnitsChange(() => {
    if (last) showSim(last, lastCase);
    update();
  });
  update();
}
