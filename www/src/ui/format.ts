// Number formatting for the page: lengths from mm, angles in degrees.

/** "3.292 mm", or "12.35 µm" below 1 mm, "0 µm" for zero. */
export function length(mm: number | null | undefined, digits = 4): string {
  if (mm === null || mm === undefined || !Number.isFinite(mm)) return '—';
  const a = Math.abs(mm);
  if (a === 0) return '0 µm';
  if (a < 1) return `${(mm * 1000).toPrecision(digits)} µm`;
  return `${mm.toPrecision(digits)} mm`;
}

export function num(v: number | null | undefined, digits = 4): string {
  if (v === null || v === undefined || !Number.isFinite(v)) return '—';
  return Number(v.toPrecision(digits)).toString();
}

export function percent(fraction: number | null | undefined, digits = 3): string {
  if (fraction === null || fraction === undefined || !Number.isFinite(fraction)) return '—';
  return `${Number((fraction * 100).toPrecision(digits))} %`;
}

export function vector(v: ArrayLike<number>, digits = 4): string {
  return `(${Array.from(v, (x) => num(Math.abs(x) < 1e-15 ? 0 : x, digits)).join(', ')})`;
}

/** An axis turn or position in degrees to 0.0001° (what controls take), "0°" for rounding
 *  noise. */
export function turn(v: number): string {
  return `${Number(v.toFixed(4)) || 0}°`;
}

export function degrees(v: number, digits = 5): string {
  return `${num(v, digits)}°`;
}

/** At most `max` characters of a text the user gave, for a message: a 10,000-character paste
 *  is quoted by its start and an ellipsis, not repeated whole. */
export function excerpt(text: string, max = 40): string {
  const t = text.replace(/\s+/g, ' ').trim();
  const chars = [...t];
  return chars.length <= max ? t : `${chars.slice(0, max - 1).join('')}…`;
}
