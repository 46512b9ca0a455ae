// The toolpath workers: one fewer than the processor has cores (at least 1, at most 6; each holds
// a copy of the path), the twelve types shared among them. Also on `window.fiveaxisToolpath` for the console
// and the benchmark (scripts/bench.mjs).
import type { ParsedToolpath, RotaryType, ToolpathCase, ToolpathPath, ToolpathReadInput, ToolpathSummary } from '@engine';
import { EngineError } from '../engine/client';
import { callStarted } from '../engine/idle';
import { copied } from '../engine/transfer';
import { loadSchema } from '../ui/form';

/** The twelve rotary-axis types in the engine's order (Group I then Group II): the choices of
 *  the machine's `type` in the engine's schema. */
export async function engineTypes(): Promise<RotaryType[]> {
  const field = (await loadSchema()).machine.find((f) => f.path === 'machine.type');
  if (!field?.choices.length) throw new EngineError('the engine declares no rotary-axis types');
  return field.choices.map((c) => c.value as RotaryType);
}

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

/** Compares two rows by the engine's ranking key (`rank`, numbers compared in turn). */
const byRank = (a: ToolpathSummary, b: ToolpathSummary) => {
  for (let i = 0; i < a.rank.length; i++) if (a.rank[i] !== b.rank[i]) return a.rank[i] - b.rank[i];
  return 0;
};

/**
 * The ranking rows of the path on each of `types` (the engine's twelve when left out; the
 * machine's kind and travel), computed by `workers` workers, in the engine's order: each row
 * carries its place by the engine's rule (`rank`, `fiveaxis::toolpath::rank`), so the rows
 * computed apart are merged by sorting on it.
 */
export async function rankTypes(input: ToolpathCase, path: ToolpathPath | Float64Array, types?: readonly RotaryType[], count = WORKERS): Promise<ToolpathSummary[]> {
  const all = types ?? (await engineTypes());
  const n = Math.max(1, Math.min(count, all.length));
  const shares = Array.from({ length: n }, (_, i) => all.filter((_, j) => j % n === i));
  const parts = await Promise.all(shares.map((share, i) => run<ToolpathSummary[]>(i, { op: 'summaries', input, path, types: share })));
  return parts.flat().sort(byRank);
}

(window as unknown as { fiveaxisToolpath: unknown }).fiveaxisToolpath = { readToolpath, rankTypes, engineTypes, WORKERS };
