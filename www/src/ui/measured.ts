// The identification of a measurement on a panel (the probe-and-sphere and the rotary ball-bar
// panels): the request to the engine and its state, what is on screen and what it came from, and
// how a file that cannot be used is said. The panel keeps its inputs and its views (`MeasuredViews`).
import { EngineError, SUPERSEDED } from '../engine/client';
import type { Verdict } from './verdict';

/** The identification: no measurement, on its way, done (its result), or refused (why). */
export type MeasuredState<R, F> =
  | { s: 'none' }
  | { s: 'pending'; from: F }
  | { s: 'ok'; r: R; from: F }
  | { s: 'error'; message: string; from: F };

/** What the panel draws and clears; `F` says where a measurement came from. */
export interface MeasuredViews<R, F> {
  /** The source in a sentence ("probe.csv", "the sample …"). */
  name(from: F): string;
  /** What an earlier result came from when it is not known ("the file before it"). */
  before: string;
  /** The panel's alert line, over its results. */
  alert: HTMLElement;
  /** "Use these errors" and its message. */
  useButton: HTMLButtonElement;
  useMsg: HTMLElement;
  /** Greys every output of the identification (it no longer answers the inputs), with `why`. */
  grey(why?: string): void;
  /** No measurement: the outputs say how to give one. */
  clear(): void;
  /** Draws a result. */
  show(r: R, from: F): void;
  /** Recomputes the verdict. */
  judge(): void;
  /** The measurement's field: its message cleared, or the engine's error shown at its field. */
  fieldOk(): void;
  fieldError(e: unknown): void;
}

/** A request channel of the engine (`channel('probeIdentify')`). */
interface Run<I, R> {
  (input: I): Promise<R | typeof SUPERSEDED>;
  cancel(): void;
}

/** The identification of a panel's measurement, drawn through `v`. */
export function measured<I extends { csv: string }, R, F>(run: Run<I, R>, v: MeasuredViews<R, F>) {
  let state: MeasuredState<R, F> = { s: 'none' };
  /** The result on screen (current or greyed) and what it came from. */
  let shown: { r: R; from: F } | null = null;

  const setAlert = (text: string | null) => {
    v.alert.textContent = text ?? '';
    v.alert.hidden = !text;
    if (text) v.alert.scrollIntoView({ block: 'nearest' });
  };
  const clear = () => {
    shown = null;
    v.clear();
    v.useButton.disabled = true;
  };

  /** A measurement that cannot be used (`message`): said at the top, the last result greyed. */
  const refuse = (from: F, message: string) => {
    run.cancel();
    state = { s: 'error', message, from };
    const name = v.name(from);
    message = /[.!?]$/.test(message) ? message : `${message}.`;
    const last = shown ? ` The results below are greyed: they belong to ${v.name(shown.from)}.` : '';
    setAlert(`No identification from ${name}: ${message}${last}`);
    v.grey(`Greyed: ${name} could not be used (${message.replace(/\.$/, '')}). This is the result of ${shown ? v.name(shown.from) : v.before}.`);
    v.useButton.disabled = true;
    v.judge();
  };

  /** Identifies `input` (its measurement from `from`); an empty measurement clears the outputs. */
  const identify = (input: I, from: F) => {
    if (input.csv.trim() === '') {
      v.fieldOk();
      setAlert(null);
      run.cancel();
      state = { s: 'none' };
      clear();
      v.judge();
      return;
    }
    state = { s: 'pending', from };
    v.useButton.disabled = true;
    v.judge();
    run(input).then((r) => {
      if (r === SUPERSEDED) return;
      v.fieldOk();
      setAlert(null);
      state = { s: 'ok', r, from };
      if (shown?.from !== from) v.useMsg.textContent = '';
      shown = { r, from };
      v.show(r, from);
      v.useButton.disabled = false;
      v.judge();
    }, (e) => {
      const text = EngineError.of(e).text;
      refuse(from, text);
      v.fieldError(e);
    });
  };

  /** The panel's inputs are invalid: no request, the outputs greyed, a request on its way dropped. */
  const invalid = () => {
    run.cancel();
    if (state.s === 'pending') state = shown ? { s: 'ok', r: shown.r, from: shown.from } : { s: 'none' };
    v.grey();
    v.useButton.disabled = true;
  };

  /**
   * The verdict while there is no result to judge: `none` (how to give a measurement), on its
   * way, or refused; returns the result to judge, or null when the verdict is said here.
   */
  const toJudge = (verdict: Verdict, none: string): { r: R; from: F } | null => {
    const st = state;
    if (st.s === 'ok') return { r: st.r, from: st.from };
    if (st.s === 'none') verdict.none(none);
    else if (st.s === 'pending') verdict.pending(`Identifying the errors from ${v.name(st.from)}…`);
    else verdict.none(`No verdict: ${v.name(st.from)} could not be used (${st.message}).${shown ? ` The results below are greyed: they belong to ${v.name(shown.from)}.` : ''}`);
    return null;
  };

  return {
    /** The state of the identification. */
    get state() { return state; },
    /** The result on screen (current or greyed). */
    get shown() { return shown; },
    identify,
    refuse,
    invalid,
    clear,
    toJudge,
  };
}
