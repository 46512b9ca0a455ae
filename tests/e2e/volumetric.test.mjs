// The "Volumetric error" panel in Debian's Chromium: a measured table of X positioning read from
// CSV changes the map (the worst |Δ| is the engine's for that table), heads the error budget and
// is exported with the map; a CSV with a bad line is refused at its error with the line number
// while the last map stays, greyed; a share link carries the table; the panel fits a phone.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, downloaded, guardedPage, optionValue, startBrowser, waitPlotted } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
const SAMPLE = new URL('../../public/samples/x-positioning.csv', import.meta.url);
const presets = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const tanLim = presets.find((p) => p.name.startsWith('C/A double turntable on an X table'));

/** The largest value of the heat map shown (µm). */
const mapMax = (page) => page.$eval('#vm-map', (gd) => Math.max(...gd.data[0].z.flat()));
const sentence = (page) => page.textContent('#vm-sentence');

test('volumetric panel: a measured table changes the map, heads the budget, is exported; a bad CSV names its line', async () => {
  const b = await startBrowser();
  try {
    const context = await b.browser.newContext({ acceptDownloads: true, viewport: { width: 1366, height: 768 } });
    const { page, assertClean } = await guardedPage(context, b.url);
    await page.goto(b.url);
    await page.waitForSelector('#machine[data-ready=true]');
    await page.click('#tab-volumetric');
    await page.waitForSelector('#panel-volumetric[data-ready=true]');
    // Tan & Lim's machine without errors: the map is 0.
    await page.selectOption('#m-preset-menu', await optionValue(page, 'm-preset-menu', 'C/A double turntable'));
    await page.waitForFunction(() => /type CAZ/.test(document.getElementById('machine-summary')?.textContent ?? ''));
    await page.waitForFunction(() => /No error is entered/.test(document.getElementById('vm-sentence')?.textContent ?? ''));
    const before = await waitPlotted(page, 'vm-map');

    // The laser file of X positioning: the worst |Δ| is the engine's for that table: the largest
    // |E_XX| interpolated linearly at the map's 41 X positions from −200 to 200 mm.
    await page.setInputFiles('#vm-csv-E_XX', SAMPLE.pathname);
    await page.waitForFunction(() => /E_XX/.test(document.getElementById('vm-sentence')?.textContent ?? ''));
    await waitPlotted(page, 'vm-map', before);
    const table = fa.volumetricReadTable({ name: 'E_XX', text: readFileSync(SAMPLE, 'utf8') });
    assert.deepEqual(table.units, ['mm', 'µm']);
    const expected = fa.volumetricMap({ machine: { ...tanLim.machine, motions: { E_XX: { position: table.position, value: table.value } } }, region: {} });
    const interp = (x) => {
      const i = table.position.findIndex((p, k) => x >= p && x <= table.position[k + 1]);
      const [p0, p1, v0, v1] = [table.position[i], table.position[i + 1], table.value[i], table.value[i + 1]];
      return v0 + ((v1 - v0) * (x - p0)) / (p1 - p0);
    };
    const inMap = Math.max(...Array.from({ length: 41 }, (_, i) => Math.abs(interp(-200 + 10 * i))));
    assert.ok(Math.abs(expected.worst.norm - inMap) < 1e-12, `worst ${expected.worst.norm} vs the table's largest in the map ${inMap}`);
    assert.ok(Math.abs((await mapMax(page)) - expected.worst.norm * 1000) < 1e-9, 'the map shows the engine’s |Δ| (µm)');
    assert.match(await page.textContent('#vm-worst'), new RegExp(`\\|Δ\\| = ${Number((expected.worst.norm * 1000).toPrecision(4))} µm`));
    assert.match(await page.textContent('#machine-summary'), /1 error motion entered \(Volumetric tab\)/);
    await waitPlotted(page, 'vm-table-E_XX');
    assert.match(await page.getAttribute('#vm-table-E_XX', 'aria-label'), /x-positioning\.csv/);
    assert.equal(await page.$eval('#m-motions-E_XX', (e) => e.disabled), true, 'the table replaces the constant');
    // The budget: E_XX alone, first.
    const budget = await page.$$eval('#vm-budget-table tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((c) => c.textContent)));
    assert.equal(budget[0][0], 'E_XX');
    assert.equal(budget[0][2], '100 %');
    // A constant yaw of X on top: E_XX still first (the yaw's lever is the tool length), both ranked.
    await page.fill('#m-motions-E_CX', '0.0002');
    await page.waitForFunction(() => document.querySelectorAll('#vm-budget-table tbody tr').length === 2);
    assert.equal(await page.$eval('#vm-budget-table tbody tr td', (td) => td.textContent), 'E_XX');
    await page.fill('#m-motions-E_CX', '0');
    await page.waitForFunction(() => document.querySelectorAll('#vm-budget-table tbody tr').length === 1);
    await page.screenshot({ path: `${ARTIFACTS}volumetric-desktop.png`, fullPage: true });

    // The export: a header with units and one row per point of the 41 × 41 map.
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#vm-export')]);
    assert.equal(dl.suggestedFilename(), 'volumetric-map.csv');
    const lines = readFileSync(await downloaded(dl), 'utf8').trim().split('\n').filter((l) => !l.startsWith('#'));
    assert.equal(lines[0], 'u: X (mm),v: Y (mm),X (mm),Y (mm),Z (mm),dx (µm),dy (µm),dz (µm),|Δ| (µm),tilt (°)');
    assert.equal(lines.length - 1, 41 * 41);
    const norms = lines.slice(1).map((l) => Number(l.split(',')[8]));
    assert.ok(Math.abs(Math.max(...norms) - expected.worst.norm * 1000) < 1e-6);

    // A map reaching past the table is refused at E_XX (no extrapolation), the map greyed.
    await page.fill('#vm-region-uTo', '400');
    await page.waitForFunction(() => /covers -300 to 300 mm/.test(document.getElementById('vm-csv-msg-E_XX')?.textContent ?? ''));
    assert.ok(await page.$eval('#vm-map', (e) => e.closest('.plot-wrap').classList.contains('stale')));
    await page.fill('#vm-region-uTo', '200');
    await page.waitForFunction(() => /x-positioning\.csv: 25 points/.test(document.getElementById('vm-csv-msg-E_XX')?.textContent ?? ''));
    await page.waitForFunction(() => !document.getElementById('vm-map')?.closest('.plot-wrap').classList.contains('stale'));
    assert.match(await page.textContent('#vm-functions'), /E_XX \(x-positioning\.csv, 25 points\)/);

    // A CSV with a bad third line: the message names the line at E_YY; the map stays, greyed.
    const shown = await waitPlotted(page, 'vm-map');
    const lastSentence = await sentence(page);
    await page.setInputFiles('#vm-csv-E_YY', { name: 'y-bad.csv', mimeType: 'text/csv', buffer: Buffer.from('Y (mm), E_YY (µm)\n-200, 1\n0, 1.5x\n200, 2\n') });
    await page.waitForFunction(() => /line 3/.test(document.getElementById('vm-csv-msg-E_YY')?.textContent ?? ''));
    assert.match(await page.textContent('#vm-csv-msg-E_YY'), /y-bad\.csv was not loaded: csv: line 3: /);
    assert.ok(await page.$eval('#vm-map', (e) => e.closest('.plot-wrap').classList.contains('stale')), 'the map is greyed');
    assert.match(await page.$eval('#vm-map', (e) => e.parentElement.querySelector('.plot-note')?.textContent ?? ''), /E_YY: y-bad\.csv was not loaded .*line 3/);
    assert.equal(await page.$eval('#vm-map', (e) => Number(e.dataset.plotted)), shown, 'the last good map is kept');
    assert.equal(await sentence(page), lastSentence);
    assert.ok(Math.abs((await mapMax(page)) - expected.worst.norm * 1000) < 1e-9);
    assert.equal(await page.$eval('#m-motions', (e) => Object.keys(JSON.parse(e.value)).join()), 'E_XX', 'the machine keeps its tables');

    // A share link carries the table: a fresh browser shows the same map.
    await page.click('#copy-link');
    await page.waitForFunction(() => document.getElementById('share-link')?.value.includes('#v=2'));
    const link = await page.inputValue('#share-link');
    assertClean();
    const other = await guardedPage(await b.browser.newContext({ viewport: { width: 390, height: 844 } }), b.url);
    await other.page.goto(link);
    await other.page.waitForSelector('#panel-volumetric[data-ready=true]');
    await other.page.waitForFunction(() => /E_XX/.test(document.getElementById('vm-sentence')?.textContent ?? ''));
    await waitPlotted(other.page, 'vm-map');
    assert.ok(Math.abs((await mapMax(other.page)) - expected.worst.norm * 1000) < 1e-9, 'the link carries the table');

    // At phone width nothing scrolls sideways.
    const overflow = await other.page.evaluate(() => document.documentElement.scrollWidth - document.documentElement.clientWidth);
    assert.equal(overflow, 0, 'no horizontal scrolling at 390 px');
    const wide = await other.page.$$eval('#panel-volumetric *', (els) => els.filter((e) => e.getBoundingClientRect().right > innerWidth + 0.5 && !e.closest('.visually-hidden')).map((e) => e.id || e.className).slice(0, 5));
    assert.deepEqual(wide, [], 'nothing of the panel reaches past the screen');
    await other.page.screenshot({ path: `${ARTIFACTS}volumetric-phone.png`, fullPage: true });
    // Tan & Lim's model beside the machine's at the worst point, on their machine only.
    await other.page.waitForSelector('#vm-paper-table', { state: 'attached' });
    assert.match(await other.page.textContent('#vm-paper-table'), /Their printed first-order/);
    // Resetting the machine clears its error motions as it clears its errors. (On a phone the
    // machine starts folded to its summary: a tap opens it.)
    assert.equal(await other.page.$eval('#machine-details', (d) => d.open), false, 'folded on a phone');
    await other.page.click('#machine-summary');
    await other.page.click('#machine-reset');
    await other.page.waitForFunction(() => /No error is entered/.test(document.getElementById('vm-sentence')?.textContent ?? ''));
    assert.equal(await other.page.inputValue('#m-motions'), '');
    assert.doesNotMatch(await other.page.textContent('#machine-summary'), /error motion/);
    await other.page.waitForSelector('#vm-paper-note', { state: 'attached' });
    assert.match(await other.page.textContent('#vm-paper-note'), /Choose the preset "C\/A double turntable on an X table \(Tan & Lim\)"/);
    other.assertClean();
  } finally {
    await b.close();
  }
});
