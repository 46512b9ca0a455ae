// Page state across browser contexts, reloads and the network: share links, saved inputs,
// reset, export of plot data, offline use after the first visit.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../crate/pkg/fiveaxis.js';
import { ARTIFACTS, guardedPage, startBrowser, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../crate/pkg/fiveaxis_bg.wasm', import.meta.url)) });

/** Per panel: fields to change (id → text) and the plots whose data must match after the trip. */
const PANELS = [
  {
    tab: 'nonlinear',
    set: { 'nl-type': 'BCX', 'nl-machine': 'head-head', 'nl-length': '250', 'nl-k0': '5', 'nl-m0': '-20', 'nl-k1': '47.5', 'nl-m1': '33', 'nl-ratios': '1, 4', 'nl-grid': '21' },
    plots: ['nl-curve', 'nl-sweep-k', 'nl-sweep-m', 'nl-map-max', 'nl-map-u', 'nl-compare'],
  },
  {
    tab: 'cubic',
    set: { 'cb-dzBY': '-14.2', 'cb-betaBY': '0.0029', 'cb-transform': '0', 'cb-reference': 'zone1-plane', 'cb-coffset': '12', 'cb-grid': '97', 'cb-range': '10' },
    plots: ['cb-zones', 'cb-sens', 'cb-map'],
  },
  {
    tab: 'sshape',
    set: { 'ss-l0': '520', 'ss-branch': 'continuous', 'ss-reference': 'axesZero', 'ss-point': 'contact', 'ss-ea0c': '0.001', 'ss-ex0b': '0.01', 'ss-dr': '0.005', 'ss-nu': '131', 'ss-nv': '5', 'ss-radius': '0' },
    plots: ['ss-defects', 'ss-overcut-a', 'ss-overcut-b'],
  },
];

async function setField(page, id, value) {
  const tag = await page.$eval(`#${id}`, (e) => e.tagName);
  if (tag === 'SELECT') await page.selectOption(`#${id}`, value);
  else if ((await page.getAttribute(`#${id}`, 'type')) === 'checkbox') await page.setChecked(`#${id}`, value === '1');
  else await page.fill(`#${id}`, value);
}
const fieldValue = (page, id) =>
  page.$eval(`#${id}`, (e) => (e.type === 'checkbox' ? (e.checked ? '1' : '0') : e.value));
/** Waits until the plots show data computed from the current inputs (no further redraws). */
async function settle(page, plots) {
  for (const id of plots) await waitPlotted(page, id);
  let last = '';
  for (;;) {
    const now = JSON.stringify(await Promise.all(plots.map((id) => page.$eval(`#${id}`, (e) => e.dataset.plotted))));
    if (now === last) return;
    last = now;
    await page.waitForTimeout(400);
  }
}
/** Every trace's x, y and z of each plot. */
const allData = (page, plots) =>
  Promise.all(
    plots.map((id) =>
      page.$eval(`#${id}`, (gd) => [gd.id, gd.data.map((t) => ({ x: Array.from(t.x ?? []), y: Array.from(t.y ?? []), z: t.z ? Array.from(t.z, (r) => Array.from(r)) : null }))]),
    ),
  );

test('share link, reload, reset, units', async () => {
  const b = await startBrowser();
  try {
    const ctx = await b.browser.newContext({ viewport: { width: 1300, height: 1000 } });
    const { page, assertClean } = await guardedPage(ctx, b.url);
    await page.goto(b.url);
    // Units first, so that the data seen here and after the trip are in the same units.
    await page.selectOption('#units-length', 'mm');
    await page.selectOption('#units-angle', 'arcsec');
    const expected = {};
    for (const p of PANELS) {
      await page.click(`#tab-${p.tab}`);
      await settle(page, p.plots);
      for (const [id, v] of Object.entries(p.set)) await setField(page, id, v);
      await settle(page, p.plots);
      expected[p.tab] = await allData(page, p.plots);
    }
    await page.click('#copy-link');
    await page.waitForFunction(() => document.getElementById('share-link')?.value.includes('#v=1'));
    const link = await page.inputValue('#share-link');
    assert.ok(link.startsWith(b.url) && link.length < 1500, `short link: ${link.length} characters`);
    assertClean();

    // A fresh browser context (nothing stored) opens the link and shows the same view.
    const fresh = await b.browser.newContext({ viewport: { width: 1300, height: 1000 } });
    const other = await guardedPage(fresh, b.url);
    await other.page.goto(link);
    assert.equal(await other.page.inputValue('#units-length'), 'mm');
    assert.equal(await other.page.inputValue('#units-angle'), 'arcsec');
    for (const p of PANELS) {
      await other.page.click(`#tab-${p.tab}`);
      await settle(other.page, p.plots);
      for (const [id, v] of Object.entries(p.set)) assert.equal(await fieldValue(other.page, id), v, id);
      assert.deepEqual(await allData(other.page, p.plots), expected[p.tab], `${p.tab}: the same plotted data`);
    }
    other.assertClean();

    // A reload keeps the inputs of every panel (local storage), and reset restores the defaults
    // of the open panel.
    await other.page.evaluate(() => history.replaceState(null, '', location.pathname));
    await other.page.reload();
    for (const p of PANELS) {
      await other.page.click(`#tab-${p.tab}`);
      await settle(other.page, p.plots);
      for (const [id, v] of Object.entries(p.set)) assert.equal(await fieldValue(other.page, id), v, `${id} after reload`);
    }
    for (const p of PANELS) {
      await other.page.click(`#tab-${p.tab}`);
      await other.page.click('#reset');
      for (const id of Object.keys(p.set)) {
        const def = await other.page.$eval(`#${id}`, (e) =>
          e.tagName === 'SELECT' ? [...e.options].find((o) => o.defaultSelected)?.value : e.type === 'checkbox' ? (e.defaultChecked ? '1' : '0') : e.defaultValue,
        );
        assert.equal(await fieldValue(other.page, id), def, `${id} reset`);
      }
    }
    other.assertClean();
    await fresh.close();
  } finally {
    await b.close();
  }
});

test('a link from another version opens with a message and the defaults', async () => {
  await withPage({}, async ({ page, url }) => {
    await page.goto(`${url}#v=99&p=nonlinear&nl-length=5`);
    await page.waitForSelector('#banner:not([hidden])');
    assert.match(await page.textContent('#banner'), /different version/);
    await waitPlotted(page, 'nl-curve');
    assert.equal(await page.inputValue('#nl-length'), '100');
    await page.goto(`${url}#v=1&z=not-deflate-data`);
    await page.reload();
    await page.waitForSelector('#banner:not([hidden])');
    assert.match(await page.textContent('#banner'), /damaged/);
    await page.goto(`${url}#v=1&p=nonlinear&nl-length=7&nl-removed-field=3`);
    await page.reload();
    await page.waitForSelector('#banner:not([hidden])');
    assert.match(await page.textContent('#banner'), /nl-removed-field/);
    assert.equal(await page.inputValue('#nl-length'), '7');
  });
});

test('export: CSV and PNG of a plot, numbers as the engine gives them', async () => {
  await withPage({ acceptDownloads: true, viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.selectOption('#units-length', 'mm');
    await waitPlotted(page, 'nl-curve');
    await settle(page, ['nl-curve', 'nl-sweep-k']);
    const csvButton = page.locator('#nl-curve ~ .plot-tools button[data-export=csv]');
    const [csv] = await Promise.all([page.waitForEvent('download'), csvButton.click()]);
    const text = readFileSync(await csv.path(), 'utf8');
    const [header, ...lines] = text.trim().split('\n');
    // Traces with different x (the curve and its markers) come in long form: trace, x, y.
    assert.equal(header, 'trace,interpolation parameter u,δ (mm)');
    const rows = lines.filter((l) => l.startsWith('δ(u),')).map((l) => l.slice('δ(u),'.length));
    // Independent of the page: the engine called directly with the default inputs.
    const r = fa.nonlinearMove({ type: 'CAZ', length: 100, start: { k: 0, m: 10 }, end: { k: 30, m: 25 }, samples: 201 });
    assert.equal(rows.length, 201);
    rows.forEach((row, i) => {
      const [u, d] = row.split(',').map(Number);
      assert.ok(Math.abs(u - r.u[i]) < 1e-12 && Math.abs(d - r.delta[i]) < 1e-12, `row ${i}: ${row}`);
    });
    const [png] = await Promise.all([page.waitForEvent('download'), page.locator('#nl-curve ~ .plot-tools button[data-export=png]').click()]);
    const bytes = readFileSync(await png.path());
    assert.deepEqual([...bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a], 'a PNG file');
    assert.ok(bytes.length > 10_000);
  });
});

test('export: a heat map as CSV (the cubic 3 × 3 map), heights as the engine gives them', async () => {
  await withPage({ acceptDownloads: true, viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.selectOption('#units-length', 'mm');
    await page.click('#tab-cubic');
    await waitPlotted(page, 'cb-zones');
    await page.selectOption('#cb-preset-menu', { label: "Table 5: the paper's machine (identified by ball bar)" });
    await page.waitForFunction(() => document.getElementById('cb-dxBY')?.value === '0.0146');
    await settle(page, ['cb-zones', 'cb-map', 'cb-sens']);
    const [csv] = await Promise.all([page.waitForEvent('download'), page.locator('#cb-zones ~ .plot-tools button[data-export=csv]').click()]);
    const lines = readFileSync(await csv.path(), 'utf8').trim().split('\n');
    assert.match(lines[0], /^# .*rows: Y \(mm\); columns: X \(mm\)/);
    const xs = lines[1].split(',').slice(1).map(Number);
    const grid = lines.slice(2).map((l) => l.split(',').map(Number));
    assert.deepEqual(xs, [-16, 0, 16]);
    assert.equal(grid.length, 3);
    // Independent of the page: the engine called directly with Table 5 (mm and degrees).
    const r = fa.cubicTest({ errors: { dxBY: 0.0146, dyBY: -0.0089, dzBY: -0.0142, alphaBY: -0.0023, betaBY: 0.0029, gammaBY: -0.00002, alphaCB: -0.00017, dxCB: 0.0094 } });
    assert.equal(r.zones.length, 9);
    for (const z of r.zones) {
      const row = grid.find((g) => Math.abs(g[0] - z.y) < 1e-9);
      const cell = row[1 + xs.findIndex((x) => Math.abs(x - z.x) < 1e-9)];
      assert.ok(Math.abs(cell - z.height) < 1e-12, `ZONE ${z.name}: CSV ${cell} vs engine ${z.height} mm`);
    }
  });
});

test('works offline after the first visit', async () => {
  await withPage({}, async ({ page, url, context, problems }) => {
    await page.goto(url);
    await waitPlotted(page, 'nl-curve');
    await page.evaluate(async () => {
      const reg = await navigator.serviceWorker.ready;
      while (!navigator.serviceWorker.controller) await new Promise((r) => setTimeout(r, 50));
      return reg.active?.state;
    });
    await context.setOffline(true);
    await page.reload();
    await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-k1', '50');
    await waitPlotted(page, 'nl-curve', 1);
    // Every other panel loads (their code, presets and sample data come from the cache too).
    for (const p of PANELS.slice(1)) {
      await page.click(`#tab-${p.tab}`);
      for (const id of p.plots) await waitPlotted(page, id);
    }
    await page.click('#tab-sshape');
    await page.click('#ss-load-sample');
    await page.waitForFunction(() => document.getElementById('ss-csv')?.value.split('\n').length > 100);
    await waitPlotted(page, 'ss-residuals');
    await page.screenshot({ path: `${ARTIFACTS}offline.png` });
    // Failed network requests while offline would show up as console errors: there are none.
    assert.deepEqual(problems, []);
  });
});
