// Shared set-up of the browser end-to-end tests: serves dist/, drives Debian's Chromium through
// playwright-core, and collects every console error, page error and request that leaves the
// page's own origin. Each test calls `assertClean()` at its end.
import { chromium } from 'playwright-core';
import { mkdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { serve } from '../../scripts/serve.mjs';

export const ARTIFACTS = fileURLToPath(new URL('../artifacts/', import.meta.url));
mkdirSync(ARTIFACTS, { recursive: true });

const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';
export const LAUNCH_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--disable-quic',
];

export async function startBrowser() {
  const { server, url } = await serve(fileURLToPath(new URL('../../dist', import.meta.url)));
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: LAUNCH_ARGS, headless: true });
  return {
    url,
    browser,
    async close() {
      await browser.close();
      await new Promise((r) => server.close(r));
    },
  };
}

/** A page with guards: console errors, page errors and foreign requests are recorded. */
export async function guardedPage(context, origin) {
  const page = await context.newPage();
  const problems = [];
  const log = [];
  page.on('console', (msg) => {
    log.push(`[${msg.type()}] ${msg.text()}`);
    if (msg.type() === 'error') problems.push(`console error: ${msg.text()}`);
  });
  page.on('pageerror', (err) => problems.push(`page error: ${err.message}`));
  page.on('request', (req) => {
    const u = req.url();
    if (!u.startsWith(origin) && !u.startsWith('data:') && !u.startsWith('blob:')) {
      problems.push(`request outside the page's origin: ${u}`);
    }
  });
  page.setDefaultTimeout(30_000);
  return {
    page,
    problems,
    assertClean() {
      if (problems.length) {
        throw new Error(`${problems.join('\n')}\n--- console ---\n${log.join('\n')}`);
      }
    },
  };
}

/** The y data of trace `i` of the Plotly graph with element id `id`. */
export function traceY(page, id, i = 0) {
  return page.evaluate(([id, i]) => {
    const gd = document.getElementById(id);
    const t = gd && gd.data && gd.data[i];
    return t ? Array.from(t.y ?? t.z ?? []) : null;
  }, [id, i]);
}

/** Waits until the plot `id` has been drawn more than `count` times. */
export async function waitPlotted(page, id, count = 0) {
  await page.waitForFunction(
    ([id, count]) => Number(document.getElementById(id)?.dataset.plotted ?? 0) > count,
    [id, count],
  );
  return page.evaluate((id) => Number(document.getElementById(id)?.dataset.plotted ?? 0), id);
}

/**
 * Runs `fn({ page, assertClean, problems, context, url, browser })` on a fresh guarded page of a
 * fresh browser (the served dist/), and closes everything afterwards. `assertClean()` is called
 * at the end: any console error, page error or foreign request fails the test.
 */
export async function withPage(contextOptions, fn) {
  const b = await startBrowser();
  try {
    const context = await b.browser.newContext(contextOptions);
    const guarded = await guardedPage(context, b.url);
    await fn({ ...guarded, context, url: b.url, browser: b.browser });
    guarded.assertClean();
  } finally {
    await b.close();
  }
}

/**
 * The value of the option of the menu `menu` (an element id) whose text starts with `start`,
 * once the menu has it (presets are fetched after the panel is ready).
 */
export async function optionValue(page, menu, start) {
  const handle = await page.waitForFunction(
    ([menu, start]) => [...(document.getElementById(menu)?.options ?? [])].find((o) => o.text.startsWith(start))?.value,
    [menu, start],
  );
  return handle.jsonValue();
}

/**
 * Waits until the page is idle: no engine call in flight (the engine's worker and the toolpath
 * workers), no edit waiting for its debounce, no plot being drawn, no file being fetched
 * (`www/src/engine/idle.ts`). Returns the counters then (`calls`, `done`, `draws`): a test that
 * asserts "nothing was redrawn" compares them, and the plots' draw counts, after this.
 */
export async function waitIdle(page, timeout = 60_000) {
  await page.waitForFunction(() => window.__fiveaxis?.idle(), null, { timeout });
  return page.evaluate(() => ({ calls: window.__fiveaxis.calls, done: window.__fiveaxis.done, draws: window.__fiveaxis.draws }));
}
