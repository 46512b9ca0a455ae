// The "Ball-bar (ISO 230-4)" panel in Debian's Chromium: it opens on the sample trace; a trace
// chosen or dropped is evaluated and named; the faults shown hold the faults the sample was
// made from (scripts/make-ballbar-sample.mjs, the independent numbers) within their 95 %
// intervals; G shown is the engine's (called here through wasm/pkg); the polar plot draws the
// trace at the µm per division its title states; a tolerance gives the verdict; a bad file names
// its line at the field and greys the last result; screenshots at 1366 × 768 and 390 × 844.
// "Use the squareness in the machine" enters the sample's squareness as E_C0Y with the sign the
// chain gives (crate/tests/ballbar/to_machine.rs: E_C0Y = −α, α = 30 µm/m here, Y leaning
// towards +X), keeps the machine's other values and errors, and changes the volumetric map to
// what E_C0Y alone makes: Δx = −E_C0Y·Y.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { FAULTS, ballbarSample } from '../../scripts/make-ballbar-sample.mjs';
import { ARTIFACTS, drop, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const SAMPLE_PATH = new URL('../../public/samples/ballbar-xy.csv', import.meta.url);
const SAMPLE = readFileSync(SAMPLE_PATH, 'utf8');
/** The first number in a text ("8.023 µm" → 8.023; "−3.02 µm" → −3.02). */
const number = (text) => Number(/[-−]?\d+(\.\d+)?(e[-+]?\d+)?/.exec(text)?.[0].replace('−', '-'));

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
    assert.match(await page.textContent('#bb-verdict-notes'), /backlash of X \(u\) 8\.\d+ µm/);
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
    assert.match(await page.$eval('#bb-csv', (e) => e.closest('.field').querySelector('.field-msg').textContent), new RegExp(`line ${k + 1}: expected 3 columns like the header, got 2`));
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

test('Ball-bar panel: the squareness into the machine, the volumetric map after it, the plane, a bad file', async () => {
  await withPage({ viewport: { width: 1366, height: 768 } }, async ({ page, url }) => {
    await page.goto(url);
    // Small angles in µrad, so that the machine's field reads in µm/m.
    await page.selectOption('#units-angle', 'urad');
    // A value of the machine that is not an error, to see it kept.
    await page.fill('#m-geometry-toolLength', '150');
    // The volumetric map before: no error entered.
    await page.click('#tab-volumetric');
    await page.waitForSelector('#panel-volumetric[data-ready=true]');
    await waitPlotted(page, 'vm-map');
    await waitIdle(page);
    const mapBefore = await page.textContent('#vm-worst');
    assert.match(mapBefore, /\|Δ\| = 0 /);

    await page.click('#tab-ballbar');
    await page.waitForSelector('#panel-ballbar[data-ready=true]');
    await waitPlotted(page, 'bb-polar');
    await waitIdle(page);
    // The plane is a field (XY by default) and names u and v.
    assert.equal(await page.inputValue('#bb-plane'), 'XY');
    assert.match(await page.textContent('#bb-faults-table caption'), /u is X and v is Y \(the XY plane\)/);
    const button = '#bb-use-squareness';
    assert.equal(await page.$eval(button, (b) => b.disabled), false);
    assert.match(await page.textContent(button), /^Use the squareness in the machine \(E_C0Y = -30\.\d+ µrad\)$/);
    const sq = await fault(page, 'squareness');
    assert.equal(await page.inputValue('#m-errors-E_C0Y'), '0');

    await page.click(button);
    await page.waitForFunction(() => /^Entered E_C0Y/.test(document.getElementById('bb-machine-msg')?.textContent ?? ''));
    // The field holds −30 µm/m (= µrad) within the interval the fit states: the sample's
    // squareness with the chain's sign, not the engine's number read back.
    const e = number(await page.inputValue('#m-errors-E_C0Y'));
    assert.ok(e < 0 && Math.abs(e - -FAULTS.squareness) <= sq.half, `E_C0Y ${e} µrad, want −${FAULTS.squareness} ± ${sq.half}`);
    const msg = await page.textContent('#bb-machine-msg');
    assert.match(msg, /^Entered E_C0Y = -30\.\d+ µrad into the machine \(it held 0 µrad\): Y leans towards \+X by 30\.\d+ µm\/m \(\+X and \+Y closer than 90°\)\. /);
    assert.match(msg, /the sample ballbar-xy\.csv \(synthetic\)/);
    assert.match(msg, /volumetric map .* now include it/);
    // The machine's other value is kept, and the summary counts one error.
    assert.equal(await page.inputValue('#m-geometry-toolLength'), '150');
    await page.waitForFunction(() => /1 error entered/.test(document.getElementById('machine-summary')?.textContent ?? ''));
    // What is not sent, and why.
    const notSent = await page.$$eval('#bb-not-sent li', (lis) => lis.map((l) => l.textContent));
    assert.ok(notSent.some((l) => /^backlash and reversal spikes: they depend on the direction of travel/.test(l)), notSent.join('\n'));
    assert.ok(notSent.some((l) => /^scale mismatch: only the difference of the X and Y positioning errors/.test(l)), notSent.join('\n'));
    await page.click('#bb-not-sent summary');
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}ballbar-machine-1366.png`, fullPage: true });

    // The volumetric map changes to what E_C0Y alone makes: the Y axis turned about Z moves the
    // tip by Δ = E_C0Y·ẑ × (Y·ŷ) = −E_C0Y·Y·x̂, largest at Y = ±200 mm: |Δ| = 200 mm·|E_C0Y|,
    // 6 µm for the sample's 30 µm/m (µrad = µm/m; 200 mm·1 µm/m = 0.2 µm).
    await page.click('#tab-volumetric');
    await page.waitForFunction((before) => (document.getElementById('vm-worst')?.textContent ?? before) !== before, mapBefore);
    await waitIdle(page);
    const worst = await page.textContent('#vm-worst');
    const w = number(worst.split('=')[1]);
    assert.ok(Math.abs(w - 0.2 * FAULTS.squareness) <= 0.2 * sq.half, `worst ${worst}`);
    assert.ok(Math.abs(w - 0.2 * Math.abs(e)) <= 1e-3 * w, `worst ${worst} vs 200 mm × ${e} µrad`);
    const y = Number(/Y (-?\d+)/.exec(worst)?.[1]);
    assert.equal(Math.abs(y), 200, worst);
    const dx = number((await page.textContent('#vm-worst-dev')).split('Δx')[1]);
    assert.ok(Math.abs(dx - -e * y * 1e-3) <= 2e-3 * Math.abs(dx), `Δx ${dx} µm at Y ${y}, E_C0Y ${e} µrad`);

    // Another error entered by hand, then the button again: it is kept, E_C0Y is replaced (by
    // the same value), and the message says what the machine held.
    await page.fill('#m-errors-E_X0B', '10');
    await page.click('#tab-ballbar');
    await page.click(button);
    await page.waitForFunction(() => /it held -30\.\d+ µrad/.test(document.getElementById('bb-machine-msg')?.textContent ?? ''));
    assert.equal(await page.inputValue('#m-errors-E_X0B'), '10');
    assert.equal(number(await page.inputValue('#m-errors-E_C0Y')), e);
    await page.waitForFunction(() => /2 errors entered/.test(document.getElementById('machine-summary')?.textContent ?? ''));

    // On a cross table (Y on the bed carrying X) E_C0Y turns X with Y: the message says that the
    // model cannot hold this squareness (crate/tests/ballbar/to_machine.rs shows the round circle).
    await page.selectOption('#m-linear', 'table-xy');
    await page.click(button);
    await page.waitForFunction(() => /Y carries X \(a cross table\)/.test(document.getElementById('bb-machine-msg')?.textContent ?? ''));
    await page.selectOption('#m-linear', 'spindle-xyz');

    // The plane YZ: u = Y, v = Z; the same trace gives E_A0Z = −α.
    let n = await waitPlotted(page, 'bb-polar');
    await page.selectOption('#bb-plane', 'YZ');
    n = await waitPlotted(page, 'bb-polar', n);
    await page.waitForFunction(() => /E_A0Z = -30\.\d+ µrad/.test(document.getElementById('bb-use-squareness')?.textContent ?? ''));
    assert.match(await page.textContent('#bb-faults-table caption'), /u is Y and v is Z \(the YZ plane\)/);
    assert.equal(await page.textContent('#bb-faults-table tr[data-name=backlashU] th'), 'Backlash of Y (u)');
    await page.selectOption('#bb-plane', 'XY');
    await waitPlotted(page, 'bb-polar', n);

    // A bad file: the button goes off and the box is greyed with the rest of the result; the
    // machine keeps what was entered.
    const lines = SAMPLE.split('\n');
    const k = lines.findIndex((l) => l.startsWith('45.5,'));
    lines[k] = lines[k].split(',').slice(0, 2).join(',');
    const bad = `${ARTIFACTS}ballbar-bad-2.csv`;
    writeFileSync(bad, lines.join('\n'));
    await page.setInputFiles('#bb-file', bad);
    await page.waitForFunction(() => document.getElementById('bb-faults')?.classList.contains('stale'));
    assert.ok(await page.$eval(button, (b) => b.disabled), 'nothing to enter');
    assert.ok(await page.$eval('#bb-machine', (b) => b.classList.contains('stale')), 'the machine box greyed');
    assert.equal(number(await page.inputValue('#m-errors-E_C0Y')), e);
    // Clicking the greyed button does nothing.
    await page.$eval(button, (b) => b.click());
    assert.match(await page.textContent('#bb-machine-msg'), /it held -30/);
  });
});

test('Ball-bar panel on a phone', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-ballbar');
    await page.waitForSelector('#panel-ballbar[data-ready=true]');
    await waitPlotted(page, 'bb-polar');
    await waitPlotted(page, 'bb-trace');
    await page.click('#bb-use-squareness');
    await page.waitForFunction(() => /^Entered E_C0Y/.test(document.getElementById('bb-machine-msg')?.textContent ?? ''));
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}ballbar-390.png`, fullPage: true });
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= 390), 'no sideways scrolling');
    for (const id of ['bb-polar', 'bb-trace']) {
      const w = await page.$eval(`#${id}`, (e) => e.getBoundingClientRect().width);
      assert.ok(w <= 390, `${id}: ${w} px`);
    }
  });
});
