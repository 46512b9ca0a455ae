// The toolpath workers: one fewer than the processor has cores (at least 1, at most 6; each holds
// a copy of the path), the twelve types shared among them. Each is an engine worker
// (../engine/worker.ts, driven by ../engine/port.ts), the same protocol as the engine's own. Also on `window.fiveaxisToolpath` for the console
// and the benchmark (scripts/bench.mjs).
import type { RotaryType, ToolpathCase, ToolpathPath, ToolpathReadInput, ToolpathSummary } from '@engine';
import { EngineError, EnginePort } from '../engine/port';
import type { ReadFile } from '../engine/worker';
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

const ports: EnginePort[] = [];
const port = (i: number) => (ports[i] ??= new EnginePort('toolpath worker'));

export type { ReadFile };

/** Reads a toolpath file (or text) in a worker, piece by piece; `progress` gets the fraction read. */
export function readToolpath(file: Blob | string, options: ToolpathReadInput, progress?: (fraction: number) => void): Promise<ReadFile> {
  const blob = typeof file === 'string' ? new Blob([file], { type: 'text/plain' }) : file;
  return port(0).call<ReadFile>('readToolpath', [blob, options], progress);
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
  const parts = await Promise.all(shares.map((share, i) => port(i).call<ToolpathSummary[]>('toolpathCompare', [input, path, share])));
  return parts.flat().sort(byRank);
}

(window as unknown as { fiveaxisToolpath: unknown }).fiveaxisToolpath = { readToolpath, rankTypes, engineTypes, WORKERS };
