// Display units. The engine works in one system (mm, degrees at its JavaScript API); the page
// converts at the edge: what a field shows and what a plot draws follows the user's choice.
//
// Quantities:
//   'length'    geometry (tool length, part size): always mm
//   'angle'     axis positions: always degrees
//   'errLength' small lengths: machine errors and computed deviations, mm or µm
//   'errAngle'  small angles: machine errors, degrees, radians, arc-seconds or µrad

export type Quantity = 'length' | 'angle' | 'errLength' | 'errAngle' | 'none';
export type LengthUnit = 'mm' | 'um';
export type AngleUnit = 'deg' | 'rad' | 'arcsec' | 'urad';

interface UnitDef {
  /** display value = base value × factor */
  factor: number;
  label: string;
  /** Name in menus. */
  name: string;
}

export const LENGTH_UNITS: Record<LengthUnit, UnitDef> = {
  mm: { factor: 1, label: 'mm', name: 'millimetres (mm)' },
  um: { factor: 1000, label: 'µm', name: 'micrometres (µm)' },
};
export const ANGLE_UNITS: Record<AngleUnit, UnitDef> = {
  deg: { factor: 1, label: '°', name: 'degrees (°)' },
  rad: { factor: Math.PI / 180, label: 'rad', name: 'radians (rad)' },
  arcsec: { factor: 3600, label: '″', name: 'arc-seconds (″)' },
  urad: { factor: (Math.PI / 180) * 1e6, label: 'µrad', name: 'microradians (µrad)' },
};

export interface UnitPrefs {
  length: LengthUnit;
  angle: AngleUnit;
}
export const DEFAULT_UNITS: UnitPrefs = { length: 'um', angle: 'deg' };

const prefs: UnitPrefs = { ...DEFAULT_UNITS };
const listeners = new Set<(p: UnitPrefs) => void>();

export function units(): Readonly<UnitPrefs> {
  return prefs;
}

/** Changes the preferences; listeners (fields, panels) convert what they show. */
export function setUnits(next: Partial<UnitPrefs>) {
  const changed =
    (next.length && next.length !== prefs.length && next.length in LENGTH_UNITS) ||
    (next.angle && next.angle !== prefs.angle && next.angle in ANGLE_UNITS);
  if (!changed) return;
  if (next.length && next.length in LENGTH_UNITS) prefs.length = next.length;
  if (next.angle && next.angle in ANGLE_UNITS) prefs.angle = next.angle;
  for (const l of listeners) l(prefs);
}

export function onUnitsChange(listener: (p: UnitPrefs) => void): () => void {
  listeners.add(listener);
  return () => listeners.delete(listener);
}

export function unitDef(q: Quantity): UnitDef {
  switch (q) {
    case 'length':
      return LENGTH_UNITS.mm;
    case 'angle':
      return ANGLE_UNITS.deg;
    case 'errLength':
      return LENGTH_UNITS[prefs.length];
    case 'errAngle':
      return ANGLE_UNITS[prefs.angle];
    default:
      return { factor: 1, label: '', name: '' };
  }
}

/** Base (mm, degrees) to the unit shown now. */
export function toDisplay(q: Quantity, base: number): number {
  return base * unitDef(q).factor;
}

/** The unit shown now to base (mm, degrees). */
export function fromDisplay(q: Quantity, shown: number): number {
  return shown / unitDef(q).factor;
}

/** "δ (µm)": an axis title with the unit shown now. */
export function titled(text: string, q: Quantity): string {
  const l = unitDef(q).label;
  return l ? `${text} (${l})` : text;
}

/**
 * Below this magnitude (mm or degrees, the base units) a computed value is round-off, not a
 * result: a deviation of 1e-9 mm is a picometre. It is shown as 0.
 */
export const ROUND_OFF = 1e-9;

/** A value as text in the unit shown now, with the unit: "12.35 µm" (round-off shown as 0). */
export function show(q: Quantity, base: number | null | undefined, digits = 4): string {
  if (base === null || base === undefined || !Number.isFinite(base)) return '—';
  const v = Math.abs(base) < ROUND_OFF && (q === 'errLength' || q === 'errAngle') ? 0 : toDisplay(q, base);
  const d = unitDef(q);
  const text = v === 0 ? '0' : Number(v.toPrecision(digits)).toString();
  return d.label === '°' || d.label === '″' ? `${text}${d.label}` : `${text} ${d.label}`;
}

/** Shortest text that reads back as the same number (for converted field values). */
export function numberText(v: number): string {
  if (!Number.isFinite(v)) return '';
  const r = Number(v.toPrecision(12));
  return String(Object.is(r, -0) ? 0 : r);
}
