/// <reference lib="webworker" />
// The engine's Web Worker: every computation of the page runs here, off the main thread.
// Messages in: { id, fn, args } naming an export of the engine; out: { id, ok, result | error }.
import init, * as engine from '@engine';

const ready = init();
const callable = engine as unknown as Record<string, unknown>;

/** The ArrayBuffers of every typed array in `value`, so they move instead of being copied. */
function transferables(value: unknown, out: Transferable[] = [], depth = 0): Transferable[] {
  if (depth > 4 || value === null || typeof value !== 'object') return out;
  if (ArrayBuffer.isView(value)) {
    if (value.buffer instanceof ArrayBuffer && !out.includes(value.buffer)) out.push(value.buffer);
    return out;
  }
  for (const v of Array.isArray(value) ? value : Object.values(value)) transferables(v, out, depth + 1);
  return out;
}

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
