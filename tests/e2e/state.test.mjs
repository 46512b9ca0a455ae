// Page state across browser contexts, reloads and the network: share links (the machine's
// fields with every panel's), saved inputs, reset, export of plot data, offline use after the
// first visit.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, downloaded, guardedPage, optionValue, startBrowser, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

/**
 * The Machine section's fields to change (id → text as shown, in mm and arcseconds; the kind
 * first, since the pivot field shows only on a machine with a head) and its drawing.
 */
const MACHINE = {
  set: {
    'm-kind': 'head-table', 'm-linear': 'table-y', 'm-geometry-tableHeight': '20', 'm-geometry-pivotLength': '420', 'm-geometry-toolLength': '90',
    'm-rotary-kReversed': '1', 'm-rotary-mFrom': '-100', 'm-rotary-mTo': '110',
    'm-errors-E_X0B': '0.012', 'm-errors-E_A0C': '7.2', 'm-errors-E_C0Y': '3.6', 'md-k': '30', 'md-m': '-20',
  },
  plots: ['machine-schematic'],
};
/** Per panel: fields to change (id → text) and the plots whose data must match after the trip. */
const PANELS = [
  {
    tab: 'nonlinear',
    set: { 'nl-length': '250', 'nl-start-k': '5', 'nl-start-m': '-20', 'nl-end-k': '47.5', 'nl-end-m': '33', 'nl-ratios': '1, 4', 'nl-nx': '21', 'nl-vector': '0, 0.5, 0.8660254' },
    plots: ['nl-curve', 'nl-sweep-k', 'nl-sweep-m', 'nl-map-max', 'nl-map-u', 'nl-compare'],
  },
  {
    tab: 'cubic',
    set: { 'cb-transform': '0', 'cb-reference': 'zone1-plane', 'cb-setup-workpieceX': '12', 'cb-setup-zoneSize': '12', 'cb-nx': '97', 'cb-range': '0.01' },
    plots: ['cb-zones', 'cb-sens', 'cb-map'],
  },
  {
    tab: 'sshape',
    set: {
      'ss-tool-rTool': '9', 'ss-model-branch': 'continuous', 'ss-model-reference': 'axesZero', 'ss-model-point': 'contact', 'ss-dR': '0.005',
      'ss-nu': '131', 'ss-nv': '5', 'ss-radiusTerm': '0', 'ss-rtol': '0.001', 'ss-parameters-value': 'E_X0B,E_A0B,E_C0Y',
    },
    plots: ['ss-defects', 'ss-overcut-a', 'ss-overcut-b'],
  },
];

/** Sets a field as a user does: a choice, a tick, typed text, or the boxes of a list of names. */
async function setField(page, id, value) {
  const [tag, type] = await page.$eval(`#${id}`, (e) => [e.tagName, e.type]);
  if (tag === 'SELECT') await page.selectOption(`#${id}`, value);
  else if (type === 'checkbox') await page.setChecked(`#${id}`, value === '1');
  else if (type === 'hidden') {
    // The state of a list of names (its boxes' text): tick exactly those named.
    const boxes = await page.$$eval(`#${id}`, (es) => [...es[0].closest('fieldset').querySelectorAll('input[type=checkbox]')].map((b) => b.id));
    const want = new Set(value.split(','));
    for (const b of boxes) await page.setChecked(`#${b}`, want.has(b.slice(b.lastIndexOf('-') + 1)));
  } else await page.fill(`#${id}`, value);
}
const fieldValue = (page, id) =>
  page.$eval(`#${id}`, (e) => (e.type === 'checkbox' ? (e.checked ? '1' : '0') : e.value));
/** Waits until the plots show data computed from the current inputs: drawn, and the page idle
 *  (no engine call in flight, no edit waiting, no plot being drawn). */
async function settle(page, plots) {
  for (const id of plots) await waitPlotted(page, id);
  await waitIdle(page);
}
/** Every trace's x, y and z of each plot (z a grid or, in 3D, a list). */
const allData = (page, plots) =>
  Promise.all(
    plots.map((id) =>
      page.$eval(`#${id}`, (gd) => [gd.id, gd.data.map((t) => ({
        x: Array.from(t.x ?? []), y: Array.from(t.y ?? []),
        z: t.z ? Array.from(t.z, (r) => (r !== null && typeof r === 'object' ? Array.from(r) : r)) : null,
      }))]),
    ),
  );
/** The default text of a field, as the page wrote it. */
const defaultOf = (page, id) =>
  page.$eval(`#${id}`, (e) =>
    e.tagName === 'SELECT' ? [...e.options].find((o) => o.defaultSelected)?.value ?? e.options[0]?.value : e.type === 'checkbox' ? (e.defaultChecked ? '1' : '0') : e.defaultValue,
  );

test('share link, reload, reset, units: the machine and every panel', async () => {
  const b = await startBrowser();
  try {
    const ctx = await b.browser.newContext({ viewport: { width: 1300, height: 1000 } });
    const { page, assertClean } = await guardedPage(ctx, b.url);
    await page.goto(b.url);
    await page.waitForSelector('#machine[data-ready=true]');
    // Units first, so that the data seen here and after the trip are in the same units.
    await page.selectOption('#units-length', 'mm');
    await page.selectOption('#units-angle', 'arcsec');
    // The machine first: every panel computes on it.
    await settle(page, MACHINE.plots);
    for (const [id, v] of Object.entries(MACHINE.set)) await setField(page, id, v);
    await page.waitForFunction(() => /head-table/.test(document.getElementById('machine-summary')?.textContent ?? ''));
    await settle(page, MACHINE.plots);
    const expected = { machine: await allData(page, MACHINE.plots) };
    for (const p of PANELS) {
      await page.click(`#tab-${p.tab}`);
      await page.waitForSelector(`#panel-${p.tab}[data-ready=true]`);
      await settle(page, p.plots);
      for (const [id, v] of Object.entries(p.set)) await setField(page, id, v);
      await settle(page, p.plots);
      expected[p.tab] = await allData(page, p.plots);
    }
    // Every field holds what was set (nothing undone by a redraw).
    for (const p of [MACHINE, ...PANELS]) for (const [id, v] of Object.entries(p.set)) assert.equal(await fieldValue(page, id), v, `${id} as set`);
    await page.click('#copy-link');
    await page.waitForFunction(() => document.getElementById('share-link')?.value.includes('#v=2'));
    const link = await page.inputValue('#share-link');
    assert.ok(link.startsWith(b.url) && link.length < 1500, `short link: ${link.length} characters`);
    assertClean();

    // A fresh browser context (nothing stored) opens the link and shows the same view.
    const fresh = await b.browser.newContext({ viewport: { width: 1300, height: 1000 } });
    const other = await guardedPage(fresh, b.url);
    await other.page.goto(link);
    await other.page.waitForSelector('#machine[data-ready=true]');
    assert.equal(await other.page.inputValue('#units-length'), 'mm');
    assert.equal(await other.page.inputValue('#units-angle'), 'arcsec');
    for (const [id, v] of Object.entries(MACHINE.set)) assert.equal(await fieldValue(other.page, id), v, id);
    await settle(other.page, MACHINE.plots);
    assert.deepEqual(await allData(other.page, MACHINE.plots), expected.machine, 'the same drawing of the machine');
    for (const p of PANELS) {
      await other.page.click(`#tab-${p.tab}`);
      await other.page.waitForSelector(`#panel-${p.tab}[data-ready=true]`);
      await settle(other.page, p.plots);
      for (const [id, v] of Object.entries(p.set)) assert.equal(await fieldValue(other.page, id), v, id);
      assert.deepEqual(await allData(other.page, p.plots), expected[p.tab], `${p.tab}: the same plotted data`);
    }
    other.assertClean();

    // A reload keeps the inputs of the machine and every panel (local storage).
    await other.page.evaluate(() => history.replaceState(null, '', location.pathname));
    await other.page.reload();
    await other.page.waitForSelector('#machine[data-ready=true]');
    for (const [id, v] of Object.entries(MACHINE.set)) assert.equal(await fieldValue(other.page, id), v, `${id} after reload`);
    for (const p of PANELS) {
      await other.page.click(`#tab-${p.tab}`);
      await other.page.waitForSelector(`#panel-${p.tab}[data-ready=true]`);
      await settle(other.page, p.plots);
      for (const [id, v] of Object.entries(p.set)) assert.equal(await fieldValue(other.page, id), v, `${id} after reload`);
    }
    // Units: the machine's small lengths and angles are converted, not reinterpreted.
    await other.page.selectOption('#units-angle', 'deg');
    await other.page.selectOption('#units-length', 'um');
    assert.equal(await other.page.inputValue('#m-errors-E_A0C'), '0.002');
    assert.equal(await other.page.inputValue('#m-errors-E_X0B'), '12');
    await other.page.selectOption('#units-angle', 'arcsec');
    await other.page.selectOption('#units-length', 'mm');
    assert.equal(await other.page.inputValue('#m-errors-E_A0C'), '7.2');
    assert.equal(await other.page.inputValue('#m-errors-E_X0B'), '0.012');
    // Reset restores the defaults of the open panel only; the machine has its own reset.
    for (const p of PANELS) {
      await other.page.click(`#tab-${p.tab}`);
      await other.page.click('#reset');
      for (const id of Object.keys(p.set)) assert.equal(await fieldValue(other.page, id), await defaultOf(other.page, id), `${id} reset`);
    }
    for (const [id, v] of Object.entries(MACHINE.set)) assert.equal(await fieldValue(other.page, id), v, `${id} kept by a panel's reset`);
    await other.page.click('#machine-reset');
    for (const id of Object.keys(MACHINE.set)) assert.equal(await fieldValue(other.page, id), await defaultOf(other.page, id), `${id} reset`);
    assert.equal(await other.page.inputValue('#m-kind'), 'table-table');
    other.assertClean();
    await fresh.close();
  } finally {
    await b.close();
  }
});

/** The user's own work, as the inputs kept in this browser show it. */
async function ownWork(page) {
  const tab = await page.$eval('[role=tab][aria-selected=true]', (t) => t.dataset.panel);
  return {
    // A field of the open panel (the others are mounted when first opened).
    panelField: await page.inputValue(tab === 'cubic' ? '#cb-setup-workpieceX' : '#nl-length'),
    tableHeight: await page.inputValue('#m-geometry-tableHeight'),
    errorX0B: await page.inputValue('#m-errors-E_X0B'),
    units: [await page.inputValue('#units-length'), await page.inputValue('#units-angle')],
    tab,
  };
}
const savedCases = (page) => page.evaluate(() => JSON.parse(localStorage.getItem('fiveaxis:cases:v2') ?? '{}'));

test('an unreadable link says so and changes nothing; a link opens beside the user\'s own inputs, one click from them', async () => {
  await withPage({ viewport: { width: 1300, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    // The user's own work: inputs in a panel and in the machine, the units, another panel open.
    await page.selectOption('#units-length', 'um');
    await page.selectOption('#units-angle', 'arcsec');
    await page.fill('#nl-length', '33');
    await page.fill('#m-geometry-tableHeight', '150');
    await page.fill('#m-errors-E_X0B', '12');
    await page.click('#tab-cubic');
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    await page.fill('#cb-setup-workpieceX', '12');
    await page.waitForFunction(() => /m-geometry-tableHeight=150/.test(location.hash) && /p=cubic/.test(location.hash) && /workpieceX=12/.test(location.hash));
    const mine = { panelField: '12', tableHeight: '150', errorX0B: '12', units: ['um', 'arcsec'], tab: 'cubic' };
    assert.deepEqual(await ownWork(page), mine);

    // Links the page cannot read: not a state at all, the first format (before the Machine
    // section), a future format, compressed data that is not, a panel that does not exist.
    const unreadable = [
      ['#garbage', /holds no inputs of this calculator/],
      ['#v=1&p=nonsense', /different version of the calculator \(format 1\)/],
      ['#v=1&p=cubic&cb-dxBY=14.6&cb-transform=0', /different version of the calculator \(format 1\)/],
      ['#v=99&p=nonlinear&nl-length=5&m-geometry-tableHeight=120', /different version of the calculator \(format 99\)/],
      ['#v=2&z=not-deflate-data', /damaged/],
      ['#v=2&p=nonsense&nl-length=5', /names a panel this version does not have \(“nonsense”\)/],
    ];
    for (const [link, why] of unreadable) {
      // Pasted into this tab's address bar (only the fragment changes), then opened afresh.
      for (const how of ['in this tab', 'opened afresh']) {
        await page.evaluate(() => delete document.body.dataset.link);
        if (how === 'opened afresh') await page.goto('about:blank');
        await page.goto(`${url}${link}`);
        await page.waitForSelector('body[data-link=refused]');
        await page.waitForSelector('#banner:not([hidden])');
        const text = await page.textContent('#banner .banner-text');
        assert.match(text, /^This link could not be read: it /, `${link} ${how}: ${text}`);
        assert.match(text, why, `${link} ${how}: ${text}`);
        assert.match(text, /Nothing was changed/, `${link} ${how}`);
        await page.waitForSelector('#panel-cubic[data-ready=true]');
        assert.deepEqual(await ownWork(page), mine, `${link} ${how}: the user's inputs, units and panel`);
        assert.deepEqual(await savedCases(page), {}, `${link} ${how}: no case made`);
        // The address holds the user's own state again, not the link's.
        await page.waitForFunction(() => /m-geometry-tableHeight=150/.test(location.hash));
      }
    }
    await page.screenshot({ path: `${ARTIFACTS}link-refused.png` });

    // A readable link: it opens, and the user's own inputs are first kept as a case.
    await page.evaluate(() => delete document.body.dataset.link);
    await page.goto('about:blank');
    await page.goto(`${url}#v=2&p=nonlinear&nl-length=5&m-geometry-tableHeight=120`);
    await page.waitForSelector('body[data-link=opened]');
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    assert.deepEqual(await ownWork(page), { panelField: '5', tableHeight: '120', errorX0B: '0', units: ['um', 'deg'], tab: 'nonlinear' });
    const text = await page.textContent('#banner .banner-text');
    const m = /^Opened a shared link\. Your own inputs are kept as case “(My inputs before opening a link, [^”]+)”\.$/.exec(text);
    assert.ok(m, text);
    const cases = await savedCases(page);
    assert.deepEqual(Object.keys(cases), [m[1]]);
    assert.equal(cases[m[1]].p, 'cubic');
    assert.deepEqual(cases[m[1]].u, { length: 'um', angle: 'arcsec' });
    assert.equal(cases[m[1]].f['nl-length'], '33');
    assert.equal(cases[m[1]].f['cb-setup-workpieceX'], '12');
    assert.equal(cases[m[1]].f['m-geometry-tableHeight'], '150');
    assert.equal(cases[m[1]].f['m-errors-E_X0B'], '12');
    assert.equal(await page.textContent('#banner-action'), 'Back to my inputs');
    await page.screenshot({ path: `${ARTIFACTS}link-opened.png` });
    // One click brings the user's inputs back; the case stays under Saved cases.
    await page.click('#banner-action');
    await page.waitForFunction(() => document.getElementById('m-geometry-tableHeight')?.value === '150');
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    assert.deepEqual(await ownWork(page), mine);
    assert.match(await page.textContent('#banner .banner-text'), /Your own inputs are back/);
    await page.click('.cases summary');
    // The list is drawn when the menu opens: wait for the case's name in it.
    await page.waitForFunction((name) => [...document.querySelectorAll('#case-list .case-name')].some((n) => n.textContent === name), m[1]);
    // Reloading the page's own address is not opening a link: no message, no new case.
    await page.waitForFunction(() => /m-geometry-tableHeight=150/.test(location.hash));
    await page.reload();
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    assert.deepEqual(await ownWork(page), mine);
    assert.equal(await page.$eval('#banner', (b) => b.hidden), true);
    assert.equal(Object.keys(await savedCases(page)).length, 1);

    // Settings this version does not know, of a panel and of the machine, are named; the rest
    // is applied.
    await page.goto('about:blank');
    await page.goto(`${url}#v=2&p=nonlinear&nl-length=7&nl-removed-field=3&m-geometry-tableHeight=150&m-removed-field=1`);
    await page.waitForSelector('#banner:not([hidden])');
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    const ignoredText = await page.textContent('#banner');
    assert.match(ignoredText, /nl-removed-field/);
    assert.match(ignoredText, /m-removed-field/);
    assert.match(ignoredText, /Your own inputs are kept as case/);
    assert.equal(await page.inputValue('#nl-length'), '7');
    assert.equal(await page.inputValue('#m-geometry-tableHeight'), '150');
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
    const text = readFileSync(await downloaded(csv), 'utf8');
    const [header, ...lines] = text.trim().split('\n');
    // Long form: trace, x, the value and its quantity with the unit (each trace its own axis).
    assert.equal(header, 'trace,interpolation parameter u,value,quantity (unit)');
    const rows = lines.filter((l) => l.startsWith('δ(u),')).map((l) => l.slice('δ(u),'.length));
    // Independent of the page: the engine called directly with the default inputs.
    // The default machine: table-table, CBZ, table 100 mm above the rotary centre (L = 100 mm).
    const r = fa.nonlinearMove({ machine: { kind: 'table-table', type: 'CBZ', geometry: { tableHeight: 100 } }, start: { k: 0, m: 10 }, end: { k: 30, m: 25 }, samples: 201 });
    assert.equal(rows.length, 201);
    rows.forEach((row, i) => {
      const [u, d, quantity] = row.split(',');
      assert.equal(quantity.replace(/"/g, ''), 'δ (mm)');
      assert.ok(Math.abs(Number(u) - r.u[i]) < 1e-12 && Math.abs(Number(d) - r.delta[i]) < 1e-12, `row ${i}: ${row}`);
    });
    const [png] = await Promise.all([page.waitForEvent('download'), page.locator('#nl-curve ~ .plot-tools button[data-export=png]').click()]);
    const bytes = readFileSync(await downloaded(png));
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
    await page.selectOption('#cb-preset-menu', await optionValue(page, 'cb-preset-menu', 'Paper example: B/C tilting table with the errors its ball bar found (Li et al. 2021, Table 5)'));
    await page.waitForFunction(() => document.getElementById('m-errors-E_X0B')?.value === '-0.0146');
    await settle(page, ['cb-zones', 'cb-map', 'cb-sens']);
    const [csv] = await Promise.all([page.waitForEvent('download'), page.locator('#cb-zones ~ .plot-tools button[data-export=csv]').click()]);
    const lines = readFileSync(await downloaded(csv), 'utf8').trim().split('\n');
    assert.match(lines[0], /^# .*rows: Y \(mm\); columns: X \(mm\)/);
    const xs = lines[1].split(',').slice(1).map(Number);
    const grid = lines.slice(2).map((l) => l.split(',').map(Number));
    assert.deepEqual(xs, [-16, 0, 16]);
    assert.equal(grid.length, 3);
    // Independent of the page: the engine called directly with Table 5 (mm and degrees) in ISO
    // names, E = −ε, on Li et al.'s machine (the table at the B axis, B and C intersecting).
    const li = { kind: 'table-table', type: 'CBZ', geometry: { rotaryOffset: 0, tableHeight: 0, toolLength: 0 }, rotary: { mFrom: -120, mTo: 120 } };
    const t5 = { dxBY: 0.0146, dyBY: -0.0089, dzBY: -0.0142, alphaBY: -0.0023, betaBY: 0.0029, gammaBY: -0.00002, alphaCB: -0.00017, dxCB: 0.0094 };
    const errors = { E_X0B: -t5.dxBY, E_Y0B: -t5.dyBY, E_Z0B: -t5.dzBY, E_A0B: -t5.alphaBY, E_B0B: -t5.betaBY, E_C0B: -t5.gammaBY, E_A0C: -t5.alphaCB, E_X0C: -t5.dxCB };
    const r = fa.cubicTest({ machine: { ...li, errors } });
    assert.equal(r.zones.length, 9);
    for (const z of r.zones) {
      const row = grid.find((g) => Math.abs(g[0] - z.y) < 1e-9);
      const cell = row[1 + xs.findIndex((x) => Math.abs(x - z.x) < 1e-9)];
      assert.ok(Math.abs(cell - z.height) < 1e-12, `ZONE ${z.name}: CSV ${cell} vs engine ${z.height} mm`);
    }

    // The sensitivity bars: positions on the first y axis (mm/mm), angles on the second (mm/°).
    // Each column's unit is its own axis's, and each value is the engine's k = ∂height/∂error.
    const [sens] = await Promise.all([page.waitForEvent('download'), page.locator('#cb-sens ~ .plot-tools button[data-export=csv]').click()]);
    const [head, ...body] = readFileSync(await downloaded(sens), 'utf8').trim().split('\n');
    /** One CSV line's cells (RFC 4180 quoting: a quoted cell may hold commas). */
    const cellsOf = (line) => [...line.matchAll(/(?:^|,)(?:"((?:[^"]|"")*)"|([^,]*))/g)].map((m) => m[1]?.replace(/""/g, '"') ?? m[2]);
    const columns = cellsOf(head);
    assert.equal(columns[0], 'zone');
    const n = r.errorNames.length;
    let angles = 0;
    for (const [c, title] of columns.entries()) {
      if (c === 0) continue;
      const name = title.split(' ')[0];
      const e = r.errorNames.indexOf(name);
      assert.ok(e >= 0, `column ${title}`);
      const angular = r.errorUnits[e] === 'deg';
      angles += angular;
      assert.ok(title.endsWith(angular ? '[k, angles (mm/°)]' : '[k, positions (mm/mm)]'), `column "${title}" (${r.errorUnits[e]})`);
      for (const line of body) {
        const cells = cellsOf(line);
        const zi = r.zones.findIndex((z) => z.name === cells[0]);
        assert.ok(Math.abs(Number(cells[c]) - r.kHeight[zi * n + e]) < 1e-9, `${name} on ${cells[0]}: ${cells[c]} vs ${r.kHeight[zi * n + e]}`);
      }
    }
    assert.ok(angles > 0 && angles < columns.length - 1, `both axes exported: ${columns.join(' | ')}`);
  });
});

test('works offline after the first visit, for what that visit loaded', async () => {
  await withPage({}, async ({ page, url, context, problems }) => {
    await page.goto(url);
    await waitPlotted(page, 'nl-curve');
    await page.evaluate(async () => {
      const reg = await navigator.serviceWorker.ready;
      while (!navigator.serviceWorker.controller) await new Promise((r) => setTimeout(r, 50));
      return reg.active?.state;
    });
    // The service worker keeps what the page fetched (it downloads nothing of its own): the
    // first visit opens every panel and the S-shape sample, so that all of it works offline.
    for (const p of PANELS.slice(1)) {
      await page.click(`#tab-${p.tab}`);
      for (const id of p.plots) await waitPlotted(page, id);
    }
    await page.click('#tab-sshape');
    await page.click('#ss-load-sample');
    await page.waitForFunction(() => document.getElementById('ss-csv')?.value.split('\n').length > 100);
    await page.click('#tab-nonlinear');
    // Every fetch answered (the service worker stores each as it passes) before going offline.
    await waitIdle(page);
    await page.waitForLoadState('networkidle');
    await context.setOffline(true);
    await page.reload();
    await waitPlotted(page, 'nl-curve');
    const n = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-end-k', '50');
    await waitPlotted(page, 'nl-curve', n);
    // The machine presets come from the cache: choosing one redraws the machine and the panel.
    await waitPlotted(page, 'machine-schematic');
    const drawn = await waitPlotted(page, 'machine-schematic');
    const curve = await waitPlotted(page, 'nl-curve');
    await page.selectOption('#m-preset-menu', await optionValue(page, 'm-preset-menu', 'A/C fork head on a gantry'));
    await waitPlotted(page, 'machine-schematic', drawn);
    await waitPlotted(page, 'nl-curve', curve);
    assert.equal(await page.inputValue('#m-kind'), 'head-head');
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
