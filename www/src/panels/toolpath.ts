// The "Toolpath" panel: the customer's five-axis program read as the machine reads it (its
// dialect, unit, frames, rapids and arcs; see fiveaxis::toolpath::read), followed on the machine
// of the Machine section and on the other eleven rotary-axis types of its kind, ranked by
// nonlinear error on the cutting moves (Geng, Wu & Qiu 2018, Section 5), the rapids listed
// apart, and the path refined to a tolerance.
import type { Data } from 'plotly.js';
import type { Machine, ParsedToolpath, Report, RotaryType, ToolpathAnalysis, ToolpathPath, ToolpathRefined, ToolpathSummary } from '@engine';
import { call, channel, EngineError, SUPERSEDED } from '../engine/client';
import { debounced } from '../engine/idle';
import { deltaSeries, MOST_IN_3D, pathPoints } from '../toolpath/decimate';
import { engineTypes, rankTypes, readToolpath, type ReadFile } from '../toolpath/pool';
import type { MachineSection } from '../machine/section';
import { download } from '../ui/export';
import { el, selectField } from '../ui/fields';
import { checkFile, FileRefused, WINDOWS_1252_NOTE } from '../ui/files';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, drawnOrWaiting, note, stale } from '../ui/plot';
import { blockedBy, invalidFields } from '../ui/status';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay } from '../ui/units';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';
import { judge, unseenOf, verdictBox } from '../ui/verdict';

/** A length from the engine (mm) in the unit shown now. */
const D = (mm: number) => toDisplay('errLength', mm);
/** Sample paths shipped in public/samples/ (written by scripts/samples.mjs). */
const SAMPLES = [
  { value: '', label: 'none: drop or choose a file' },
  { value: 'impeller-swarf.apt', label: 'Impeller, swarf cut over the hub (APT, 751 points)' },
  { value: 'dome-past-the-pole.csv', label: 'Dome, a meridian 0.3° beside the top (CSV, 81 points)' },
];
/** The fields that change how the file is read: a change reads it again. */
const READING = ['tp-format', 'tp-unit', 'tp-aptFrame', 'tp-chordTolerance'];
/** The ranking's columns and what each means (their tooltips). */
const HEADERS: [string, string][] = [
  ['rank', 'Best first: by the largest δ of a cutting segment, then the mean.'],
  ['type', 'The rotary-axis configuration (the two rotary axes and the order in the chain).'],
  ['largest δ', 'The largest nonlinear error of a cutting segment: how far the tool tip leaves the programmed motion between two points.'],
  ['mean δ', 'The mean nonlinear error over the cutting segments.'],
  ['95 % of segments below', 'The 95th percentile of δ: 95 % of the cutting segments have a smaller δ. It can be below the tolerance while a few segments are above it.'],
  ['segments above the tolerance', 'How many cutting segments have δ above the tolerance, of all the cutting segments.'],
  ['flips', 'Cutting segments where the rotary axes swing round (the other solution): the tool stops and turns there.'],
  ['by the pole', 'Cutting segments where the tool axis passes near the pole (the tilt near 0°), where a small change of direction needs a large turn of the other axis.'],
  ['travel K, M', 'How far the two rotary axes (K the one next to the bed, M the other) turn in all along the cutting moves.'],
  ['rapids (apart)', 'Rapid positioning moves: not cutting, not ranked; how many, and how far each rotary axis swings at most in one of them.'],
];
/** True when the cutting moves turn neither rotary axis (a 3-axis or 3+2 program): δ = 0. */
const still = (s: { kTravel: number; mTravel: number }) => s.kTravel < 1e-9 && s.mTravel < 1e-9;
/** Rapids listed one by one, the largest excursions first. */
const RAPIDS_LISTED = 8;

export const toolpathPanel: Panel = {
  id: 'toolpath',
  prefix: 'tp',
  title: 'Toolpath',
  exports: ['toolpathParse', 'toolpathAnalyse'],
  mount,
};

/** A file read: its name and what the engine made of it. */
interface Loaded {
  name: string;
  parsed: ParsedToolpath;
  /** The file (to read it again for another machine or another reading). */
  source: Blob | string;
  /** The machine and the reading options it was read with. */
  key: string;
}

/** "1 234" */
const count = (n: number) => n.toLocaleString('en-GB');
const plural = (n: number, one: string, many = `${one}s`) => `${count(n)} ${n === 1 ? one : many}`;

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Your toolpath on every rotary-axis configuration',
    'Drop the program or CL file you would run (ISO G-code for Fanuc or Haas, Siemens 840D, Heidenhain conversational, ' +
      'APT CL data from NX, CATIA or SolidWorks CAM, or a CSV of x, y, z, i, j, k). It is read as the machine reads it: ' +
      'its dialect, unit and frames, rapids apart from cutting moves, arcs as the control moves along them. The cutting ' +
      'moves are then followed on this machine (with the program\'s own rotary commands) and on the other eleven ' +
      'rotary-axis types of its kind: between two points the control turns the rotary axes linearly, and the tool tip ' +
      'leaves the programmed motion by δ (the nonlinear error). The ranking says which configuration machines the path ' +
      'more accurately; flips are flagged, rapid positioning moves are listed apart. δ is taken at one length L (the ' +
      'tool tip\'s distance from the axis it swings about). Geng, Wu & Qiu, Math. Problems in Engineering 2018, ' +
      'Section 5. The file stays in this browser.',
  );

  // ---- inputs
  const fileSet = el('fieldset');
  fileSet.append(el('legend', {}, 'Toolpath file'));
  const sample = selectField('tp-sample', 'Sample path', SAMPLES, SAMPLES[1].value, 'Written by scripts/samples.mjs; the README explains their ranking. The panel opens with the impeller.');
  const fileLabel = el('label', { for: 'tp-file', class: 'file-label' }, 'Or a file of your own (drop it on this box)');
  const file = el('input', { type: 'file', id: 'tp-file', accept: '.apt,.cls,.cl,.clsf,.aptsource,.csv,.txt,.nc,.ngc,.mpf,.spf,.tap,.iso,.h,.ptp,.eia,.cnc,.min' });
  const fileMsg = el('p', { class: 'file-msg', id: 'tp-file-msg', role: 'status', 'aria-live': 'polite' });
  const progress = el('progress', { id: 'tp-progress', max: '1', value: '0', 'aria-label': 'Part of the file read' });
  progress.hidden = true;
  /** What the reader found: dialect, unit, frames, notes, skipped kinds. */
  const readBox = el('div', { class: 'read-report', id: 'tp-read' });
  fileSet.append(sample.root, fileLabel, file, progress, fileMsg, readBox);
  form.append(fileSet);
  const fieldsOf = toolpathPanel.exports.flatMap((name) => schema.exports[name]);
  const inputs = renderFields(fieldsOf, 'tp', form, machine.context());
  const typeSel = selectField('tp-type', 'Configuration shown in detail', [{ value: 'machine', label: 'this machine' }, ...(await engineTypes()).map((t) => ({ value: t, label: t }))], 'machine',
    'The plots and the refined path are for this configuration; click a row of the ranking to choose it.');
  inputs.groups.get('Toolpath')?.append(typeSel.root);

  // ---- outputs
  const tolField = inputs.field('tolerance');
  if (!tolField) throw new Error('the engine declares no tolerance for the toolpath');
  const verdict = verdictBox({ prefix: 'tp', tolerance: { adopt: tolField }, onTolerance: () => update() });
  const summary = el('dl', { class: 'summary', id: 'tp-summary', 'aria-live': 'polite' });
  const tableWrap = el('div', { class: 'table-wrap', id: 'tp-ranking' });
  const rapidsBox = el('section', { class: 'rapids', id: 'tp-rapids' });
  const plot = (id: string) => {
    const wrap = el('div', { class: 'plot-wrap wide' });
    const p = el('div', { class: 'plot', id });
    wrap.append(p);
    return { wrap, p };
  };
  const along = plot('tp-delta');
  const path3d = plot('tp-path');
  const refineBox = el('div', { class: 'refine', id: 'tp-refine-box' });
  const refineButton = el('button', { type: 'button', id: 'tp-refine' }, 'Insert the points that keep every cutting segment within the tolerance');
  const refineOut = el('p', { id: 'tp-refine-out', 'aria-live': 'polite' });
  const exportButton = el('button', { type: 'button', id: 'tp-export', disabled: '', title: 'The geometry only: X Y Z and the rotary commands (or the tool axes), with rapids as G0. No feeds, tools, spindle or coolant: add them before running it.' }, 'Download the refined path (geometry only, no feeds)');
  refineBox.append(refineButton, refineOut, exportButton);
  const plots = el('div', { class: 'plots' });
  plots.append(along.wrap, path3d.wrap);
  results.append(verdict.root, summary, tableWrap, rapidsBox, refineBox, plots);

  let ranks = 0;
  let details = 0;
  let refines = 0;
  const runAnalyse = channel('toolpathAnalyse');
  const engineError = engineErrors(inputs.byPath, machine);
  let loaded: Loaded | null = null;
  /** The file the user chose last, read or not: the reading fields and the machine read it
   *  again (`key`: the options of its last reading). Results show only while it is `loaded`. */
  let chosen: { name: string; source: Blob | string; key: string } | null = null;
  let refined: { type: string; r: ToolpathRefined; from: Loaded } | null = null;

  const fileText = (text: string, error = false) => {
    fileMsg.textContent = text;
    fileMsg.classList.toggle('error', error);
  };
  /** A sentence: ends with a full stop. */
  const sentence = (t: string) => (/[.!?]$/.test(t.trim()) ? t.trim() : `${t.trim()}.`);
  /** Tooltips of the summary's symbols: the plain meaning and the paper's symbol. */
  const tips: Record<string, string> = {
    'Largest δ': 'δ: the nonlinear error of a cutting segment, the largest distance of the tool tip from the motion programmed between two points of the path, when the control interpolates the rotary axes\' angles in a straight line (Geng, Wu & Qiu 2018, eqs 19–21). Rapid moves do not cut and are not counted.',
    L: 'L: the distance of the tool tip from the axis it swings about (tool length, or the pivot distance).',
    Flips: 'A flip: the rotary axes swing round (the other of the two solutions) between two cutting points, the tool stopping meanwhile.',
  };
  const setSummary = (rows: [string, string][]) => {
    summary.replaceChildren();
    for (const [k, v] of rows) summary.append(el('dt', tips[k] ? { title: tips[k] } : {}, k), el('dd', {}, v));
  };

  /** The reading options now (the machine, format, unit, frame, chord tolerance), or null. */
  const readOptions = () => {
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) return null;
    const options = {
      machine: m as Machine,
      format: own.format as 'auto',
      unit: own.unit as 'auto',
      aptFrame: own.aptFrame as 'apply',
      ...(own.chordTolerance === undefined ? {} : { chordTolerance: own.chordTolerance as number }),
    };
    return { options, key: JSON.stringify(options) };
  };

  /** What the reader found, in the file box: the dialect line, the unit line, frames and notes. */
  const showReport = (name: string, p: ReadFile) => {
    const r: Report = p.report;
    readBox.replaceChildren();
    const tcp = r.tcp ? `, tool-centre-point control: ${r.tcp}` : '';
    readBox.append(el('p', { id: 'tp-read-dialect' }, `${r.dialect}, ${plural(r.blocks, 'block')}${tcp}.`));
    readBox.append(el('p', { id: 'tp-read-unit' }, `Unit: ${r.unitReason}.`));
    const moves = [`${plural(r.feeds, 'feed move')}`, `${plural(r.arcPoints, 'chord')} of arcs`, `${plural(r.rapids, 'rapid')} (not cutting)`];
    readBox.append(el('p', { id: 'tp-read-moves' }, `${count(p.count)} points; the moves between them: ${moves.join(', ')}.`));
    if (r.frameChoice) {
      const f = r.frameChoice;
      const how = f.reading === 'apply' ? 'read in it (origin + R·p)' : 'left as written';
      const line = el('p', { id: 'tp-read-frame', class: 'frame-found' }, `Output frame: ${f.statement} on line ${f.line}: ${f.frame}. The points are ${how}; change it in “APT output frame” below if your machine runs in the other frame.`);
      readBox.append(line);
    }
    if (r.notes.length) {
      const list = el('ul', { id: 'tp-read-notes' });
      // Frames first, then what breaks the path, then the rest.
      const order = ['frame', 'tcp', 'rotary', 'break', 'partial'];
      for (const n of [...r.notes].sort((a, b) => order.indexOf(a.kind) - order.indexOf(b.kind))) {
        list.append(el('li', { class: `note-${n.kind}` }, n.count > 1 ? `${n.text} (${n.count} times)` : n.text));
      }
      readBox.append(list);
    }
    if (r.skipped.length) {
      const d = el('details', { id: 'tp-read-skipped' });
      const total = r.skipped.reduce((s, k) => s + k.count, 0);
      d.append(el('summary', {}, `Skipped, changing no geometry: ${plural(total, 'word or statement', 'words and statements')} of ${plural(r.skipped.length, 'kind')}`));
      const ul = el('ul');
      for (const s of r.skipped) ul.append(el('li', {}, `${s.what}: ${count(s.count)} (first on line ${s.firstLine})`));
      d.append(ul);
      readBox.append(d);
    }
    fileText(`Read ${name}${p.windows1252 ? ` (${WINDOWS_1252_NOTE})` : ''}: ${count(p.count)} points (${p.format.toUpperCase()}, ${count(p.linesRead)} lines).`);
  };

  /** Reads a file in a worker; on a bad line the message names it and the results are greyed
   *  (still saying which file they came from). `get` fetches the file (a sample) or is it. */
  let loads = 0;
  const load = async (name: string, get: () => Promise<Blob | string>) => {
    const mine = ++loads; // taken first: a file chosen while a sample downloads wins
    const ro = readOptions();
    if (!ro) return fileText(`${name}: ${blockedBy(invalidFields(fileMsg), 'an input is missing')} first.`);
    fileText(`Reading ${name}…`);
    // Whatever shows the last file no longer answers: greyed until the new one is computed.
    rankLater.cancel();
    ranks++;
    details++;
    verdict.pending(`Reading ${name}…`);
    if (loaded) greyResults(`Reading ${name}…`);
    try {
      const source = await get();
      if (mine !== loads) return;
      chosen = { name, source, key: ro.key };
      // An image, a PDF, an archive: refused by its first bytes, never read as a program.
      const refused = typeof source === 'string' ? null : await checkFile(source, name);
      if (mine !== loads) return;
      if (refused) throw new FileRefused(refused);
      progress.hidden = false;
      progress.value = 0;
      const parsed = await readToolpath(source, ro.options, (f) => {
        if (mine === loads) progress.value = f;
      });
      if (mine !== loads) return; // a newer file was chosen meanwhile
      progress.hidden = true;
      loaded = { name, parsed, source, key: ro.key };
      showReport(name, parsed);
      update();
    } catch (err) {
      if (mine !== loads) return;
      progress.hidden = true;
      readBox.replaceChildren();
      let said: string;
      if (err instanceof FileRefused) said = err.message;
      else {
        const e = showAtField(err, inputs.byPath, machine);
        said = `${name} could not be read: ${e ? sentence(e.message.replace(/^toolpath: /, '')) : 'See the field marked.'}`;
      }
      fileText(`${said}${loaded ? ` The results below are still those of ${loaded.name}.` : ''}`, true);
      // The reason in the verdict too: on a phone the file box is far below it.
      greyAll(`${said}${loaded ? ` Greyed below: ${loaded.name}.` : ''}`);
    }
  };

  const chosenType = (m: Machine) => (typeSel.select.value === 'machine' ? String(m.type ?? 'CBZ') : typeSel.select.value);
  const greyAll = (why?: string) => {
    if (why) verdict.none(`No verdict: ${why}`);
    else verdict.invalid();
    greyResults(why);
  };
  /** Every result of the file greyed (or, never drawn, a note saying why), the refined path
   *  dropped. */
  const greyResults = (why?: string) => {
    for (const p of [along.p, path3d.p]) {
      // A plot never drawn says why instead of spinning (one whose drawing waits behind its
      // tab is greyed: it is drawn greyed when the tab is opened).
      if (drawnOrWaiting(p)) stale(p, true, why);
      else note(p, why ?? `No plot: ${blockedBy(invalidFields(p), 'an input is missing')}.`);
    }
    tableWrap.classList.add('stale');
    rapidsBox.classList.add('stale');
    dropRefined();
  };
  /** A refined path belongs to the inputs it was made with: any change drops it. */
  const dropRefined = () => {
    refined = null;
    refines++;
    refineOut.textContent = '';
    exportButton.setAttribute('disabled', '');
  };

  /** The inputs of the analyses, or null (messages at the fields). */
  const current = () => {
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own || !loaded || chosen?.source !== loaded.source) return null;
    const base = { machine: m as Machine, tolerance: own.tolerance as number, ...(own.length === undefined ? {} : { length: own.length as number }) };
    return { m, base, t: chosenType(m), loaded };
  };

  /** The ranking of the twelve types (a moment after the last edit: each one copies the path to
   *  every worker). */
  let rankJob: () => void = () => {};
  const rankLater = debounced(() => rankJob(), 150);
  const rerank = () => {
    const mine = ++ranks;
    rankLater.cancel();
    const c = current();
    if (!c) return;
    rankJob = () => {
      const { m, base, t, loaded: l } = c;
      rankTypes(base, l.parsed.path).then((rows) => {
        if (mine === ranks) ranking(rows, String(m.type ?? ''), t, base.tolerance, l.name, l.parsed.lines);
      }, (e) => {
        if (mine !== ranks) return;
        engineError(e, along.p);
        tableWrap.classList.add('stale');
      });
    };
    rankLater();
  };

  /** The detail of the configuration shown: δ along the path, the 3D path, the rapids. */
  const detail = () => {
    const mine = ++details;
    const c = current();
    if (!c) return;
    const { m, base, t, loaded: l } = c;
    for (const tr of tableWrap.querySelectorAll<HTMLElement>('tbody tr')) tr.classList.toggle('shown', tr.dataset.type === t);
    verdict.pending();
    runAnalyse({ ...base, machine: { ...(m as Machine), type: t as Machine['type'] } }, l.parsed.path).then((a) => {
      if (a === SUPERSEDED || mine !== details) return;
      showAnalysis(a, t, l.name, l.parsed);
    }, (e) => {
      if (mine !== details) return;
      engineError(e, along.p);
      const err = EngineError.of(e);
      const why = sentence(err.text);
      for (const p of [along.p, path3d.p]) if (!drawnOrWaiting(p)) note(p, `No plot: ${why}`);
      rapidsBox.classList.add('stale');
      if (err.field) verdict.invalid(why);
      else verdict.error(why);
    });
  };

  const update = () => {
    inputs.setContext(machine.context());
    dropRefined();
    // The file is read for the machine and the reading chosen: another one reads it again.
    const ro = readOptions();
    if (ro && chosen && chosen.key !== ro.key) {
      const { name, source } = chosen;
      void load(name, async () => source);
      return;
    }
    if (!current()) {
      // Whatever is still being computed no longer answers the inputs.
      ranks++;
      details++;
      runAnalyse.cancel();
      // The file chosen last could not be read: its refusal stays (the verdict says it).
      if (chosen && chosen.source !== loaded?.source) return;
      if (!loaded) verdict.none('No verdict yet: choose a sample path or a file of your own.');
      else verdict.invalid();
      if (loaded) greyResults();
      return;
    }
    rerank();
    detail();
  };

  const ranking = (rows: ToolpathSummary[], own: string, shown: string, tolerance: number, name: string, lines: Float64Array) => {
    const follow = rows.filter((r) => !r.unreachable);
    if (follow.length && follow.every(still)) {
      const cannot = rows.filter((r) => r.unreachable).map((r) => r.type);
      tableWrap.replaceChildren(el('p', { id: 'tp-ranking-none' }, `${name}: the cutting moves do not turn the rotary axes, so no configuration adds a nonlinear error; there is nothing to rank` +
        (cannot.length ? ` (${cannot.join(', ')} cannot reach the tool direction within the travel).` : '.')));
      tableWrap.classList.remove('stale');
      return;
    }
    const table = el('table', { class: 'ranking' });
    table.append(el('caption', {}, `${name} on the twelve configurations of this kind, best first, on the cutting moves (tolerance ${show('errLength', tolerance)})`));
    const head = el('tr');
    for (const [h, tip] of HEADERS) head.append(el('th', { scope: 'col', title: tip }, h));
    table.append(el('thead'));
    table.tHead?.append(head);
    const body = el('tbody');
    rows.forEach((r, i) => {
      const tr = el('tr');
      tr.dataset.type = r.type;
      if (r.type === own) tr.classList.add('own');
      if (r.type === shown) tr.classList.add('shown');
      const mark = r.type === own ? (r.commanded ? ' (this machine, the program\'s commands)' : ' (this machine)') : '';
      const rapids = r.rapids.count ? `${count(r.rapids.count)}, swings up to ${fmt.turn(r.rapids.kSwing)}, ${fmt.turn(r.rapids.mSwing)}` : 'none';
      const cells = r.unreachable
        ? [String(i + 1), `${r.type}${mark}`, `cannot follow the path: point ${r.unreachable.point + 1} (line ${lines[r.unreachable.point]}) is ${r.unreachable.message}`]
        : [String(i + 1), `${r.type}${mark}`, show('errLength', r.max), show('errLength', r.mean), show('errLength', r.p95), `${r.above} of ${r.segments}`, String(r.flips), String(r.poles), `${fmt.turn(r.kTravel)}, ${fmt.turn(r.mTravel)}`, rapids];
      cells.forEach((c, j) => {
        const td = el('td', r.unreachable && j === 2 ? { colspan: '8' } : {}, c);
        tr.append(td);
      });
      tr.addEventListener('click', () => {
        typeSel.select.value = r.type;
        dropRefined();
        detail();
      });
      body.append(tr);
    });
    table.append(body);
    tableWrap.replaceChildren(table);
    tableWrap.classList.remove('stale');
  };

  /** The rapid moves, apart: a positioning and collision note. */
  const showRapids = (a: ToolpathAnalysis, t: string, parsed: ParsedToolpath) => {
    rapidsBox.replaceChildren();
    rapidsBox.classList.remove('stale');
    const r = a.summary.rapids;
    const [kl, ml] = [machine.context().k, machine.context().m];
    rapidsBox.append(el('h3', {}, 'Rapid moves (positioning, not cutting)'));
    if (a.summary.unreachable) {
      const n = parsed.report.rapids;
      rapidsBox.append(el('p', { id: 'tp-rapids-line' }, `${n ? `${plural(n, 'rapid move')} in the file, not analysed` : 'No rapid moves in the file'}: ${t} cannot follow the path (see the verdict).`));
      return;
    }
    if (!r.count) {
      rapidsBox.append(el('p', { id: 'tp-rapids-line' }, 'The path has no rapid moves: every segment is judged.'));
      return;
    }
    rapidsBox.append(el('p', { id: 'tp-rapids-line' },
      `${plural(r.count, 'rapid move')} on ${t}, ${count(r.swings)} of them turning the rotary axes (up to ${fmt.turn(r.kSwing)} of ${kl} and ${fmt.turn(r.mSwing)} of ${ml}). ` +
      `They are not in the ranking or the verdict. In the largest the tool tip leaves the straight line by ${show('errLength', r.max)} (line ${parsed.lines[r.maxSegment + 1]})` +
      (r.max > a.tolerance ? ': check the clearance there.' : ', within the tolerance.')));
    const moves = [...a.rapidMoves].sort((x, y) => y.excursion - x.excursion).slice(0, RAPIDS_LISTED);
    const table = el('table', { class: 'rapid-moves' });
    table.append(el('caption', {}, `The ${plural(moves.length, 'rapid')} with the largest tip excursion`));
    const head = el('tr');
    for (const h of ['line', `${kl} turns`, `${ml} turns`, 'tip excursion']) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'));
    table.tHead?.append(head);
    const body = el('tbody');
    for (const mv of moves) {
      const tr = el('tr');
      for (const c of [String(parsed.lines[mv.segment + 1]), fmt.turn(mv.kTurn), fmt.turn(mv.mTurn), show('errLength', mv.excursion)]) tr.append(el('td', {}, c));
      body.append(tr);
    }
    table.append(body);
    rapidsBox.append(table);
  };

  const showAnalysis = (a: ToolpathAnalysis, t: string, name: string, parsed: ParsedToolpath) => {
    const s = a.summary;
    judgeAnalysis(a, t, name, parsed);
    showRapids(a, t, parsed);
    note(along.p, null);
    setSummary([
      ['File', `${name} (${count(parsed.count)} points, ${parsed.report.dialect}, ${parsed.report.unit === 'inch' ? 'inches' : 'mm'})`],
      ['Configuration', `${t}${s.commanded ? ' (the program\'s own commands)' : ''}`],
      ['Largest δ', s.segments ? `${show('errLength', s.max)} (segment ${s.maxSegment + 1}, line ${parsed.lines[s.maxSegment + 1]})${s.unreachable ? `, before point ${s.unreachable.point + 1} only: the rest cannot be followed` : ''}` : '—'],
      ['Cutting segments above the tolerance', `${s.above} of ${s.segments}${s.unreachable ? ` (up to point ${s.unreachable.point + 1})` : ''}`],
      ['Rapids (apart)', s.unreachable ? `${count(parsed.report.rapids)} in the file, not analysed` : count(s.rapids.count)],
      ['Flips', String(s.flips)],
      ['L', `${fmt.num(a.length)} mm`],
    ]);
    if (s.unreachable) note(along.p, `${t} cannot follow the path from point ${s.unreachable.point + 1} (line ${parsed.lines[s.unreachable.point]} of the file) on: it is ${s.unreachable.message}`);
    // δ along the path: the cutting segments solid, the rapids dotted apart (not judged).
    const n = a.delta.length;
    const rapid = new Uint8Array(n);
    for (const i of a.rapids) rapid[i] = 1;
    // A long path is thinned for drawing only: each run's largest δ (deltaSeries).
    const series = deltaSeries(a.delta, rapid);
    const cut = series.cut.y.map((d) => (d === null ? null : D(d)));
    const flips = a.flips.map((i) => i + 1);
    const data: Data[] = [
      { x: series.cut.x, y: cut, type: 'scatter', mode: 'lines', name: 'δ, cutting', connectgaps: false, line: { color: '#1f77b4', width: 1 }, hovertemplate: 'segment %{x}<br>δ %{y:.4g}<extra></extra>' },
      { x: [1, Math.max(1, n)], y: [D(a.tolerance), D(a.tolerance)], type: 'scatter', mode: 'lines', name: 'tolerance', line: { color: '#2ca02c', dash: 'dash' } },
    ];
    if (flips.length) data.push({ x: flips, y: a.flips.map((i) => D(a.delta[i])), type: 'scatter', mode: 'markers', name: 'flip', marker: { color: '#d62728', size: 9, symbol: 'x' } });
    // The rapids on their own axis (right): their excursions do not set the cutting δ's scale.
    if (a.rapids.length) data.push({ x: series.rapid.x, y: series.rapid.y.map(D), yaxis: 'y2', type: 'scatter', mode: 'markers', name: 'rapid, tip excursion (right axis; not cutting, not judged)', marker: { color: '#888', size: 6, symbol: 'circle-open' }, hovertemplate: 'rapid, segment %{x}<br>tip excursion %{y:.4g}<extra></extra>' });
    const layout2 = a.rapids.length
      ? { yaxis2: { ...axis(titled('rapid tip excursion', 'errLength'), { rangemode: 'tozero' }), overlaying: 'y', side: 'right', showgrid: false },
          legend: { orientation: 'h', x: 0, y: -0.3, xanchor: 'left', yanchor: 'top' } }
      : {};
    const thinned = series.step > 1 ? `<br>drawn: the largest δ of each run of ${count(series.step)} segments (${count(n)} segments in all)` : '';
    draw(along.p, `δ along the path on ${t} (Fig 12 style)<br>${s.above} of ${s.segments} cutting segments above the tolerance, ${s.flips} flips, ${s.rapids.count} rapids apart${thinned}`, data,
      { xaxis: axis('segment (from point n to n + 1)'), yaxis: axis(titled('δ, cutting', 'errLength'), { rangemode: 'tozero', type: s.max > 100 * Math.max(s.p95, 1e-9) ? 'log' : 'linear' }), ...layout2 } as Parameters<typeof draw>[3], 'toolpath-delta');
    // The path: cutting moves coloured by the δ of the segment that ends at each point, rapids
    // dashed grey. Gaps (null) separate the pieces of each trace.
    const p = parsed.path.points;
    const count3 = n + 1;
    const cx: (number | null)[] = [];
    const cy: (number | null)[] = [];
    const cz: (number | null)[] = [];
    const cc: (number | null)[] = [];
    const rx: (number | null)[] = [];
    const ry: (number | null)[] = [];
    const rz: (number | null)[] = [];
    const at = (i: number) => [p[6 * i], p[6 * i + 1], p[6 * i + 2]];
    // A long path: every step-th point drawn, and each one where cutting and rapids meet, so
    // that the run between two points drawn is all cutting or all rapid.
    const { step: pstep, keep } = pathPoints(n, rapid, MOST_IN_3D);
    for (let j = 0; j < keep.length; j++) {
      const i = keep[j];
      const prev = j > 0 ? keep[j - 1] : -1;
      const rapidIn = prev >= 0 && rapid[prev] === 1;
      const rapidOut = j + 1 < keep.length && rapid[i] === 1;
      const [px, py, pz] = at(i);
      if (rapidIn) {
        rx.push(px, null);
        ry.push(py, null);
        rz.push(pz, null);
      }
      if (rapidOut) {
        rx.push(px);
        ry.push(py);
        rz.push(pz);
      }
      // A cutting piece starts at a point not reached by a cutting move.
      if (rapidIn || i === 0) {
        cx.push(null);
        cy.push(null);
        cz.push(null);
        cc.push(null);
      }
      cx.push(px);
      cy.push(py);
      cz.push(pz);
      // The colour: the largest δ of the cutting segments since the point drawn before.
      let worst = 0;
      if (prev >= 0 && !rapidIn) for (let k = prev; k < i; k++) worst = Math.max(worst, a.delta[k]);
      cc.push(D(worst));
    }
    const scale3d = { cmin: 0, cmax: D(a.tolerance), showscale: true, colorbar: { title: { text: titled('δ', 'errLength') } } };
    const traces3d: Data[] = [{
      // A thinned path without markers: half the geometry to draw (in software where there is no GPU).
      type: 'scatter3d', mode: pstep > 1 ? 'lines' : 'lines+markers', name: 'cutting', x: cx, y: cy, z: cz, connectgaps: false,
      // The colour bar on the markers, or on the line when there are none.
      line: { color: cc, colorscale: 'Viridis', width: 4, ...(pstep > 1 ? scale3d : {}) },
      ...(pstep > 1 ? {} : { marker: { size: 2, color: cc, colorscale: 'Viridis', ...scale3d } }),
      hovertemplate: 'x %{x:.3f}<br>y %{y:.3f}<br>z %{z:.3f}<extra></extra>',
    } as Data];
    if (rx.length) traces3d.push({ type: 'scatter3d', mode: 'lines', name: 'rapid', x: rx, y: ry, z: rz, connectgaps: false, line: { color: '#888', width: 2, dash: 'dash' }, hoverinfo: 'skip' } as Data);
    const thinned3d = pstep > 1 ? ` (drawn: every ${count(pstep)}th point of ${count(count3)}, coloured by the largest δ since the one before)` : '';
    draw(path3d.p, `The path on ${t}<br>cutting coloured by δ of the segment ending at each point, rapids dashed${thinned3d}`, traces3d,
      { scene: { xaxis: { title: { text: 'x (mm)' } }, yaxis: { title: { text: 'y (mm)' } }, zaxis: { title: { text: 'z (mm)' } }, aspectmode: 'auto', camera: { eye: { x: 1.6, y: 1.6, z: 1.2 } } }, margin: { l: 0, r: 0, b: 0 }, showlegend: rx.length > 0 }, 'toolpath-3d');
  };

  /** The verdict: the engine's largest deviation along the cutting moves against the tolerance. */
  const judgeAnalysis = (a: ToolpathAnalysis, t: string, name: string, parsed: ParsedToolpath) => {
    const s = a.summary;
    const tol = show('errLength', a.tolerance);
    const on = `${name} on ${t}`;
    // The engine analyses the path on the machine without its errors (the control's model).
    const m = machine.current();
    const unseen = m ? unseenOf('the toolpath comparison', m, schema, () => false, 'it follows the path with the control’s model of the machine, whatever the machine’s errors') : undefined;
    const notes = [
      ...(s.flips ? [`${s.flips} flip${s.flips > 1 ? 's' : ''} of the rotary axes while cutting (a swing round, marked on the plot): the tool stops and turns there.`] : []),
      ...(s.rapids.count ? [`${plural(s.rapids.count, 'rapid positioning move')} not cutting, not judged: listed apart below.`] : []),
      ...(s.commanded ? ['This machine follows the program\'s own rotary commands (its branch and its turns).'] : []),
    ];
    if (s.unreachable) {
      return verdict.show({ source: name, status: 'fail', worst: s.max, tolerance: a.tolerance, unseen, notes,
        sentence: `${on}: this configuration cannot follow the path from point ${s.unreachable.point + 1} (line ${parsed.lines[s.unreachable.point]} of the file) on: it is ${s.unreachable.message}.` });
    }
    if (!s.segments) return verdict.none(`No verdict: ${name} has no cutting moves${s.rapids.count ? ` (${plural(s.rapids.count, 'rapid')} only)` : ''}.`);
    if (still(s)) {
      return verdict.show({ source: name, status: 'pass', worst: s.max, tolerance: a.tolerance, unseen, notes: notes.filter((n) => !n.startsWith('This machine follows')),
        sentence: `${on}: the cutting moves do not turn the rotary axes, so the control makes no nonlinear error on them (δ = 0 on every configuration); the machine's other errors are not part of this study.` });
    }
    const worst = `${show('errLength', s.max)} (cutting segment ${s.maxSegment + 1}, line ${parsed.lines[s.maxSegment + 1]} of the file)`;
    if (judge(s.max, a.tolerance) === 'pass') {
      return verdict.show({ source: name, status: 'pass', worst: s.max, tolerance: a.tolerance, unseen, notes,
        sentence: `${on}: largest nonlinear error ${worst}, every one of the ${count(s.segments)} cutting segments within the ${tol} tolerance.` });
    }
    verdict.show({ source: name, status: 'fail', worst: s.max, tolerance: a.tolerance, unseen, notes,
      sentence: `${on}: largest nonlinear error ${worst}, above the ${tol} tolerance; ${s.above} of ${count(s.segments)} cutting segments are above it. ` +
        'Insert points with the button below to keep every cutting segment within it.' });
  };

  refineButton.addEventListener('click', async () => {
    const c = current();
    if (!c) return;
    const { base, t, loaded: l } = c;
    const mine = ++refines;
    refineOut.textContent = 'Refining…';
    try {
      const r = await call('toolpathRefine', { ...base, machine: { ...base.machine, type: t as Machine['type'] } }, l.parsed.path);
      if (mine !== refines || loaded !== l) return; // the inputs or the file changed meanwhile
      refined = { type: t, r, from: l };
      const unfixed = r.unfixed.length
        ? ` ${r.unfixed.length} segment${r.unfixed.length > 1 ? 's' : ''} (from point${r.unfixed.length > 1 ? 's' : ''} ${r.unfixed.slice(0, 5).map((i) => i + 1).join(', ')}${r.unfixed.length > 5 ? ' …' : ''}) cannot be fixed by points: the rotary axes swing round there (the end of their travel, or a change of branch the program commands).`
        : '';
      refineOut.textContent = `${r.added} points inserted into ${l.name} for ${t}: the largest δ of a cutting segment is now ${show('errLength', r.max)} (${r.k.length} points in all; rapids left as they are).${unfixed}`;
      exportButton.removeAttribute('disabled');
    } catch (err) {
      if (mine !== refines) return;
      refineOut.textContent = `Could not refine: ${String((err as Error).message ?? err)}`;
      exportButton.setAttribute('disabled', '');
    }
  });

  exportButton.addEventListener('click', async () => {
    const m = machine.current();
    if (!m || !refined) return;
    const { r, type, from } = refined;
    // NC dialects are written as ISO blocks for this machine; CL data as it came.
    const nc = ['nc', 'siemens', 'heidenhain'].includes(from.parsed.format);
    const format = nc ? 'nc' : (from.parsed.format as 'csv' | 'apt');
    if (nc && type !== String(m.type)) {
      refineOut.textContent = `NC blocks are written for this machine (${String(m.type)}) only: choose it in the ranking, or set the machine to ${type}.`;
      return;
    }
    const angles = new Float64Array(2 * r.k.length);
    for (let i = 0; i < r.k.length; i++) (angles[2 * i] = r.k[i]), (angles[2 * i + 1] = r.m[i]);
    const path: ToolpathPath = { points: r.points, motions: r.motions, angles: nc ? angles : null, readFor: nc ? (type as RotaryType) : null };
    try {
      const text = await call('toolpathWrite', { machine: { ...(m as Machine), type: type as Machine['type'] }, format }, path);
      const stem = from.name.replace(/\.[^.]*$/, '');
      download(`${stem}-refined-${type}.${format}`, text, 'text/plain');
    } catch (err) {
      refineOut.textContent = `Could not write the refined path: ${String((err as Error).message ?? err)}`;
    }
  });

  sample.select.addEventListener('change', async () => {
    const name = sample.select.value;
    if (!name) return;
    await load(name, async () => {
      const res = await fetch(`samples/${name}`);
      if (!res.ok) throw new Error(`could not load the sample: ${res.status} ${res.statusText}`);
      return res.blob();
    });
  });
  const readFile = async (f: File) => {
    sample.select.value = '';
    await load(f.name, async () => f);
  };
  file.addEventListener('change', async () => {
    const f = file.files?.[0];
    if (f) await readFile(f);
    file.value = '';
  });
  fileSet.addEventListener('dragover', (e) => {
    e.preventDefault();
    fileSet.classList.add('drop');
  });
  fileSet.addEventListener('dragleave', () => fileSet.classList.remove('drop'));
  fileSet.addEventListener('drop', async (e) => {
    e.preventDefault();
    fileSet.classList.remove('drop');
    const f = e.dataTransfer?.files?.[0];
    if (f) await readFile(f);
  });

  form.addEventListener('input', (e) => {
    const id = (e.target as HTMLElement).id;
    if (id === 'tp-file' || id === 'tp-sample' || id === 'tp-type') return;
    // A reading option reads the file again (update() sees the key change).
    if (READING.includes(id) && !chosen) return;
    update();
  });
  form.addEventListener('change', (e) => {
    if ((e.target as HTMLElement).id === 'tp-type') {
      dropRefined();
      detail();
    }
  });
  machine.onChange(update);
  onUnitsChange(update);
  // Open with the sample chosen (the impeller, or the one a saved state names).
  if (sample.select.value) sample.select.dispatchEvent(new Event('change'));
}
