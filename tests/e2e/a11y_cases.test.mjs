// Accessibility (axe-core: labels, contrast, roles, keyboard-reachable controls; unique ids) on
// every panel with the Machine section above, and named cases (save, list, load, delete, export
// and import as JSON) holding the machine with the panel's inputs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { ARTIFACTS, downloaded, waitIdle, waitPlotted, withPage } from './harness.mjs';

const axeSource = readFileSync(createRequire(import.meta.url).resolve('axe-core/axe.min.js'), 'utf8');
const TABS = ['nonlinear', 'cubic', 'sshape', 'probe'];

/** Ids used more than once, outside the markup Plotly draws inside a plot. */
const duplicateIds = (page) =>
  page.evaluate(() => {
    const count = {};
    for (const e of document.querySelectorAll('[id]')) {
      if (e.parentElement?.closest('.js-plotly-plot')) continue;
      count[e.id] = (count[e.id] ?? 0) + 1;
    }
    return Object.keys(count).filter((id) => count[id] > 1);
  });

test('accessibility: no serious or critical axe violations on any panel; unique ids; tabs work by keyboard', async () => {
  await withPage({ viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await waitPlotted(page, 'nl-curve');
    // The default machine (a table-table one), then one with a head (its pivot field and head
    // axes' errors shown).
    for (const kind of ['table-table', 'head-table']) {
      if (kind !== 'table-table') {
        await page.selectOption('#m-kind', kind);
        await page.waitForFunction(() => !document.getElementById('m-geometry-pivotLength')?.closest('[hidden]'));
      }
      for (const tab of TABS) {
        await page.click(`#tab-${tab}`);
        await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
        await waitIdle(page);
        // axe is injected as a script element: the page's CSP allows scripts from its own origin
        // only, so this goes through Playwright's privileged evaluation instead.
        await page.evaluate(axeSource);
        const result = await page.evaluate(async () => {
          const r = await window.axe.run(document, { resultTypes: ['violations'] });
          return r.violations.map((v) => ({ id: v.id, impact: v.impact, help: v.help, nodes: v.nodes.slice(0, 3).map((n) => n.target.join(' ')) }));
        });
        const bad = result.filter((v) => v.impact === 'serious' || v.impact === 'critical');
        assert.deepEqual(bad, [], `${kind}, ${tab}: ${JSON.stringify(bad, null, 1)}`);
        // A label, a link or a test finds one element by its id.
        assert.deepEqual(await duplicateIds(page), [], `${kind}, ${tab}: ids used twice`);
      }
    }
    // Keyboard: the selected tab is focusable and arrow keys move between tabs (from the
    // first tab, selected again: the loop above left the last one selected).
    await page.click(`#tab-${TABS[0]}`);
    await page.focus(`#tab-${TABS[0]}`);
    await page.keyboard.press('ArrowRight');
    const selected = await page.$eval('[role=tab][aria-selected=true]', (e) => e.id);
    assert.equal(selected, `tab-${TABS[1 % TABS.length]}`);
  });
});

test('named cases: save, list, load, delete, export and import', async () => {
  await withPage({ acceptDownloads: true }, async ({ page, url }) => {
    await page.goto(url);
    await waitPlotted(page, 'nl-curve');
    await page.click('details.cases summary');
    // A case holds the machine with the panel's inputs.
    await page.fill('#nl-length', '321');
    await page.fill('#m-errors-E_A0C', '0.004');
    await page.fill('#case-name', 'long tool');
    await page.click('#case-save');
    await page.fill('#nl-length', '12');
    await page.fill('#m-errors-E_A0C', '0');
    await page.selectOption('#m-type', 'CAZ');
    await page.fill('#case-name', 'short tool');
    await page.click('#case-save');
    const names = await page.$$eval('#case-list .case-name', (els) => els.map((e) => e.textContent));
    assert.deepEqual(names, ['long tool', 'short tool']);
    await page.click('button[aria-label="Load case long tool"]');
    await page.waitForFunction(() => document.getElementById('nl-length').value === '321');
    assert.equal(await page.inputValue('#m-errors-E_A0C'), '0.004');
    assert.equal(await page.inputValue('#m-type'), 'CBZ');
    // Export, delete, then import the file again.
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#case-export')]);
    const json = JSON.parse(readFileSync(await downloaded(dl), 'utf8'));
    assert.equal(json['long tool'].f['nl-length'], '321');
    assert.equal(json['long tool'].f['m-errors-E_A0C'], '0.004');
    assert.equal(json['short tool'].f['m-type'], 'CAZ');
    assert.equal(json['long tool'].v, 2);
    await page.click('button[aria-label="Delete case long tool"]');
    assert.deepEqual(await page.$$eval('#case-list .case-name', (els) => els.map((e) => e.textContent)), ['short tool']);
    const file = `${ARTIFACTS}cases.json`;
    writeFileSync(file, JSON.stringify(json));
    await page.setInputFiles('#case-import', file);
    await page.waitForFunction(() => document.querySelectorAll('#case-list .case-name').length === 2);
    // A file that is not a set of cases is refused with a reason.
    writeFileSync(`${ARTIFACTS}not-cases.json`, '[1, 2]');
    await page.setInputFiles('#case-import', `${ARTIFACTS}not-cases.json`);
    await page.waitForFunction(() => /Could not import/.test(document.querySelector('.cases-body')?.textContent ?? ''));
  });
});
