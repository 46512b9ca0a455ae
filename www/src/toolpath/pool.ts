// The toolpath workers: one fewer than the processor has cores (at least 1, at most 6; each holds
// a copy of the path), the twelve types shared among them. Also on `window.fiveaxisToolpath` for the console
// and the benchmark (scripts/bench.mjs).
import type { ParsedToolpath, ToolpathCase, ToolpathPath, ToolpathReadInput, ToolpathSummary } from '@engine';
import { EngineError } from '../engine/client';
import { callStarted } from '../engine/idle';
import { copied } from '../engine/transfer';

/** The twelve types, Group I then Group II (the engine's order). */
export const TYPES = ['ABX', 'ACX', 'BCY', 'BAY', 'CAZ', 'CBZ', 'ABZ', 'ACY', 'BCX', 'BAZ', 'CAY', 'CBX'];

/** Workers the pool uses by default: one core fewer than the processor has (at most 6), so
 *  that the page itself (and the engine's worker, which follows the path on the configuration
 *  shown meanwhile) keeps a core and answers clicks while a large file is ranked. */
export const WORKERS = Math.max(1, Math.min((navigator.hardwareConcurrency || 2) - 1, 6));

interface Job {
  worker: number;
  resolve: (v: unknown) => void;
  reject: (e: Error) => void;
  progress?: (fraction: number) => void;
  /** Ends the job's count of calls in flight (engine/idle.ts). */
  end: () => void;
}

const workers: (Worker | undefined)[] = [];
const jobs = new Map<number, Job>();
let nextId = 1;

function worker(i: number): Worker {
  const existing = workers[i];
  if (existing) return existing;
  const w = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  w.onmessage = (event: MessageEvent<{ id: number; ok?: boolean; result?: unknown; error?: string; progress?: number }>) => {
    const { id, ok, result, error, progress } = event.data;
    const job = jobs.get(id);
    if (!job) return;
    if (progress !== undefined) return job.progress?.(progress);
    jobs.delete(id);
    if (ok) job.resolve(result);
    else job.reject(new EngineError(error ?? 'unknown toolpath error'));
    job.end();
  };
  // A worker that fails (out of memory, say) fails its own jobs and is replaced by the next call.
  w.onerror = (event) => {
    event.preventDefault();
    for (const [id, job] of jobs) {
      if (job.worker !== i) continue;
      jobs.delete(id);
      job.reject(new EngineError(`toolpath worker failed: ${event.message || 'it stopped'}`));
      job.end();
    }
    w.terminate();
    workers[i] = undefined;
  };
  workers[i] = w;
  return w;
}

function run<T>(i: number, message: Record<string, unknown>, progress?: (f: number) => void): Promise<T> {
  const id = nextId++;
  return new Promise<T>((resolve, reject) => {
    jobs.set(id, { worker: i, resolve: resolve as (v: unknown) => void, reject, progress, end: callStarted() });
    // A path's typed arrays are copied and the copies transferred (../engine/transfer.ts).
    const { value, transfer } = copied(message);
    worker(i).postMessage({ id, ...value }, transfer);
  });
}

/** A file read by a worker: the engine's reading, and whether its bytes were not all UTF-8. */
export type ReadFile = ParsedToolpath & { windows1252: boolean };

/** Reads a toolpath file (or text) in a worker, piece by piece; `progress` gets the fraction read. */
export function readToolpath(file: Blob | string, options: ToolpathReadInput, progress?: (fraction: number) => void): Promise<ReadFile> {
  const blob = typeof file === 'string' ? new Blob([file], { type: 'text/plain' }) : file;
  return run<ReadFile>(0, { op: 'read', file: blob, options }, progress);
}

/**
 * The ranking rows of the path on each of `types` (the machine's kind and travel), computed by
 * `workers` workers, in the engine's order (`fiveaxis::toolpath::rank`: the types that follow the
 * whole path first, by largest δ, then mean δ; then the others, the farthest along first).
 */
export async function rankTypes(input: ToolpathCase, path: ToolpathPath | Float64Array, types = TYPES, count = WORKERS): Promise<ToolpathSummary[]> {
  const n = Math.max(1, Math.min(count, types.length));
  const shares = Array.from({ length: n }, (_, i) => types.filter((_, j) => j % n === i));
  const parts = await Promise.all(shares.map((share, i) => run<ToolpathSummary[]>(i, { op: 'summaries', input, path, types: share })));
  // In the types' order first, so that ties keep it, as the engine's stable sort does.
  const rows = parts.flat().sort((a, b) => TYPES.indexOf(a.type) - TYPES.indexOf(b.type));
  const stop = (r: ToolpathSummary) => r.unreachable?.point ?? Infinity;
  return rows.sort((a, b) => stop(b) - stop(a) || a.max - b.max || a.mean - b.mean);
}

(window as unknown as { fiveaxisToolpath: unknown }).fiveaxisToolpath = { readToolpath, rankTypes, TYPES, WORKERS };
