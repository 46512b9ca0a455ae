// The "Nonlinear error" panel in Debian's Chromium, on the machine of the Machine section: it
// computes, replots when the machine or the move changes, shows eq 26 at the pole, and keeps the
// last good plot (greyed) while a field shows why its text is not acceptable.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, traceY, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const rad = (d) => (d * Math.PI) / 180;
const PLOTS = ['nl-curve', 'nl-sweep-k', 'nl-sweep-m', 'nl-map-max', 'nl-map-u', 'nl-compare'];
/** Whether the plot `id` is greyed as no longer showing what the inputs ask for. */
const isStale = (page, id) => page.$eval(`#${id}`, (e) => (e.closest('.plot-wrap') ?? e).classList.contains('stale'));
/** The message at a field. */
const message = (page, id) => page.$eval(`#${id}`, (e) => e.closest('.field')?.querySelector('.field-msg')?.textContent ?? '');
/** The number at the start of a summary value, in µm ("3292 µm at u = …"). */
const micrometres = (text) => {
  const m = /^(-?[\d.]+(?:e[-+]?\d+)?) (µm|mm)/.exec(text);
  assert.ok(m, `a length: ${text}`);
  return Number(m[1]) * (m[2] === 'mm' ? 1000 : 1);
};

test('nonlinear panel: machine and move changes replot, eq 26 at the pole, bad input shows a message', async () => {
  await withPage({ viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    for (const id of PLOTS) await waitPlotted(page, id);

    // Default move on the default machine (table-table, CBZ, table 100 mm above the rotary
    // centre; L left empty: the machine's 100 mm), (0°, 10°) → (30°, 25°): δ(u) is zero at both
    // ends, positive inside, and the marked maximum is the curve's largest value.
    assert.equal(await page.inputValue('#nl-length'), '');
    assert.match(await page.getAttribute('#nl-length', 'placeholder'), /100/);
    assert.equal(await page.textContent('#nl-summary #nl-used-length'), '100 mm');
    const y0 = await traceY(page, 'nl-curve');
    assert.equal(y0.length, 201);
    assert.ok(Math.abs(y0[0]) < 1e-9 && Math.abs(y0[200]) < 1e-9);
    const max0 = (await traceY(page, 'nl-curve', 1))[0];
    assert.ok(max0 >= Math.max(...y0) - 1e-12 && max0 > 1, `max ${max0}`);
    // Independent of the page: the engine called directly with the same machine and move (µm).
    const direct = fa.nonlinearMove({ machine: { kind: 'table-table', type: 'CBZ', geometry: { tableHeight: 100 } }, start: { k: 0, m: 10 }, end: { k: 30, m: 25 }, samples: 201 });
    y0.forEach((v, i) => assert.ok(Math.abs(v - direct.delta[i] * 1000) < 1e-9, `u = ${direct.u[i]}: ${v} vs ${direct.delta[i] * 1000}`));
    // Fig 4: constant in θk.
    const fig4 = await traceY(page, 'nl-sweep-k');
    assert.ok(fig4.every((v) => Math.abs(v - fig4[0]) < 1e-9 * Math.max(1, fig4[0])));
    // The 12-type comparison has 12 bars, and the machine's own type is among them.
    assert.equal((await traceY(page, 'nl-compare')).length, 12);
    // The angle between the start and end tool, in degrees: on a CBZ table the tool makes θm
    // with Z and turns by θk about it, so cos γ = sin θm0·sin θm1·cos Δθk + cos θm0·cos θm1
    // (spherical law of cosines): 17.041° for (0°, 10°) → (30°, 25°).
    const gamma = Math.acos(Math.sin(rad(10)) * Math.sin(rad(25)) * Math.cos(rad(30)) + Math.cos(rad(10)) * Math.cos(rad(25)));
    assert.equal(await page.textContent('#nl-summary #nl-sweep'), `${((gamma * 180) / Math.PI).toPrecision(5)}°`);

    // Change the machine's type in the Machine section: the curve changes.
    let n = await waitPlotted(page, 'nl-curve');
    await page.selectOption('#m-type', 'ABZ');
    await waitPlotted(page, 'nl-curve', n);
    const y1 = await traceY(page, 'nl-curve');
    assert.notDeepEqual(y1, y0);
    assert.match(await page.textContent('#nl-approx'), /µm|mm/);

    // Change an angle: the curve changes again.
    n = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-end-k', '60');
    await waitPlotted(page, 'nl-curve', n);
    const y2 = await traceY(page, 'nl-curve');
    assert.notDeepEqual(y2, y1);

    // A move starting at the pole of Group I (θm = 0) on a CAZ machine shows eq 26:
    // L·sin(Δθk/2)·sin(Δθm/2) = 100 mm · sin 30° · sin 12.5°.
    await page.selectOption('#m-type', 'CAZ');
    n = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-start-m', '0');
    await waitPlotted(page, 'nl-curve', n);
    await page.waitForFunction(() => /µm|mm/.test(document.getElementById('nl-eq26')?.textContent ?? ''));
    const eq26 = micrometres(await page.textContent('#nl-eq26'));
    const expected = 100_000 * Math.sin(rad(30)) * Math.sin(rad(12.5));
    assert.ok(Math.abs(eq26 - expected) < 1e-3 * expected, `eq 26 ${eq26} µm vs ${expected}`);

    // The inverse kinematics of the tool vector (0.5, 0, cos 30°) on a CAZ table: the tool
    // tilted 30° in the XZ plane is A = ±30° with C = ∓90°; the solution nearest the start pose
    // is marked.
    await page.waitForFunction(() => /nearest the start pose/.test(document.getElementById('nl-ik-out')?.textContent ?? ''));
    const ik = await page.$$eval('#nl-ik-out li', (ls) => ls.map((l) => l.textContent));
    assert.equal(ik.length, 2, ik.join(' | '));
    for (const line of ik) assert.match(line, /^C = -?90°, A = -?30°/);

    // Bad input: a message at the field, the last good plot stays (greyed).
    const before = await traceY(page, 'nl-curve');
    const plotsBefore = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-length', 'abc');
    await page.waitForFunction(() => /not a number/.test(document.querySelector('#nl-length')?.closest('.field')?.textContent ?? ''));
    assert.equal(await page.getAttribute('#nl-length', 'aria-invalid'), 'true');
    assert.ok(await isStale(page, 'nl-curve'), 'the plot is greyed while a field is invalid');
    await page.fill('#nl-nx', '');
    await page.waitForFunction(() => /Enter a value/.test(document.querySelector('#nl-nx')?.closest('.field')?.textContent ?? ''));
    await page.fill('#nl-start-k', '99999');
    await page.waitForFunction(() => /between/.test(document.querySelector('#nl-start-k')?.closest('.field')?.textContent ?? ''));
    await waitIdle(page);
    assert.deepEqual(await traceY(page, 'nl-curve'), before);
    assert.equal(await waitPlotted(page, 'nl-curve'), plotsBefore);
    // Fixing the fields clears the messages and replots. L empty again: from the machine.
    await page.fill('#nl-length', '');
    await page.fill('#nl-nx', '61');
    await page.fill('#nl-start-k', '0');
    await waitPlotted(page, 'nl-curve', plotsBefore);
    for (const id of ['nl-length', 'nl-nx', 'nl-start-k']) assert.equal(await page.getAttribute(`#${id}`, 'aria-invalid'), null, id);
    assert.ok(!(await isStale(page, 'nl-curve')));

    // The 12-type chart compares the same tool path, not the same joint move. The issue's
    // numbers: CAZ (0°, 10°) → (30°, 25°) at L = 100 mm, as a tool path, is 0.129 mm on ABZ and
    // 3.292 mm on CAY (the same joint move gave 1.391 mm on both).
    n = await waitPlotted(page, 'nl-compare');
    await page.fill('#nl-start-m', '10');
    await page.fill('#nl-end-k', '30');
    await page.fill('#nl-length', '100');
    await page.waitForFunction(() => Number(document.getElementById('nl-compare')?.dataset.plotted) > 0);
    await page.waitForFunction((k) => {
      const y = document.getElementById('nl-compare')?.data?.[0]?.y;
      return y && Math.abs(y[6] - 129.2) < 0.5;
    }, n);
    const bars = await traceY(page, 'nl-compare');
    assert.ok(Math.abs(bars[6] - 129) < 0.5 && Math.abs(bars[10] - 3292) < 0.5, `ABZ ${bars[6]} µm, CAY ${bars[10]} µm`);
    assert.match(await page.$eval('#nl-compare .gtitle', (e) => e.textContent), /same tool path/);
    await page.fill('#nl-length', '');

    // An invalid machine field greys every plot it fed; the message is at the machine's field.
    await page.fill('#m-geometry-tableHeight', 'abc');
    await page.waitForFunction(() => document.getElementById('m-geometry-tableHeight')?.getAttribute('aria-invalid') === 'true');
    assert.match(await message(page, 'm-geometry-tableHeight'), /not a number/);
    for (const id of PLOTS) assert.ok(await isStale(page, id), `${id} greyed`);
    // A machine that gives no L (its table surface at the rotary centre) while L is empty: the
    // engine's message appears at the L field.
    await page.fill('#m-geometry-tableHeight', '0');
    await page.waitForFunction(() => /enter L/.test(document.querySelector('#nl-length')?.closest('.field')?.textContent ?? ''));
    assert.ok(await isStale(page, 'nl-curve'));
    // Back to a good machine: the plots are current again, with L from it (150 mm).
    n = await waitPlotted(page, 'nl-curve');
    await page.fill('#m-geometry-tableHeight', '150');
    await waitPlotted(page, 'nl-curve', n);
    await page.waitForFunction(() => document.getElementById('nl-used-length')?.textContent === '150 mm');
    assert.equal(await message(page, 'nl-length'), '');
    assert.ok(!(await isStale(page, 'nl-curve')));
    // A machine the engine refuses (C's travel ending below its start): the engine's message at
    // the machine's field, every plot greyed; fixed, they are current again.
    await page.fill('#m-rotary-kTo', '-400');
    await page.waitForFunction(() => /must be above where the travel of . starts/.test(document.querySelector('#m-rotary-kTo')?.closest('.field')?.textContent ?? ''));
    await page.waitForFunction((ids) => ids.every((id) => document.getElementById(id)?.closest('.plot-wrap')?.classList.contains('stale')), PLOTS);
    n = await waitPlotted(page, 'nl-curve');
    await page.fill('#m-rotary-kTo', '360');
    await waitPlotted(page, 'nl-curve', n);
    assert.equal(await message(page, 'm-rotary-kTo'), '');
    await page.waitForFunction((ids) => ids.every((id) => !document.getElementById(id)?.closest('.plot-wrap')?.classList.contains('stale')), PLOTS);

    // The console API: the same engine on `window.fiveaxis`, one object with the machine.
    const fromConsole = await page.evaluate(async () => {
      while (!window.fiveaxis) await new Promise((r) => setTimeout(r, 20));
      return window.fiveaxis.nonlinearMove({ machine: { type: 'CAZ' }, length: 1, start: { k: 0, m: 0 }, end: { k: 40, m: 40 } }).max;
    });
    assert.ok(Math.abs(fromConsole - Math.sin(rad(20)) ** 2) < 1e-9);

    await page.screenshot({ path: `${ARTIFACTS}nonlinear.png`, fullPage: true });
  });
});
