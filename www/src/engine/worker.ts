/// <reference lib="webworker" />
// The engine's Web Worker: every computation of the page runs here, off the main thread.
// Messages in: { id, fn, args } naming an export of the engine; out: { id, ok, result | error }.
import init, * as engine from '@engine';
import { transferables } from './transfer';

const ready = init();
const callable = engine as unknown as Record<string, unknown>;

self.onmessage = async (event: MessageEvent<{ id: number; fn: string; args: unknown[] }>) => {
  const { id, fn, args } = event.data;
  try {
    await ready;
    const f = callable[fn];
    if (typeof f !== 'function' || fn === 'default' || fn === 'initSync') {
      throw new Error(`unknown engine function ${fn}`);
    }
    const result = (f as (...a: unknown[]) => unknown)(...args);
    (self as DedicatedWorkerGlobalScope).postMessage({ id, ok: true, result }, transferables(result));
  } catch (err) {
    const message = err instanceof Error ? err.message : String(err);
    (self as DedicatedWorkerGlobalScope).postMessage({ id, ok: false, error: message });
  }
};
