// A study's panel: mounted once, the first time it is shown.
export interface Panel {
  /** Stable id, used in the tab and the URL. */
  id: string;
  /** Tab text. */
  title: string;
  mount(root: HTMLElement): Promise<void>;
}
