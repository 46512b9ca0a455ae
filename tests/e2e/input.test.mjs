// Input from the shop floor: a decimal comma in semicolon-separated CSV (European CMM exports),
// a 10,000-character paste (a short quote in the message, no stretched layout), and plots
// greyed with a label while a field is invalid, back to normal when it is fixed.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { ARTIFACTS, waitIdle, waitPlotted, withPage } from './harness.mjs';

const sample = (name) => readFileSync(new URL(`../../public/samples/${name}`, import.meta.url), 'utf8');

/** The same CSV written as European software writes it: `;` between cells, a decimal comma. */
const european = (text) =>
  text
    .split('\n')
    .map((l) => (l.startsWith('#') ? l : l.replace(/,/g, ';').replace(/(\d)\.(\d)/g, '$1,$2')))
    .join('\n');

test('a decimal comma in semicolon-separated CSV gives the same identification as the comma file', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    // The cubic test's nine zones measured (µm), written here with decimal points.
    const zones = ['I', 'II-1', 'II-2', 'II-3', 'II-4', 'III-1', 'III-2', 'III-3', 'III-4'];
    const cubicFile = `zone,height_um\n${zones.map((z, i) => `${z},${(i * 0.75 - 2.5).toFixed(2)}`).join('\n')}\n`;
    for (const [tab, text, area, out] of [
      ['sshape', sample('sshape-measured.csv'), 'ss-csv', 'ss-ident'],
      ['cubic', cubicFile, 'cb-csv', 'cb-ident'],
    ]) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      const euro = european(text);
      assert.ok(/\d,\d/.test(euro) && euro.includes(';') && !/\d\.\d/.test(euro.split('\n').filter((l) => !l.startsWith('#')).join('\n')), `${tab}: rewritten with ; and decimal commas`);
      const results = [];
      for (const t of [text, euro]) {
        await page.fill(`#${area}`, t);
        await waitIdle(page);
        assert.equal(await page.$eval(`#${area}`, (e) => e.closest('.field')?.querySelector('.field-msg')?.textContent ?? ''), '', `${tab}: no message`);
        results.push(await page.$eval(`#${out}`, (e) => e.querySelector('table')?.textContent ?? e.textContent));
      }
      assert.ok(results[0].length > 50, `${tab}: ${results[0]}`);
      assert.equal(results[1], results[0], `${tab}: the same result from both spellings`);
    }
  });
});

test('a 10,000-character paste: the message quotes its start only and the layout does not stretch', async () => {
  await withPage({ viewport: { width: 1200, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    await waitPlotted(page, 'nl-curve');
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    assert.ok(width <= 1200, `${width}`);
    const paste = 'x'.repeat(10_000);
    const cases = [
      // A number field (the page's message), a list field, and CSV read by the engine.
      ['nonlinear', '#nl-length'],
      ['nonlinear', '#nl-ratios'],
      ['sshape', '#ss-csv', `curve;point;deviation_mm\ntop;1;${paste}\n`],
      ['reversal', '#rv-csv', `angle_deg;deviation_mm\n1;${paste}\n`],
    ];
    for (const [tab, id, text = paste] of cases) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      await page.fill(id, text);
      await waitIdle(page);
      // The message: at the field, or in the panel's alert for a file.
      const msg = await page.evaluate((id) => {
        const field = document.querySelector(id).closest('.field')?.querySelector('.field-msg')?.textContent ?? '';
        const alert = document.querySelector(`.panel:not([hidden]) [role=alert]`)?.textContent ?? '';
        return field || alert;
      }, id);
      assert.ok(msg.length > 10, `${id}: a message (${msg.slice(0, 100)})`);
      assert.ok(msg.length < 400, `${id}: ${msg.length} characters: ${msg.slice(0, 200)}`);
      assert.ok(!msg.includes('x'.repeat(41)) && msg.includes('…'), `${id}: ${msg}`);
      assert.equal(await page.evaluate(() => document.documentElement.scrollWidth), width, `${id}: the page is as wide as before`);
      const [box, panel] = await page.evaluate((id) => {
        const m = document.querySelector(id).closest('.field').querySelector('.field-msg');
        return [m.getBoundingClientRect().right, document.querySelector('.panel:not([hidden])').getBoundingClientRect().right];
      }, id);
      assert.ok(box <= panel + 1, `${id}: the message stays in the panel (${box} > ${panel})`);
    }
    await page.screenshot({ path: `${ARTIFACTS}input-long-paste.png` });
  });
});

/** Drawn plots of the open panel: id, greyed, the label above it. */
const plotsOf = (page, tab) =>
  page.$$eval(`#panel-${tab} .plot.js-plotly-plot`, (gs) =>
    gs.map((g) => {
      const wrap = g.closest('.plot-wrap');
      return { id: g.id, stale: !!wrap?.classList.contains('stale'), label: wrap?.querySelector(':scope > .stale-label')?.textContent ?? null, plotted: g.dataset.plotted };
    }),
  );

test('an invalid field greys every plot it feeds with a label; fixing it redraws them without', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      // The toolpath panel opens with a sample path, read in a worker.
      if (tab === 'toolpath') await waitPlotted(page, 'tp-delta');
      await waitIdle(page);
      const before = (await plotsOf(page, tab)).filter((p) => Number(p.plotted) > 0);
      assert.ok(before.length >= 1, `${tab}: drawn plots`);
      for (const p of before) assert.ok(!p.stale && p.label === null, `${tab}: ${p.id} current`);
      // The panel's first number field: a text that is not a number.
      const id = await page.$eval(`#panel-${tab} form.inputs input[data-number]:not([hidden])`, (e) => e.id);
      const original = await page.inputValue(`#${id}`);
      const counters = await waitIdle(page);
      await page.fill(`#${id}`, 'x');
      const after = await waitIdle(page);
      assert.equal(await page.getAttribute(`#${id}`, 'aria-invalid'), 'true', `${tab}: ${id} marked`);
      assert.equal(after.draws, counters.draws, `${tab}: nothing redrawn from ${id} = x`);
      // The label names the field, its tab and its message (read from the field, as shown).
      const label = (await page.textContent(`label[for="${id}"]`)).trim().replace(/\s+/g, ' ');
      const tabName = (await page.textContent(`#tab-${tab}`)).trim();
      const message = (await page.$eval(`#${id}`, (e) => e.closest('.field').querySelector('.field-msg').textContent)).trim().replace(/\.$/, '').replace(/^[A-Z](?=[a-z])/, (c) => c.toLowerCase());
      for (const p of await plotsOf(page, tab)) {
        if (!before.some((b) => b.id === p.id)) continue;
        assert.ok(p.stale, `${tab}: ${p.id} greyed while ${id} is invalid`);
        assert.equal(p.label, `Showing the last valid result; fix ${label} (${tabName} tab): ${message}.`, `${tab}: ${p.id}`);
      }
      if (tab === 'nonlinear') await page.screenshot({ path: `${ARTIFACTS}input-stale.png` });
      await page.fill(`#${id}`, original);
      await waitIdle(page);
      for (const p of await plotsOf(page, tab)) {
        if (!before.some((b) => b.id === p.id)) continue;
        assert.ok(!p.stale && p.label === null, `${tab}: ${p.id} current again after ${id} was fixed`);
      }
    }
  });
});
