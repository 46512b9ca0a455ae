// The "Rotary-axis reversal" panel in Debian's Chromium: Table 1's presets set the B/C tilting
// table and the test; the ball-bar plot, the radial deviation, C against time and the linear axes
// draw; the dent shown is the engine's (called here directly) and doubles with r; X and Y keep
// their direction; a bad input greys the plots with a message at the field; the sample trace is
// fitted (its f_c within the interval); a damaged file names its line; screenshots at 1366 × 768
// and 390 × 844; nothing is logged as an error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, optionValue, traceY, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const SAMPLE = readFileSync(new URL('../../public/samples/reversal-measured.csv', import.meta.url), 'utf8');
const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const LI = MACHINES.find((p) => p.name.startsWith('B/C tilting table')).machine;
const number = (text) => Number(/(-?[\d.]+)/.exec(text)?.[1]);

async function choose(page, start) {
  const n = await waitPlotted(page, 'rv-polar');
  await page.selectOption('#rv-preset-menu', await optionValue(page, 'rv-preset-menu', start));
  return waitPlotted(page, 'rv-polar', n);
}

test('Rotary-axis reversal panel: trace, dent, directions, fit of the sample trace', async () => {
  await withPage({ viewport: { width: 1366, height: 768 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-reversal');
    await page.waitForSelector('#panel-reversal[data-ready=true]');
    for (const id of ['rv-polar', 'rv-radial', 'rv-time', 'rv-linear']) await waitPlotted(page, id);

    // Table 1, F = 1000 mm/min, r = 25 mm on the B/C tilting table: the dent is the engine's.
    await choose(page, 'Paper example: feed 1000 mm/min, circle 25 mm off the C axis');
    assert.equal(await page.inputValue('#rv-test-feed'), '1000');
    assert.equal(await page.inputValue('#m-type'), 'CBZ');
    await page.waitForFunction(() => /deep at/.test(document.getElementById('rv-sum-dent')?.textContent ?? ''));
    const r25 = fa.reversalSimulate({ machine: LI, test: { feed: 1000, offset: 25 } });
    const shown25 = number(await page.textContent('#rv-sum-dent'));
    assert.ok(Math.abs(shown25 - r25.dent.depth * 1000) < 1e-3 * r25.dent.depth * 1000 + 1e-3, `${shown25} µm vs ${r25.dent.depth * 1000}`);
    // The polar plot: nominal circle, without and with friction; the trace with friction is the
    // engine's radial deviation, magnified by the scale per division in the title.
    const names = await page.$eval('#rv-polar', (gd) => gd.data.map((t) => t.name));
    assert.deepEqual(names, ['nominal circle', 'without friction', 'with friction (eq 2)']);
    // X and Y keep their direction at the reversal; the step check is shown.
    const dirs = await page.textContent('#rv-sum-directions');
    assert.match(dirs, /X keeps its direction.*Y keeps its direction/);
    assert.doesNotMatch(dirs, /REVERSES/);
    assert.match(await page.textContent('#rv-sum-step'), /halving it changes the trace by/);
    // The ball-bar plot's CSV: trace angle and the radial deviations (µm), not the drawing's
    // magnified radius; the engine's numbers.
    const csvButton = await page.$('#rv-polar ~ .plot-tools button[data-export=csv]');
    const [dl] = await Promise.all([page.waitForEvent('download'), csvButton.click()]);
    const [header, ...csvLines] = readFileSync(await dl.path(), 'utf8').trim().split('\n');
    assert.equal(header, 'trace angle θ (°),nominal circle [radial deviation (µm)],without friction [radial deviation (µm)],with friction (eq 2) [radial deviation (µm)]');
    assert.equal(csvLines.length, r25.theta.length);
    const k0 = r25.reversalIndex;
    const cols = csvLines[k0].split(',').map(Number);
    assert.ok(Math.abs(cols[0] - r25.theta[k0]) < 1e-9 && Math.abs(cols[3] - r25.deviation[k0] * 1000) < 1e-9, csvLines[k0]);
    // Table 1's six conditions in the dent table.
    await page.waitForFunction(() => document.querySelectorAll('#rv-dents-table tbody tr').length === 6);
    await page.screenshot({ path: `${ARTIFACTS}reversal.png`, fullPage: true });
    await page.screenshot({ path: `${ARTIFACTS}reversal-1366.png`, fullPage: false });

    // r = 50 mm: the dent doubles (Fig 13), and one axis stops without reversing (Section 5.2).
    await choose(page, 'Paper example: feed 1000 mm/min, circle 50 mm off the C axis');
    await page.waitForFunction(() => /r 50 mm/.test(document.getElementById('rv-sum-came')?.textContent ?? ''));
    const shown50 = number(await page.textContent('#rv-sum-dent'));
    assert.ok(Math.abs(shown50 / shown25 - 2) < 0.1, `${shown50} / ${shown25}`);
    assert.match(await page.textContent('#rv-sum-directions'), /stops, keeps its direction/);

    // A bad input: a message at the field, every plot greyed.
    await page.fill('#rv-test-feed', '-5');
    await page.waitForFunction(() => document.getElementById('rv-polar')?.closest('.plot-wrap')?.classList.contains('stale'));
    assert.equal(await page.getAttribute('#rv-test-feed', 'aria-invalid'), 'true');
    for (const id of ['rv-radial', 'rv-time', 'rv-linear']) {
      assert.ok(await page.$eval(`#${id}`, (e) => e.closest('.plot-wrap').classList.contains('stale')), id);
    }
    let n = await waitPlotted(page, 'rv-polar');
    await page.fill('#rv-test-feed', '1000');
    await waitPlotted(page, 'rv-polar', n);

    // The sample trace: the fit holds the values it was simulated with (its header).
    await choose(page, 'Paper example: feed 1000 mm/min, circle 25 mm off the C axis');
    await page.click('#rv-load-sample');
    await waitPlotted(page, 'rv-residuals');
    assert.equal(await page.inputValue('#rv-csv'), SAMPLE);
    const cells = async (name) => page.$$eval(`#rv-fit-table tr[data-name=${name}] td`, (tds) => tds.map((t) => t.textContent));
    for (const [name, truth] of [['friction', 12], ['frictionSlope', 800], ['positionGain', 28]]) {
      const [, interval] = await cells(name);
      const [lo, hi] = interval.match(/-?[\d.]+(e[-+]?\d+)?/g).map(Number);
      assert.ok(lo <= truth && truth <= hi, `${name}: ${interval}`);
    }
    assert.match(await page.textContent('#rv-compensator'), /torque step of 2·f_c = /);
    const residuals = await traceY(page, 'rv-residuals');
    const rms = Math.sqrt(residuals.reduce((s, r) => s + r * r, 0) / residuals.length);
    assert.ok(rms > 0.2 && rms < 0.4, `residual RMS ${rms} µm (the sample's noise is 0.3 µm)`);
    await page.screenshot({ path: `${ARTIFACTS}reversal-fit.png`, fullPage: true });

    // A damaged file: the message names its line, the last fit stays.
    const before = await traceY(page, 'rv-residuals');
    const lines = SAMPLE.split('\n');
    const k = lines.findIndex((l) => l.startsWith('1.000,'));
    lines[k] = lines[k].replace(',', ',x');
    const file = `${ARTIFACTS}reversal-bad.csv`;
    writeFileSync(file, lines.join('\n'));
    await page.setInputFiles('#rv-file', file);
    await page.waitForFunction((line) => new RegExp(`line ${line}:`).test(document.querySelector('#rv-csv')?.closest('.field')?.textContent ?? ''), k + 1);
    assert.equal(await page.getAttribute('#rv-csv', 'aria-invalid'), 'true');
    assert.deepEqual(await traceY(page, 'rv-residuals'), before);
  });
});

test('Rotary-axis reversal panel on a phone', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-reversal');
    await page.waitForSelector('#panel-reversal[data-ready=true]');
    for (const id of ['rv-polar', 'rv-radial', 'rv-time', 'rv-linear']) await waitPlotted(page, id);
    await page.screenshot({ path: `${ARTIFACTS}reversal-390.png`, fullPage: true });
    // The plots fit the screen.
    for (const id of ['rv-polar', 'rv-time']) {
      const w = await page.$eval(`#${id}`, (e) => e.getBoundingClientRect().width);
      assert.ok(w <= 390, `${id}: ${w} px`);
    }
  });
});
