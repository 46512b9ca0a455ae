// The "Rotary-axis reversal" panel in Debian's Chromium: Table 1's presets set the B/C tilting
// table and the test; the ball-bar plot, the radial deviation, C against time and the linear axes
// draw; the dent shown is the engine's (called here directly) and doubles with r; X and Y keep
// their direction; a bad input greys the plots with a message at the field; the sample trace is
// fitted (its f_c within the interval); a damaged file names its line; screenshots at 1366 × 768
// and 390 × 844; nothing is logged as an error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, downloaded, optionValue, traceY, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const SAMPLE = readFileSync(new URL('../../public/samples/reversal-measured.csv', import.meta.url), 'utf8');
const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const LI = MACHINES.find((p) => p.name.startsWith('B/C tilting table')).machine;
/** Screenshots to look at: the test artifacts, or the folder SHOTS names. */
const SHOTS = process.env.SHOTS ?? ARTIFACTS;
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
    const [header, ...csvLines] = readFileSync(await downloaded(dl), 'utf8').trim().split('\n');
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

/**
 * The dent of a trace file measured here from its rows, by the definition the engine states
 * (crate/src/reversal/measure.rs): baseline b = median deviation over 170°–179° of trace angle;
 * fall g = b − deviation; depth = the largest g over 180°–190°; width = the span around it where
 * g ≥ depth/2, its ends interpolated linearly, up to the last point of 170°–190° when it does not
 * come back (`open`). Deviations in mm, angles in degrees.
 */
function dentOf(csv) {
  const rows = csv.split('\n').map((l) => l.trim()).filter((l) => l && !l.startsWith('#'));
  const [header, ...data] = rows;
  assert.deepEqual(header.split(','), ['angle_deg', 'deviation_mm']);
  const pts = data.map((l) => l.split(',').map(Number));
  const within = (lo, hi) => pts.filter(([a]) => a >= lo && a <= hi);
  const median = (v) => {
    const s = [...v].sort((x, y) => x - y);
    const n = s.length;
    return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
  };
  const b = median(within(170, 179).map(([, d]) => d));
  const span = within(170, 190).map(([a, d]) => [a, b - d]);
  let k = -1;
  span.forEach(([a, g], j) => { if (a >= 180 && (k < 0 || g > span[k][1])) k = j; });
  const [angle, depth] = span[k];
  const half = depth / 2;
  const cross = (i, o) => span[i][0] + ((half - span[i][1]) / (span[o][1] - span[i][1])) * (span[o][0] - span[i][0]);
  let i = k;
  while (i > 0 && span[i - 1][1] >= half) i--;
  let j = k;
  while (j + 1 < span.length && span[j + 1][1] >= half) j++;
  const open = j + 1 === span.length;
  const low = i > 0 ? cross(i, i - 1) : span[0][0];
  const high = open ? span[j][0] : cross(j, j + 1);
  return { baseline: b, depth, angle, width: high - low, open };
}

test('Rotary-axis reversal: with a trace loaded the verdict is on the trace, its machine is offered, the friction in a drive’s terms', async () => {
  const truth = dentOf(SAMPLE);
  const made = /^# machine: (.+)$/m.exec(SAMPLE)?.[1];
  assert.ok(made && MACHINES.some((p) => p.name === made), `the sample names a machine preset: ${made}`);
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-reversal');
    await page.waitForSelector('#panel-reversal[data-ready=true]');
    await waitPlotted(page, 'rv-polar');
    const sentence = () => page.textContent('#rv-verdict-sentence');
    // Without a trace the verdict is on the simulation, and says so.
    await page.waitForFunction(() => document.getElementById('rv-verdict')?.dataset.verdict !== 'none');
    assert.match(await sentence(), /^Simulated \(no measured trace loaded\)/);
    assert.match(await page.textContent('#rv-verdict-notes'), /No measured trace is loaded/);

    // Another machine: the A/C trunnion. The sample was made on the B/C tilting table.
    let n = await waitPlotted(page, 'rv-polar');
    await page.selectOption('#m-preset-menu', await optionValue(page, 'm-preset-menu', 'A/C trunnion'));
    n = await waitPlotted(page, 'rv-polar', n);
    assert.equal(await page.inputValue('#m-type'), 'CAZ');
    await page.click('#rv-load-sample');

    // The verdict is on the trace: its depth is the one measured here from the file's rows.
    await page.waitForFunction(() => /^On the measured trace/.test(document.getElementById('rv-verdict-sentence')?.textContent ?? ''));
    const worst = Number(await page.getAttribute('#rv-verdict', 'data-worst'));
    assert.ok(Math.abs(worst - truth.depth) < 1e-12, `verdict ${worst} mm, file ${truth.depth} mm`);
    const s = await sentence();
    assert.match(s, /\(the sample trace\)/);
    const falls = Number(/falls (-?[\d.]+) µm/.exec(s)?.[1]);
    assert.ok(Math.abs(falls - truth.depth * 1000) <= 5e-4 * truth.depth * 1000, `${falls} µm shown, ${truth.depth * 1000} µm in the file`);
    const deepest = Number(/deepest at ([\d.]+)°/.exec(s)?.[1]);
    assert.ok(Math.abs(deepest - truth.angle) <= 0.05, `${deepest}° vs ${truth.angle}°`);
    const wide = Number(/([\d.]+)° wide at half depth/.exec(s)?.[1]);
    assert.ok(Math.abs(wide - truth.width) <= 5e-3 * truth.width, `${wide}° vs ${truth.width}°`);
    assert.equal(/at least [\d.]+° wide/.test(s), truth.open, s);
    const tol = Number(await page.getAttribute('#rv-verdict', 'data-tolerance'));
    assert.equal(await page.getAttribute('#rv-verdict', 'data-verdict'), truth.depth <= tol ? 'pass' : 'fail');

    // The file's machine is offered; the fit on this machine says the trace was made on another
    // (whether the fit converges there or not: with A at 0 the trunnion draws the same circle).
    await page.waitForSelector('#rv-switch-machine');
    assert.equal((await page.textContent('#rv-switch-machine')).trim(), `Switch to ${made}`);
    const madeOn = `made on “${made}”`;
    assert.ok((await page.textContent('#rv-trace-machine')).includes(madeOn));
    assert.ok((await page.textContent('#rv-verdict-notes')).includes(madeOn));
    await page.waitForFunction((m) => (document.getElementById('rv-fit')?.textContent ?? '').includes(m), madeOn, { timeout: 120_000 });

    // Switch: the machine becomes the file's, the fit converges, the offer goes.
    await page.click('#rv-switch-machine');
    await page.waitForFunction(() => document.getElementById('m-type')?.value === 'CBZ');
    await waitPlotted(page, 'rv-residuals');
    await page.waitForFunction(() => !document.getElementById('rv-switch-machine'));
    assert.match(await page.textContent('#rv-trace-machine'), /the layout of the machine above/);

    // The friction as a share of the rated torque, from the numbers shown.
    const checkShares = async () => {
      await page.waitForFunction(() => /rated torque/.test(document.getElementById('rv-verdict-notes')?.textContent ?? ''));
      const notes = await page.textContent('#rv-verdict-notes');
      const fc = Number(/f_c = ([\d.]+) N·m/.exec(notes)?.[1]);
      const share = Number(/([\d.]+) % of the drive’s rated torque \(([\d.]+) N·m\)/.exec(notes)?.[1]);
      const ratedShown = Number(/of the drive’s rated torque \(([\d.]+) N·m\)/.exec(notes)?.[1]);
      const rated = Number(await page.inputValue('#rv-c-ratedTorque'));
      assert.equal(ratedShown, rated);
      assert.ok(Math.abs(share - (100 * fc) / rated) <= 1e-3 * share, `${share} % vs ${fc} / ${rated}`);
      const step = Number(/torque step of 2·f_c = ([\d.]+) N·m/.exec(notes)?.[1]);
      const stepShare = Number(/at each reversal \(([\d.]+) % of the rated torque\)/.exec(notes)?.[1]);
      assert.ok(Math.abs(step - 2 * fc) <= 1e-3 * step, `${step} vs 2 × ${fc}`);
      assert.ok(Math.abs(stepShare - (100 * step) / rated) <= 1e-3 * stepShare, `${stepShare} % vs ${step} / ${rated}`);
      // The fit table's f_c is the verdict's.
      const [fitted] = await page.$$eval('#rv-fit-table tr[data-name=friction] td', (tds) => tds.map((t) => t.textContent));
      assert.equal(Number(/[\d.]+/.exec(fitted)[0]), fc);
      return share;
    };
    const share250 = await checkShares();
    // Another rated torque: the share follows it.
    let r = await waitPlotted(page, 'rv-residuals');
    await page.fill('#rv-c-ratedTorque', '125');
    r = await waitPlotted(page, 'rv-residuals', r);
    const share125 = await checkShares();
    assert.ok(Math.abs(share125 / share250 - 2) < 2e-3, `${share125} / ${share250}`);
    // A rated torque above the torque limit is refused at its field.
    await page.fill('#rv-c-ratedTorque', '600');
    await page.waitForFunction(() => document.getElementById('rv-c-ratedTorque')?.getAttribute('aria-invalid') === 'true');
    assert.match(await page.$eval('#rv-c-ratedTorque', (e) => e.closest('.field').textContent), /above the torque limit/);
    await page.fill('#rv-c-ratedTorque', '250');
    await waitPlotted(page, 'rv-residuals', r);

    // Screenshots of the panel with the trace (1366 px), for a look.
    mkdirSync(SHOTS, { recursive: true });
    await page.screenshot({ path: `${SHOTS}reversal-trace-1366.png`, fullPage: true });
    await (await page.$('#rv-verdict')).screenshot({ path: `${SHOTS}reversal-verdict-1366.png` });
  });
});

test('Rotary-axis reversal: a trace on a phone, its machine offered within the screen', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-reversal');
    await page.waitForSelector('#panel-reversal[data-ready=true]');
    await waitPlotted(page, 'rv-polar');
    // The machine section starts folded on a phone.
    await page.selectOption('#m-preset-menu', await optionValue(page, 'm-preset-menu', 'A/C trunnion'), { force: true });
    await page.waitForFunction(() => document.getElementById('m-type')?.value === 'CAZ');
    await page.click('#rv-load-sample');
    await page.waitForSelector('#rv-switch-machine');
    await page.waitForFunction(() => /^On the measured trace/.test(document.getElementById('rv-verdict-sentence')?.textContent ?? ''));
    const box = await page.$eval('#rv-switch-machine', (e) => e.getBoundingClientRect().right);
    assert.ok(box <= 390, `switch button ends at ${box} px`);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= 390), 'no sideways scroll');
    mkdirSync(SHOTS, { recursive: true });
    await page.screenshot({ path: `${SHOTS}reversal-trace-390.png`, fullPage: true });
    await (await page.$('#rv-verdict')).screenshot({ path: `${SHOTS}reversal-verdict-390.png` });
    await (await page.$('#rv-trace-machine')).screenshot({ path: `${SHOTS}reversal-machine-390.png` });
  });
});
