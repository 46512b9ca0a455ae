// The "Cubic-machining test" panel in Debian's Chromium: a preset fills the errors, the 3 × 3
// map shows the engine's zone heights on the zones, and bad input shows a message at the field
// while the last good plots stay.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../crate/pkg/fiveaxis.js';
import { ARTIFACTS, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../crate/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const TABLE5 = { dxBY: 0.0146, dyBY: -0.0089, dzBY: -0.0142, alphaBY: -0.0023, betaBY: 0.0029, gammaBY: -0.00002, alphaCB: -0.00017, dxCB: 0.0094 };
const PLOTS = ['cb-zones', 'cb-map', 'cb-sens'];

/** The 3 × 3 heat map's values (rows bottom to top) and the texts written on the zones. */
const zonesShown = (page) =>
  page.$eval('#cb-zones', (gd) => ({ z: gd.data[0].z.map((r) => Array.from(r)), text: gd.layout.annotations.map((a) => a.text) }));

/** Waits until every plot has been drawn more often than in `before`, then for quiet. */
async function redrawn(page, before) {
  for (const id of PLOTS) await waitPlotted(page, id, before[id]);
  await page.waitForTimeout(300);
}
const counts = async (page) => Object.fromEntries(await Promise.all(PLOTS.map(async (id) => [id, await waitPlotted(page, id)])));

test('cubic panel: the Table 5 preset gives the engine\'s zone heights on the 3 × 3 map; bad input shows a message', async () => {
  await withPage({ viewport: { width: 1400, height: 1900 } }, async ({ page, url }) => {
    await page.goto(`${url}#v=1&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    // Zero errors: every zone at 0.
    let before = await counts(page);
    assert.ok((await zonesShown(page)).z.flat().every((v) => Math.abs(v) < 1e-9));

    // Choose the Table 5 machine from the preset menu (µm shown: the default unit).
    const option = await page.$eval('#cb-preset-menu', (s) => [...s.options].find((o) => o.text.startsWith('Table 5: '))?.value);
    await page.selectOption('#cb-preset-menu', option);
    await redrawn(page, before);
    assert.equal(await page.inputValue('#cb-dxBY'), '14.6');
    assert.equal(await page.inputValue('#cb-alphaCB'), '-0.00017');
    // Independent of the page: the engine called directly with the paper's values.
    const r = fa.cubicTest({ errors: TABLE5 });
    const shown = await zonesShown(page);
    for (const zone of r.zones) {
      const v = shown.z[zone.row + 1][zone.col + 1];
      assert.ok(Math.abs(v - zone.height * 1000) < 1e-9, `${zone.name}: ${v} µm vs ${zone.height * 1000}`);
      // The value written on the zone: "<b>II-1</b><br>-5.4 µm".
      const label = shown.text.find((t) => t.includes(`<b>${zone.name}</b>`));
      assert.ok(label, zone.name);
      const written = Number(label.split('<br>')[1].replace(/[^0-9.eE+-]/g, ''));
      assert.ok(Math.abs(written - zone.height * 1000) <= 0.006 * Math.max(1, Math.abs(zone.height * 1000)), `${zone.name}: ${label}`);
    }
    // The height map's zone averages are on it too, and the summary names the extremes.
    const mapTexts = await page.$eval('#cb-map', (gd) => gd.layout.annotations.map((a) => a.text));
    assert.equal(mapTexts.length, 9);
    const hs = r.zones.map((z) => z.height);
    const extremes = `${r.zones[hs.indexOf(Math.max(...hs))].name} / ${r.zones[hs.indexOf(Math.min(...hs))].name}`;
    assert.equal(await page.textContent('#cb-high'), extremes);
    // The sensitivity chart: 8 errors × 9 zones.
    const bars = await page.$eval('#cb-sens', (gd) => gd.data.map((t) => t.y.length));
    assert.deepEqual(bars, [9, 9, 9, 9, 9, 9, 9, 9]);
    await page.screenshot({ path: `${ARTIFACTS}cubic.png`, fullPage: true });
    for (const id of PLOTS) await page.locator(`#${id}`).screenshot({ path: `${ARTIFACTS}${id}.png` });

    // Without the workpiece transformation ZONE I follows δzBY: −14.2 µm.
    before = await counts(page);
    await page.setChecked('#cb-transform', false);
    await redrawn(page, before);
    const zoneI = (await zonesShown(page)).z[1][1];
    assert.ok(Math.abs(zoneI + 14.2) < 0.01, `ZONE I ${zoneI}`);

    // Bad input: a message at the field; the plots keep their last good data.
    const last = await zonesShown(page);
    await page.fill('#cb-dzBY', 'abc');
    await page.waitForFunction(() => /not a number/.test(document.querySelector('#cb-dzBY')?.closest('.field')?.textContent ?? ''));
    assert.equal(await page.getAttribute('#cb-dzBY', 'aria-invalid'), 'true');
    await page.fill('#cb-dzBY', '-14.2');
    await page.fill('#cb-alphaBY', '9');
    await page.waitForFunction(() => /between/.test(document.querySelector('#cb-alphaBY')?.closest('.field')?.textContent ?? ''));
    await page.fill('#cb-alphaBY', '-0.0023');
    await page.waitForTimeout(500);
    // A pick feed larger than the ball: the engine refuses it, its message appears at the
    // field, and no plot is redrawn.
    before = await counts(page);
    await page.fill('#cb-pick', '7');
    await page.waitForFunction(() => /diameter/.test(document.querySelector('#cb-pick')?.closest('.field')?.textContent ?? ''));
    await page.waitForTimeout(300);
    assert.deepEqual(await counts(page), before);
    assert.deepEqual(await zonesShown(page), last);
    await page.fill('#cb-pick', '0.1');
    await waitPlotted(page, 'cb-zones', before['cb-zones']);
    assert.equal(await page.getAttribute('#cb-pick', 'aria-invalid'), null);
    await page.screenshot({ path: `${ARTIFACTS}cubic-no-transform.png`, fullPage: true });
  });
});
