/// <reference lib="webworker" />
// The engine's Web Worker, the one protocol every worker of the page speaks (./port.ts drives
// it): the engine's worker (./client.ts) and the toolpath pool's (../toolpath/pool.ts) are
// instances of this module.
// In:  { id, fn, args } naming an export of the engine, or `readToolpath` (a file read piece by
//      piece through the engine's ToolpathReader, so that a large file never becomes one string).
// Out: { id, progress } while a file is read, then { id, ok: true, result } or
//      { id, ok: false, error }. Typed arrays of a result are transferred, not copied.
import init, * as engine from '@engine';
import { utf8Check } from '../ui/decode';
import { transferables } from './transfer';

/** A module of one function that uses WebAssembly SIMD (`i32.const 0; i8x16.splat;
 *  i8x16.popcnt`): valid only where the browser runs SIMD, which the engine is built with. */
const SIMD_PROBE = new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 10, 1, 8, 0, 65, 0, 253, 15, 253, 98, 11]);
// A browser without SIMD cannot compile the engine: say so rather than the compiler's words.
const ready = init().catch((err: unknown) => {
  if (!WebAssembly.validate(SIMD_PROBE)) {
    throw new Error('this browser cannot run the engine: it lacks WebAssembly SIMD (Chrome or Edge 91, Firefox 89, Safari 16.4 or later have it)');
  }
  throw err;
});
const callable = engine as unknown as Record<string, unknown>;
const post = (msg: unknown, transfer: Transferable[] = []) => (self as DedicatedWorkerGlobalScope).postMessage(msg, transfer);

/** A file read: the engine's reading, and whether its bytes were not all UTF-8 (`windows1252`:
 *  the page notes it beside the file). */
export type ReadFile = engine.ParsedToolpath & { windows1252: boolean };

/** Reads `file` through the engine's ToolpathReader, its bytes as they come (the engine decodes
 *  them: UTF-8, else Windows-1252, and refuses an image or an archive by its first bytes),
 *  posting the fraction of bytes read. */
async function readToolpath(id: number, file: Blob, options: engine.ToolpathReadInput): Promise<ReadFile> {
  const reader = new engine.ToolpathReader(options);
  const utf8 = utf8Check();
  try {
    const source = file.stream().getReader();
    let bytes = 0;
    let shown = 0;
    for (;;) {
      const { value, done } = await source.read();
      if (done) break;
      bytes += value.byteLength;
      utf8.feed(value);
      reader.feed(value);
      if (bytes - shown > file.size / 50) {
        shown = bytes;
        post({ id, progress: bytes / Math.max(1, file.size) });
      }
    }
    return { ...(reader.finish() as engine.ParsedToolpath), windows1252: !utf8.finish() };
  } finally {
    reader.free();
  }
}

self.onmessage = async (event: MessageEvent<{ id: number; fn: string; args: unknown[] }>) => {
  const { id, fn, args } = event.data;
  try {
    await ready;
    let result: unknown;
    if (fn === 'readToolpath') {
      result = await readToolpath(id, args[0] as Blob, args[1] as engine.ToolpathReadInput);
    } else {
      const f = callable[fn];
      if (typeof f !== 'function' || fn === 'default' || fn === 'initSync') {
        throw new Error(`unknown engine function ${fn}`);
      }
      result = (f as (...a: unknown[]) => unknown)(...args);
    }
    post({ id, ok: true, result }, transferables(result));
  } catch (err) {
    post({ id, ok: false, error: err instanceof Error ? err.message : String(err) });
  }
};
