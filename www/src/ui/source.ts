// Where a panel's measurement file comes from: the sample, a file chosen or dropped, or text typed
// or pasted into its field. The file goes through the page's one reader (files.ts: a picture, a
// PDF or an archive refused by its first bytes, Windows-1252 when not UTF-8) into the panel's
// text field; the panel computes from the field and names the source with its result.
import { track } from '../engine/idle';
import { el, fields } from './fields';
import { encodingNote, readOrRefuse } from './files';

export interface SourceOptions {
  /** Field prefix of the panel ("bb"): the elements are `<prefix>-load-sample`, `<prefix>-file`,
   *  `<prefix>-file-msg`. */
  prefix: string;
  /** The id of the text field the file's text goes into. */
  field: string;
  /** The sample: its address (relative to the page), its button's text and what it is. */
  sample: { url: string; button: string; note: string };
  /** What the file should be, for a refusal ("a ball-bar trace (CSV or text)"). */
  expected: string;
  /** A file was refused (not text): the panel greys what it would have replaced. */
  refused(message: string): void;
}

export interface Source {
  /** The buttons and the message, to put above the field. */
  readonly root: HTMLElement;
  /** Where the field's text came from: "ballbar-xy.csv" or "the sample ballbar-xy.csv" when it
   *  was loaded here; null when typed, pasted or restored (the panel names it). */
  name(): string | null;
}

/** Largest file read: a trace or a laser table is a few hundred kB at most. */
const MAX_BYTES = 5_000_000;

/** The sample button, the file chooser, a drop zone (`zone`: the panel's form) and a message. */
export function fileSource(zone: HTMLElement, o: SourceOptions): Source {
  const root = el('div', { class: 'source' });
  const row = el('div', { class: 'file-row' });
  const sample = el('button', { type: 'button', id: `${o.prefix}-load-sample` }, o.sample.button);
  const label = el('label', { class: 'import', for: `${o.prefix}-file` }, 'Choose a file ');
  const input = el('input', { id: `${o.prefix}-file`, type: 'file', accept: '.csv,.txt,.tsv,text/csv,text/plain' });
  label.append(input);
  row.append(sample, label, el('span', { class: 'field-hint' }, 'or drop one here, or paste its text into the field'));
  const msg = el('p', { class: 'field-hint', id: `${o.prefix}-file-msg`, 'aria-live': 'polite' });
  root.append(row, msg);
  /** The text last loaded here and its name: the name holds while the field holds that text. */
  let loaded: { text: string; name: string } | null = null;
  const sampleFile = o.sample.url.split('/').pop() ?? o.sample.url;

  const set = (text: string, from: string) => {
    const h = fields.get(o.field);
    loaded = { text, name: from };
    h?.setText(text);
  };
  const read = async (file: File) => {
    if (file.size > MAX_BYTES) {
      msg.textContent = `${file.name} is larger than 5 MB: not ${o.expected}.`;
      o.refused(msg.textContent);
      return;
    }
    const r = await readOrRefuse(file, (message) => {
      msg.textContent = message;
      o.refused(message);
    }, o.expected);
    if (!r) return;
    msg.textContent = `Loaded ${file.name}${encodingNote(r)}.`;
    set(r.text, file.name);
  };

  sample.addEventListener('click', () => {
    void track((async () => {
      try {
        const res = await fetch(o.sample.url);
        if (!res.ok) throw new Error(`${res.status} ${res.statusText}`);
        const text = await res.text();
        msg.textContent = `Loaded the sample ${sampleFile}: ${o.sample.note}`;
        set(text, `the sample ${sampleFile}`);
      } catch (e) {
        msg.textContent = `Could not load the sample: ${String(e)}`;
      }
    })());
  });
  input.addEventListener('change', () => {
    const f = input.files?.[0];
    input.value = '';
    if (f) void read(f);
  });
  zone.addEventListener('dragover', (e) => {
    if (!e.dataTransfer?.types.includes('Files')) return;
    e.preventDefault();
    e.dataTransfer.dropEffect = 'copy';
    zone.classList.add('dragging');
  });
  zone.addEventListener('dragleave', (e) => {
    if (!zone.contains(e.relatedTarget as Node | null)) zone.classList.remove('dragging');
  });
  zone.addEventListener('drop', (e) => {
    zone.classList.remove('dragging');
    const f = e.dataTransfer?.files?.[0];
    if (!f) return;
    // Not the browser's own handling (it would open the file in place of the page).
    e.preventDefault();
    void read(f);
  });
  // Typed or pasted into the field: the message about the file loaded goes.
  fields.get(o.field)?.control.addEventListener('input', (e) => {
    if (e.isTrusted) msg.textContent = '';
  });
  return {
    root,
    name: () => {
      const h = fields.get(o.field);
      // (A text field keeps line ends as \n: a file with \r\n reads back so.)
      const norm = (t: string) => t.replace(/\r\n?/g, '\n');
      return loaded && h && norm(h.text()) === norm(loaded.text) ? loaded.name : null;
    },
  };
}

/**
 * The sample as the field's default: the panel opens on it, *Reset to defaults* brings it back,
 * and saved inputs and share links leave it out (they keep only what differs from a default).
 * Returns the sample's text ('' when it could not be fetched: the field's default stays empty).
 */
export async function sampleAsDefault(field: string, url: string): Promise<string> {
  let text = '';
  try {
    const res = await track(fetch(url));
    if (res.ok) text = await track(res.text());
  } catch {
    return '';
  }
  const h = fields.get(field);
  if (!h || !text) return '';
  fields.set(field, { ...h, defaultText: () => text });
  if (h.text() === '') h.setText(text);
  return text;
}
