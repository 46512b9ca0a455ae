// The "Toolpath" panel in Debian's Chromium: a sample path ranked on the twelve configurations,
// δ along the path and the 3D path plotted, the refined path exported and read back, a bad file
// named by its line while the last result stays, and no request leaving the page's origin.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, downloaded, traceY, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

test('toolpath panel: a sample ranked, plotted, refined and exported; a bad file names its line', async () => {
  await withPage({ acceptDownloads: true, viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    // It opens with the impeller sample.
    await page.waitForFunction(() => /751 points \(APT/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    // The dome passes 0.3° beside the vertical: the four types whose K turns about Z flip
    // twice (see crate/tests/toolpath/compare.rs for why), ABX and ACX cannot start.
    // The dome sample, dropped on the file box as a user's file.
    const domeText = readFileSync(new URL('../../public/samples/dome-past-the-pole.csv', import.meta.url), 'utf8');
    const domeFile = await page.evaluateHandle((text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], 'dome-past-the-pole.csv', { type: 'text/csv' }));
      return dt;
    }, domeText);
    await page.dispatchEvent('#tp-file', 'drop', { dataTransfer: domeFile });
    await page.waitForFunction(() => /Read dome-past-the-pole\.csv: 81 points/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await page.waitForFunction(() => document.querySelector('#tp-ranking caption')?.textContent?.startsWith('dome-past-the-pole.csv'));
    await page.waitForFunction(() => /dome-past-the-pole\.csv/.test(document.getElementById('tp-summary')?.textContent ?? ''));
    await waitPlotted(page, 'tp-delta');
    await waitPlotted(page, 'tp-path');
    const rows = await page.$$eval('#tp-ranking tbody tr', (trs) => trs.map((tr) => ({ type: tr.dataset.type, cells: [...tr.cells].map((c) => c.textContent) })));
    assert.equal(rows.length, 12);
    for (const r of rows) {
      if (['CAZ', 'CBZ', 'CAY', 'CBX'].includes(r.type)) assert.equal(r.cells[6], '2', `${r.type}: ${r.cells}`);
      else if (['ABX', 'ACX'].includes(r.type)) assert.match(r.cells[2], /cannot follow the path: point 1/);
      else assert.equal(r.cells[6], '0', r.type);
    }
    assert.deepEqual(rows.slice(-2).map((r) => r.type).sort(), ['ABX', 'ACX']);
    // The machine's own row (the Machine section's CBZ) is marked, and no other.
    const marked = rows.filter((r) => /\(this machine/.test(r.cells[1]));
    assert.deepEqual(marked.map((r) => r.type), ['CBZ'], rows.map((r) => r.cells[1]).join(' | '));
    assert.equal(marked[0].cells[1], 'CBZ (this machine)');
    // The page's workers share the types among them; the order is the engine's own ranking.
    const dome = fa.toolpathParse(readFileSync(new URL('../../public/samples/dome-past-the-pole.csv', import.meta.url), 'utf8'), {});
    const engineOrder = fa.toolpathCompare({ machine: { type: 'CBZ', geometry: { tableHeight: 100 } }, tolerance: 0.01 }, dome.path).map((r) => r.type);
    assert.deepEqual(rows.map((r) => r.type), engineOrder);
    assert.match(await page.textContent('#tp-file-msg'), /81 points \(CSV/);
    // The machine is the default CBZ table: δ along its 80 segments, two flips marked.
    assert.equal((await traceY(page, 'tp-delta')).length, 80);
    assert.equal((await traceY(page, 'tp-delta', 2)).length, 2);
    assert.match(await page.textContent('#tp-summary'), /dome-past-the-pole\.csv/);
    await page.screenshot({ path: `${ARTIFACTS}toolpath-desktop.png`, fullPage: true });

    // Refine for CBZ at 10 µm and export: the file reads back as CSV, every original point in it,
    // and every segment of it within the tolerance on CBZ (the engine, called directly).
    await page.click('#tp-refine');
    await page.waitForFunction(() => /points inserted/.test(document.getElementById('tp-refine-out')?.textContent ?? ''));
    const added = Number(/^(\d+) points inserted/.exec(await page.textContent('#tp-refine-out'))[1]);
    assert.ok(added > 0);
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#tp-export')]);
    assert.equal(dl.suggestedFilename(), 'dome-past-the-pole-refined-CBZ.csv');
    const text = readFileSync(await downloaded(dl), 'utf8');
    const back = fa.toolpathParse(text, { format: 'auto' });
    assert.equal(back.format, 'csv');
    assert.equal(back.count, 81 + added);
    const check = fa.toolpathAnalyse({ machine: { type: 'CBZ', geometry: { tableHeight: 100 } }, tolerance: 0.01 }, back.path);
    assert.ok(check.summary.max <= 0.0100001, `refined max ${check.summary.max}`);
    assert.equal(check.summary.above, 0);
    // A refined path belongs to its inputs: another tolerance drops it.
    await page.fill('#tp-tolerance', '20');
    await page.waitForFunction(() => document.getElementById('tp-export')?.hasAttribute('disabled'));
    assert.equal(await page.textContent('#tp-refine-out'), '');
    await page.fill('#tp-tolerance', '10');

    // A bad file, dropped on the file box: the message names the line and column; the last
    // ranking stays, greyed.
    const dropped = await page.evaluateHandle(() => {
      const dt = new DataTransfer();
      dt.items.add(new File(['x,y,z,i,j,k\n0,0,0,0,0,1\n1,0,0,0,0,1x\n'], 'bad.csv', { type: 'text/csv' }));
      return dt;
    });
    await page.dispatchEvent('#tp-file', 'dragover', { dataTransfer: dropped });
    await page.dispatchEvent('#tp-file', 'drop', { dataTransfer: dropped });
    await page.waitForFunction(() => /could not be read/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    const msg = await page.textContent('#tp-file-msg');
    assert.match(msg, /line 3, column 11/);
    assert.match(msg, /still those of dome-past-the-pole\.csv/);
    assert.equal(await page.$$eval('#tp-ranking tbody tr', (t) => t.length), 12);
    assert.ok(await page.$eval('#tp-ranking', (e) => e.classList.contains('stale')));

    // The impeller's APT file, at phone width.
    await page.setViewportSize({ width: 390, height: 900 });
    await page.selectOption('#tp-sample', 'impeller-swarf.apt');
    await page.waitForFunction(() => /751 points \(APT/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await page.waitForFunction(() => !document.getElementById('tp-ranking')?.classList.contains('stale'));
    await page.screenshot({ path: `${ARTIFACTS}toolpath-phone.png`, fullPage: true });
  });
});
