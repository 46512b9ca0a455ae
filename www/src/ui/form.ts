// Forms rendered from the engine's schema (`schema()`): every input a study declares in Rust
// appears here with its label, help, unit and limits, and is read back into the nested input
// object the engine takes (API units: mm and degrees). Nothing about an input is written in
// this file; the engine's reader checks it again and refuses what it does not know.
import type { FieldInfo, Quantity as EngineQuantity, Schema } from '@engine';
import { call } from '../engine/client';
import { checkField, el, listField, namesField, numberField, selectField, textField } from './fields';
import type { Quantity } from './units';

let schemaPromise: Promise<Schema> | null = null;

/** The engine's schema, fetched once. */
export function loadSchema(): Promise<Schema> {
  schemaPromise ??= call('schema') as Promise<Schema>;
  return schemaPromise;
}

/** The id of the page field for an input path: `cb` + `setup.zoneSize` → `cb-setup-zoneSize`. */
export function fieldId(prefix: string, path: string): string {
  return `${prefix}-${path.replace(/\./g, '-')}`;
}

/** The letters the labels' placeholders stand for, and the machine's kind. */
export interface Context {
  /** K and M: the machine's rotary axes ("C", "B"). */
  k: string;
  m: string;
  /** The face's axes u, v (X, Y for a vertical spindle). */
  u: string;
  v: string;
  /** "table-table", "head-table" or "head-head". */
  kind: string;
}

/** `{K}` etc. replaced by the machine's letters. */
export function fill(text: string, ctx: Context | null): string {
  if (!ctx) return text.replace(/\{K\}/g, 'K').replace(/\{M\}/g, 'M').replace(/\{U\}/g, 'u').replace(/\{V\}/g, 'v');
  return text.replace(/\{K\}/g, ctx.k).replace(/\{M\}/g, ctx.m).replace(/\{U\}/g, ctx.u).replace(/\{V\}/g, ctx.v);
}

/** The page's display quantity of an engine quantity. */
export function displayQuantity(q: EngineQuantity | null | undefined): Quantity {
  switch (q) {
    case 'length':
      return 'length';
    case 'smallLength':
      return 'errLength';
    case 'angle':
      return 'angle';
    case 'smallAngle':
      return 'errAngle';
    default:
      return 'none';
  }
}

/** Anything that can show a message (every kind of field). */
export interface ShowsError {
  setError(message: string | null): void;
}

interface Rendered extends ShowsError {
  info: FieldInfo;
  root: HTMLElement;
  label: HTMLElement;
  /** The value for the input object: undefined to leave it out, null when invalid. */
  read(): unknown;
  /** The names field's options (errorNames). */
  setOptions?(options: { name: string; label: string }[]): void;
}

export interface RenderedForm {
  /** Each rendered field by its input path. */
  byPath: Record<string, ShowsError>;
  /** The fieldsets by group name. */
  groups: Map<string, HTMLElement>;
  /** The input object (paths nested), or null when a field is invalid (its message shown). */
  read(): Record<string, unknown> | null;
  /** Relabels for a machine and hides fields that do not apply to its kind. */
  setContext(ctx: Context): void;
  /** The fields of kind errorNames get these names to choose from. */
  setNames(options: { name: string; label: string }[]): void;
  /** The rendered field of an input path (its root, its control, its reader), if rendered. */
  field(path: string): { root: HTMLElement; input: HTMLInputElement; read(): unknown } | undefined;
}

/** Sets `value` at a dotted path of `obj`. */
export function setPath(obj: Record<string, unknown>, path: string, value: unknown) {
  const parts = path.split('.');
  let at = obj;
  for (const p of parts.slice(0, -1)) {
    at[p] ??= {};
    at = at[p] as Record<string, unknown>;
  }
  at[parts[parts.length - 1]] = value;
}

function render(info: FieldInfo, id: string, ctx: Context | null): Rendered {
  const label = fill(info.label, ctx);
  const hint = info.help ? fill(info.help, ctx) : undefined;
  const def = info.default;
  switch (info.kind) {
    case 'number':
    case 'count': {
      const f = numberField({
        id,
        label,
        quantity: displayQuantity(info.quantity),
        value: typeof def === 'number' ? def : null,
        min: info.min ?? -Infinity,
        max: info.max ?? Infinity,
        positive: info.exclusiveMin && info.min === 0,
        integer: info.kind === 'count',
        optional: info.optional,
        hint,
      });
      f.input.dataset.min = String(info.min ?? '');
      f.input.dataset.max = String(info.max ?? '');
      return { info, root: f.root, label: f.label, read: () => f.read(), setError: f.setError };
    }
    case 'flag': {
      const f = checkField(id, label, def === true, hint);
      return { info, root: f.root, label: f.label, read: () => f.input.checked, setError: () => {} };
    }
    case 'choice': {
      const options = info.choices.map((c) => ({ value: c.value, label: fill(c.label, ctx) }));
      const f = selectField(id, label, options, String(def ?? options[0]?.value ?? ''), hint);
      return { info, root: f.root, label: f.label, read: () => f.select.value, setError: () => {} };
    }
    case 'text': {
      // A short text (a name) on one line; a file's text in a box.
      const f = textField(id, label, typeof def === 'string' ? def : '', (info.max ?? Infinity) <= 200 ? 1 : 6, hint);
      return { info, root: f.root, label: f.label, read: () => f.area.value, setError: f.setError };
    }
    case 'numberList': {
      const values = typeof def === 'string' ? def.split(',').map((x) => Number(x)) : [];
      const f = listField(id, label, values, info.min ?? -Infinity, info.max ?? Infinity, hint,
        { minLen: info.list?.minLen, maxLen: info.list?.maxLen, nonzero: info.list?.nonzero });
      return { info, root: f.root, label: f.root.querySelector('label') as HTMLElement, read: () => f.read(), setError: f.setError };
    }
    case 'errorNames': {
      const f = namesField(id, label, hint);
      return { info, root: f.root, label: f.label, read: () => f.read(), setError: f.setError, setOptions: (o) => f.setOptions(o) };
    }
    default:
      throw new Error(`a field of kind ${info.kind} cannot be rendered here (${info.path})`);
  }
}

/**
 * Renders `fields` (shown ones, not under `machine.`) into `container`, one fieldset per group
 * in the order the groups first appear (a field without a group goes in its section's).
 */
export function renderFields(fields: FieldInfo[], prefix: string, container: HTMLElement, ctx: Context | null = null): RenderedForm {
  const groups = new Map<string, HTMLElement>();
  const rendered: Rendered[] = [];
  const seen = new Set<string>();
  for (const info of fields) {
    if (!info.shown || info.path.startsWith('machine.') || info.kind === 'errors' || info.kind === 'motions' || seen.has(info.path)) continue;
    seen.add(info.path);
    const group = info.group || info.section || 'Inputs';
    let set = groups.get(group);
    if (!set) {
      set = el('fieldset');
      set.dataset.group = group;
      set.append(el('legend', {}, group));
      groups.set(group, set);
      container.append(set);
    }
    const r = render(info, fieldId(prefix, info.path), ctx);
    r.root.dataset.path = info.path;
    // The label's tooltip: the plain meaning (the engine's help), which also names the paper's symbol.
    if (info.help) r.label.title = fill(info.help, ctx);
    set.append(r.root);
    rendered.push(r);
  }
  const byPath: Record<string, ShowsError> = {};
  for (const r of rendered) byPath[r.info.path] = r;
  return {
    byPath,
    groups,
    read() {
      const out: Record<string, unknown> = {};
      let ok = true;
      for (const r of rendered) {
        if (r.root.hidden) continue;
        const v = r.read();
        if (v === null) ok = false;
        else if (v !== undefined) setPath(out, r.info.path, v);
      }
      return ok ? out : null;
    },
    setContext(next: Context) {
      for (const r of rendered) {
        const text = fill(r.info.label, next);
        // The label element may hold only text (inputs and selects) or a legend.
        if (r.label.textContent !== text) r.label.textContent = text;
        const hint = r.root.querySelector(':scope > .field-hint');
        if (hint && r.info.help) hint.textContent = fill(r.info.help, next);
        if (r.info.help) r.label.title = fill(r.info.help, next);
        // A choice's options may name the axes too ("{K}").
        const select = r.info.kind === 'choice' ? r.root.querySelector('select') : null;
        r.info.choices.forEach((c, j) => {
          const o = select?.options[j];
          if (o && o.textContent !== fill(c.label, next)) o.textContent = fill(c.label, next);
        });
        r.root.hidden = r.info.kinds.length > 0 && !r.info.kinds.includes(next.kind);
      }
      for (const set of groups.values()) {
        set.hidden = [...set.querySelectorAll<HTMLElement>(':scope > [data-path]')].every((f) => f.hidden);
      }
    },
    setNames(options) {
      for (const r of rendered) r.setOptions?.(options);
    },
    field(path) {
      const r = rendered.find((x) => x.info.path === path);
      const input = r?.root.querySelector<HTMLInputElement>('input');
      return r && input ? { root: r.root, input, read: () => r.read() } : undefined;
    },
  };
}
