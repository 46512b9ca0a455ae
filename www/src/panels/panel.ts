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
