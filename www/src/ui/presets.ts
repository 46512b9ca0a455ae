// Presets: the papers' machines and cases, as data files in public/presets/<panel>.json
// (values in base units: mm and degrees; field id → value). Choosing one resets the panel's
// fields to their defaults and then sets the preset's values.
import { el, fields } from './fields';
import { resetPanel } from './state';

export interface Preset {
  name: string;
  /** Where the numbers come from (paper, table, figure). */
  source?: string;
  values: Record<string, number | string>;
}

export async function loadPresets(panel: string): Promise<Preset[]> {
  const res = await fetch(`presets/${panel}.json`);
  if (!res.ok) throw new Error(`presets/${panel}.json: ${res.status} ${res.statusText}`);
  const data = (await res.json()) as { presets?: Preset[] };
  return (data.presets ?? []).filter((p) => p && typeof p.name === 'string' && p.values && typeof p.values === 'object');
}

export function applyPreset(prefix: string, preset: Preset) {
  resetPanel(prefix);
  for (const [id, v] of Object.entries(preset.values)) fields.get(id)?.setBase(v);
}

/** A "Preset" menu for a panel (not part of the page state itself). */
export function presetPicker(panel: string, prefix: string): HTMLElement {
  const root = el('div', { class: 'field preset' });
  const id = `${prefix}-preset-menu`;
  const label = el('label', { for: id }, 'Preset');
  const select = el('select', { id });
  const note = el('div', { class: 'field-hint', 'aria-live': 'polite' });
  select.append(el('option', { value: '' }, 'Choose a preset…'));
  root.append(label, select, note);
  loadPresets(panel).then(
    (presets) => {
      presets.forEach((p, i) => select.append(el('option', { value: String(i) }, p.name)));
      select.addEventListener('change', () => {
        const p = presets[Number(select.value)];
        if (!p || select.value === '') return;
        applyPreset(prefix, p);
        note.textContent = p.source ? `Source: ${p.source}` : '';
        select.value = '';
      });
    },
    (err) => (note.textContent = `Presets unavailable: ${String(err)}`),
  );
  return root;
}
