// The printed report of every panel (print media, as "Save as PDF" does): the machine it was
// computed for (its summary, its inputs and the errors entered) and a table of the panel's
// inputs instead of the forms, the plots redrawn to fit the page width, and the screen layout
// back afterwards. Tabs are found on the page, so a new panel is covered without editing this
// file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ARTIFACTS, waitIdle, withPage } from './harness.mjs';

/** Widths of the drawn plots (their SVG) in the open panel, CSS pixels. */
const plotWidths = (page) =>
  page.$$eval('.panel:not([hidden]) .js-plotly-plot', (gs) => gs.map((g) => g.querySelector('svg.main-svg')?.getBoundingClientRect().width ?? 0));

test('print report: inputs, key numbers and plots that fit the page, for every panel', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    // One error entered in the Machine section (µm): the report lists it, and no error left at 0.
    await page.fill('#m-errors-E_X0B', '20');
    await page.waitForFunction(() => /1 error entered/.test(document.getElementById('machine-summary')?.textContent ?? ''));
    // One study's report per panel (the machine's report is tested in report.test.mjs).
    await page.click('#report-menu summary');
    await page.selectOption('#rp-scope', 'study');
    await page.click('#report-menu summary');
    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    assert.ok(tabs.length >= 1);
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      // Wait until the panel has drawn its plots and the page is idle (some plots, such as an
      // identification's, stay empty until the user gives data).
      await page.waitForFunction((tab) => document.querySelector(`#panel-${tab} .js-plotly-plot`), tab, { timeout: 60_000 });
      // L left empty: the machine's own value is used, and the report must say so.
      if (tab === 'nonlinear') await page.fill('#nl-length', '');
      await waitIdle(page);
      const screen = await plotWidths(page);
      assert.ok(screen.some((w) => w > 700), `${tab}: some plot is wider than a page on screen (${screen})`);

      await page.emulateMedia({ media: 'print' });
      await page.waitForSelector(`#panel-${tab} .print-inputs`, { state: 'attached' });
      await page.waitForSelector('body[data-report=ready]');
      await page.waitForFunction(
        (tab) => [...document.querySelectorAll(`#panel-${tab} .js-plotly-plot`)].every((g) => (g.querySelector('svg.main-svg')?.getBoundingClientRect().width ?? 0) <= 700),
        tab,
      );
      // Two lists: the machine's, under its summary, then the panel's inputs.
      const [machineRows, rows] = await page.$$eval(`#panel-${tab} .print-inputs dl`, (ds) => ds.map((d) => [...d.querySelectorAll('dt')].map((t, i) => [t.textContent, d.querySelectorAll('dd')[i]?.textContent])));
      const heads = await page.$$eval(`#panel-${tab} .print-inputs h3`, (hs) => hs.map((h) => h.textContent));
      // Each verdict's tolerance is printed beside its badge and in no list of inputs.
      assert.ok(![...machineRows, ...rows].some(([label]) => /^Tolerance on /.test(label)), `${tab}: a verdict's tolerance among the inputs`);
      assert.match(heads[0], /^Machine: table-table, type CBZ/, `${tab}: ${heads}`);
      const errorRows = machineRows.filter(([label]) => /^E_/.test(label));
      assert.deepEqual(errorRows.map(([label, value]) => [label.split(':')[0], value]), [['E_X0B', '20 µm']], `${tab}: the errors entered`);
      assert.ok(machineRows.length >= 8, `${tab}: ${machineRows.length} machine rows`);
      // The panel's inputs: its form (the verdict's tolerance is printed beside the verdict).
      const controls = await page.$$eval(`#panel-${tab} form.inputs :is(input, select, textarea):not([id$=preset-menu])`, (d) => d.length);
      assert.ok(rows.length >= 3 && rows.length <= controls, `${tab}: ${rows.length} input rows printed for ${controls} controls`);
      // No value printed as a bare unit: an empty optional field says what it stands for.
      for (const [label, value] of [...machineRows, ...rows]) assert.ok(!/^\s*(mm|µm|°|%)?\s*$/.test(value ?? ''), `${tab}: ${label} printed as "${value}"`);
      if (tab === 'nonlinear') {
        const l = rows.find(([label]) => /^Tool length/.test(label));
        assert.match(l?.[1] ?? '', /^\(empty: the machine's \d/, `nonlinear: L left empty prints the machine's value (${l})`);
      }
      assert.equal(await page.$eval(`#panel-${tab} form.inputs`, (f) => getComputedStyle(f).display), 'none');
      assert.equal(await page.$eval('#machine', (m) => getComputedStyle(m).display), 'none', 'the Machine section itself is not printed');
      await page.pdf({ path: `${ARTIFACTS}report-${tab}.pdf`, format: 'A4', printBackground: true });

      await page.emulateMedia({ media: 'screen' });
      await page.waitForSelector(`#panel-${tab} .print-inputs`, { state: 'detached' });
      await page.waitForFunction((tab) => [...document.querySelectorAll(`#panel-${tab} .js-plotly-plot`)].some((g) => (g.querySelector('svg.main-svg')?.getBoundingClientRect().width ?? 0) > 700), tab);
    }
  });
});
