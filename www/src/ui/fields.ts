// Labelled form fields that validate what the user typed and show the reason next to the field.
//
// Every field registers itself by id in `fields`, so that the page state (share links, saved
// inputs, named cases, presets, reset) works for every panel without per-panel code. A field's
// value in the state is its text as shown, together with the unit preferences; presets give
// values in base units (mm, degrees) and are converted to what is shown.
import { fromDisplay, numberText, onUnitsChange, toDisplay, unitDef, type Quantity } from './units';
import { excerpt } from './format';

/** What the page state needs to know of a field. */
export interface FieldHandle {
  readonly id: string;
  readonly control: HTMLInputElement | HTMLSelectElement | HTMLTextAreaElement;
  /** The text as shown (what the state stores). */
  text(): string;
  /** The default text in the units shown now. */
  defaultText(): string;
  /** Sets the text and tells the panel (an 'input' event). */
  setText(text: string): void;
  /** Sets a value given in base units (mm, degrees); for presets. */
  setBase(value: number | string | boolean | string[]): void;
}

/** Every field on the page, by id. */
export const fields = new Map<string, FieldHandle>();

let uid = 0;

export function el<K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {}, text?: string) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

function fire(control: HTMLElement) {
  control.dispatchEvent(new Event('input', { bubbles: true }));
}

export interface NumberFieldOptions {
  /** Element id of the input (stable: links, saved cases and tests use it). */
  id: string;
  label: string;
  /** What the number is; its unit follows the unit preferences (see units.ts). */
  quantity?: Quantity;
  /** Unit text for quantity 'none' (e.g. "" for ratios and counts). */
  unit?: string;
  /** Default, minimum and maximum in base units (mm, degrees); a null default: empty. */
  value: number | null;
  min: number;
  max: number;
  /** May be left empty: then `read()` gives undefined (the engine's default applies). */
  optional?: boolean;
  /** Reject 0 and negative values (lengths that must be positive). */
  positive?: boolean;
  integer?: boolean;
  hint?: string;
}

export interface NumberField {
  readonly root: HTMLElement;
  readonly input: HTMLInputElement;
  readonly label: HTMLElement;
  /** The value in base units; undefined when an optional field is empty; null after showing
   *  why the text is not acceptable. */
  read(): number | null | undefined;
  /** Shows (or clears, with null) a message at the field. */
  setError(message: string | null): void;
}

/** Minus signs and dashes typed or pasted for "-": U+2212 minus, the hyphens U+2010 and
 *  U+2011, the figure and en dashes U+2012 and U+2013, the small hyphen-minus U+FE63. */
const MINUS_LIKE = /[\u2212\u2010-\u2013\uFE63]/g;

/** The text with full-width forms (U+FF01–U+FF5E: `１２`, `－３．５`) as their ASCII characters,
 *  the ideographic space as a space and minus look-alikes as "-". */
export function asciiText(text: string): string {
  return text
    .replace(/[\uFF01-\uFF5E]/g, (c) => String.fromCharCode(c.charCodeAt(0) - 0xfee0))
    .replace(/\u3000/g, ' ')
    .replace(MINUS_LIKE, '-');
}

/** A number as a user types it ("1.5", "-0.00017", "1e-3", "2,5", "１２", "−3.5"): its value,
 *  ±Infinity beyond the range of a double ("1e400"), or null when it is not a number. */
export function parseNumberText(text: string): number | null {
  const t = asciiText(text).trim().replace(/^\+/, '').replace(/^(-?\d*),(\d+)$/, '$1.$2');
  if (t === '' || !/^-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t)) return null;
  return Number(t);
}

/** [`parseNumberText`], finite values only. */
export function parseNumber(text: string): number | null {
  const v = parseNumberText(text);
  return v !== null && Number.isFinite(v) ? v : null;
}

/** The `pattern` of a signed number field: what `parseNumberText` reads, full-width forms
 *  included (a hint for the browser, compiled in its `v` mode; the field's own check decides). */
export const SIGNED_PATTERN = (() => {
  const digit = '[0-9\\uFF10-\\uFF19]';
  const sign = '[+\\-\\u2212\\u2010-\\u2013\\uFE63\\uFF0B\\uFF0D]';
  const dot = '[.\\uFF0E]';
  const comma = '[,\\uFF0C]';
  const exp = `[eE\\uFF25\\uFF45]${sign}?${digit}+`;
  return `\\s*${sign}?(${digit}+(${dot}${digit}*|${comma}${digit}+)?|(${dot}|${comma})${digit}+)(${exp})?\\s*`;
})();

function fieldShell(id: string, labelText: string, hint?: string) {
  const root = el('div', { class: 'field' });
  const label = el('label', { for: id }, labelText);
  const msg = el('div', { class: 'field-msg', id: `msg-${id}-${++uid}`, 'aria-live': 'polite' });
  root.append(label);
  const finish = (control: HTMLElement, row: HTMLElement = control) => {
    control.setAttribute('aria-describedby', msg.id);
    root.append(row);
    if (hint) root.append(el('div', { class: 'field-hint' }, hint));
    root.append(msg);
  };
  const setError = (control: HTMLElement, message: string | null) => {
    msg.textContent = message ?? '';
    root.classList.toggle('invalid', !!message);
    if (message) control.setAttribute('aria-invalid', 'true');
    else control.removeAttribute('aria-invalid');
  };
  return { root, label, finish, setError };
}

export function numberField(o: NumberFieldOptions): NumberField {
  const q: Quantity = o.quantity ?? 'none';
  const shell = fieldShell(o.id, o.label, o.hint);
  const row = el('div', { class: 'field-row' });
  // A field that takes negative values: iOS's decimal keypad has no minus key, so the full
  // keyboard, with the pattern as a hint.
  const signed = o.min < 0;
  const input = el('input', {
    id: o.id,
    name: o.id,
    type: 'text',
    inputmode: signed ? 'text' : 'decimal',
    ...(signed ? { pattern: SIGNED_PATTERN } : {}),
    autocomplete: 'off',
    spellcheck: 'false',
    'data-number': '',
  });
  const unitEl = el('span', { class: 'unit' });
  row.append(input, unitEl);
  shell.finish(input, row);

  let factor = unitDef(q).factor; // the factor the text is written in
  const showUnit = () => {
    const d = unitDef(q);
    unitEl.textContent = q === 'none' ? (o.unit ?? '') : d.label;
    unitEl.title = d.name;
  };
  const defaultText = () => (o.value === null ? '' : numberText(toDisplay(q, o.value)));
  input.value = defaultText();
  input.defaultValue = input.value;
  showUnit();
  onUnitsChange(() => {
    const v = parseNumber(input.value);
    const next = unitDef(q).factor;
    if (v !== null && next !== factor) input.value = numberText((v / factor) * next);
    factor = next;
    input.defaultValue = defaultText();
    showUnit();
  });

  const setError = (m: string | null) => shell.setError(input, m);
  const limit = (base: number) => `${numberText(toDisplay(q, base))}${unitEl.textContent ? ` ${unitEl.textContent}` : ''}`;
  /** The field's limits in words: "must be between 0 mm and 500 mm", or one of them, or none. */
  const bounds = () => {
    const [lo, hi] = [Number.isFinite(o.min), Number.isFinite(o.max)];
    if (lo && hi) return `must be between ${limit(o.min)} and ${limit(o.max)}`;
    if (lo) return `must be at least ${limit(o.min)}`;
    if (hi) return `must be at most ${limit(o.max)}`;
    return 'too large for a number';
  };
  const read = (): number | null | undefined => {
    const text = input.value;
    if (text.trim() === '' && o.optional) return setError(null), undefined;
    if (text.trim() === '') return setError('Enter a value.'), null;
    const shown = parseNumberText(text);
    if (shown === null) return setError(`"${excerpt(text)}" is not a number.`), null;
    if (!Number.isFinite(shown)) return setError(`"${excerpt(text)}" is out of range: ${bounds()}.`), null;
    if (o.integer && !Number.isInteger(shown)) return setError('Enter a whole number.'), null;
    const v = fromDisplay(q, shown);
    if (o.positive && v <= 0) return setError('Must be greater than 0.'), null;
    if (v < o.min || v > o.max) return setError(`Must be between ${limit(o.min)} and ${limit(o.max)}.`), null;
    if (!Number.isFinite(v)) return setError(`"${excerpt(text)}" is out of range: ${bounds()}.`), null;
    setError(null);
    return v;
  };
  fields.set(o.id, {
    id: o.id,
    control: input,
    text: () => input.value,
    defaultText,
    setText: (t) => ((input.value = t), fire(input)),
    setBase: (v) => ((input.value = typeof v === 'number' ? numberText(toDisplay(q, v)) : String(v)), fire(input)),
  });
  return { root: shell.root, input, label: shell.label, read, setError };
}

export interface SelectOption {
  value: string;
  label: string;
  group?: string;
}

export function selectField(id: string, labelText: string, options: SelectOption[], value: string, hint?: string) {
  const shell = fieldShell(id, labelText, hint);
  const select = el('select', { id, name: id });
  const groups = new Map<string, HTMLOptGroupElement>();
  for (const opt of options) {
    const option = el('option', { value: opt.value }, opt.label);
    option.defaultSelected = opt.value === value;
    if (opt.group) {
      let g = groups.get(opt.group);
      if (!g) {
        g = el('optgroup', { label: opt.group });
        groups.set(opt.group, g);
        select.append(g);
      }
      g.append(option);
    } else select.append(option);
  }
  select.value = value;
  shell.finish(select);
  const valid = (v: string) => options.some((o) => o.value === v);
  fields.set(id, {
    id,
    control: select,
    text: () => select.value,
    defaultText: () => value,
    setText: (t) => {
      if (valid(t)) (select.value = t), fire(select);
    },
    setBase: (v) => {
      if (valid(String(v))) (select.value = String(v)), fire(select);
    },
  });
  return { root: shell.root, select, label: shell.label };
}

/** A checkbox (its state text is "1" or "0"). */
export function checkField(id: string, labelText: string, checked: boolean, hint?: string) {
  const root = el('div', { class: 'field check' });
  const input = el('input', { id, name: id, type: 'checkbox' });
  input.checked = checked;
  input.defaultChecked = checked;
  const label = el('label', { for: id }, labelText);
  root.append(input, label);
  if (hint) root.append(el('div', { class: 'field-hint' }, hint));
  const set = (t: string) => ((input.checked = t === '1' || t === 'true'), fire(input));
  fields.set(id, {
    id,
    control: input,
    text: () => (input.checked ? '1' : '0'),
    defaultText: () => (checked ? '1' : '0'),
    setText: set,
    setBase: (v) => set(String(v)),
  });
  return { root, input, label };
}

/** A list of numbers typed as "0.5, 2, 3, 5" (quantity none). */
export function listField(id: string, labelText: string, value: number[], min: number, max: number, hint?: string,
  limits: { minLen?: number; maxLen?: number; nonzero?: boolean } = {}) {
  const { minLen = 1, maxLen = 8, nonzero = true } = limits;
  const shell = fieldShell(id, labelText, hint);
  const input = el('input', { id, name: id, type: 'text', autocomplete: 'off', spellcheck: 'false' });
  input.value = value.join(', ');
  input.defaultValue = input.value;
  shell.finish(input);
  const setError = (m: string | null) => shell.setError(input, m);
  const read = (): number[] | null => {
    const parts = asciiText(input.value).split(/[,;\s]+/).filter((p) => p !== '');
    if (parts.length < minLen) return setError(minLen === 1 ? 'Enter at least one value.' : `Enter ${minLen} values.`), null;
    if (parts.length > maxLen) return setError(`At most ${maxLen} values.`), null;
    const out: number[] = [];
    for (const p of parts) {
      const v = parseNumberText(p);
      if (v === null) return setError(`"${excerpt(p)}" is not a number.`), null;
      if (!Number.isFinite(v)) return setError(`"${excerpt(p)}" is out of range: each value must be between ${min} and ${max}.`), null;
      if (v < min || v > max || (nonzero && v === 0)) return setError(`Each value must be${nonzero ? ' non-zero,' : ''} between ${min} and ${max}.`), null;
      out.push(v);
    }
    setError(null);
    return out;
  };
  fields.set(id, {
    id,
    control: input,
    text: () => input.value,
    defaultText: () => value.join(', '),
    setText: (t) => ((input.value = t), fire(input)),
    setBase: (v) => ((input.value = Array.isArray(v) ? v.join(', ') : String(v)), fire(input)),
  });
  return { root: shell.root, input, read, setError };
}

/** A multi-line text field (pasted data such as a CSV file). */
export function textField(id: string, labelText: string, value: string, rows = 6, hint?: string) {
  const shell = fieldShell(id, labelText, hint);
  const area = el('textarea', { id, name: id, rows: String(rows), spellcheck: 'false', autocomplete: 'off' });
  area.value = value;
  area.defaultValue = value;
  shell.finish(area);
  fields.set(id, {
    id,
    control: area,
    text: () => area.value,
    defaultText: () => value,
    setText: (t) => ((area.value = t), fire(area)),
    setBase: (v) => ((area.value = String(v)), fire(area)),
  });
  return { root: shell.root, area, label: shell.label, setError: (m: string | null) => shell.setError(area, m) };
}

/**
 * A choice of several names (e.g. the errors to identify) as checkboxes; the options change with
 * the machine. Its state text is "" for all of them, else the chosen names joined by commas.
 */
export function namesField(id: string, labelText: string, hint?: string) {
  const root = el('fieldset', { class: 'field names', id });
  const legend = el('legend', {}, labelText);
  const box = el('div', { class: 'names-box' });
  root.append(legend, box);
  if (hint) root.append(el('div', { class: 'field-hint' }, hint));
  const msg = el('div', { class: 'field-msg', 'aria-live': 'polite' });
  root.append(msg);
  // The control the page state reads and writes: a hidden input holding the text.
  const store = el('input', { type: 'hidden', id: `${id}-value` });
  root.append(store);
  let options: { name: string; label: string }[] = [];
  const chosen = (): string[] => [...box.querySelectorAll<HTMLInputElement>('input[type=checkbox]')].filter((c) => c.checked).map((c) => c.value);
  const render = () => {
    const picked = store.value === '' ? null : new Set(store.value.split(','));
    box.replaceChildren();
    for (const o of options) {
      const cid = `${id}-${o.name}`;
      const c = el('input', { type: 'checkbox', id: cid, value: o.name });
      c.checked = picked === null || picked.has(o.name);
      // On 'input', before the panel sees the event: the panel re-renders the boxes from the
      // store when it reads its fields, which would undo a click not yet stored.
      c.addEventListener('input', (e) => {
        e.stopPropagation();
        const all = chosen();
        store.value = all.length === options.length ? '' : all.join(',');
        fire(store);
      });
      const l = el('label', { for: cid, title: o.label }, o.name);
      const item = el('span', { class: 'name-item' });
      item.append(c, l);
      box.append(item);
    }
  };
  fields.set(`${id}`, {
    id,
    control: store,
    text: () => store.value,
    defaultText: () => '',
    setText: (t) => {
      store.value = t;
      render();
      fire(store);
    },
    setBase: (v) => {
      store.value = Array.isArray(v) ? v.join(',') : String(v);
      render();
      fire(store);
    },
  });
  return {
    root,
    label: legend,
    /** Sets the names offered (the machine's errors), keeping the choice. */
    setOptions(next: { name: string; label: string }[]) {
      options = next;
      render();
    },
    /** The chosen names, or undefined when all are chosen (the engine's default). */
    read(): string[] | undefined {
      if (store.value === '') return undefined;
      const offered = new Set(options.map((o) => o.name));
      return store.value.split(',').filter((n) => offered.has(n));
    },
    setError(m: string | null) {
      msg.textContent = m ?? '';
      root.classList.toggle('invalid', !!m);
    },
  };
}
