// The Machine section, shared by every panel: the machine's kind, rotary-axis type, linear axes,
// geometry, travel and its ISO 230-1 errors, entered once, with a drawing of the machine from its
// chain. Its fields come from the engine's schema (machine fields and the error table); the
// panels read the machine from here and recompute when it changes.
import type { ErrorDef, ErrorFunction, Machine, MachineDrawing } from '@engine';
import { channel, EngineError, SUPERSEDED } from '../engine/client';
import { debounced, track } from '../engine/idle';
import { el, fields, numberField, type NumberField } from '../ui/fields';
import { displayQuantity, fieldId, fill, loadSchema, renderFields, type Context, type RenderedForm } from '../ui/form';
import { note, stale } from '../ui/plot';
import * as fmt from '../ui/format';
import { leaves } from '../ui/presets';
import { resetPanel } from '../ui/state';
import { drawSchematic } from './schematic';

/** Field prefix of the machine's fields, and of the drawing's pose. */
export const MACHINE_PREFIX = 'm';
export const DRAWING_PREFIX = 'md';
/** The linear axes: every machine has them, and their squareness errors. */
const LINEAR = ['X', 'Y', 'Z'];

/**
 * An error motion given as a function of the axis position (API units: mm or degrees): a
 * polynomial, or a measured table with the file it came from and the units of its header.
 * A constant is the motion's field instead.
 */
export type MotionFunction =
  | { poly: number[] }
  | { position: number[]; value: number[]; file?: string; units?: [string, string] };

export interface MachinePreset {
  name: string;
  source?: string;
  machine: Record<string, unknown>;
}

export interface MachineSection {
  /** The machine input object (mm, degrees), or null when a field is invalid. */
  current(): Machine | null;
  /** The letters the labels use, from the last valid machine. */
  context(): Context;
  /** The machine's errors, for choosing which to identify. */
  errorOptions(): { name: string; label: string }[];
  /** The machine's pivot-to-tool-tip distance (the nonlinear study's L), mm, or null. */
  swingLength(): number | null;
  /** Shows an engine error at the machine field its path names; false when it names none. */
  showError(err: EngineError): boolean;
  /** Called after every change of the machine (once the drawing knows its letters). */
  onChange(listener: () => void): void;
  /** Resets the machine to the defaults, then sets the values of a machine object. */
  apply(machine: Record<string, unknown>, reset?: boolean): void;
  /** The machine presets (public/presets/machines.json). */
  presets(): Promise<MachinePreset[]>;
  /** The error motions (E_XX … E_CC) of the schema, and the field of each one's constant. */
  motions(): { def: ErrorDef; field: NumberField }[];
  /** An error motion given as a polynomial or table, or undefined (then its constant applies). */
  motionFunction(name: string): MotionFunction | undefined;
  /** Sets an error motion's polynomial or table (its constant goes back to 0), or clears it. */
  setMotion(name: string, fn: MotionFunction | null): void;
}

/** The papers' symbols of an error, for its tooltip: " (δxBY of Li et al.: E_X0B = −δxBY)". */
function aliasText(def: ErrorDef): string {
  const aliases = def.aliases.map((a) => `${a.symbol} of ${a.source}: ${def.name} = ${a.sign < 0 ? '−' : ''}${a.symbol}`).join('; ');
  return aliases ? ` (${aliases})` : '';
}

let presetCache: Promise<MachinePreset[]> | null = null;
function loadMachinePresets(): Promise<MachinePreset[]> {
  presetCache ??= track(fetch('presets/machines.json').then(async (res) => {
    if (!res.ok) throw new Error(`presets/machines.json: ${res.status} ${res.statusText}`);
    return ((await res.json()) as { presets: MachinePreset[] }).presets;
  }));
  return presetCache;
}

export async function mountMachine(root: HTMLElement): Promise<MachineSection> {
  const schema = await loadSchema();
  // On a phone the machine starts folded to its one-line summary, so that the open panel's
  // verdict is on the first screen; a tap on the summary opens it.
  const phone = window.matchMedia?.('(max-width: 600px)').matches ?? false;
  const details = el('details', phone ? { id: 'machine-details' } : { id: 'machine-details', open: '' });
  const summary = el('summary', { id: 'machine-summary' }, 'Machine');
  const grid = el('div', { class: 'machine-grid' });
  const form = el('form', { class: 'inputs machine-form', novalidate: '' });
  form.addEventListener('submit', (e) => e.preventDefault());
  const view = el('div', { class: 'machine-view' });
  details.append(summary, grid);
  grid.append(form, view);
  root.append(details);

  // ---- presets
  const presetField = el('div', { class: 'field preset' });
  const presetSelect = el('select', { id: 'm-preset-menu' });
  const presetNote = el('div', { class: 'field-hint', 'aria-live': 'polite' });
  presetSelect.append(el('option', { value: '' }, 'Choose a machine…'));
  presetField.append(el('label', { for: 'm-preset-menu' }, 'Machine preset'), presetSelect, presetNote);
  const resetButton = el('button', { type: 'button', id: 'machine-reset', class: 'small' }, 'Reset the machine');
  form.append(presetField);

  // ---- the machine's own fields (the schema's paths without "machine.")
  const own = schema.machine.filter((f) => f.kind !== 'errors' && f.kind !== 'motions').map((f) => ({ ...f, path: f.path.slice('machine.'.length) }));
  const machineForm: RenderedForm = renderFields(own, MACHINE_PREFIX, form);

  // ---- errors: one field per entry of the table, grouped by axis, shown for the machine's axes
  const errorSets = new Map<string, HTMLFieldSetElement>();
  const errorFields = new Map<string, { def: ErrorDef; field: NumberField }>();
  const errorBox = el('div', { class: 'errors' });
  errorBox.append(el('h3', {}, 'Geometric errors (ISO 230-1)'), el('p', { class: 'field-hint' },
    'Location errors of the axes: where each axis line lies and how it is turned, relative to where the control believes. Leave a value at 0 when it is not known. Positions in the small-length unit, angles in the small-angle unit chosen above.'));
  for (const def of schema.errors) {
    const group = LINEAR.includes(def.axis) ? 'linear' : def.axis;
    let set = errorSets.get(group);
    if (!set) {
      set = el('fieldset', { class: 'error-set' });
      set.dataset.axis = group;
      set.append(el('legend', {}, group === 'linear' ? 'Linear axes: squareness' : `${group} axis`));
      errorSets.set(group, set);
      errorBox.append(set);
    }
    const f = numberField({
      id: fieldId(MACHINE_PREFIX, `errors.${def.name}`),
      label: `${def.name}: ${def.label}`,
      quantity: displayQuantity(def.quantity),
      value: 0,
      min: -def.limit,
      max: def.limit,
    });
    f.root.title = `${def.description}${aliasText(def)}`;
    f.root.dataset.error = def.name;
    set.append(f.root);
    errorFields.set(def.name, { def, field: f });
  }
  // ---- error motions (E_XX … E_CC): a constant each (its field, placed on the page by the
  // Volumetric panel), or a polynomial or measured table (the store: one hidden field of the page
  // state holding them as JSON, API units). current() puts them into `machine.motions`.
  const motionFields = new Map<string, { def: ErrorDef; field: NumberField }>();
  for (const def of schema.motions) {
    const f = numberField({
      id: fieldId(MACHINE_PREFIX, `motions.${def.name}`),
      label: `${def.name}: ${def.label}`,
      quantity: displayQuantity(def.quantity),
      value: 0,
      min: -def.limit,
      max: def.limit,
    });
    f.root.title = `${def.description}${aliasText(def)}`;
    f.root.dataset.motion = def.name;
    // The field may sit outside this form (in the panel): its edits change the machine too.
    f.input.addEventListener('input', () => onInput());
    motionFields.set(def.name, { def, field: f });
  }
  const motionStore = new Map<string, MotionFunction>();
  const motionInput = el('input', { type: 'hidden', id: fieldId(MACHINE_PREFIX, 'motions'), hidden: '' });
  form.append(motionInput);
  const storeMotions = () => {
    const sorted = [...motionStore].sort(([a], [b]) => a.localeCompare(b));
    motionInput.value = sorted.length ? JSON.stringify(Object.fromEntries(sorted)) : '';
    motionInput.dispatchEvent(new Event('input', { bubbles: true }));
  };
  /** The store from its text in a page state: entries that are not a polynomial or a table of
   *  numbers are dropped (the engine checks the rest). */
  const readMotions = (text: string) => {
    motionStore.clear();
    let data: unknown = {};
    try {
      data = text ? JSON.parse(text) : {};
    } catch {
      data = {};
    }
    const numbers = (v: unknown): v is number[] => Array.isArray(v) && v.every((x) => typeof x === 'number');
    for (const [name, v] of Object.entries((data && typeof data === 'object' ? data : {}) as Record<string, Record<string, unknown>>)) {
      if (!motionFields.has(name) || !v || typeof v !== 'object') continue;
      if (numbers(v.poly)) motionStore.set(name, { poly: v.poly });
      else if (numbers(v.position) && numbers(v.value)) {
        const units = Array.isArray(v.units) && v.units.length === 2 ? (v.units.map(String) as [string, string]) : undefined;
        motionStore.set(name, { position: v.position, value: v.value, ...(typeof v.file === 'string' ? { file: v.file } : {}), ...(units ? { units } : {}) });
      }
    }
    storeMotions();
  };
  fields.set(motionInput.id, {
    id: motionInput.id,
    control: motionInput,
    text: () => motionInput.value,
    defaultText: () => '',
    setText: readMotions,
    setBase: (v) => readMotions(typeof v === 'string' ? v : JSON.stringify(v)),
  });

  const errorNote = el('p', { class: 'field-hint', id: 'machine-errors-note', 'aria-live': 'polite' });
  errorBox.append(errorNote);
  form.append(errorBox, resetButton);

  // ---- the drawing
  const roles = el('p', { class: 'roles', id: 'machine-roles', 'aria-live': 'polite' });
  const plotWrap = el('div', { class: 'plot-wrap' });
  const plot = el('div', { class: 'plot tall', id: 'machine-schematic' });
  plotWrap.append(plot);
  const poseBox = el('div', { class: 'inputs drawing-pose' });
  const drawingFields = schema.exports.machineSchematic.filter((f) => !f.path.startsWith('machine.'));
  const drawingForm = renderFields(drawingFields, DRAWING_PREFIX, poseBox);
  view.append(roles, plotWrap, poseBox);

  let ctx: Context = { k: '', m: '', u: 'u', v: 'v', kind: '' };
  let axes: string[] = [];
  let swing: number | null = null;
  const listeners: (() => void)[] = [];

  const machineFields = () => [...errorFields.values()];
  /** The error belongs to one of the machine's axes (its rotary axes or a linear one). */
  const onMachine = (def: ErrorDef) => axes.includes(def.axis) || LINEAR.includes(def.axis);

  /**
   * The kind and the rotary axes as chosen right now (from the type's letters: K, M, then the
   * spindle direction), so that fields of another kind and errors of axes the machine lacks are
   * hidden before the machine is read. The face letters come with the drawing.
   */
  const syncChoice = () => {
    const kind = fields.get(fieldId(MACHINE_PREFIX, 'kind'))?.text() ?? ctx.kind;
    const type = fields.get(fieldId(MACHINE_PREFIX, 'type'))?.text() ?? `${ctx.k}${ctx.m}`;
    if (kind === ctx.kind && type[0] === ctx.k && type[1] === ctx.m) return;
    ctx = { ...ctx, kind, k: type[0], m: type[1] };
    machineForm.setContext(ctx);
    drawingForm.setContext(ctx);
    axes = [ctx.k, ctx.m];
    for (const [group, set] of errorSets) {
      set.hidden = !(group === 'linear' || axes.includes(group));
      const role = group === ctx.k ? ' (K, nearer the workpiece)' : group === ctx.m ? ' (M, nearer the tool)' : '';
      set.querySelector('legend')!.textContent = group === 'linear' ? 'Linear axes: squareness' : `${group} axis${role}`;
    }
  };

  const current = (): Machine | null => {
    syncChoice();
    const m = machineForm.read();
    let ok = m !== null;
    const errors: Record<string, number> = {};
    for (const { def, field } of machineFields()) {
      if (field.root.closest('fieldset')?.hidden) continue;
      const v = field.read();
      if (v === null) ok = false;
      else if (typeof v === 'number' && v !== 0) errors[def.name] = v;
    }
    const motions: Record<string, ErrorFunction> = {};
    for (const { def, field } of motionFields.values()) {
      if (!onMachine(def)) continue;
      const fn = motionStore.get(def.name);
      if (fn) {
        motions[def.name] = 'poly' in fn ? { poly: fn.poly } : { position: fn.position, value: fn.value };
        continue;
      }
      const v = field.read();
      if (v === null) ok = false;
      else if (typeof v === 'number' && v !== 0) motions[def.name] = v;
    }
    if (!ok || !m) return null;
    m.errors = errors;
    if (Object.keys(motions).length) m.motions = motions;
    return m as Machine;
  };

  /** The letters of the type as the schematic gave them, and which error groups to show. */
  const applyContext = (r: MachineDrawing) => {
    ctx = { ...ctx, k: r.k, m: r.m, u: r.face[0], v: r.face[1] };
    swing = r.swingLength;
    // Each axis's errors under what the axis is on this machine ("C (K): head axis on the ram").
    for (const a of r.axes) {
      const legend = errorSets.get(a.name)?.querySelector('legend');
      if (legend) legend.textContent = `${a.description}`;
    }
    machineForm.setContext(ctx);
    drawingForm.setContext(ctx);
    // Values entered for axes this machine does not have are kept but not used: say so.
    const given = ({ def, field }: { def: ErrorDef; field: NumberField }) => motionStore.has(def.name) || (field.read() ?? 0) !== 0;
    const unused = [...machineFields(), ...motionFields.values()].filter((e) => !onMachine(e.def) && given(e));
    errorNote.textContent = unused.length
      ? `Kept but not used (this machine has no such axis): ${unused.map((u) => u.def.name).join(', ')}.`
      : '';
    const entered = machineFields().filter(({ def, field }) => onMachine(def) && (field.read() ?? 0) !== 0);
    const moving = [...motionFields.values()].filter((e) => onMachine(e.def) && given(e)).length;
    summary.textContent = `Machine: ${ctx.kind}, type ${r.k}${r.m}${r.home} (${r.k}: K, ${r.m}: M, spindle along ${r.home}); ${entered.length ? `${entered.length} error${entered.length === 1 ? '' : 's'} entered` : 'no errors entered'}` +
      (moving ? `; ${moving} error motion${moving === 1 ? '' : 's'} entered (Volumetric tab)` : '');
    roles.textContent = `${r.axes.filter((a) => a.motion === 'rotary').map((a) => a.description).join('. ')}. Tool ${r.group === 'I' ? `along ${r.k}’s axis` : `across ${r.k}’s axis`} with both at zero (Geng et al.’s Group ${r.group}). ${r.swingLength === null ? '' : `Pivot to tool tip (the nonlinear study's L): ${fmt.num(r.swingLength)} mm.`}`;
  };

  const runSchematic = channel('machineSchematic');
  const update = async () => {
    const m = current();
    const pose = drawingForm.read();
    if (!m || !pose) return;
    await runSchematic({ machine: m, ...pose }).then((r) => {
      if (r === SUPERSEDED) return;
      note(plot, null);
      applyContext(r);
      void drawSchematic(plot, r, `The machine as entered, ${fill('{K}', ctx)} at ${fmt.num(Number(pose.k ?? 0))}° and ${fill('{M}', ctx)} at ${fmt.num(Number(pose.m ?? 0))}°`);
      for (const l of listeners) l();
    }, (e) => {
      const err = EngineError.of(e);
      if (!section.showError(err)) note(plot, err.message);
      // The panels try this machine too: the engine refuses it there as well, and they grey
      // the plots it fed.
      for (const l of listeners) l();
    });
  };

  const section: MachineSection = {
    current,
    context: () => ctx,
    swingLength: () => swing,
    errorOptions: () =>
      machineFields()
        .filter(({ def }) => onMachine(def))
        .map(({ def }) => ({ name: def.name, label: `${def.label}: ${def.description}` })),
    showError(err) {
      const path = err.field;
      if (path.startsWith('machine.errors.')) {
        const f = errorFields.get(path.slice('machine.errors.'.length));
        if (f) return f.field.setError(err.text), true;
      }
      const f = machineForm.byPath[path.slice('machine.'.length)];
      if (path.startsWith('machine.') && f) return f.setError(err.text), true;
      return false;
    },
    onChange(l) {
      listeners.push(l);
    },
    apply(machine, reset = true) {
      if (reset) resetPanel(MACHINE_PREFIX);
      const { motions = {}, ...rest } = machine as { motions?: Record<string, unknown> };
      for (const [name, value] of Object.entries(motions)) {
        if (typeof value === 'number') fields.get(fieldId(MACHINE_PREFIX, `motions.${name}`))?.setBase(value);
        else if (value && typeof value === 'object') section.setMotion(name, value as MotionFunction);
      }
      for (const [path, value] of leaves(rest)) {
        fields.get(fieldId(MACHINE_PREFIX, path))?.setBase(value as number | string | boolean);
      }
    },
    presets: loadMachinePresets,
    motions: () => [...motionFields.values()],
    motionFunction: (name) => motionStore.get(name),
    setMotion(name, fn) {
      if (fn) {
        motionStore.set(name, fn);
        fields.get(fieldId(MACHINE_PREFIX, `motions.${name}`))?.setBase(0);
      } else motionStore.delete(name);
      storeMotions();
    },
  };

  loadMachinePresets().then((presets) => {
    presets.forEach((p, i) => presetSelect.append(el('option', { value: String(i) }, p.name)));
    presetSelect.addEventListener('change', () => {
      const p = presets[Number(presetSelect.value)];
      if (!p || presetSelect.value === '') return;
      section.apply(p.machine);
      presetNote.textContent = p.source ? `Source: ${p.source}` : '';
      presetSelect.value = '';
    });
  }, (err) => (presetNote.textContent = `Presets unavailable: ${String(err)}`));
  resetButton.addEventListener('click', () => {
    resetPanel(MACHINE_PREFIX);
    resetPanel(DRAWING_PREFIX);
  });

  // Any edit: mark what the machine fed as stale until the new machine is computed.
  const later = debounced(() => void update(), 60);
  const onInput = () => {
    if (!current()) {
      stale(plot, true);
      // No machine now: the panels grey the plots it fed (they read current() as null).
      for (const l of listeners) l();
    }
    later();
  };
  form.addEventListener('input', onInput);
  poseBox.addEventListener('input', onInput);
  await update();
  return section;
}
