// The page state: every input of every panel, the open panel and the unit preferences.
// It round-trips through the URL fragment (share links; the fragment never reaches a server),
// through local storage (inputs kept across reloads) and through named cases (JSON).
//
// A state holds only what differs from the defaults: field id → text as shown.
import { fields } from './fields';
import { excerpt } from './format';
import { DEFAULT_UNITS, setUnits, units, type UnitPrefs, ANGLE_UNITS, LENGTH_UNITS } from './units';

export const STATE_VERSION = 2;
const STORAGE_KEY = 'fiveaxis:state:v2';
const CASES_KEY = 'fiveaxis:cases:v2';
/** Above this many characters a link is compressed (deflate + base64url). */
const PLAIN_LIMIT = 1200;

export interface PageState {
  v: number;
  /** The open panel. */
  p: string;
  u: UnitPrefs;
  /** Field id → text, only where it differs from the default. */
  f: Record<string, string>;
}

/** Values for fields of panels not mounted yet (applied when they mount). */
const pending = new Map<string, string>();

export function capture(panel: string): PageState {
  const f: Record<string, string> = Object.fromEntries(pending);
  for (const h of fields.values()) {
    const t = h.text();
    if (t !== h.defaultText()) f[h.id] = t;
  }
  return { v: STATE_VERSION, p: panel, u: { ...units() }, f };
}

/** Applies a state: units first (fields convert), then every field that exists; the rest waits. */
export function apply(state: PageState) {
  setUnits(state.u);
  pending.clear();
  for (const h of fields.values()) {
    const t = state.f[h.id] ?? h.defaultText();
    if (h.text() !== t) h.setText(t);
  }
  for (const [id, t] of Object.entries(state.f)) if (!fields.has(id)) pending.set(id, t);
}

/** After a panel mounted: applies its waiting values; returns ids no field recognised. */
export function applyPending(prefix: string): string[] {
  const unknown: string[] = [];
  for (const [id, t] of [...pending]) {
    if (!id.startsWith(`${prefix}-`)) continue;
    pending.delete(id);
    const h = fields.get(id);
    if (h) h.setText(t);
    else unknown.push(id);
  }
  return unknown;
}

/** Restores the defaults of one panel's fields. */
export function resetPanel(prefix: string) {
  for (const id of [...pending.keys()]) if (id.startsWith(`${prefix}-`)) pending.delete(id);
  for (const h of fields.values()) {
    if (h.id.startsWith(`${prefix}-`) && h.text() !== h.defaultText()) h.setText(h.defaultText());
  }
}

// ---- encoding

function toBase64Url(bytes: Uint8Array): string {
  let s = '';
  for (const b of bytes) s += String.fromCharCode(b);
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}
function fromBase64Url(text: string): Uint8Array {
  const s = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  return Uint8Array.from(s, (c) => c.charCodeAt(0));
}
async function pipe(bytes: Uint8Array, stream: CompressionStream | DecompressionStream): Promise<Uint8Array> {
  const out = new Response(new Blob([bytes as BlobPart]).stream().pipeThrough(stream));
  return new Uint8Array(await out.arrayBuffer());
}

/** The URL fragment (without '#') for a state: readable query form, compressed when long. */
export async function encode(state: PageState): Promise<string> {
  const q = new URLSearchParams();
  q.set('v', String(state.v));
  q.set('p', state.p);
  if (state.u.length !== DEFAULT_UNITS.length || state.u.angle !== DEFAULT_UNITS.angle) {
    q.set('u', `${state.u.length},${state.u.angle}`);
  }
  for (const [k, v] of Object.entries(state.f)) q.set(k, v);
  const plain = q.toString();
  if (plain.length <= PLAIN_LIMIT) return plain;
  const packed = await pipe(new TextEncoder().encode(JSON.stringify(state)), new CompressionStream('deflate-raw'));
  return `v=${state.v}&z=${toBase64Url(packed)}`;
}

export class StateError extends Error {}

function checkState(s: unknown): PageState {
  const o = s as Partial<PageState> | null;
  if (!o || typeof o !== 'object' || o.v !== STATE_VERSION || typeof o.p !== 'string') {
    throw new StateError(`was made by a different version of the calculator (format ${excerpt(String(o?.v), 12)})`);
  }
  const u = (o.u ?? DEFAULT_UNITS) as UnitPrefs;
  const f: Record<string, string> = {};
  for (const [k, v] of Object.entries(o.f ?? {})) {
    if (/^[a-z]+-[\w-]+$/.test(k) && typeof v === 'string') f[k] = v;
  }
  return {
    v: STATE_VERSION,
    p: o.p,
    u: {
      length: u.length in LENGTH_UNITS ? u.length : DEFAULT_UNITS.length,
      angle: u.angle in ANGLE_UNITS ? u.angle : DEFAULT_UNITS.angle,
    },
    f,
  };
}

/**
 * Reads a URL fragment: null when there is none, a StateError (its message says why, after
 * "it": "was made by a different version …") when it cannot be read.
 */
export async function decode(fragment: string): Promise<PageState | null> {
  const text = fragment.replace(/^#/, '');
  if (text.trim() === '') return null;
  const q = new URLSearchParams(text);
  if (!q.has('v')) throw new StateError(`holds no inputs of this calculator (“#${excerpt(text)}”)`);
  if (q.get('v') !== String(STATE_VERSION)) {
    throw new StateError(`was made by a different version of the calculator (format ${excerpt(q.get('v') ?? '', 12)})`);
  }
  const z = q.get('z');
  if (z !== null) {
    try {
      const bytes = await pipe(fromBase64Url(z), new DecompressionStream('deflate-raw'));
      return checkState(JSON.parse(new TextDecoder().decode(bytes)));
    } catch (e) {
      if (e instanceof StateError) throw e;
      throw new StateError('is damaged: its compressed inputs could not be unpacked');
    }
  }
  const [length, angle] = (q.get('u') ?? `${DEFAULT_UNITS.length},${DEFAULT_UNITS.angle}`).split(',');
  const f: Record<string, string> = {};
  for (const [k, v] of q) if (!['v', 'p', 'u', 'z'].includes(k)) f[k] = v;
  return checkState({ v: STATE_VERSION, p: q.get('p') ?? '', u: { length, angle }, f });
}

// ---- local storage

export function saveLocal(state: PageState) {
  try {
    localStorage.setItem(STORAGE_KEY, JSON.stringify(state));
  } catch {
    // Storage full or disabled: inputs are then only kept in the URL.
  }
}

export function loadLocal(): PageState | null {
  try {
    const text = localStorage.getItem(STORAGE_KEY);
    return text ? checkState(JSON.parse(text)) : null;
  } catch {
    return null;
  }
}

export function clearLocal() {
  try {
    localStorage.removeItem(STORAGE_KEY);
  } catch {
    /* nothing stored */
  }
}

// ---- named cases

export type Cases = Record<string, PageState>;

export function loadCases(): Cases {
  try {
    return parseCases(localStorage.getItem(CASES_KEY) ?? '{}');
  } catch {
    return {};
  }
}

export function storeCases(cases: Cases) {
  localStorage.setItem(CASES_KEY, JSON.stringify(cases));
}

/** Reads cases from JSON text (an export of this page); throws a StateError saying why not. */
export function parseCases(text: string): Cases {
  let data: unknown;
  try {
    data = JSON.parse(text);
  } catch {
    throw new StateError('is not JSON');
  }
  if (!data || typeof data !== 'object' || Array.isArray(data)) throw new StateError('is not a set of named cases');
  const out: Cases = {};
  for (const [name, s] of Object.entries(data as Record<string, unknown>)) out[name] = checkState(s);
  return out;
}
