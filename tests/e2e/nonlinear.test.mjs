// The "Nonlinear error" panel in Debian's Chromium: it computes, replots on change, and keeps
// the last good plot while a field shows why its text is not acceptable.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ARTIFACTS, traceY, waitPlotted, withPage } from './harness.mjs';

test('nonlinear panel: type and angle changes replot, bad input shows a message', async () => {
  await withPage({ viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    const ids = ['nl-curve', 'nl-sweep-k', 'nl-sweep-m', 'nl-map-max', 'nl-map-u', 'nl-compare'];
    for (const id of ids) await waitPlotted(page, id);

    // Default move (CAZ, L = 100 mm, (0°, 10°) → (30°, 25°)): δ(u) is zero at both ends,
    // positive inside, and the marked maximum is the curve's largest value.
    const y0 = await traceY(page, 'nl-curve');
    assert.equal(y0.length, 201);
    assert.ok(Math.abs(y0[0]) < 1e-9 && Math.abs(y0[200]) < 1e-9);
    const max0 = (await traceY(page, 'nl-curve', 1))[0];
    assert.ok(max0 >= Math.max(...y0) - 1e-12 && max0 > 1, `max ${max0}`);
    // Fig 4: constant in θk.
    const fig4 = await traceY(page, 'nl-sweep-k');
    assert.ok(fig4.every((v) => Math.abs(v - fig4[0]) < 1e-9 * Math.max(1, fig4[0])));
    // The 12-type comparison has 12 bars.
    assert.equal((await traceY(page, 'nl-compare')).length, 12);

    // Change the type: the curve changes.
    let n = await waitPlotted(page, 'nl-curve');
    await page.selectOption('#nl-type', 'ABZ');
    await waitPlotted(page, 'nl-curve', n);
    const y1 = await traceY(page, 'nl-curve');
    assert.notDeepEqual(y1, y0);
    assert.match(await page.textContent('#nl-approx'), /µm|mm/);

    // Change an angle: the curve changes again.
    n = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-k1', '60');
    await waitPlotted(page, 'nl-curve', n);
    const y2 = await traceY(page, 'nl-curve');
    assert.notDeepEqual(y2, y1);

    // A move starting at the pole of Group I (θm = 0) shows eq 26.
    await page.selectOption('#nl-type', 'CAZ');
    n = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-m0', '0');
    await waitPlotted(page, 'nl-curve', n);
    assert.match(await page.textContent('#nl-eq26'), /µm|mm/);

    // Bad input: a message at the field, the last good plot stays.
    const before = await traceY(page, 'nl-curve');
    const plotsBefore = await waitPlotted(page, 'nl-curve');
    await page.fill('#nl-length', 'abc');
    await page.waitForFunction(() => /not a number/.test(document.querySelector('#nl-length')?.closest('.field')?.textContent ?? ''));
    assert.equal(await page.getAttribute('#nl-length', 'aria-invalid'), 'true');
    await page.fill('#nl-length', '');
    await page.waitForFunction(() => /Enter a value/.test(document.querySelector('#nl-length')?.closest('.field')?.textContent ?? ''));
    await page.fill('#nl-k0', '99999');
    await page.waitForFunction(() => /between/.test(document.querySelector('#nl-k0')?.closest('.field')?.textContent ?? ''));
    await page.waitForTimeout(300);
    assert.deepEqual(await traceY(page, 'nl-curve'), before);
    assert.equal(await waitPlotted(page, 'nl-curve'), plotsBefore);
    // Fixing the fields clears the messages and replots.
    await page.fill('#nl-length', '100');
    await page.fill('#nl-k0', '0');
    await waitPlotted(page, 'nl-curve', plotsBefore);
    assert.equal(await page.getAttribute('#nl-length', 'aria-invalid'), null);

    // The console API: the same engine on `window.fiveaxis`.
    const fromConsole = await page.evaluate(async () => {
      while (!window.fiveaxis) await new Promise((r) => setTimeout(r, 20));
      return window.fiveaxis.nonlinearMove({ type: 'CAZ', length: 1, start: { k: 0, m: 0 }, end: { k: 40, m: 40 } }).max;
    });
    assert.ok(Math.abs(fromConsole - Math.sin((20 * Math.PI) / 180) ** 2) < 1e-9);

    await page.screenshot({ path: `${ARTIFACTS}nonlinear.png`, fullPage: true });
  });
});
