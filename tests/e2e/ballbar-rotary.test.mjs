// The "Ball-bar: rotary axes" panel in Debian's Chromium (issue 32, ISO 10791-6 style tests): it
// opens on the sample traces with the sample's three tests; the location errors the sample was
// made from (stated here on their own, as scripts/make-ballbar-rotary-sample.mjs states them)
// lie within the 95 % intervals the page shows; the worst range judged is the largest
// range of the measured traces (recomputed here from the file's own numbers); a tolerance
// above it passes; a dropped file is named; "Use these errors" puts the errors found into the
// Machine section and the volumetric map changes from nothing to something; a file with a bad
// line names it at the field and at the top and greys the last result; no sideways scrolling at
// 390 px. Screenshots at 1366 × 768 and 390 × 844.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { rotarySample } from '../../scripts/make-ballbar-rotary-sample.mjs';
import { ARTIFACTS, drop, waitIdle, waitPlotted, withPage } from './harness.mjs';

const SAMPLE_PATH = new URL('../../public/samples/ballbar-rotary.csv', import.meta.url);
const SAMPLE = readFileSync(SAMPLE_PATH, 'utf8');
/** The errors the sample was made with (mm, degrees). */
const TRUTH = { E_X0C: 0.012, E_X0B: 0.005, E_Z0B: -0.008 };
/** The first number in a text ("12.03 µm" → 12.03; "−8.289 µm" → −8.289). */
const number = (text) => Number(/[-−]?\d+(\.\d+)?(e[-+]?\d+)?/.exec(text)?.[0].replace('−', '-'));

/** Each test's range (largest − smallest deviation, µm) from the file's own lines. */
function ranges(text) {
  const out = new Map();
  for (const line of text.split('\n')) {
    if (!line || line.startsWith('#') || line.startsWith('test')) continue;
    const [name, , dev] = line.split(',').map((s) => s.trim());
    const [lo, hi] = out.get(name) ?? [Infinity, -Infinity];
    out.set(name, [Math.min(lo, Number(dev)), Math.max(hi, Number(dev))]);
  }
  return new Map([...out].map(([n, [lo, hi]]) => [n, hi - lo]));
}

test('the sample is what scripts/make-ballbar-rotary-sample.mjs writes', () => {
  assert.equal(SAMPLE, rotarySample());
});

test('Ball-bar rotary panel: sample, errors within their intervals, verdict, dropped file, into the machine, bad file', async () => {
  await withPage({ viewport: { width: 1366, height: 768 } }, async ({ page, url }) => {
    await page.goto(url);
    // ---- the volumetric map before: the machine has no errors
    await page.click('#tab-volumetric');
    await page.waitForSelector('#panel-volumetric[data-ready=true]');
    await waitPlotted(page, 'vm-map');
    await waitIdle(page);
    const worstBefore = Number(await page.getAttribute('#vm-verdict', 'data-worst'));
    assert.equal(worstBefore, 0, 'no error entered: no volumetric error');

    await page.click('#tab-ballbar-rotary');
    await page.waitForSelector('#panel-ballbar-rotary[data-ready=true]');
    await page.waitForFunction(() => document.getElementById('br-verdict')?.dataset.state === 'result');
    await waitPlotted(page, 'br-trace-0');
    await waitIdle(page);
    // It opens on the sample, with the sample's three tests, and says so.
    assert.equal(await page.inputValue('#br-csv'), SAMPLE);
    assert.equal(await page.inputValue('#br-count'), '3');
    assert.equal(await page.inputValue('#br-tests-2-name'), 'B tilt');
    assert.equal(await page.inputValue('#br-tests-1-ball-height'), '200');
    assert.ok(await page.$eval('#br-test-3', (e) => e.hidden), 'a fourth test is not shown');
    // The axis moved is named by the machine's letters, not a placeholder.
    assert.deepEqual(await page.$$eval('#br-tests-0-axis option', (o) => o.map((x) => x.textContent)), ['C', 'B']);
    assert.match(await page.textContent('#br-sum-came'), /^the sample ballbar-rotary\.csv \(synthetic\): 3 tests, 846 points/);

    // The errors the sample was made with, each within the 95 % interval shown, found present.
    for (const [name, truth] of Object.entries(TRUTH)) {
      const cells = await page.$$eval(`#br-ident-table tr[data-name=${name}] td`, (tds) => tds.map((t) => t.textContent));
      const value = number(cells[0]) / 1000;
      const half = number(cells[1]) / 1000;
      assert.ok(Math.abs(value - truth) <= half, `${name}: ${cells[0]} ± ${cells[1]} vs ${truth * 1000} µm`);
      assert.equal(cells[2], 'present', name);
      assert.ok(await page.$(`#br-corrections-table tr[data-name=${name}]`), `${name} among the numbers to enter`);
    }

    // The verdict: the worst range over a test as the file has it, against 20 µm (the default).
    const r = ranges(SAMPLE);
    const worst = Math.max(...r.values());
    assert.equal(await page.getAttribute('#br-verdict', 'data-verdict'), 'fail');
    assert.ok(Math.abs(Number(await page.getAttribute('#br-verdict', 'data-worst')) * 1000 - worst) < 1e-6, `worst range ${worst} µm`);
    assert.match(await page.textContent('#br-verdict-sentence'), new RegExp(`up to ${worst.toPrecision(4)} µm over a test \\(test C high`));
    await page.fill('#br-tolerance', '60');
    await page.waitForFunction(() => document.getElementById('br-verdict')?.dataset.verdict === 'pass');
    await page.screenshot({ path: `${ARTIFACTS}ballbar-rotary-1366.png` });
    await page.screenshot({ path: `${ARTIFACTS}ballbar-rotary-full-1366.png`, fullPage: true });

    // ---- the same traces dropped as a file of one's own: named with the result
    await drop(page, '#panel-ballbar-rotary form', 'my-traces.csv', SAMPLE);
    await page.waitForFunction(() => /^my-traces\.csv: 3 tests/.test(document.getElementById('br-sum-came')?.textContent ?? ''));
    await page.waitForFunction(() => document.getElementById('br-verdict')?.dataset.state === 'result');
    assert.match(await page.textContent('#br-verdict'), /my-traces\.csv/);

    // ---- "Use these errors": into the Machine section, the machine's other values kept
    const kept = {};
    for (const id of ['m-kind', 'm-type', 'm-linear', 'm-geometry-toolLength']) kept[id] = await page.inputValue(`#${id}`);
    await page.click('#br-use-errors');
    await page.waitForFunction(() => /Entered in the Machine section from my-traces\.csv/.test(document.getElementById('br-use-msg')?.textContent ?? ''));
    for (const [name, truth] of Object.entries(TRUTH)) {
      const field = Number(await page.inputValue(`#m-errors-${name}`)) / 1000;
      assert.ok(Math.abs(field - truth) < 0.1 * Math.abs(truth), `${name}: the machine holds ${field} mm, made with ${truth}`);
    }
    for (const [id, v] of Object.entries(kept)) assert.equal(await page.inputValue(`#${id}`), v, `${id} unchanged`);
    await page.click('#tab-volumetric');
    await page.waitForFunction(() => Number(document.getElementById('vm-verdict')?.dataset.worst ?? 0) > 0);
    const worstAfter = Number(await page.getAttribute('#vm-verdict', 'data-worst'));
    assert.ok(worstAfter > 5e-3, `the machine as measured: ${worstAfter} mm`);

    // ---- a bad file: a line whose angle is not a number names its line and greys the result
    await page.click('#tab-ballbar-rotary');
    const lines = SAMPLE.split('\n');
    const k = lines.findIndex((l) => l.startsWith('C high, 10,'));
    lines[k] = lines[k].replace('C high, 10,', 'C high, ten,');
    await drop(page, '#panel-ballbar-rotary form', 'bad-traces.csv', lines.join('\n'));
    await page.waitForFunction(() => !document.getElementById('br-alert')?.hidden);
    assert.match(await page.textContent('#br-alert'), new RegExp(`No identification from bad-traces\\.csv: line ${k + 1}:.*greyed: they belong to my-traces\\.csv`));
    assert.match(await page.$eval('#br-csv', (e) => e.closest('.field').textContent), new RegExp(`line ${k + 1}:`));
    for (const sel of ['#br-ident', '#br-corrections', '#br-summary']) assert.ok(await page.$eval(sel, (e) => e.classList.contains('stale')), `${sel} greyed`);
    assert.ok(await page.$eval('#br-trace-0', (e) => e.closest('.plot-wrap').classList.contains('stale')), 'the trace plot greyed');
    assert.equal(await page.getAttribute('#br-verdict', 'data-verdict'), 'none');
    assert.ok(await page.$eval('#br-use-errors', (b) => b.disabled), 'nothing to use');
    await page.screenshot({ path: `${ARTIFACTS}ballbar-rotary-bad-1366.png` });
  });
});

test('Ball-bar rotary panel at 390 px: no sideways scrolling', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-ballbar-rotary');
    await page.waitForSelector('#panel-ballbar-rotary[data-ready=true]');
    await waitPlotted(page, 'br-trace-0');
    await waitPlotted(page, 'br-sim-plot');
    await waitIdle(page);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'no sideways scrolling');
    await page.screenshot({ path: `${ARTIFACTS}ballbar-rotary-390.png`, fullPage: true });
  });
});
