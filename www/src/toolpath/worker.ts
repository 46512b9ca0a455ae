/// <reference lib="webworker" />
// A toolpath worker: reads a file piece by piece (so that a large file never becomes one string,
// and the page shows progress), and computes the ranking rows of the types it is given. The page
// keeps a few of them (./pool.ts), one per processor core.
// Messages in: { id, op: 'read', file, options } | { id, op: 'summaries', input, path, types };
// out: { id, progress } while reading, then { id, ok, result | error }.
import init, * as engine from '@engine';
import { utf8Check } from '../ui/decode';

const ready = init();
const post = (msg: unknown, transfer: Transferable[] = []) => (self as DedicatedWorkerGlobalScope).postMessage(msg, transfer);

/** Reads `file` through the engine's ToolpathReader, its bytes as they come (the engine decodes
 *  them: UTF-8, else Windows-1252, and refuses an image or an archive by its first bytes),
 *  posting the fraction of bytes read. The result says whether the bytes were all UTF-8
 *  (`windows1252` when not: the page notes it beside the file). */
async function read(id: number, file: Blob, options: engine.ToolpathReadInput) {
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
    const result = reader.finish() as engine.ParsedToolpath;
    const p = result.path;
    const transfer = [p.points.buffer, p.motions.buffer, result.lines.buffer, ...(p.angles ? [p.angles.buffer] : [])] as ArrayBuffer[];
    post({ id, ok: true, result: { ...result, windows1252: !utf8.finish() } }, transfer);
  } finally {
    reader.free();
  }
}

self.onmessage = async (event: MessageEvent) => {
  const msg = event.data as
    | { id: number; op: 'read'; file: Blob; options: engine.ToolpathReadInput }
    | { id: number; op: 'summaries'; input: engine.ToolpathCase; path: engine.ToolpathPath; types: string[] };
  try {
    await ready;
    if (msg.op === 'read') return await read(msg.id, msg.file, msg.options);
    post({ id: msg.id, ok: true, result: engine.toolpathCompare(msg.input, msg.path, msg.types as engine.RotaryType[]) });
  } catch (err) {
    post({ id: msg.id, ok: false, error: err instanceof Error ? err.message : String(err) });
  }
};
