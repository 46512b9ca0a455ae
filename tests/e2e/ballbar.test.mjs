// The "Ball-bar (ISO 230-4)" panel in Debian's Chromium: it opens on the sample trace; a trace
// chosen or dropped is evaluated and named; the faults shown hold the faults the sample was
// made from (scripts/make-ballbar-sample.mjs, the independent numbers) within their 95 %
// intervals; G shown is the engine's (called here through wasm/pkg); the polar plot draws the
// trace at the µm per division its title states; a tolerance gives the verdict; a bad file names
// its line at the field and greys the last result; screenshots at 1366 × 768 and 390 × 844.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { FAULTS, ballbarSample } from '../../scripts/make-ballbar-sample.mjs';
import { ARTIFACTS, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const SAMPLE_PATH = new URL('../../public/samples/ballbar-xy.csv', import.meta.url);
const SAMPLE = readFileSync(SAMPLE_PATH, 'utf8');
/** The first number in a text ("8.023 µm" → 8.023; "−3.02 µm" → −3.02). */
const number = (text) => Number(/[-−]?\d+(\.\d+)?(e[-+]?\d+)?/.exec(text)?.[0].replace('−', '-'));

/** Drops a file named `name` holding `text` on the element `selector` (as a user drags one). */
async function drop(page, selector, name, text) {
  await page.evaluate(([selector, name, text]) => {
    const dt = new DataTransfer();
    dt.items.add(new File([text], name, { type: 'text/csv' }));
    const zone = document.querySelector(selector);
    for (const type of ['dragenter', 'dragover', 'drop']) zone.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, [selector, name, text]);
}

/** The value and half-width shown for a fault (display units) and its row's text. */
async function fault(page, name) {
  const [value, interval] = await page.$$eval(`#bb-faults-table tr[data-name=${name}] td`, (tds) => tds.map((t) => t.textContent));
  return { value: number(value), half: number(interval.replace('±', '')), text: `${value} ${interval}` };
}

test('the sample is what scripts/make-ballbar-sample.mjs writes', () => {
  assert.equal(SAMPLE, ballbarSample());
});

test('Ball-bar panel: sample, file chosen and dropped, faults against the sample’s own, verdict, polar scale, bad file', async () => {
  await withPage({ viewport: { width: 1366, height: 768 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-ballbar');
    await page.waitForSelector('#panel-ballbar[data-ready=true]');
    let n = await waitPlotted(page, 'bb-polar');
    // It opens on the sample, and says so.
    assert.equal(await page.inputValue('#bb-csv'), SAMPLE);
    assert.match(await page.textContent('#bb-sum-came'), /^the sample ballbar-xy\.csv \(synthetic\): radius 100 mm \(from the file\), feed 1000 mm\/min \(from the file\), 360 points CCW and 360 CW/);
    // No tolerance of G yet: no verdict, G named.
    assert.equal(await page.getAttribute('#bb-verdict', 'data-verdict'), 'none');
    assert.match(await page.textContent('#bb-verdict-sentence'), /No tolerance of G entered/);

    // The same trace chosen as a file: the result names the file.
    await page.setInputFiles('#bb-file', SAMPLE_PATH.pathname);
    await page.waitForFunction(() => /^ballbar-xy\.csv: radius 100 mm/.test(document.getElementById('bb-sum-came')?.textContent ?? ''));
    n = await waitPlotted(page, 'bb-polar', n - 1);

    // G shown is the engine's (mm → µm, 4 significant digits).
    const engine = fa.ballbarEvaluate({ csv: SAMPLE });
    const g = number(await page.textContent('#bb-sum-g'));
    assert.ok(Math.abs(g - engine.g * 1000) <= 5e-4 * engine.g * 1000, `G ${g} µm vs the engine's ${engine.g * 1000}`);
    assert.ok(Math.abs(number(await page.textContent('#bb-sum-h')) - engine.h * 1000) <= 5e-4 * engine.h * 1000, 'H');

    // The faults the sample was made from, each within its 95 % interval as shown; those it was
    // made without (servo mismatch, backlash of v) hold 0.
    const truth = {
      backlashU: FAULTS.backlashX,
      squareness: FAULTS.squareness,
      scaleMismatch: FAULTS.scaleMismatch,
      centreU: FAULTS.centre[0],
      centreV: FAULTS.centre[1],
      backlashV: 0,
      servoMismatch: 0,
    };
    for (const [name, want] of Object.entries(truth)) {
      const f = await fault(page, name);
      assert.ok(Math.abs(f.value - want) <= f.half, `${name}: ${f.text} should hold ${want}`);
      // An interval that says something: narrower than a tenth of the fault, or of 1 unit.
      assert.ok(f.half < Math.max(0.1 * Math.abs(want), 0.5), `${name}: ${f.text} is too wide to test anything`);
    }
    assert.match((await fault(page, 'squareness')).text, /µm\/m/);
    assert.match((await fault(page, 'scaleMismatch')).text, /ppm/);
    assert.match((await fault(page, 'servoMismatch')).text, / ms/);
    assert.equal(await page.$$eval('#bb-spikes-table tbody tr', (rs) => rs.length), 8);
    assert.equal(await page.$$eval('#bb-harmonics-table tbody tr', (rs) => rs.length), 4);

    // The polar plot at the scale its title states: r = 4 divisions + deviation / (µm per
    // division), the deviation (hover and CSV) the engine's, in µm.
    const title = await page.getAttribute('#bb-polar', 'aria-label');
    const perDiv = number(/([\d.]+) µm per division/.exec(title)?.[1] ?? '');
    assert.ok(perDiv > 0, title);
    const polar = await page.$eval('#bb-polar', (gd) => gd.data.map((t) => ({ name: t.name, r: Array.from(t.r), d: Array.from(t.customdata ?? []) })));
    assert.deepEqual(polar.map((t) => t.name), ['nominal circle', 'CCW measured', 'CCW fitted faults', 'CW measured', 'CW fitted faults']);
    const ccw = engine.deviation.filter((_, i) => engine.direction[i] > 0);
    const fittedCw = engine.fitted.filter((_, i) => engine.direction[i] < 0);
    ccw.forEach((d, i) => assert.ok(Math.abs(polar[1].d[i] - d * 1000) < 1e-9 && Math.abs(polar[1].r[i] - (4 + (d * 1000) / perDiv)) < 1e-9, `CCW point ${i}`));
    fittedCw.forEach((d, i) => assert.ok(Math.abs(polar[4].r[i] - (4 + (d * 1000) / perDiv)) < 1e-9, `CW fitted point ${i}`));
    // Every point within the drawn rings (the radial axis ends at 7 divisions).
    assert.ok(polar.every((t) => t.r.every((r) => r > 0 && r < 7)), 'the trace within the plot');

    // A tolerance: pass above G, fail below it.
    for (const [tol, want] of [[Math.ceil(g) + 1, 'pass'], [Math.floor(g) - 1, 'fail']]) {
      await page.fill('#bb-tolerance', String(tol));
      await page.waitForFunction((want) => document.getElementById('bb-verdict')?.dataset.verdict === want, want);
      const sentence = await page.textContent('#bb-verdict-sentence');
      assert.match(sentence, new RegExp(`G = ${g} µm over both directions, ${want === 'pass' ? 'within' : 'above'} the ${tol} µm tolerance`));
      assert.equal(Number(await page.getAttribute('#bb-verdict', 'data-tolerance')), tol / 1000);
    }
    assert.match(await page.textContent('#bb-verdict-notes'), /backlash of u 8\.\d+ µm/);
    await page.fill('#bb-tolerance', '15');
    await page.waitForFunction(() => document.getElementById('bb-verdict')?.dataset.verdict === 'pass');
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}ballbar-1366.png`, fullPage: true });

    // The trace dropped on the form under another name: that name is what the result says.
    n = await waitPlotted(page, 'bb-polar');
    const dropped = SAMPLE.replace('# radius: 100 mm', '# radius: 150 mm');
    await drop(page, '#panel-ballbar form.inputs', 'machine-7 xy.csv', dropped);
    await page.waitForFunction(() => /^machine-7 xy\.csv: radius 150 mm \(from the file\)/.test(document.getElementById('bb-sum-came')?.textContent ?? ''));
    await waitPlotted(page, 'bb-polar', n);
    // The same deviations read as a 150 mm bar: squareness in µm/m scales with 100/150.
    const sq150 = await fault(page, 'squareness');
    assert.ok(Math.abs(sq150.value - FAULTS.squareness * (100 / 150)) <= sq150.half, sq150.text);

    // A bad file: line k loses its CW column. The message names the line at the field; the
    // plots and tables of the trace before stay, greyed; no verdict.
    const lines = SAMPLE.split('\n');
    const k = lines.findIndex((l) => l.startsWith('90.5,'));
    lines[k] = lines[k].split(',').slice(0, 2).join(',');
    const bad = `${ARTIFACTS}ballbar-bad.csv`;
    writeFileSync(bad, lines.join('\n'));
    const before = await page.$eval('#bb-polar', (gd) => gd.data[1].r.slice(0, 5));
    await page.setInputFiles('#bb-file', bad);
    await page.waitForFunction((line) => new RegExp(`line ${line}:`).test(document.querySelector('#bb-csv')?.closest('.field')?.querySelector('.field-msg')?.textContent ?? ''), k + 1);
    assert.match(await page.$eval('#bb-csv', (e) => e.closest('.field').querySelector('.field-msg').textContent), /CW deviation is not a number/);
    await page.waitForFunction(() => document.getElementById('bb-polar')?.closest('.plot-wrap')?.classList.contains('stale'));
    for (const id of ['bb-trace']) assert.ok(await page.$eval(`#${id}`, (e) => e.closest('.plot-wrap').classList.contains('stale')), `${id} greyed`);
    for (const id of ['bb-faults', 'bb-spikes', 'bb-harmonics']) assert.ok(await page.$eval(`#${id}`, (e) => e.classList.contains('stale')), `${id} greyed`);
    assert.ok(await page.$eval('#bb-summary', (e) => e.classList.contains('stale')), 'the key numbers greyed');
    assert.notEqual(await page.getAttribute('#bb-verdict', 'data-verdict'), 'pass');
    assert.notEqual(await page.getAttribute('#bb-verdict', 'data-verdict'), 'fail');
    assert.deepEqual(await page.$eval('#bb-polar', (gd) => gd.data[1].r.slice(0, 5)), before, 'the last good trace is kept');
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}ballbar-bad.png`, fullPage: true });
  });
});

test('Ball-bar panel on a phone', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-ballbar');
    await page.waitForSelector('#panel-ballbar[data-ready=true]');
    await waitPlotted(page, 'bb-polar');
    await waitPlotted(page, 'bb-trace');
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}ballbar-390.png`, fullPage: true });
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= 390), 'no sideways scrolling');
    for (const id of ['bb-polar', 'bb-trace']) {
      const w = await page.$eval(`#${id}`, (e) => e.getBoundingClientRect().width);
      assert.ok(w <= 390, `${id}: ${w} px`);
    }
  });
});
