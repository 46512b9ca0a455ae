// A million-point toolpath on the page (issue 29, "big files"): the old file's results are greyed
// at once with the new file's name, the page keeps drawing frames while the file is read (the
// progress bar is seen at several values on the way: the page once froze for 16 s on 200,000
// points), and the plots are thinned for drawing only: the δ plot keeps each run's largest δ, so
// its highest point is the verdict's, which is the engine's. No time is asserted: how long the
// page's longest task takes is printed by `npm run bench` (scripts/bench-page.mjs).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { withPage, waitIdle, waitPlotted } from './harness.mjs';
import { makeBigFile } from './bigfile.mjs';

const N = 1_000_000;

test('toolpath panel: a 10^6-point file greys the old results at once, never freezes the page, and is drawn thinned', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await page.waitForFunction(() => /751 points/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await waitPlotted(page, 'tp-delta');
    await waitIdle(page);
    const drawn = Number(await page.getAttribute('#tp-delta', 'data-plotted'));
    await page.evaluate(makeBigFile, N);
    await page.evaluate(() => {
      // What the page showed of the progress bar, frame by frame: a frozen page draws no frame
      // between the start of the reading and its end, so it would show none of the values between.
      window.shown = new Set();
      const watch = () => {
        const bar = document.getElementById('tp-progress');
        if (bar && !bar.hidden) window.shown.add(bar.value);
        if (!window.stopWatching) requestAnimationFrame(watch);
      };
      requestAnimationFrame(watch);
      const d = new DataTransfer();
      d.items.add(window.bigFile);
      document.getElementById('tp-file').dispatchEvent(new DragEvent('drop', { dataTransfer: d, bubbles: true, cancelable: true }));
    });
    // At once: the old plots greyed, the file named with "Reading".
    assert.match(await page.textContent('#tp-file-msg'), /^Reading million\.csv…/);
    assert.ok(await page.$eval('#tp-delta', (p) => p.closest('.plot-wrap').classList.contains('stale')));
    // The verdict says it is computing (not "no verdict", not the old file's badge).
    assert.deepEqual(await page.$eval('#tp-verdict', (v) => [v.dataset.state, v.querySelector('.verdict-badge').textContent]), ['computing', 'COMPUTING…']);
    await page.waitForFunction(() => /^Read million\.csv: 1,000,000 points/.test(document.getElementById('tp-file-msg')?.textContent ?? ''), null, { timeout: 120_000 });
    await page.waitForFunction(() => ['pass', 'fail'].includes(document.getElementById('tp-verdict')?.dataset.verdict ?? ''), null, { timeout: 120_000 });
    await waitPlotted(page, 'tp-delta', drawn);
    await waitPlotted(page, 'tp-path', drawn);
    await waitIdle(page, 120_000);
    const between = await page.evaluate(() => {
      window.stopWatching = true;
      return [...window.shown].filter((v) => v > 0 && v < 1).length;
    });
    // Drawn while reading: the bar seen at several values between empty and full.
    assert.ok(between >= 3, `the progress bar was drawn at ${between} values between 0 and 1 while the file was read`);
    // Drawn thinned, and saying so; the highest δ drawn is the verdict's worst.
    const plot = await page.evaluate(() => {
      const p = document.getElementById('tp-delta');
      const cut = p.data.find((t) => t.name === 'δ, cutting');
      let top = 0;
      for (const y of cut.y) if (y !== null && y > top) top = y;
      return { drawn: cut.x.length, top, title: p.layout.title.text, path3d: document.getElementById('tp-path').data[0].x.length };
    });
    assert.ok(plot.drawn <= 20_000, `${plot.drawn} points drawn`);
    assert.ok(plot.path3d <= 4_100, `${plot.path3d} 3D points drawn`);
    assert.match(plot.title, /drawn: the largest δ of each run of 50 segments \(999,999 segments in all\)/);
    const worst = Number(await page.getAttribute('#tp-verdict', 'data-worst'));
    assert.match(await page.textContent('#tp-verdict-source'), /^Computed at \d\d:\d\d:\d\d from million\.csv\.$/);
    assert.ok(Math.abs(plot.top / 1000 - worst) <= 1e-12 * Math.max(1, worst), `plot ${plot.top} µm, verdict ${worst} mm`);
    assert.ok(!(await page.$eval('#tp-delta', (p) => p.closest('.plot-wrap').classList.contains('stale'))));
  });
});
