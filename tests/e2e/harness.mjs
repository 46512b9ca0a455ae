// Shared set-up of the browser end-to-end tests: serves dist/, drives Debian's Chromium through
// playwright-core, and collects every console error, page error and request that leaves the
// page's own origin. Each test calls `assertClean()` at its end.
import { chromium } from 'playwright-core';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
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
/** How the tests launch Chromium (`tests/run.mjs` launches the shared one so too). */
export const LAUNCH = { executablePath: CHROMIUM, args: LAUNCH_ARGS, headless: true };

/**
 * The browser and the served dist/ of a test. Under `tests/run.mjs` every test file connects to
 * the one Chromium and the one server it started (FIVEAXIS_E2E_BROWSER, FIVEAXIS_E2E_URL);
 * alone (`node --test tests/e2e/x.test.mjs`, `npm run bench`) it launches its own. `close()`
 * closes what the test opened: the contexts it made (and its own browser and server, if any).
 */
export async function startBrowser() {
  const ws = process.env.FIVEAXIS_E2E_BROWSER;
  const shared = process.env.FIVEAXIS_E2E_URL;
  if (ws && shared) {
    // A connection of its own: closing it closes the contexts made through it, and only those.
    const browser = await chromium.connect(ws);
    return { url: shared, browser, close: () => browser.close() };
  }
  const { server, url } = await serve(fileURLToPath(new URL('../../dist', import.meta.url)));
  const browser = await chromium.launch(LAUNCH);
  return {
    url,
    browser,
    async close() {
      await browser.close();
      await new Promise((r) => server.close(r));
    },
  };
}

/**
 * The file of a finished download, copied to a folder of this process that is removed when it
 * exits (`download.path()` is not available from a browser connected to, as the shared one is).
 */
export async function downloaded(download) {
  if (!downloads) {
    downloads = mkdtempSync(join(tmpdir(), 'fiveaxis-downloads-'));
    process.on('exit', () => rmSync(downloads, { recursive: true, force: true }));
  }
  const path = join(downloads, `${++downloadCount}-${download.suggestedFilename()}`);
  await download.saveAs(path);
  return path;
}
let downloads = '';
let downloadCount = 0;

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
 * Runs `fn({ page, assertClean, problems, context, url, browser })` on a fresh guarded page in a
 * fresh browser context (nothing stored or cached shared with another test) of the browser of
 * `startBrowser()`, on the served dist/, and closes what it opened afterwards. `assertClean()` is called
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

/** Drops a file named `name` holding `text` on the element `selector`, as a user drags one. */
export async function drop(page, selector, name, text) {
  await page.evaluate(([selector, name, text]) => {
    const dt = new DataTransfer();
    dt.items.add(new File([text], name, { type: 'text/csv' }));
    const zone = document.querySelector(selector);
    for (const type of ['dragenter', 'dragover', 'drop']) zone.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, [selector, name, text]);
}
