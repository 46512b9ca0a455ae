// Typed arrays across a worker boundary. postMessage copies a typed array by serialising it on
// the sending thread, at a few hundred MB/s: a 10⁶-point path (about 56 MB) sent to three workers
// held the page's main thread for 0.65 s. A copy made with `slice()` is a memory copy, ten times
// faster, and transferring the copy costs nothing; the sender keeps its own arrays.

type View = ArrayBufferView & { slice?: () => ArrayBufferView };

/** The ArrayBuffers of every typed array in `value` (objects and arrays walked 4 levels deep),
 *  for a transfer list: they move instead of being copied. */
export function transferables(value: unknown, out: Transferable[] = [], depth = 0): Transferable[] {
  if (depth > 4 || value === null || typeof value !== 'object') return out;
  if (ArrayBuffer.isView(value)) {
    if (value.buffer instanceof ArrayBuffer && !out.includes(value.buffer)) out.push(value.buffer);
    return out;
  }
  for (const v of Array.isArray(value) ? value : Object.values(value)) transferables(v, out, depth + 1);
  return out;
}

/** `value` with each typed array (4 levels deep) replaced by a copy of it, and the copies'
 *  buffers to transfer: a message as postMessage would have copied it, without the cost. */
export function copied<T>(value: T): { value: T; transfer: Transferable[] } {
  const transfer: Transferable[] = [];
  const walk = (v: unknown, d: number): unknown => {
    if (d > 4 || v === null || typeof v !== 'object') return v;
    if (ArrayBuffer.isView(v)) {
      const view = v as View;
      if (!(view.buffer instanceof ArrayBuffer) || typeof view.slice !== 'function') return v;
      const copy = view.slice();
      transfer.push(copy.buffer as ArrayBuffer);
      return copy;
    }
    if (Array.isArray(v)) return v.map((x) => walk(x, d + 1));
    if (Object.getPrototypeOf(v) !== Object.prototype) return v;
    return Object.fromEntries(Object.entries(v).map(([k, x]) => [k, walk(x, d + 1)]));
  };
  return { value: walk(value, 0) as T, transfer };
}
