// The "Toolpath" panel: the customer's five-axis path on the machine of the Machine section and
// on the other eleven rotary-axis types of its kind, ranked by nonlinear error (Geng, Wu & Qiu
// 2018, Section 5), and the path refined to a tolerance.
import type { Data } from 'plotly.js';
import type { Machine, ParsedToolpath, ToolpathAnalysis, ToolpathRefined, ToolpathSummary } from '@engine';
import { call, channel, SUPERSEDED } from '../engine/client';
import { debounced } from '../engine/idle';
import { rankTypes, readToolpath, TYPES } from '../toolpath/pool';
import type { MachineSection } from '../machine/section';
import { download } from '../ui/export';
import { el, selectField } from '../ui/fields';
import { loadSchema, renderFields } from '../ui/form';
import { axis, draw, note, stale } from '../ui/plot';
import * as fmt from '../ui/format';
import { onUnitsChange, show, titled, toDisplay } from '../ui/units';
import { engineErrors, panelShell, showAtField, type Panel } from './panel';
import { verdictBox } from '../ui/verdict';

/** A length from the engine (mm) in the unit shown now. */
const D = (mm: number) => toDisplay('errLength', mm);
/** Sample paths shipped in public/samples/ (written by scripts/samples.mjs). */
const SAMPLES = [
  { value: '', label: 'none: drop or choose a file' },
  { value: 'impeller-swarf.apt', label: 'Impeller, swarf cut over the hub (APT, 751 points)' },
  { value: 'dome-past-the-pole.csv', label: 'Dome, a meridian 0.3° beside the top (CSV, 81 points)' },
];

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
  /** The file (to read NC blocks again for another machine). */
  source: Blob | string;
  /** The machine it was read for. */
  machineKey: string;
}

async function mount(root: HTMLElement, machine: MachineSection) {
  const schema = await loadSchema();
  const { form, results } = panelShell(
    root,
    'Your toolpath on every rotary-axis configuration',
    'Drop a five-axis toolpath (APT CL data, CSV x, y, z, i, j, k, or NC blocks for the machine above). It is ' +
      'followed on this machine and on the other eleven rotary-axis types of its kind, with the same travel: ' +
      'between two points the control turns the rotary axes linearly, and the tool tip leaves the programmed ' +
      'motion by δ (the nonlinear error). The ranking says which configuration machines the path more ' +
      'accurately; flips (the rotary axes swinging round near their pole or at the end of their travel) are ' +
      'flagged. δ is taken at one length L (the tool tip\'s distance from the axis it swings about), not point by ' +
      'point. Geng, Wu & Qiu, Math. Problems in Engineering 2018, Section 5. The file stays in this browser.',
  );

  // ---- inputs
  const fileSet = el('fieldset');
  fileSet.append(el('legend', {}, 'Toolpath file'));
  const sample = selectField('tp-sample', 'Sample path', SAMPLES, SAMPLES[1].value, 'Written by scripts/samples.mjs; the README explains their ranking. The panel opens with the impeller.');
  const fileLabel = el('label', { for: 'tp-file', class: 'file-label' }, 'Or a file of your own (drop it on this box)');
  const file = el('input', { type: 'file', id: 'tp-file', accept: '.apt,.cls,.cl,.csv,.txt,.nc,.ngc,.mpf,.tap,.iso,.h' });
  const fileMsg = el('p', { class: 'file-msg', id: 'tp-file-msg', role: 'status', 'aria-live': 'polite' });
  const progress = el('progress', { id: 'tp-progress', max: '1', value: '0', 'aria-label': 'Part of the file read' });
  progress.hidden = true;
  fileSet.append(sample.root, fileLabel, file, progress, fileMsg);
  form.append(fileSet);
  const fieldsOf = toolpathPanel.exports.flatMap((name) => schema.exports[name]);
  const inputs = renderFields(fieldsOf, 'tp', form, machine.context());
  const typeSel = selectField('tp-type', 'Configuration shown in detail', [{ value: 'machine', label: 'this machine' }, ...TYPES.map((t) => ({ value: t, label: t }))], 'machine',
    'The plots and the refined path are for this configuration; click a row of the ranking to choose it.');
  inputs.groups.get('Toolpath')?.append(typeSel.root);

  // ---- outputs
  const tolField = inputs.field('tolerance');
  if (!tolField) throw new Error('the engine declares no tolerance for the toolpath');
  const verdict = verdictBox({ prefix: 'tp', tolerance: { adopt: tolField }, onTolerance: () => update() });
  const summary = el('dl', { class: 'summary', id: 'tp-summary', 'aria-live': 'polite' });
  const tableWrap = el('div', { class: 'table-wrap', id: 'tp-ranking' });
  const plot = (id: string) => {
    const wrap = el('div', { class: 'plot-wrap wide' });
    const p = el('div', { class: 'plot', id });
    wrap.append(p);
    return { wrap, p };
  };
  const along = plot('tp-delta');
  const path3d = plot('tp-path');
  const refineBox = el('div', { class: 'refine', id: 'tp-refine-box' });
  const refineButton = el('button', { type: 'button', id: 'tp-refine' }, 'Insert the points that keep every segment within the tolerance');
  const refineOut = el('p', { id: 'tp-refine-out', 'aria-live': 'polite' });
  const exportButton = el('button', { type: 'button', id: 'tp-export', disabled: '' }, 'Download the refined path');
  refineBox.append(refineButton, refineOut, exportButton);
  const plots = el('div', { class: 'plots' });
  plots.append(along.wrap, path3d.wrap);
  results.append(verdict.root, summary, tableWrap, refineBox, plots);

  let ranks = 0;
  let details = 0;
  let refines = 0;
  const runAnalyse = channel('toolpathAnalyse');
  const engineError = engineErrors(inputs.byPath, machine);
  let loaded: Loaded | null = null;
  let refined: { type: string; r: ToolpathRefined; from: Loaded } | null = null;

  const fileText = (text: string) => (fileMsg.textContent = text);
  /** Tooltips of the summary's symbols: the plain meaning and the paper's symbol. */
  const tips: Record<string, string> = {
    'Largest δ': 'δ: the nonlinear error of a segment, the largest distance of the tool tip from the motion programmed between two points of the path, when the control interpolates the rotary axes\' angles in a straight line (Geng, Wu & Qiu 2018, eqs 19–21).',
    L: 'L: the distance of the tool tip from the axis it swings about (tool length, or the pivot distance).',
    Flips: 'A flip: the rotary axes swing round (the other of the two solutions) between two points, the tool stopping meanwhile.',
  };
  const setSummary = (rows: [string, string][]) => {
    summary.replaceChildren();
    for (const [k, v] of rows) summary.append(el('dt', tips[k] ? { title: tips[k] } : {}, k), el('dd', {}, v));
  };

  /** Reads a file in a worker; on a bad line the message names it and the last analysis stays
   *  (greyed, still saying which file it came from). `get` fetches the file (a sample) or is it. */
  let loads = 0;
  const load = async (name: string, get: () => Promise<Blob | string>) => {
    const mine = ++loads; // taken first: a file chosen while a sample downloads wins
    const m = machine.current();
    const own = inputs.read();
    if (!m || !own) return fileText(`${name}: fix the fields marked first.`);
    fileText(`Reading ${name}…`);
    try {
      const source = await get();
      if (mine !== loads) return;
      progress.hidden = false;
      progress.value = 0;
      const parsed = await readToolpath(source, { machine: m as Machine, format: own.format as 'auto' }, (f) => {
        if (mine === loads) progress.value = f;
      });
      if (mine !== loads) return; // a newer file was chosen meanwhile
      progress.hidden = true;
      loaded = { name, parsed, source, machineKey: JSON.stringify(m) };
      fileText(`Read ${name}: ${parsed.count} points (${parsed.format.toUpperCase()}, ${parsed.linesRead} lines).` +
        (parsed.format === 'nc' ? ' NC blocks: the tool axes come from their commands on this machine; each configuration then follows those axes by its own continuity.' : ''));
      update();
    } catch (err) {
      if (mine !== loads) return;
      progress.hidden = true;
      const e = showAtField(err, inputs.byPath, machine);
      fileText(`${name} could not be read: ${e ? e.message.replace(/^toolpath: /, '') : 'see the field marked'}${loaded ? ` The results below are still those of ${loaded.name}.` : ''}`);
      // What is still being computed for the last file must not make it look current again.
      rankLater.cancel();
      ranks++;
      details++;
      greyAll();
    }
  };

  const chosenType = (m: Machine) => (typeSel.select.value === 'machine' ? String(m.type ?? 'CBZ') : typeSel.select.value);
  const greyAll = () => {
    verdict.none('No verdict: the inputs marked (here or in the machine above) need a valid value first.');
    for (const p of [along.p, path3d.p]) stale(p, true);
    tableWrap.classList.add('stale');
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
    if (!m || !own || !loaded) return null;
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
      rankTypes(base, l.parsed.points).then((rows) => {
        if (mine === ranks) ranking(rows, String(m.type ?? ''), t, base.tolerance, l.name, l.parsed.lines);
      }, (e) => {
        if (mine !== ranks) return;
        engineError(e, along.p);
        tableWrap.classList.add('stale');
      });
    };
    rankLater();
  };

  /** The detail of the configuration shown: δ along the path and the 3D path. */
  const detail = () => {
    const mine = ++details;
    const c = current();
    if (!c) return;
    const { m, base, t, loaded: l } = c;
    for (const tr of tableWrap.querySelectorAll<HTMLElement>('tbody tr')) tr.classList.toggle('shown', tr.dataset.type === t);
    verdict.pending();
    runAnalyse({ ...base, machine: { ...(m as Machine), type: t as Machine['type'] } }, l.parsed.points).then((a) => {
      if (a === SUPERSEDED || mine !== details) return;
      showAnalysis(a, t, l.name, l.parsed);
    }, (e) => {
      if (mine !== details) return;
      engineError(e, along.p);
      verdict.none('No verdict: the engine could not follow the path (see the message at the field or over the plot).');
    });
  };

  const update = () => {
    inputs.setContext(machine.context());
    dropRefined();
    const m = machine.current();
    // NC blocks are this machine's commands: another machine reads them again.
    if (m && loaded && loaded.parsed.format === 'nc' && loaded.machineKey !== JSON.stringify(m)) {
      const { name, source } = loaded;
      void load(name, async () => source);
      return;
    }
    if (!current()) {
      if (!loaded) verdict.none('No verdict yet: choose a sample path or a file of your own.');
      else if (verdict.tolerance() === null) verdict.none('No verdict: enter a tolerance greater than 0 (see the message at the field).');
      else verdict.none('No verdict: the inputs marked (here or in the machine above) need a valid value first.');
      // Whatever is still being computed no longer answers the inputs.
      ranks++;
      details++;
      runAnalyse.cancel();
      if (loaded) greyAll();
      return;
    }
    rerank();
    detail();
  };

  const ranking = (rows: ToolpathSummary[], own: string, shown: string, tolerance: number, name: string, lines: Float64Array) => {
    const table = el('table', { class: 'ranking' });
    table.append(el('caption', {}, `${name} on the twelve configurations of this kind, best first (tolerance ${show('errLength', tolerance)})`));
    const head = el('tr');
    for (const h of ['rank', 'type', 'largest δ', 'mean δ', '95 % of segments below', 'segments above the tolerance', 'flips', 'by the pole', 'travel K, M']) head.append(el('th', { scope: 'col' }, h));
    table.append(el('thead'));
    table.tHead?.append(head);
    const body = el('tbody');
    rows.forEach((r, i) => {
      const tr = el('tr');
      tr.dataset.type = r.type;
      if (r.type === own) tr.classList.add('own');
      if (r.type === shown) tr.classList.add('shown');
      const cells = r.unreachable
        ? [String(i + 1), `${r.type}${r.type === own ? ' (this machine)' : ''}`, `cannot follow the path: point ${r.unreachable.point + 1} (line ${lines[r.unreachable.point]}) is ${r.unreachable.message}`]
        : [String(i + 1), `${r.type}${r.type === own ? ' (this machine)' : ''}`, show('errLength', r.max), show('errLength', r.mean), show('errLength', r.p95), `${r.above} of ${r.segments}`, String(r.flips), String(r.poles), `${fmt.num(r.kTravel, 4)}°, ${fmt.num(r.mTravel, 4)}°`];
      cells.forEach((c, j) => {
        const td = el('td', r.unreachable && j === 2 ? { colspan: '7' } : {}, c);
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

  const showAnalysis = (a: ToolpathAnalysis, t: string, name: string, parsed: ParsedToolpath) => {
    const s = a.summary;
    judgeAnalysis(a, t, name, parsed);
    note(along.p, null);
    setSummary([
      ['File', `${name} (${parsed.count} points, ${parsed.format.toUpperCase()})`],
      ['Configuration', t],
      ['Largest δ', s.segments ? `${show('errLength', s.max)} (segment ${s.maxSegment + 1})` : '—'],
      ['Segments above the tolerance', `${s.above} of ${s.segments}`],
      ['Flips', String(s.flips)],
      ['L', `${fmt.num(a.length)} mm`],
    ]);
    if (s.unreachable) note(along.p, `${t} cannot follow the path from point ${s.unreachable.point + 1} (line ${parsed.lines[s.unreachable.point]} of the file) on: it is ${s.unreachable.message}`);
    const x = Array.from({ length: a.delta.length }, (_, i) => i + 1);
    const flips = a.flips.map((i) => i + 1);
    const data: Data[] = [
      { x, y: Array.from(a.delta, D), type: 'scatter', mode: 'lines', name: 'δ', line: { color: '#1f77b4', width: 1 }, hovertemplate: 'segment %{x}<br>δ %{y:.4g}<extra></extra>' },
      { x: [1, Math.max(1, x.length)], y: [D(a.tolerance), D(a.tolerance)], type: 'scatter', mode: 'lines', name: 'tolerance', line: { color: '#2ca02c', dash: 'dash' } },
    ];
    if (flips.length) data.push({ x: flips, y: a.flips.map((i) => D(a.delta[i])), type: 'scatter', mode: 'markers', name: 'flip', marker: { color: '#d62728', size: 9, symbol: 'x' } });
    draw(along.p, `δ along the path on ${t} (Fig 12 style)<br>${s.above} of ${s.segments} segments above the tolerance, ${s.flips} flips`, data,
      { xaxis: axis('segment (from point n to n + 1)'), yaxis: axis(titled('δ', 'errLength'), { rangemode: 'tozero', type: s.max > 100 * Math.max(s.p95, 1e-9) ? 'log' : 'linear' }) }, 'toolpath-delta');
    // The path, each point coloured by the δ of the segment that ends there.
    const p = parsed.points;
    const n = a.delta.length + 1;
    const px = Array.from({ length: n }, (_, i) => p[6 * i]);
    const py = Array.from({ length: n }, (_, i) => p[6 * i + 1]);
    const pz = Array.from({ length: n }, (_, i) => p[6 * i + 2]);
    const c = [0, ...Array.from(a.delta, D)];
    draw(path3d.p, `The path on ${t}<br>coloured by δ of the segment ending at each point`, [{
      type: 'scatter3d', mode: 'lines+markers', x: px, y: py, z: pz,
      line: { color: c, colorscale: 'Viridis', width: 4 }, marker: { size: 2, color: c, colorscale: 'Viridis', cmin: 0, cmax: D(a.tolerance), showscale: true, colorbar: { title: { text: titled('δ', 'errLength') } } },
      hovertemplate: 'x %{x:.3f}<br>y %{y:.3f}<br>z %{z:.3f}<extra></extra>',
    } as Data], { scene: { xaxis: { title: { text: 'x (mm)' } }, yaxis: { title: { text: 'y (mm)' } }, zaxis: { title: { text: 'z (mm)' } }, aspectmode: 'auto' }, margin: { l: 0, r: 0, b: 0 } }, 'toolpath-3d');
  };

  /** The verdict: the engine's largest deviation along the path against the tolerance. */
  const judgeAnalysis = (a: ToolpathAnalysis, t: string, name: string, parsed: ParsedToolpath) => {
    const s = a.summary;
    const tol = show('errLength', a.tolerance);
    const on = `${name} on ${t}`;
    const flips = s.flips ? [`${s.flips} flip${s.flips > 1 ? 's' : ''} of the rotary axes (a swing round, marked on the plot): the tool stops and turns there.`] : [];
    if (s.unreachable) {
      return verdict.show({ status: 'fail', worst: s.max, tolerance: a.tolerance, notes: flips,
        sentence: `${on}: this configuration cannot follow the path from point ${s.unreachable.point + 1} (line ${parsed.lines[s.unreachable.point]} of the file) on: it is ${s.unreachable.message}.` });
    }
    if (!s.segments) return verdict.none(`No verdict: ${name} has fewer than two points.`);
    const worst = `${show('errLength', s.max)} (segment ${s.maxSegment + 1}, from line ${parsed.lines[s.maxSegment]} of the file)`;
    if (s.max <= a.tolerance) {
      return verdict.show({ status: 'pass', worst: s.max, tolerance: a.tolerance, notes: flips,
        sentence: `${on}: largest nonlinear error ${worst}, every one of the ${s.segments} segments within the ${tol} tolerance.` });
    }
    verdict.show({ status: 'fail', worst: s.max, tolerance: a.tolerance, notes: flips,
      sentence: `${on}: largest nonlinear error ${worst}, above the ${tol} tolerance; ${s.above} of ${s.segments} segments are above it. ` +
        'Insert points with the button below to keep every segment within it.' });
  };

  refineButton.addEventListener('click', async () => {
    const c = current();
    if (!c) return;
    const { base, t, loaded: l } = c;
    const mine = ++refines;
    refineOut.textContent = 'Refining…';
    try {
      const r = await call('toolpathRefine', { ...base, machine: { ...base.machine, type: t as Machine['type'] } }, l.parsed.points);
      if (mine !== refines || loaded !== l) return; // the inputs or the file changed meanwhile
      refined = { type: t, r, from: l };
      const unfixed = r.unfixed.length
        ? ` ${r.unfixed.length} segment${r.unfixed.length > 1 ? 's' : ''} (from point${r.unfixed.length > 1 ? 's' : ''} ${r.unfixed.slice(0, 5).map((i) => i + 1).join(', ')}${r.unfixed.length > 5 ? ' …' : ''}) cannot be fixed by points: the rotary axes swing round there (the end of their travel).`
        : '';
      refineOut.textContent = `${r.added} points inserted into ${l.name} for ${t}: the largest δ is now ${show('errLength', r.max)} (${r.k.length} points in all).${unfixed}`;
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
    const format = from.parsed.format as 'csv' | 'apt' | 'nc';
    if (format === 'nc' && type !== String(m.type)) {
      refineOut.textContent = `NC blocks are written for this machine (${String(m.type)}) only: choose it in the ranking, or set the machine to ${type}.`;
      return;
    }
    const angles = new Float64Array(2 * r.k.length);
    for (let i = 0; i < r.k.length; i++) (angles[2 * i] = r.k[i]), (angles[2 * i + 1] = r.m[i]);
    try {
      const text = await call('toolpathWrite', { machine: { ...(m as Machine), type: type as Machine['type'] }, format }, r.points, format === 'nc' ? angles : undefined);
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
    if (id === 'tp-format' && loaded) return fileText('The format applies to the next file read.');
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
