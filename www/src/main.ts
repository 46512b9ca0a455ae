// The page shell: one tab per study; each panel is mounted when first opened.
import './style.css';
import type { Panel } from './panels/panel';
import { nonlinearPanel } from './panels/nonlinear';

const panels: Panel[] = [nonlinearPanel];

function setup() {
  const tabs = document.getElementById('tabs');
  const host = document.getElementById('panels');
  if (!tabs || !host) return;
  const mounted = new Map<string, HTMLElement>();

  const show = async (id: string) => {
    const panel = panels.find((p) => p.id === id) ?? panels[0];
    for (const b of tabs.querySelectorAll<HTMLButtonElement>('button[role=tab]')) {
      const on = b.dataset.panel === panel.id;
      b.setAttribute('aria-selected', String(on));
      b.tabIndex = on ? 0 : -1;
    }
    for (const [pid, el] of mounted) el.hidden = pid !== panel.id;
    if (!mounted.has(panel.id)) {
      const section = document.createElement('section');
      section.id = `panel-${panel.id}`;
      section.className = 'panel';
      section.setAttribute('role', 'tabpanel');
      section.setAttribute('aria-labelledby', `tab-${panel.id}`);
      host.append(section);
      mounted.set(panel.id, section);
      try {
        await panel.mount(section);
        section.dataset.ready = 'true';
      } catch (err) {
        section.append(Object.assign(document.createElement('p'), { className: 'warn', textContent: `This panel failed to load: ${String(err)}` }));
        throw err;
      }
    }
  };

  for (const p of panels) {
    const b = document.createElement('button');
    b.type = 'button';
    b.id = `tab-${p.id}`;
    b.setAttribute('role', 'tab');
    b.setAttribute('aria-controls', `panel-${p.id}`);
    b.dataset.panel = p.id;
    b.textContent = p.title;
    b.addEventListener('click', () => void show(p.id));
    tabs.append(b);
  }
  tabs.addEventListener('keydown', (e) => {
    const list = [...tabs.querySelectorAll<HTMLButtonElement>('button[role=tab]')];
    const i = list.findIndex((b) => b.getAttribute('aria-selected') === 'true');
    const j = e.key === 'ArrowRight' ? (i + 1) % list.length : e.key === 'ArrowLeft' ? (i - 1 + list.length) % list.length : -1;
    if (j >= 0) {
      list[j].focus();
      void show(list[j].dataset.panel ?? '');
    }
  });
  void show(panels[0].id);
}

// The same engine on the main thread, for the browser console: `fiveaxis.nonlinearMove({...})`.
// The page itself computes in a Web Worker.
import('@engine').then(async (engine) => {
  await engine.default();
  (window as unknown as { fiveaxis: typeof engine }).fiveaxis = engine;
});

setup();
