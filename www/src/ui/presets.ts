// Presets: the papers' cases as data files in public/presets/<panel>.json, written as the
// engine's input objects (mm and degrees): `machinePreset` names a machine of
// public/presets/machines.json, `machine` sets (or, without a machine preset, changes) machine
// inputs such as errors, `input` the study's own inputs by their paths. Choosing one resets the
// panel's fields (and, with a machine preset, the machine) and then sets the preset's values.
import type { MachineSection } from '../machine/section';
import { el, fields } from './fields';
import { fieldId } from './form';
import { resetPanel } from './state';
import { track } from '../engine/idle';

export interface Preset {
  name: string;
  /** Where the numbers come from (paper, table, figure). */
  source?: string;
  /** Name (or the start of it) of a machine preset the case runs on. */
  machinePreset?: string;
  /** Machine inputs set on top of it (or on the current machine without a machine preset). */
  machine?: Record<string, unknown>;
  /** The study's inputs, by path. */
  input?: Record<string, unknown>;
}

export function loadPresets(panel: string): Promise<Preset[]> {
  return track(fetchPresets(panel));
}

async function fetchPresets(panel: string): Promise<Preset[]> {
  const res = await fetch(`presets/${panel}.json`);
  if (!res.ok) throw new Error(`presets/${panel}.json: ${res.status} ${res.statusText}`);
  const data = (await res.json()) as { presets?: Preset[] };
  return (data.presets ?? []).filter((p) => p && typeof p.name === 'string');
}

/** Every (path, value) of a nested object, paths dotted; lists are values. */
export function leaves(obj: Record<string, unknown>, path = ''): [string, unknown][] {
  const out: [string, unknown][] = [];
  for (const [k, v] of Object.entries(obj)) {
    const p = path ? `${path}.${k}` : k;
    if (v && typeof v === 'object' && !Array.isArray(v)) out.push(...leaves(v as Record<string, unknown>, p));
    else out.push([p, v]);
  }
  return out;
}

/** `b` laid over `a`, objects merged. */
function merge(a: Record<string, unknown>, b: Record<string, unknown>): Record<string, unknown> {
  const out: Record<string, unknown> = { ...a };
  for (const [k, v] of Object.entries(b)) {
    const old = out[k];
    out[k] = v && typeof v === 'object' && !Array.isArray(v) && old && typeof old === 'object' ? merge(old as Record<string, unknown>, v as Record<string, unknown>) : v;
  }
  return out;
}

export async function applyPreset(prefix: string, preset: Preset, machine: MachineSection) {
  if (preset.machinePreset) {
    const all = await machine.presets();
    const base = all.find((m) => m.name.startsWith(preset.machinePreset ?? ''));
    if (!base) throw new Error(`no machine preset named ${preset.machinePreset}`);
    machine.apply(merge(base.machine, preset.machine ?? {}), true);
  } else if (preset.machine) {
    machine.apply(preset.machine, false);
  }
  resetPanel(prefix);
  for (const [path, v] of leaves(preset.input ?? {})) {
    fields.get(fieldId(prefix, path))?.setBase(v as number | string | boolean | string[]);
  }
}

/** A "Preset" menu for a panel (not part of the page state itself). */
export function presetPicker(panel: string, prefix: string, machine: MachineSection): HTMLElement {
  const root = el('div', { class: 'field preset' });
  const id = `${prefix}-preset-menu`;
  const label = el('label', { for: id }, 'Preset');
  const select = el('select', { id });
  const note = el('div', { class: 'field-hint', 'aria-live': 'polite' });
  select.append(el('option', { value: '' }, 'Choose a preset…'));
  root.append(label, select, note);
  loadPresets(panel).then(
    (presets) => {
      // A preset that sets the machine says so: it changes every panel.
      presets.forEach((p, i) => select.append(el('option', { value: String(i) }, p.machinePreset || p.machine ? `${p.name} (sets the machine)` : p.name)));
      select.addEventListener('change', async () => {
        const p = presets[Number(select.value)];
        if (!p || select.value === '') return;
        try {
          await applyPreset(prefix, p, machine);
          const set = p.machinePreset ? `The machine above is now: ${p.machinePreset}${p.machine ? ', with the preset’s values' : ''}. ` : p.machine ? 'The preset changed the machine above. ' : '';
          note.textContent = `${set}${p.source ? `Source: ${p.source}` : ''}`;
        } catch (err) {
          note.textContent = `This preset could not be applied: ${String(err)}`;
        }
        select.value = '';
      });
    },
    (err) => (note.textContent = `Presets unavailable: ${String(err)}`),
  );
  return root;
}
