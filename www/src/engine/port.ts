// One engine worker (./worker.ts) and the calls in flight to it: the one protocol of the page's
// workers. A call posts { id, fn, args } (its typed arrays copied and the copies transferred,
// ./transfer.ts) and settles on { id, ok, result | error }; { id, progress } messages go to the
// call's progress callback. A worker that fails (out of memory, say) fails its calls and is
// replaced by the next call. Every call counts as in flight for the idle signal (./idle.ts).
import { callStarted } from './idle';
import { copied } from './transfer';

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

interface Pending {
  resolve: (v: unknown) => void;
  reject: (e: Error) => void;
  progress?: (fraction: number) => void;
  end: () => void;
}

let nextId = 1;

export class EnginePort {
  private worker: Worker | null = null;
  private readonly pending = new Map<number, Pending>();

  /** `name` goes into the message of a worker failure ("engine worker failed: …"). */
  constructor(private readonly name: string) {}

  private get(): Worker {
    if (this.worker) return this.worker;
    const w = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
    w.onmessage = (event: MessageEvent<{ id: number; ok?: boolean; result?: unknown; error?: string; progress?: number }>) => {
      const { id, ok, result, error, progress } = event.data;
      const p = this.pending.get(id);
      if (!p) return;
      if (progress !== undefined) return p.progress?.(progress);
      this.pending.delete(id);
      if (ok) p.resolve(result);
      else p.reject(new EngineError(error ?? `unknown ${this.name} error`));
      p.end();
    };
    w.onerror = (event) => {
      event.preventDefault();
      const err = new EngineError(`${this.name} failed: ${event.message || 'it stopped'}`);
      for (const p of this.pending.values()) {
        p.reject(err);
        p.end();
      }
      this.pending.clear();
      w.terminate();
      this.worker = null;
    };
    this.worker = w;
    return w;
  }

  /** Runs `fn` (an engine export, or `readToolpath`) on `args` in the worker. */
  call<T>(fn: string, args: unknown[], progress?: (fraction: number) => void): Promise<T> {
    const id = nextId++;
    return new Promise<T>((resolve, reject) => {
      this.pending.set(id, { resolve: resolve as (v: unknown) => void, reject, progress, end: callStarted() });
      const { value, transfer } = copied(args);
      this.get().postMessage({ id, fn, args: value }, transfer);
    });
  }
}
