// Labelled form fields that validate what the user typed and show the reason next to the field.

let uid = 0;

function el<K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {}, text?: string) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}
export { el };

export interface NumberFieldOptions {
  /** Element id of the input (stable: tests and links use it). */
  id: string;
  label: string;
  /** Unit shown after the field, e.g. "mm" or "°". */
  unit?: string;
  value: number;
  min: number;
  max: number;
  /** Reject 0 (for lengths that must be positive). */
  positive?: boolean;
  integer?: boolean;
  step?: string;
  hint?: string;
}

export interface NumberField {
  readonly root: HTMLElement;
  readonly input: HTMLInputElement;
  readonly label: HTMLElement;
  /** The value, or null after showing why the text is not acceptable. */
  read(): number | null;
  /** Shows (or clears, with null) a message at the field. */
  setError(message: string | null): void;
  set(value: number): void;
}

/** Parses a number the way a user types it: "1.5", "-0.00017", "1e-3"; a comma decimal too. */
export function parseNumber(text: string): number | null {
  const t = text.trim().replace(/^\+/, '').replace(/^(-?\d*),(\d+)$/, '$1.$2');
  if (t === '' || !/^-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t)) return null;
  const v = Number(t);
  return Number.isFinite(v) ? v : null;
}

export function numberField(o: NumberFieldOptions): NumberField {
  const root = el('div', { class: 'field' });
  const label = el('label', { for: o.id }, o.label);
  const row = el('div', { class: 'field-row' });
  const input = el('input', {
    id: o.id,
    name: o.id,
    type: 'text',
    inputmode: 'decimal',
    autocomplete: 'off',
    spellcheck: 'false',
    value: String(o.value),
  });
  const msgId = `msg-${o.id}-${++uid}`;
  input.setAttribute('aria-describedby', msgId);
  row.append(input);
  if (o.unit) row.append(el('span', { class: 'unit' }, o.unit));
  const msg = el('div', { class: 'field-msg', id: msgId, 'aria-live': 'polite' });
  root.append(label, row);
  if (o.hint) root.append(el('div', { class: 'field-hint' }, o.hint));
  root.append(msg);

  const setError = (message: string | null) => {
    msg.textContent = message ?? '';
    root.classList.toggle('invalid', !!message);
    if (message) input.setAttribute('aria-invalid', 'true');
    else input.removeAttribute('aria-invalid');
  };
  const unit = o.unit ? ` ${o.unit}` : '';
  const read = (): number | null => {
    const text = input.value;
    if (text.trim() === '') return setError('Enter a value.'), null;
    const v = parseNumber(text);
    if (v === null) return setError(`"${text.trim()}" is not a number.`), null;
    if (o.integer && !Number.isInteger(v)) return setError('Enter a whole number.'), null;
    if (o.positive && v <= 0) return setError(`Must be greater than 0${unit}.`), null;
    if (v < o.min || v > o.max) return setError(`Must be between ${o.min} and ${o.max}${unit}.`), null;
    setError(null);
    return v;
  };
  return { root, input, label, read, setError, set: (v) => ((input.value = String(v)), setError(null)) };
}

export interface SelectOption {
  value: string;
  label: string;
  group?: string;
}

export function selectField(id: string, labelText: string, options: SelectOption[], value: string) {
  const root = el('div', { class: 'field' });
  const label = el('label', { for: id }, labelText);
  const select = el('select', { id, name: id });
  const groups = new Map<string, HTMLOptGroupElement>();
  for (const opt of options) {
    const option = el('option', { value: opt.value }, opt.label);
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
  root.append(label, select);
  return { root, select, label };
}

/** A list of numbers typed as "0.5, 2, 3, 5". */
export function listField(id: string, labelText: string, value: number[], min: number, max: number, hint?: string) {
  const f = numberField({ id, label: labelText, value: 0, min, max, hint });
  f.input.value = value.join(', ');
  f.input.setAttribute('inputmode', 'text');
  const read = (): number[] | null => {
    const parts = f.input.value.split(/[,;\s]+/).filter((p) => p !== '');
    if (parts.length === 0) return f.setError('Enter at least one value.'), null;
    if (parts.length > 8) return f.setError('At most 8 values.'), null;
    const out: number[] = [];
    for (const p of parts) {
      const v = parseNumber(p);
      if (v === null) return f.setError(`"${p}" is not a number.`), null;
      if (v < min || v > max || v === 0) return f.setError(`Each value must be non-zero, between ${min} and ${max}.`), null;
      out.push(v);
    }
    f.setError(null);
    return out;
  };
  return { root: f.root, input: f.input, read, setError: f.setError };
}
