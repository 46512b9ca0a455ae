// Calls into the engine's Web Worker, typed against the .d.ts that wasm-bindgen generates.
import type * as Engine from '@engine';
import { EnginePort } from './port';

type Api = typeof Engine;
/** Names of the engine's exported functions (not the loader). */
export type FnName = Exclude<
  { [K in keyof Api]: Api[K] extends (...args: never[]) => unknown ? K : never }[keyof Api],
  'default' | 'initSync' | 'start'
>;
type Fn<F extends FnName> = Api[F] extends (...args: infer A) => infer R ? (...args: A) => R : never;
export type Args<F extends FnName> = Parameters<Fn<F>>;
export type Result<F extends FnName> = ReturnType<Fn<F>>;

export { EngineError } from './port';

const port = new EnginePort('engine worker');

/** Runs one engine function in the worker. */
export function call<F extends FnName>(fn: F, ...args: Args<F>): Promise<Result<F>> {
  return port.call<Result<F>>(fn, args);
}

/** Returned by a channel for a request that a newer one replaced before it ran or finished. */
export const SUPERSEDED = Symbol('superseded');

/**
 * A channel runs at most one request at a time and keeps only the newest waiting one, so a
 * burst of input changes costs one computation, not one per keystroke, and never shows a
 * stale result after a newer one.
 */
export function channel<F extends FnName>(fn: F) {
  let running = false;
  let waiting: { args: Args<F>; resolve: (v: Result<F> | typeof SUPERSEDED) => void; reject: (e: Error) => void } | null = null;
  let generation = 0;

  const start = (args: Args<F>, resolve: (v: Result<F> | typeof SUPERSEDED) => void, reject: (e: Error) => void) => {
    running = true;
    const mine = ++generation;
    call(fn, ...args).then(
      (r) => finish(() => resolve(mine === generation && !waiting ? r : SUPERSEDED)),
      (e: Error) => finish(() => (mine === generation && !waiting ? reject(e) : resolve(SUPERSEDED))),
    );
  };
  const finish = (settle: () => void) => {
    settle();
    running = false;
    if (waiting) {
      const w = waiting;
      waiting = null;
      start(w.args, w.resolve, w.reject);
    }
  };
  const run = (...args: Args<F>): Promise<Result<F> | typeof SUPERSEDED> =>
    new Promise((resolve, reject) => {
      if (!running) return start(args, resolve, reject);
      waiting?.resolve(SUPERSEDED);
      waiting = { args, resolve, reject };
    });
  /** Drops the waiting request and makes the running one come back SUPERSEDED: for when the
   *  inputs turn invalid, so that a late result does not look current. */
  const cancel = () => {
    generation++;
    waiting?.resolve(SUPERSEDED);
    waiting = null;
  };
  return Object.assign(run, { cancel });
}
