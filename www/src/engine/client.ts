// Calls into the engine's Web Worker, typed against the .d.ts that wasm-bindgen generates.
import type * as Engine from '@engine';
import { callStarted } from './idle';
import { copied } from './transfer';

type Api = typeof Engine;
/** Names of the engine's exported functions (not the loader). */
export type FnName = Exclude<
  { [K in keyof Api]: Api[K] extends (...args: never[]) => unknown ? K : never }[keyof Api],
  'default' | 'initSync' | 'start'
>;
type Fn<F extends FnName> = Api[F] extends (...args: infer A) => infer R ? (...args: A) => R : never;
export type Args<F extends FnName> = Parameters<Fn<F>>;
export type Result<F extends FnName> = ReturnType<Fn<F>>;

/** An engine error: the message starts with the input field's path, e.g. "start.k: ...". */
export class EngineError extends Error {
  /** The dotted path of the offending field, or "" when the message names none. */
  readonly field: string;
  constructor(message: string) {
    super(message);
    this.name = 'EngineError';
    const m = /^([A-Za-z][\w.[\]]*): /.exec(message);
    this.field = m ? m[1] : '';
  }

  /** The message without its path (for a message shown at the field the path names). */
  get text(): string {
    return this.field ? this.message.slice(this.field.length + 2) : this.message;
  }

  /** `err` as an EngineError (a worker failure becomes one that names no field). */
  static of(err: unknown): EngineError {
    return err instanceof EngineError ? err : new EngineError(String(err));
  }
}

let worker: Worker | null = null;
let nextId = 1;
const pending = new Map<number, { resolve: (v: unknown) => void; reject: (e: Error) => void; end: () => void }>();

function getWorker(): Worker {
  if (worker) return worker;
  worker = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  worker.onmessage = (event: MessageEvent<{ id: number; ok: boolean; result?: unknown; error?: string }>) => {
    const { id, ok, result, error } = event.data;
    const p = pending.get(id);
    if (!p) return;
    pending.delete(id);
    if (ok) p.resolve(result);
    else p.reject(new EngineError(error ?? 'unknown engine error'));
    p.end();
  };
  worker.onerror = (event) => {
    const err = new EngineError(`engine worker failed: ${event.message}`);
    for (const p of pending.values()) {
      p.reject(err);
      p.end();
    }
    pending.clear();
  };
  return worker;
}

/** Runs one engine function in the worker. */
export function call<F extends FnName>(fn: F, ...args: Args<F>): Promise<Result<F>> {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve: resolve as (v: unknown) => void, reject, end: callStarted() });
    // The arguments' typed arrays (a toolpath's points) are copied and the copies transferred.
    const { value, transfer } = copied(args);
    getWorker().postMessage({ id, fn, args: value }, transfer);
  });
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
