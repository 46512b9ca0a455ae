// The verdict at the top of every panel's results: a tolerance (an ordinary field of the panel,
// carried in share links, saved cases and the printed report), a pass/fail badge, one plain
// sentence with the worst value and what to do, the contributors ranked by their share, and the
// papers' equations and symbols one level down (a <details>, never the headline).
//
// The numbers come from the engine's results; the panel only compares them with the tolerance,
// ranks and formats them. `data-verdict` is "pass", "fail" or "none" (nothing to judge yet,
// inputs invalid, a computation on its way): "none" never shows the badge of earlier inputs.
import type { Machine, Schema } from '@engine';
import { EngineError } from '../engine/client';
import { el, numberField } from './fields';
import * as fmt from './format';
import { blockedBy, fieldLinks, invalidFields } from './status';
import { show as showValue } from './units';

export type VerdictStatus = 'pass' | 'fail' | 'none';

/** One contributor to the worst value: its name, what it is in words, its share (0..1). */
export interface Contributor {
  /** ISO 230-1 name or a short name ("E_X0B", "tool radius"). */
  name: string;
  /** What it is, in plain words ("B axis offset along X"). */
  label?: string;
  /** Tooltip: the plain meaning, the ISO 230-1 name and the paper's symbol. */
  title?: string;
  /** Its share of the worst value, 0..1. */
  share: number;
  /** Its amount, formatted ("+3.2 µm"). */
  amount?: string;
}

export interface Judgement {
  status: Exclude<VerdictStatus, 'none'>;
  /** The headline: plain words, the worst value, the tolerance, what to do. */
  sentence: string;
  /** The worst value judged, mm (data-worst, for tests and the report). */
  worst: number;
  /** The tolerance it was compared with, mm. */
  tolerance: number;
  /** Ranked by share, largest first (the component keeps the order it is given). */
  contributors?: Contributor[];
  /** What the contributors' shares are of ("of the worst zone's height"). */
  contributorsOf?: string;
  /** Further plain lines under the headline. */
  notes?: string[];
  /** What was judged, when not the inputs on screen: the file's name ("impeller.apt"). */
  source?: string;
  /** The errors entered that this test cannot see (its result does not change with them): null
   *  when it sees every one entered; left out when the study does not say. */
  unseen?: Unseen | null;
  /** What `worst` and `tolerance` are when not a small length in mm: 'errAngle' (degrees) for a
   *  rotary axis's positioning (data-quantity, for the report). */
  quantity?: 'errLength' | 'errAngle';
  /** What is judged, when not what the tolerance field's label says (a study with several
   *  tolerances names the one that decides: "Reversal B"); data-what, for the report. */
  what?: string;
}

/** Errors entered that a study cannot see: which study, and each error with its value. */
export interface Unseen {
  /** The study as the subject of a sentence ("the cubic test"). */
  by: string;
  /** Each unseen error entered: its ISO name and its value as entered, formatted. */
  errors: { name: string; value: string }[];
  /** Why, when it is not a property of the test's positions ("its result is computed without
   *  the machine's errors"). */
  why?: string;
}

export interface VerdictOptions {
  /** The panel's field prefix ("nl"): the section is `<prefix>-verdict`. */
  prefix: string;
  /** The tolerance field: made here (`<prefix>-tolerance`), or a field the panel rendered from
   *  the engine's schema (moved into the verdict, so the tolerance sits next to the badge). */
  tolerance:
    | { label: string; value: number; max?: number; hint?: string }
    | { adopt: { root: HTMLElement; input: HTMLInputElement; read(): unknown } };
  /** Called when the tolerance is edited (the panel judges its last results again). */
  onTolerance: () => void;
}

export interface Verdict {
  readonly root: HTMLElement;
  readonly input: HTMLInputElement;
  /** The tolerance in mm, or null (its message shown at the field). */
  tolerance(): number | null;
  /** Shows a verdict. */
  show(j: Judgement): void;
  /** Nothing to judge: says why (no stale badge). */
  none(message: string): void;
  /** No verdict because inputs are invalid: names each field marked and where it is (this tab or
   *  the Machine section), with a button that goes to it; `otherwise` when none is marked. */
  invalid(otherwise?: string): void;
  /** No verdict because the engine refused the inputs or failed: its message. */
  error(message: string): void;
  /** After an engine error was shown (at its field, or over a plot): `invalid()` when a field
   *  is marked now, else `error()` with the engine's message. */
  refused(err: unknown): void;
  /** Inputs changed, a result is on its way: the badge says so, the last sentence stays greyed;
   *  or, with `message`, says what is being done ("Reading impeller.apt…") instead. */
  pending(message?: string): void;
  /** The papers' level: replaces the contents of the <details>. */
  details(summary: string, ...body: (Node | string)[]): void;
}

const BADGE: Record<VerdictStatus, string> = { pass: 'PASS', fail: 'FAIL', none: 'NO VERDICT' };
/** The four states a verdict is in (`data-state`): a result, being computed, invalid input, an
 *  engine error; and "none" for nothing to judge (no tolerance, an empty file). */
type State = 'result' | 'computing' | 'invalid' | 'error' | 'none';
const STATE_BADGE: Partial<Record<State, string>> = { computing: 'COMPUTING…', invalid: 'NO VERDICT', error: 'ENGINE ERROR' };

/** Makes the verdict section; the panel puts `root` first in its results. */
export function verdictBox(o: VerdictOptions): Verdict {
  const root = el('section', { class: 'verdict', id: `${o.prefix}-verdict`, 'data-verdict': 'none', 'aria-labelledby': `${o.prefix}-verdict-sentence` });
  const head = el('div', { class: 'verdict-head' });
  const badge = el('span', { class: 'verdict-badge', id: `${o.prefix}-verdict-badge` }, BADGE.none);
  const sentence = el('p', { class: 'verdict-sentence', id: `${o.prefix}-verdict-sentence`, 'aria-live': 'polite' }, 'Computing…');
  // The tolerance as printed beside the badge (the field itself is an input, not printed).
  const printedTolerance = el('span', { class: 'verdict-printed-tolerance', id: `${o.prefix}-verdict-printed-tolerance` });
  head.append(badge, printedTolerance, sentence);
  root.dataset.state = 'computing';
  badge.textContent = STATE_BADGE.computing ?? '';
  /** What the verdict was computed from and when ("Computed 14:02:31 from impeller.apt"). */
  const source = el('p', { class: 'verdict-source', id: `${o.prefix}-verdict-source` });
  /** Buttons to the invalid fields. */
  const links = el('div', { class: 'verdict-links', id: `${o.prefix}-verdict-links` });
  const notes = el('ul', { class: 'verdict-notes', id: `${o.prefix}-verdict-notes` });
  const contrib = el('div', { class: 'verdict-contrib', id: `${o.prefix}-verdict-contrib` });
  const paper = el('details', { class: 'verdict-details', id: `${o.prefix}-verdict-details` });
  const paperSummary = el('summary', {}, 'From the paper: equations and symbols');
  const paperBody = el('div', { class: 'verdict-details-body' });
  paper.append(paperSummary, paperBody);
  paper.hidden = true;

  let field: { root: HTMLElement; input: HTMLInputElement; read(): unknown };
  if ('adopt' in o.tolerance) {
    field = o.tolerance.adopt;
  } else {
    field = numberField({
      id: `${o.prefix}-tolerance`,
      label: o.tolerance.label,
      quantity: 'errLength',
      value: o.tolerance.value,
      min: 0,
      max: o.tolerance.max ?? 10,
      positive: true,
      hint: o.tolerance.hint,
    });
  }
  const fieldRoot = field.root;
  fieldRoot.classList.add('verdict-tolerance');
  // Edits of the tolerance reach the panel here; they still bubble to the page (saved state).
  field.input.addEventListener('input', () => o.onTolerance());
  root.append(head, links, source, fieldRoot, notes, contrib, paper);

  const set = (status: VerdictStatus, state: State = status === 'none' ? 'none' : 'result') => {
    root.dataset.verdict = status;
    root.dataset.state = state;
    badge.textContent = STATE_BADGE[state] ?? BADGE[status];
    links.replaceChildren();
    if (state !== 'computing') source.textContent = '';
  };
  const clear = () => {
    notes.replaceChildren();
    contrib.replaceChildren();
    delete root.dataset.worst;
    delete root.dataset.tolerance;
    delete root.dataset.unseen;
    delete root.dataset.sees;
    delete root.dataset.quantity;
    delete root.dataset.what;
    printedTolerance.textContent = '';
  };
  const none = (message: string, state: State) => {
    set('none', state);
    root.classList.remove('stale');
    sentence.textContent = message;
    clear();
  };

  return {
    root,
    input: field.input,
    tolerance: () => {
      const v = field.read();
      return typeof v === 'number' ? v : null;
    },
    show(j) {
      set(j.status);
      root.classList.remove('stale');
      sentence.textContent = j.sentence;
      const time = new Date().toTimeString().slice(0, 8);
      source.textContent = `Computed at ${time} from ${j.source ?? 'the inputs shown'}.`;
      root.dataset.worst = String(j.worst);
      root.dataset.tolerance = String(j.tolerance);
      const q = j.quantity ?? 'errLength';
      root.dataset.quantity = q;
      if (j.what) root.dataset.what = j.what;
      else delete root.dataset.what;
      const label = j.what ?? (fieldRoot.querySelector('label')?.textContent?.trim() || 'Tolerance');
      printedTolerance.textContent = `${label}: ${showValue(q, j.tolerance)}`;
      notes.replaceChildren(...(j.notes ?? []).map((n) => el('li', {}, n)));
      if (j.unseen === undefined) delete root.dataset.sees;
      else root.dataset.sees = j.unseen ? 'some' : 'all';
      if (j.unseen && j.unseen.errors.length) {
        root.dataset.unseen = j.unseen.errors.map((e) => e.name).join(' ');
        notes.append(el('li', { class: 'verdict-unseen' }, unseenSentence(j.unseen)));
      } else delete root.dataset.unseen;
      contrib.replaceChildren();
      const list = (j.contributors ?? []).filter((c) => c.share > 0);
      if (list.length) {
        contrib.append(el('p', { class: 'verdict-contrib-title' }, `Where it comes from${j.contributorsOf ? ` (${j.contributorsOf})` : ''}:`));
        const ol = el('ol');
        for (const c of list) {
          const li = el('li');
          li.dataset.name = c.name;
          li.dataset.share = String(c.share);
          const bar = el('span', { class: 'verdict-bar', 'aria-hidden': 'true' });
          bar.style.setProperty('--share', String(Math.min(1, Math.max(0, c.share))));
          const text = el('span', { class: 'verdict-contrib-text' });
          const tip = c.title ?? c.label;
          const name = el('b', tip ? { title: tip, tabindex: '0' } : {}, c.name);
          text.append(name, ` ${c.label ? `${c.label}: ` : ''}${fmt.percent(c.share, 2)}${c.amount ? ` (${c.amount})` : ''}`);
          li.append(bar, text);
          ol.append(li);
        }
        contrib.append(ol);
      }
    },
    none(message) {
      none(message, 'none');
    },
    invalid(otherwise = 'an input is missing') {
      const list = invalidFields(root);
      none(`No verdict: ${blockedBy(list, otherwise)}.`, 'invalid');
      if (list.length) links.replaceChildren(fieldLinks(list));
    },
    error(message) {
      none(`No verdict: the engine refused the inputs: ${message}`, 'error');
    },
    refused(err) {
      const e = EngineError.of(err);
      if (invalidFields(root).length) this.invalid();
      else this.error(e.field === 'machine' ? e.text : e.message);
    },
    pending(message) {
      // A result shown stays, greyed, until the new one replaces it; a message goes.
      const shown = root.dataset.state === 'result' || (root.dataset.state === 'computing' && root.classList.contains('stale'));
      set('none', 'computing');
      if (shown && !message) return void root.classList.add('stale');
      root.classList.remove('stale');
      source.textContent = '';
      sentence.textContent = message ?? 'Computing…';
      clear();
    },
    details(summary, ...body) {
      paperSummary.textContent = summary;
      paperBody.replaceChildren(...body);
      paper.hidden = body.length === 0;
    },
  };
}

/** Pass when the worst value is within the tolerance, the boundary included (|worst| ≤ tolerance): the one comparison every panel makes. */
export function judge(worst: number, tolerance: number): Exclude<VerdictStatus, 'none'> {
  return Math.abs(worst) <= tolerance ? 'pass' : 'fail';
}

/**
 * Contributors ranked by the size of their part (absolute), shares of the sum of those sizes;
 * `parts` as [name, signed amount, label]. Zero parts are left out.
 */
export function rankParts(parts: [string, number][], amount: (v: number) => string,
  words?: Map<string, { label: string; title: string }>): Contributor[] {
  const total = parts.reduce((s, [, v]) => s + Math.abs(v), 0);
  if (!(total > 0)) return [];
  return parts
    .filter(([, v]) => v !== 0)
    .map(([name, v]) => ({ name, label: words?.get(name)?.label, title: words?.get(name)?.title, share: Math.abs(v) / total, amount: amount(v) }))
    // A part below a millionth of the whole is rounding, not a contributor.
    .filter((c) => c.share > 1e-6)
    .sort((a, b) => b.share - a.share);
}

/** The machine's errors in words, from the engine's schema: a short label and a tooltip with the
 *  plain meaning, the ISO 230-1 name and the papers' symbols. */
export function errorWords(schema: Schema): Map<string, { label: string; title: string }> {
  const out = new Map<string, { label: string; title: string }>();
  for (const d of [...schema.errors, ...schema.motions]) {
    const aliases = d.aliases.map((a) => `${a.symbol} in ${a.source} (${d.name} = ${a.sign < 0 ? '−' : ''}${a.symbol})`).join('; ');
    out.set(d.name, { label: d.label, title: `${d.label} (ISO 230-1: ${d.name}). ${d.description}${aliases ? ` Paper symbol: ${aliases}.` : ''}` });
  }
  return out;
}

/** "Squareness of Y to X" → "squareness of Y to X" (after "the"); "X yaw" stays. */
export function lowerFirst(text: string): string {
  return /^[A-Z][a-z]/.test(text) ? text[0].toLowerCase() + text.slice(1) : text;
}

/** "a", "a and b", "a, b and c". */
export function listWords(items: string[]): string {
  return items.length < 2 ? (items[0] ?? '') : `${items.slice(0, -1).join(', ')} and ${items[items.length - 1]}`;
}

/** "The cubic test cannot see E_X0C and E_Y0C (entered: 12 µm and −8 µm)." */
export function unseenSentence(u: Unseen): string {
  const by = u.by[0].toUpperCase() + u.by.slice(1);
  return `${by} cannot see ${listWords(u.errors.map((e) => e.name))} (entered: ${listWords(u.errors.map((e) => e.value))})${u.why ? `: ${u.why}` : ''}.`;
}

/** The errors and error motions entered on the machine, each with its value as shown (a motion
 *  given as a table or a polynomial: "a table", "a polynomial"). */
export function enteredErrors(machine: Machine, schema: Schema): { name: string; value: string }[] {
  const quantity = new Map([...schema.errors, ...schema.motions].map((d) => [d.name, d.quantity]));
  const shown = (name: string, v: number) => showValue(quantity.get(name) === 'smallAngle' ? 'errAngle' : 'errLength', v).replace(/^-/, '−');
  const out: { name: string; value: string }[] = [];
  for (const [name, v] of Object.entries(machine.errors ?? {})) if (typeof v === 'number' && v !== 0) out.push({ name, value: shown(name, v) });
  for (const [name, f] of Object.entries(machine.motions ?? {})) {
    if (typeof f === 'number') {
      if (f !== 0) out.push({ name, value: shown(name, f) });
    } else if (f && typeof f === 'object') out.push({ name, value: 'poly' in f ? 'a polynomial' : 'a table' });
  }
  return out;
}

/** Of the errors entered, those `sees` says the study cannot see; null when it sees them all. */
export function unseenOf(by: string, machine: Machine, schema: Schema, sees: (name: string) => boolean, why?: string): Unseen | null {
  const errors = enteredErrors(machine, schema).filter((e) => !sees(e.name));
  return errors.length ? { by, errors, ...(why ? { why } : {}) } : null;
}
