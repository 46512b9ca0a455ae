import { el } from '../ui/fields';

// A study's panel: mounted once, the first time it is shown.
export interface Panel {
  /** Stable id, used in the tab, the URL and the presets file name (public/presets/<id>.json). */
  id: string;
  /** Prefix of every field id of the panel ("nl" for "nl-length"): the page state relies on it. */
  prefix: string;
  /** Tab text. */
  title: string;
  mount(root: HTMLElement): Promise<void>;
}

/**
 * The frame every panel starts with: heading, lead paragraph, then the inputs form (left; it
 * never submits) and the results column (right). Returns the form and the results element.
 */
export function panelShell(root: HTMLElement, heading: string, lead: string) {
  root.append(el('h2', {}, heading), el('p', { class: 'lead' }, lead));
  const layout = el('div', { class: 'panel-grid' });
  const form = el('form', { class: 'inputs', novalidate: '' });
  form.addEventListener('submit', (e) => e.preventDefault());
  const results = el('div', { class: 'results' });
  layout.append(form, results);
  root.append(layout);
  return { form, results };
}
