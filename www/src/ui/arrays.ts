// Extremes of long arrays without spreading them into a call: `Math.max(...a)` passes every
// element as an argument, and throws "Maximum call stack size exceeded" from about 10⁵ of them.

/** The smallest and the largest value of `values` ([Infinity, -Infinity] when empty). NaN is
 *  skipped. */
export function extent(values: ArrayLike<number>): [number, number] {
  let lo = Infinity;
  let hi = -Infinity;
  for (let i = 0; i < values.length; i++) {
    const v = values[i];
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return [lo, hi];
}
