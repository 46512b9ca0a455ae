// Input validation on every numeric field of every panel: text that is not a number, nothing, or
// a value out of range shows a message at the field (and aria-invalid for assistive technology);
// putting the value back clears it. While a field is invalid no plot is redrawn: the last good
// result stays on screen. Tabs and fields are found on the page, so new panels and fields are
// covered without editing this file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage } from './harness.mjs';

/** How often each plot of the open panel has been drawn. */
const drawCounts = (page, tab) => page.$$eval(`#panel-${tab} .plot`, (gs) => gs.map((g) => g.dataset.plotted ?? '0').join());

async function settle(page, tab) {
  let last = '';
  for (;;) {
    const now = await drawCounts(page, tab);
    if (now === last) return now;
    last = now;
    await page.waitForTimeout(600);
  }
}

const message = (page, id) => page.$eval(`#${id}`, (e) => e.closest('.field')?.querySelector('.field-msg')?.textContent ?? '');

test('every numeric field of every panel: bad text shows a message that goes when the value is good', async () => {
  await withPage({ viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    let checked = 0;
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      await page.waitForFunction((tab) => document.querySelector(`#panel-${tab} .js-plotly-plot`), tab, { timeout: 60_000 });
      await settle(page, tab);
      const ids = await page.$$eval(`#panel-${tab} form.inputs input[inputmode=decimal]`, (es) => es.map((e) => e.id));
      assert.ok(ids.length >= 3, `${tab}: numeric fields found`);
      for (const id of ids) {
        const original = await page.inputValue(`#${id}`);
        for (const [text, expected] of [['12abc', /not a number/], ['', /Enter a value/], ['1e12', /between|at most|whole number/]]) {
          await page.fill(`#${id}`, text);
          await page.waitForFunction(([id]) => document.getElementById(id)?.getAttribute('aria-invalid') === 'true', [id]);
          assert.match(await message(page, id), expected, `${id} with "${text}"`);
        }
        await page.fill(`#${id}`, original);
        await page.waitForFunction(([id]) => !document.getElementById(id)?.hasAttribute('aria-invalid'), [id]);
        assert.equal(await message(page, id), '', `${id}: the message goes when the value is good again`);
        checked++;
      }
    }
    assert.ok(checked >= 30, `${checked} fields checked`);
  });
});

test('bad text keeps the last good plot: no redraw while a field is invalid', async () => {
  await withPage({ viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      await page.waitForFunction((tab) => document.querySelector(`#panel-${tab} .js-plotly-plot`), tab, { timeout: 60_000 });
      const before = await settle(page, tab);
      const ids = await page.$$eval(`#panel-${tab} form.inputs input[inputmode=decimal]`, (es) => es.map((e) => e.id));
      for (const id of ids) await page.fill(`#${id}`, 'x');
      await page.waitForTimeout(800);
      assert.equal(await drawCounts(page, tab), before, `${tab}: no plot was redrawn from bad input`);
    }
  });
});
