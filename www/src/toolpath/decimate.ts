// Thinning a long toolpath for drawing: Plotly draws a few tens of thousands of points in a
// moment, a million in seconds. The numbers (verdict, ranking, summary) always use every
// segment; only what is drawn is thinned, keeping each run's largest δ, and the plot says so.

/** Most segments drawn in the δ plot (an SVG line). */
export const MOST_DRAWN = 20_000;
/** Most points drawn in the 3D path (WebGL, drawn in software where there is no GPU: on a
 *  two-core machine 8000 points held the main thread 0.7 s there, 2000 points 0.28 s). */
export const MOST_IN_3D = 4_000;

/** The δ plot's series: every segment, or for runs of `step` segments the largest δ of the run's
 *  cutting segments (a gap where a run has none) and of its rapids. x is the segment's number
 *  (from 1) where that largest δ is. */
export interface DeltaSeries {
  step: number;
  cut: { x: number[]; y: (number | null)[] };
  rapid: { x: number[]; y: number[] };
}

export function deltaSeries(delta: ArrayLike<number>, rapid: Uint8Array, most = MOST_DRAWN): DeltaSeries {
  const n = delta.length;
  const step = Math.max(1, Math.ceil(n / most));
  const cut = { x: [] as number[], y: [] as (number | null)[] };
  const fast = { x: [] as number[], y: [] as number[] };
  for (let start = 0; start < n; start += step) {
    const end = Math.min(n, start + step);
    let c = -1;
    let r = -1;
    for (let i = start; i < end; i++) {
      if (rapid[i]) {
        if (r < 0 || delta[i] > delta[r]) r = i;
      } else if (c < 0 || delta[i] > delta[c]) c = i;
    }
    // A run without a cutting segment breaks the cutting line (as a rapid does unthinned).
    cut.x.push((c < 0 ? start : c) + 1);
    cut.y.push(c < 0 ? null : delta[c]);
    if (r >= 0) {
      fast.x.push(r + 1);
      fast.y.push(delta[r]);
    }
  }
  return { step, cut, rapid: fast };
}

/** The points of the 3D path drawn: every one, or every `step`-th and each point where the path
 *  turns from cutting to rapid or back (so that the runs between two points drawn are all cutting
 *  or all rapid), the first and the last. `segments` is the number of segments (points − 1). */
export function pathPoints(segments: number, rapid: Uint8Array, most = MOST_DRAWN): { step: number; keep: Uint32Array } {
  const count = segments + 1;
  const step = Math.max(1, Math.ceil(count / most));
  if (step === 1) return { step, keep: Uint32Array.from({ length: count }, (_, i) => i) };
  const keep: number[] = [];
  for (let i = 0; i < count; i++) {
    const turns = i > 0 && i < segments && rapid[i - 1] !== rapid[i];
    if (i % step === 0 || i === count - 1 || turns) keep.push(i);
  }
  return { step, keep: Uint32Array.from(keep) };
}
