// The "Ball-bar" panel: a circular test of two linear axes (ISO 230-4) from a measured trace, as
// a service engineer brings it back from the machine. The engine (`ballbarEvaluate`) gives the
// circular deviation G (each way and both), the hysteresis H about the centre it states, and the
// faults fitted by least squares on their models with 95 % intervals (centre offset, scale
// mismatch, squareness, servo mismatch, backlash per axis, harmonics, reversal spikes). The
// panel judges G against the tolerance entered, tabulates the faults and draws the trace on a
// polar plot at a stated µm per division with the fitted model, and names the file, radius and
// feed the result came from. "Use the squareness in the machine" puts the squareness into the
// Machine section as the plane's ISO 230-1 location error the engine proposes (E_C0Y, E_A0Z or
// E_B0Z, its sign from the kinematic chain) and says what it entered and what it did not.
// Nothing is computed here: every number is the engine's.
import type { Data, Layout } from 'plotly.js';
import type { Ballbar, Fitted, Machine } from '@engine';
import { channel, SUPERSEDED } from '../engine/client';
import type { MachineSection } from '../machine/section';
import { el } from '../ui/fields';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, perDivision, plotBox, stale } from '../ui/plot';
import * as fmt from '../ui/format';
import { fileSource, sampleAsDefault } from '../ui/source';
import { onUnitsChange, show, titled, toDisplay, unitDef } from '../ui/units';
import { verdictBox } from '../ui/verdict';
import { engineErrors, panelShell, type Panel } from './panel';

export const ballbarPanel: Panel = {
  id: 'ballbar',
  prefix: 'bb',
  title: 'Ball-bar (ISO 230-4)',
  exports: ['ballbarEvaluate'],
  mount,
};

const SAMPLE = 'samples/ballbar-xy.csv';
const SAMPLE_NOTE = 'synthetic, made by scripts/make-ballbar-sample.mjs from 8 µm of backlash on X, 30 µm/m of squareness, 20 ppm of scale mismatch, a 4 µm / −3 µm set-up offset and 0.5 µm of noise (its header says so).';

/** The plane's axes in words (the engine names them u and v). */
const UV = 'u and v are the plane’s first and second axes, the angle measured from +u towards +v: X and Y for a test in the XY plane (G17), Z and X in ZX (G18), Y and Z in YZ (G19).';
/** The same for the plane of a result. */
const uvOf = (r: Ballbar) => `u is ${r.axes[0]} and v is ${r.axes[1]} (the ${r.plane} plane), the angle from +${r.axes[0]} towards +${r.axes[1]}.`;

/** One row of the faults' table: its name, the engine's value and what the value is. */
interface Row {
  key: string;
  name: string;
  title: string;
  fitted: Fitted;
  /** 'len': mm (shown in the small-length unit); otherwise the unit's text. */
  unit: 'len' | string;
  /** A set-up quantity (where the ball-bar was put), not a fault of the machine. */
  setup?: boolean;
}

const COLOURS = { ccw: '#1f77b4', cw: '#d62728', fitCcw: '#0b3d6b', fitCw: '#7f1416', nominal: '#8c959f' };

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Ball-bar: circular test of two axes (ISO 230-4)',
    'A ball-bar measures how far the tool strays from a circle while two axes interpolate it, counter-clockwise and clockwise. ' +
      'From its trace: the circular deviation G and the hysteresis H as ISO 230-4 defines them, and the faults that distort the circle, ' +
      'each fitted by least squares on a model of the fault with its 95 % interval: centre offset, scale mismatch between the axes (ppm), ' +
      'out-of-squareness (µm/m), servo mismatch (ms), backlash of each axis, cyclic error (harmonics 3 to 6) and the reversal spikes. ' +
      'The panel opens on a synthetic sample trace: choose or drop the trace your ball-bar software exports (angle and radial deviation, both directions), or paste it.',
  );

  // ---- inputs (the engine's fields; the tolerance of G goes beside the verdict)
  const inputs = renderFields(ballbarPanel.exports.flatMap((n) => schema.exports[n]), 'bb', form);
  const csvArea = form.querySelector<HTMLTextAreaElement>('#bb-csv');
  if (csvArea) csvArea.placeholder = '# radius: 100 mm\n# feed: 1000 mm/min\nangle (deg), ccw (µm), cw (µm)\n0.5, 10.2, 0.9\n…';
  const group = inputs.groups.get('Circular test (ISO 230-4)') ?? form;
  const tolerance = inputs.field('tolerance');
  if (!tolerance) throw new Error('ballbarEvaluate has no tolerance field');

  // ---- outputs
  const verdict = verdictBox({ prefix: 'bb', tolerance: { adopt: tolerance }, onTolerance: () => update() });
  const summary = el('dl', { class: 'summary', id: 'bb-summary', 'aria-live': 'polite' });
  const polar = plotBox('bb-polar', 'wide', 'tall');
  const trace = plotBox('bb-trace', 'wide');
  const plots = el('div', { class: 'plots' });
  plots.append(polar.wrap, trace.wrap);
  const faults = el('div', { class: 'ident', id: 'bb-faults', 'aria-live': 'polite' });
  const harmonics = el('div', { class: 'ident', id: 'bb-harmonics' });
  const spikes = el('div', { class: 'ident', id: 'bb-spikes' });
  results.append(
    verdict.root, summary, plots,
    el('h3', {}, 'Faults fitted from the trace'), faults,
    el('h3', {}, 'Cyclic error: harmonics 3 to 6'), harmonics,
    el('h3', {}, 'Reversal spikes'), spikes,
  );
  const tables = [faults, harmonics, spikes];

  // ---- into the machine: the squareness as the plane's location error
  const machineBox = el('div', { class: 'motion-use', id: 'bb-machine' });
  const useButton = el('button', { type: 'button', id: 'bb-use-squareness', disabled: '' }, 'Use the squareness in the machine');
  const machineMsg = el('p', { class: 'field-hint', id: 'bb-machine-msg', 'aria-live': 'polite' });
  const notSent = el('details', { id: 'bb-not-sent' });
  machineBox.append(useButton, machineMsg, notSent);
  summary.after(machineBox);

  const source = fileSource(form, {
    prefix: 'bb',
    field: 'bb-csv',
    sample: { url: SAMPLE, button: 'Load the sample trace', note: SAMPLE_NOTE },
    expected: 'a ball-bar trace (CSV or text)',
    refused: (message) => {
      // The result shown is of the trace before: greyed, with the reason; no verdict on it.
      run.cancel();
      fresh = false;
      useButton.disabled = true;
      for (const p of [polar, trace]) stale(p.p, true, `${message} Greyed: the result of the trace before it.`);
      for (const t of [...tables, machineBox]) stale(t, true, message);
      verdict.none(`No verdict: ${message}`);
    },
  });
  group.querySelector('legend')?.after(source.root);
  // The panel opens on the sample (the field's default): a result to look at before a trace of
  // one's own, which says that it is the sample.
  const sampleText = await sampleAsDefault('bb-csv', SAMPLE);
  const sourceName = (csv: string) => source.name() ?? (sampleText && csv === sampleText ? `the sample ${SAMPLE.split('/').pop()} (synthetic)` : 'the text in the field');

  verdict.details('ISO 230-4: what G and H are, and the fault models',
    el('p', {}, 'Circular deviation G: the radial distance between the two circles about the centre stated that just enclose the trace (CCW, CW, or both together). ' +
      'Circular hysteresis H: the largest radial difference between the CCW and the CW trace at the same angle. The centre is the least-squares circle of both traces (its offset and mean radius are set-up, not machine errors).'),
    el('pre', { class: 'formula' },
      'Δr(θ, d) = r₀ + e_u·cos θ + e_v·sin θ            (set-up: radius, centre)\n' +
      '         + R·(ε_u − ε_v)/2 · cos 2θ               (scale mismatch)\n' +
      '         + R·α/2 · sin 2θ                         (out-of-squareness)\n' +
      '         + R·ω·τ/2 · d·sin 2θ                     (servo mismatch, ω = F/R)\n' +
      '         + b_u/2 · d·cos θ·sgn(sin θ) − b_v/2 · d·sin θ·sgn(cos θ)   (backlash)\n' +
      '         + Σ_k (a_k cos kθ + b_k sin kθ), k = 3…6   (cyclic error)'),
    el('p', { class: 'field-hint' }, `d = +1 counter-clockwise, −1 clockwise. ${UV} Spikes: h·exp(−φ/w) fitted to what the model leaves over the 20° after each reversal of an axis. The derivations: crate/src/ballbar/mod.rs.`),
  );

  const run = channel('ballbarEvaluate');
  const engineError = engineErrors(inputs.byPath, machine);
  let last: { r: Ballbar; came: string } | null = null;
  /** Whether `last` answers the inputs as they are. */
  let fresh = false;

  const greyAll = (why?: string) => {
    useButton.disabled = true;
    for (const p of [polar, trace]) stale(p.p, true, why);
    for (const t of [...tables, machineBox]) stale(t, true, why);
  };

  /** What the result came from, in words. */
  const cameFrom = (r: Ballbar, own: Record<string, unknown>) => {
    const ccw = r.direction.filter((d) => d > 0).length;
    const cw = r.direction.length - ccw;
    const radius = `radius ${fmt.num(r.radius)} mm (${Number(own.radius ?? 0) > 0 ? 'entered' : 'from the file'})`;
    const feed = r.feed === null ? 'no feed given (no servo mismatch)' : `feed ${fmt.num(r.feed)} mm/min (${Number(own.feed ?? 0) > 0 ? 'entered' : 'from the file'})`;
    const points = cw ? `${ccw} points CCW and ${cw} CW` : `${ccw} points, one direction only (no H, squareness and servo mismatch not separable)`;
    return `${sourceName(String(own.csv ?? ''))}: ${radius}, ${feed}, ${points}`;
  };

  const update = () => {
    // (The tolerance of G is one of the engine's fields, moved beside the verdict.)
    const own = inputs.read();
    if (!own) {
      run.cancel();
      fresh = false;
      verdict.invalid();
      greyAll();
      return;
    }
    const csv = String(own.csv ?? '');
    if (csv.trim() === '') {
      run.cancel();
      fresh = false;
      inputs.byPath.csv?.setError(null);
      verdict.none('No verdict yet: no trace. Choose or drop the file your ball-bar software exports, paste it into the field, or load the sample trace.');
      if (last) greyAll('No trace in the field: this is the result of the trace before.');
      else for (const t of tables) t.replaceChildren(el('p', { class: 'field-hint' }, 'The faults appear here once a trace is loaded.'));
      return;
    }
    fresh = false;
    useButton.disabled = true;
    verdict.pending();
    run(own as never).then((r) => {
      if (r === SUPERSEDED) return;
      inputs.byPath.csv?.setError(null);
      last = { r, came: cameFrom(r, own) };
      fresh = true;
      showResult();
    }, (e) => {
      fresh = false;
      useButton.disabled = true;
      engineError(e, polar.p);
      stale(trace.p, true);
      for (const t of [...tables, machineBox]) stale(t, true, 'Showing the result of the trace before: this one was refused (see the message at the field).');
      verdict.refused(e);
    });
  };

  const L = (mm: number) => toDisplay('errLength', mm);
  const lu = () => unitDef('errLength').label;

  /** "8.02 µm ± 0.22 µm", or "—" with the reason. */
  const valueText = (row: Row): [string, string] => {
    const f = row.fitted;
    if (f.value === null || f.halfWidth === null) return ['—', row.key === 'servoMismatch' && last?.r.feed === null ? 'needs the feed' : 'not separable with one direction'];
    const unit = row.unit === 'len' ? lu() : row.unit;
    const v = row.unit === 'len' ? L(f.value) : f.value;
    const h = row.unit === 'len' ? L(f.halfWidth) : f.halfWidth;
    return [`${fmt.num(v, 4)} ${unit}`, `± ${fmt.num(h, 2)} ${unit}`];
  };
  /** Clearly there: its 95 % interval does not hold 0. */
  const clear = (f: Fitted) => f.value !== null && f.halfWidth !== null && Math.abs(f.value) > f.halfWidth;

  const rowsOf = (r: Ballbar): Row[] => {
    const d = r.diagnostics;
    const [u, v] = r.axes;
    return [
      { key: 'backlashU', name: `Backlash of ${u} (u)`, title: `Lost motion of ${u}, the plane’s first axis: it stops half of it short in its direction of travel (steps at 0° and 180°).`, fitted: d.backlashU, unit: 'len' },
      { key: 'backlashV', name: `Backlash of ${v} (v)`, title: `Lost motion of ${v}, the plane’s second axis (steps at 90° and 270°).`, fitted: d.backlashV, unit: 'len' },
      { key: 'squareness', name: 'Out-of-squareness', title: `${v} leans towards +${u} by this angle: positive when the axes are closer than 90° (an oval along the 45° diagonal, the same both ways).`, fitted: d.squareness, unit: 'µm/m' },
      { key: 'scaleMismatch', name: `Scale mismatch ${u} − ${v}`, title: `${u} reads longer than ${v} by this much (an oval along ${u} or ${v}).`, fitted: d.scaleMismatch, unit: 'ppm' },
      { key: 'servoMismatch', name: 'Servo mismatch', title: `${u} lags ${v} by this time: an oval along a diagonal, opposite ways CCW and CW (needs the feed).`, fitted: d.servoMismatch, unit: 'ms' },
      { key: 'centreU', name: `Centre offset along ${u}`, title: `Where the circle’s centre is from the ball-bar’s pivot, along ${u}: the set-up, removed before G.`, fitted: d.centreU, unit: 'len', setup: true },
      { key: 'centreV', name: `Centre offset along ${v}`, title: `The same along ${v}.`, fitted: d.centreV, unit: 'len', setup: true },
      { key: 'radius', name: 'Mean radius error', title: 'The mean of the trace: the bar’s calibration or a common scale error; removed before G.', fitted: d.radius, unit: 'len', setup: true },
    ];
  };

  const judgeNow = () => {
    if (!last || !fresh) return;
    const { r, came } = last;
    const significant = rowsOf(r).filter((row) => !row.setup && clear(row.fitted)).map((row) => `${row.name[0].toLowerCase()}${row.name.slice(1)} ${valueText(row)[0]}`);
    const faultsLine = significant.length
      ? `Faults the trace shows clearly (95 % interval clear of 0): ${significant.join(', ')}.`
      : 'No fault of the model stands out of the noise (every 95 % interval holds 0).';
    const parts = `G CCW ${show('errLength', r.gCcw)}, G CW ${show('errLength', r.gCw)}, H ${r.h === null ? '— (one direction)' : show('errLength', r.h)}; centre: ${r.centre}.`;
    const notes = [parts, faultsLine, uvOf(r)];
    if (!(r.tolerance > 0) || r.pass === null) {
      return verdict.none(`G = ${show('errLength', r.g)} (${came}). No tolerance of G entered, so no verdict: enter the largest circular deviation you accept beside this line.`);
    }
    const status = r.pass ? 'pass' : 'fail';
    const advice = status === 'pass' ? '.' : significant.length
      ? `: the faults below say where it comes from (${significant.slice(0, 2).join(', ')}); compensate or correct them and test again.`
      : ': no single fault of the model explains it; look at the trace for spikes and waviness.';
    verdict.show({
      status, worst: r.g, tolerance: r.tolerance, notes, source: came,
      sentence: `Circular deviation G = ${show('errLength', r.g)} over both directions, ${status === 'pass' ? 'within' : 'above'} the ${show('errLength', r.tolerance)} tolerance${advice}`,
    });
  };

  const showResult = () => {
    if (!last) return;
    const { r, came } = last;
    note(polar.p, null);
    // ---- key numbers
    summary.replaceChildren();
    const item = (id: string, k: string, v: string, title?: string) => summary.append(el('dt', title ? { title } : {}, k), el('dd', { id }, v));
    item('bb-sum-came', 'Computed from', came);
    item('bb-sum-centre', 'Centre used', r.centre);
    item('bb-sum-g', 'Circular deviation G (both)', show('errLength', r.g), 'ISO 230-4: the radial distance between the two concentric circles enclosing both traces.');
    item('bb-sum-gccw', 'G counter-clockwise', show('errLength', r.gCcw));
    item('bb-sum-gcw', 'G clockwise', show('errLength', r.gCw));
    item('bb-sum-h', 'Circular hysteresis H', r.h === null ? '— (one direction only)' : show('errLength', r.h), 'ISO 230-4: the largest radial difference between the CCW and CW traces at the same angle.');
    item('bb-sum-rms', 'What the model leaves (rms)', show('errLength', r.diagnostics.residualRms));

    // ---- the faults
    const table = el('table', { class: 'ident-table', id: 'bb-faults-table' });
    table.append(el('caption', { class: 'field-hint' }, `Each fitted by least squares on its model (details under the verdict); 95 % interval as ± half-width. ${uvOf(r)}`));
    const head = el('tr');
    for (const h of ['fault', 'value', '95 % interval']) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'), el('tbody'));
    table.tHead!.append(head);
    for (const row of rowsOf(r)) {
      const tr = el('tr');
      tr.dataset.name = row.key;
      const [v, h] = valueText(row);
      tr.dataset.value = row.fitted.value === null ? '' : String(row.fitted.value);
      tr.dataset.halfWidth = row.fitted.halfWidth === null ? '' : String(row.fitted.halfWidth);
      if (clear(row.fitted) && !row.setup) tr.classList.add('clear');
      tr.append(el('th', { scope: 'row', title: row.title }, row.setup ? `${row.name} (set-up)` : row.name), el('td', {}, v), el('td', {}, h));
      table.tBodies[0].append(tr);
    }
    const wrapTable = (t: HTMLElement) => {
      const w = el('div', { class: 'table-scroll' });
      w.append(t);
      return w;
    };
    faults.replaceChildren(wrapTable(table));

    const ht = el('table', { class: 'ident-table', id: 'bb-harmonics-table' });
    const hh = el('tr');
    for (const h of ['waves per turn k', `amplitude (${lu()})`, 'peaks at θ']) hh.append(el('th', { scope: 'col' }, h));
    ht.append(el('thead'), el('tbody'));
    ht.tHead!.append(hh);
    for (const h of r.diagnostics.harmonics) {
      const tr = el('tr');
      tr.dataset.order = String(h.order);
      tr.append(el('th', { scope: 'row' }, String(h.order)), el('td', {}, fmt.num(L(h.amplitude), 3)), el('td', {}, `${fmt.num(h.phase / h.order, 3)}° (and every ${fmt.num(360 / h.order, 3)}°)`));
      ht.tBodies[0].append(tr);
    }
    harmonics.replaceChildren(el('p', { class: 'field-hint' }, 'Waviness the axes’ screws or encoders leave: largest first.'), wrapTable(ht));

    const st = el('table', { class: 'ident-table plain', id: 'bb-spikes-table' });
    const sh = el('tr');
    for (const h of ['axis', 'at', 'way', `height (${lu()})`, 'width (°)']) sh.append(el('th', { scope: 'col' }, h));
    st.append(el('thead'), el('tbody'));
    st.tHead!.append(sh);
    for (const s of r.diagnostics.spikes) {
      const tr = el('tr');
      tr.append(el('th', { scope: 'row' }, s.axis), el('td', {}, `${fmt.num(s.at)}°`), el('td', {}, s.direction.toUpperCase()), el('td', {}, fmt.num(L(s.height), 3)), el('td', {}, fmt.num(s.width, 3)));
      st.tBodies[0].append(tr);
    }
    spikes.replaceChildren(
      el('p', { class: 'field-hint' }, `At each reversal of an axis, each way: the height h and width w of h·exp(−φ/w) fitted to what the model leaves over the next 20°. A spike stands out when its height is well above the rms the model leaves (${show('errLength', r.diagnostics.residualRms, 2)}); a width at the 10° limit is no spike.`),
      wrapTable(st),
    );
    for (const t of tables) stale(t, false);
    showMachine(r);

    // ---- the plots
    const theta = Array.from(r.angle);
    const dir = Array.from(r.direction);
    const dev = Array.from(r.deviation);
    const fit = Array.from(r.fitted);
    const pick = (a: number[], d: number) => a.filter((_, i) => dir[i] === d);
    let span = 0;
    for (const v of [...dev, ...fit]) span = Math.max(span, Math.abs(v));
    const div = perDivision(span);
    const base = 4; // the nominal circle at 4 divisions
    const rp = (a: number[]) => a.map((v) => base + v / div);
    const hover = (what: string) => `${what}<br>θ %{theta:.1f}°<br>%{customdata:.4g} ${lu()}<extra></extra>`;
    const circle = Array.from({ length: 361 }, (_, k) => k);
    const series: Data[] = [
      { type: 'scatterpolar', r: circle.map(() => base), theta: circle, customdata: circle.map(() => 0), mode: 'lines', name: 'nominal circle', line: { color: COLOURS.nominal, dash: 'dot', width: 1 }, hoverinfo: 'skip' } as Data,
    ];
    for (const [d, name, colour, fitColour] of [[1, 'CCW', COLOURS.ccw, COLOURS.fitCcw], [-1, 'CW', COLOURS.cw, COLOURS.fitCw]] as const) {
      const th = pick(theta, d);
      if (!th.length) continue;
      const m = pick(dev, d);
      const f = pick(fit, d);
      series.push(
        { type: 'scatterpolar', r: rp(m), theta: th, customdata: m.map(L), mode: 'lines', name: `${name} measured`, line: { color: colour, width: 1.4 }, hovertemplate: hover(`${name} measured`) } as Data,
        { type: 'scatterpolar', r: rp(f), theta: th, customdata: f.map(L), mode: 'lines', name: `${name} fitted faults`, line: { color: fitColour, width: 1.2, dash: 'dash' }, hovertemplate: hover(`${name} fitted`) } as Data,
      );
    }
    void draw(polar.p, `Ball-bar trace, deviation magnified:<br>${show('errLength', div, 2)} per division; G ${show('errLength', r.g, 3)}`, series, {
      polar: {
        domain: { x: [0, 1], y: [0, 0.92] },
        radialaxis: { range: [0, base + 3], dtick: 1, showticklabels: false, ticks: '', gridcolor: '#e6e8eb' },
        angularaxis: { direction: 'counterclockwise', rotation: 0, dtick: 30, ticksuffix: '°' },
      },
      // Under the angle labels (270° sits below the circle).
      legend: { orientation: 'h', x: 0, y: -0.11, yanchor: 'top' },
      margin: { l: 30, r: 30, b: 110 },
      meta: { csvX: 'angle θ from +u (°)', csvY: titled('radial deviation', 'errLength') },
    } as Partial<Layout>, 'ballbar-polar');

    const lines: Data[] = [];
    for (const [d, name, colour, fitColour] of [[1, 'CCW', COLOURS.ccw, COLOURS.fitCcw], [-1, 'CW', COLOURS.cw, COLOURS.fitCw]] as const) {
      const th = pick(theta, d);
      if (!th.length) continue;
      lines.push(
        { x: th, y: pick(dev, d).map(L), type: 'scatter', mode: 'lines', name: `${name} measured`, line: { color: colour, width: 1.2 } } as Data,
        { x: th, y: pick(fit, d).map(L), type: 'scatter', mode: 'lines', name: `${name} fitted`, line: { color: fitColour, width: 1.2, dash: 'dash' } } as Data,
      );
    }
    void draw(trace.p, 'Radial deviation against angle,<br>measured and fitted (about the centre used)', lines, {
      xaxis: axis('angle θ from +u (°)', { dtick: 90, range: [0, 360] }),
      yaxis: axis(titled('radial deviation', 'errLength')),
      legend: { orientation: 'h', x: 0, y: -0.25, yanchor: 'top' },
      margin: { b: 90 },
    } as Partial<Layout>, 'ballbar-trace');
    judgeNow();
  };

  // ---- the squareness into the machine
  const A = (deg: number) => show('errAngle', deg, 4);
  /** What the proposed error is, from the result's errors (one entry, or none). */
  const proposal = (r: Ballbar): [string, number] | null => {
    const e = Object.entries(r.errors).filter((x): x is [string, number] => typeof x[1] === 'number');
    return e.length ? e[0] : null;
  };
  const showMachine = (r: Ballbar) => {
    const p = proposal(r);
    useButton.disabled = !p || !fresh;
    useButton.textContent = p ? `Use the squareness in the machine (${p[0]} = ${A(p[1])})` : 'Use the squareness in the machine';
    const list = el('ul', { class: 'field-hint' });
    list.append(...r.notSent.map((line) => el('li', {}, line)));
    notSent.replaceChildren(el('summary', {}, p ? 'What the machine is not given, and why' : 'Nothing to give the machine: why'), list);
    stale(machineBox, false);
  };
  /** The error entered last: its message goes once the machine no longer holds it. */
  let entered: { name: string; value: number } | null = null;
  machine.onChange(() => {
    if (!entered) return;
    const now = machine.current()?.errors?.[entered.name];
    if (now === undefined || Math.abs(now - entered.value) > 1e-12) {
      entered = null;
      machineMsg.textContent = '';
    }
  });
  useButton.addEventListener('click', () => {
    if (!last || !fresh) return;
    const { r, came } = last;
    const p = proposal(r);
    if (!p) return;
    const [name, value] = p;
    const cur: Machine | null = machine.current();
    if (!cur) {
      machineMsg.textContent = 'The machine has a field that is not valid (see the Machine section): correct it first, then enter the squareness.';
      return;
    }
    const before = cur.errors?.[name] ?? 0;
    // Only this error is set: the machine's other values and errors stay as they are.
    machine.apply({ errors: { [name]: value } }, false);
    entered = { name, value };
    const sq = r.diagnostics.squareness;
    const [u, v] = r.axes;
    const crossTable = name === 'E_C0Y' && cur.linear === 'table-xy';
    machineMsg.textContent = `Entered ${name} = ${A(value)} into the machine (it held ${A(before)}): ${r.errorsMeaning ?? ''}. ` +
      `From the squareness ${fmt.num(sq.value ?? 0, 4)} ± ${fmt.num(sq.halfWidth ?? 0, 2)} µm/m of ${came}. ` +
      (crossTable
        ? `But on this machine Y carries X (a cross table): ${name} turns X with Y, so the model cannot hold the squareness between them and the volumetric map does not change.`
        : `The volumetric map and every study that uses the machine's errors now include it (the ${u}–${v} squareness of the machine, replacing what was there).`);
  });

  form.addEventListener('input', (e) => {
    if ((e.target as HTMLElement).id === 'bb-file') return;
    update();
  });
  onUnitsChange(() => {
    if (last && fresh) showResult();
  });
  update();
}
