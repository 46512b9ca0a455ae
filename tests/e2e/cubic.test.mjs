// The "Cubic-machining test" panel in Debian's Chromium: a preset sets the machine (Li et al.'s,
// with Table 5's errors in the Machine section), the 3 × 3 map shows the engine's zone heights
// on the zones with Table 2's angles, and bad input shows a message at the field (of the panel
// or of the machine) while the last good plots stay, greyed.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fa, preset, T5, T5_ISO } from '../papers.mjs';
import { ARTIFACTS, optionValue, waitIdle, waitPlotted, withPage } from './harness.mjs';

const LI = preset('B/C tilting table, vertical spindle (Li et al. 2021)');
const ISO = T5_ISO;
/** Li et al.'s Table 2: (C, B) per zone, degrees. */
const TABLE_2 = { I: [0, 0], 'II-1': [0, 30], 'II-2': [90, 30], 'II-3': [180, 30], 'II-4': [270, 30], 'III-1': [45, 30], 'III-2': [135, 30], 'III-3': [225, 30], 'III-4': [315, 30] };
const rad = (d) => (d * Math.PI) / 180;
const PLOTS = ['cb-zones', 'cb-map', 'cb-sens'];
/**
 * Li et al.'s Fig 2, rows top to bottom as printed (columns left to right): which zone is
 * where, [col, row] with −1 left/bottom. Table 1 agrees: the tool leans towards the centre,
 * so (i, j) of each zone points opposite its place.
 */
const FIG_2 = [['III-4', 'II-4', 'III-3'], ['II-1', 'I', 'II-3'], ['III-1', 'II-2', 'III-2']];
const PLACE = Object.fromEntries(FIG_2.flatMap((names, r) => names.map((n, c) => [n, [c - 1, 1 - r]])));
/** The zone labels of a plot: name and where it is written, as signs of x and y. */
const labelsAt = (page, id) =>
  page.$eval(`#${id}`, (gd) => gd.layout.annotations.map((a) => ({ name: a.text.replace(/<[^>]+>/g, ' ').trim().split(/[ :]/)[0], x: a.x, y: a.y })));

/** The 3 × 3 heat map's values (rows bottom to top), the texts on the zones and the hover texts. */
const zonesShown = (page) =>
  page.$eval('#cb-zones', (gd) => ({
    z: gd.data[0].z.map((r) => Array.from(r)),
    text: gd.layout.annotations.map((a) => a.text),
    hover: gd.data[0].text.flat(),
  }));

/** Waits until every plot has been drawn more often than in `before`, then until the page is idle. */
async function redrawn(page, before) {
  for (const id of PLOTS) await waitPlotted(page, id, before[id]);
  await waitIdle(page);
}
const counts = async (page) => Object.fromEntries(await Promise.all(PLOTS.map(async (id) => [id, await waitPlotted(page, id)])));
/** The draw counts once the page is idle (no engine call in flight, no edit waiting, no plot
 *  being drawn). */
async function settled(page) {
  await waitIdle(page);
  return counts(page);
}
const allStale = (page, on, ids = PLOTS) =>
  page.waitForFunction(([ids, on]) => ids.every((id) => document.getElementById(id)?.closest('.plot-wrap')?.classList.contains('stale') === on), [ids, on]);

test('cubic panel: the Table 5 preset gives the engine\'s zone heights on the 3 × 3 map; bad input shows a message', async () => {
  await withPage({ viewport: { width: 1400, height: 1900 } }, async ({ page, url }) => {
    await page.goto(`${url}#v=2&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    // Zero errors: every zone at 0.
    let before = await counts(page);
    assert.ok((await zonesShown(page)).z.flat().every((v) => Math.abs(v) < 1e-6));

    // Choose the Table 5 machine from the preset menu: it sets Li et al.'s machine and its
    // errors in the Machine section (µm and degrees shown: the default units).
    await page.selectOption('#cb-preset-menu', await optionValue(page, 'cb-preset-menu', 'Paper example: B/C tilting table with the errors its ball bar found'));
    await redrawn(page, before);
    await page.waitForFunction(() => document.getElementById('m-errors-E_X0B')?.value === '-14.6');
    assert.equal(await page.inputValue('#m-errors-E_A0C'), '0.00017');
    assert.equal(await page.inputValue('#m-errors-E_Z0B'), '14.2');
    assert.equal(await page.inputValue('#m-geometry-tableHeight'), '0');
    assert.equal(await page.inputValue('#m-type'), 'CBZ');
    // Independent of the page: the engine called directly with the paper's values (mm, degrees).
    const r = fa.cubicTest({ machine: { ...LI, errors: ISO } });
    const shown = await zonesShown(page);
    for (const zone of r.zones) {
      const v = shown.z[zone.row + 1][zone.col + 1];
      assert.ok(Math.abs(v - zone.height * 1000) < 1e-9, `${zone.name}: ${v} µm vs ${zone.height * 1000}`);
      // The value written on the zone: "<b>II-1</b><br>-5.4 µm".
      const label = shown.text.find((t) => t.includes(`<b>${zone.name}</b>`));
      assert.ok(label, zone.name);
      const written = Number(label.split('<br>')[1].replace(/[^0-9.eE+-]/g, ''));
      assert.ok(Math.abs(written - zone.height * 1000) <= 0.006 * Math.max(1, Math.abs(zone.height * 1000)), `${zone.name}: ${label}`);
      // The hover text names the zone's C and B commands: Table 2.
      const [c, b] = TABLE_2[zone.name];
      assert.ok(shown.hover.some((t) => t.startsWith(`ZONE ${zone.name}: C = ${c}°, B = ${b}°`)), `${zone.name}: Table 2's C = ${c}°, B = ${b}°`);
    }
    // II-1 against the first-order closed form: −sin 30°·δxBY + (cos 30° − 1)·δzBY.
    const ii1 = (-0.5 * T5.dxBY + (Math.cos(rad(30)) - 1) * T5.dzBY) * 1000;
    assert.ok(Math.abs(shown.z[1][0] - ii1) < 1e-3, `II-1 ${shown.z[1][0]} µm vs ${ii1}`);
    // The height map's zone averages are on it too, and the summary names the extremes.
    const mapTexts = await page.$eval('#cb-map', (gd) => gd.layout.annotations.map((a) => a.text));
    assert.equal(mapTexts.length, 9);
    // Each zone's label on its own cell, on both maps: Fig 2's layout (not the page's output).
    for (const id of ['cb-zones', 'cb-map']) {
      const labels = await labelsAt(page, id);
      assert.deepEqual(labels.map((l) => l.name).sort(), Object.keys(PLACE).sort(), id);
      for (const l of labels) assert.deepEqual([Math.sign(l.x) || 0, Math.sign(l.y) || 0], PLACE[l.name], `${id}: ${l.name} at (${l.x}, ${l.y})`);
    }
    for (const zone of r.zones) assert.deepEqual([zone.col, zone.row], PLACE[zone.name], `engine: ${zone.name}`);
    // ZONE I, cut at the set-up (height 0 by definition here), is never named highest or lowest.
    const judged = r.zones.filter((z) => !(z.name === 'I' && Math.abs(z.height) < 1e-9));
    const hs = judged.map((z) => z.height);
    const extremes = `${judged[hs.indexOf(Math.max(...hs))].name} / ${judged[hs.indexOf(Math.min(...hs))].name}`;
    assert.equal(await page.textContent('#cb-high'), extremes);
    // What the test cannot see (Section 4.3): δyBY and δxCB.
    const blind = await page.textContent('#cb-blind');
    assert.ok(blind.includes('E_Y0B') && blind.includes('E_X0C'), blind);
    // The sensitivity chart: one bar series of 9 zones per error the heights see; E_X0B's at
    // II-1 is sin 30° (µm per µm).
    const bars = await page.$eval('#cb-sens', (gd) => gd.data.map((t) => ({ name: t.name, x: Array.from(t.x), y: Array.from(t.y) })));
    const seen = r.errorNames.filter((n) => !r.visibility.invisible.includes(n));
    assert.deepEqual(bars.map((b) => b.name.replace(' (angle)', '')), seen);
    assert.ok(bars.every((b) => b.y.length === 9));
    const x0b = bars.find((b) => b.name === 'E_X0B');
    assert.ok(Math.abs(x0b.y[x0b.x.indexOf('II-1')] - 0.5) < 1e-9, `${x0b.y}`);
    await page.screenshot({ path: `${ARTIFACTS}cubic.png`, fullPage: true });
    for (const id of PLOTS) await page.locator(`#${id}`).screenshot({ path: `${ARTIFACTS}${id}.png` });

    // Without the workpiece transformation ZONE I follows δzBY: −14.2 µm.
    before = await counts(page);
    await page.setChecked('#cb-transform', false);
    await redrawn(page, before);
    const zoneI = (await zonesShown(page)).z[1][1];
    assert.ok(Math.abs(zoneI + 14.2) < 0.01, `ZONE I ${zoneI}`);

    // Bad input in the Machine section: a message at the field, the plots keep their last good
    // data, greyed (one field at a time made good again, the other still bad).
    before = await settled(page);
    const last = await zonesShown(page);
    await page.fill('#m-errors-E_Z0B', 'abc');
    await page.waitForFunction(() => /not a number/.test(document.querySelector('#m-errors-E_Z0B')?.closest('.field')?.textContent ?? ''));
    assert.equal(await page.getAttribute('#m-errors-E_Z0B', 'aria-invalid'), 'true');
    await allStale(page, true);
    await page.fill('#m-errors-E_A0B', '9');
    await page.waitForFunction(() => /between/.test(document.querySelector('#m-errors-E_A0B')?.closest('.field')?.textContent ?? ''));
    await page.fill('#m-errors-E_Z0B', '14.2');
    await waitIdle(page);
    await allStale(page, true);
    assert.deepEqual(await counts(page), before);
    assert.deepEqual(await zonesShown(page), last);
    await page.fill('#m-errors-E_A0B', '0.0023');
    await redrawn(page, before);
    await allStale(page, false);
    assert.deepEqual(await zonesShown(page), last);
    // A pick feed larger than the ball: the engine refuses it, its message appears at the
    // field, and no plot is redrawn; the two it refused are greyed.
    before = await settled(page);
    await page.fill('#cb-setup-pick', '7');
    await page.waitForFunction(() => /diameter/.test(document.querySelector('#cb-setup-pick')?.closest('.field')?.textContent ?? ''));
    await waitIdle(page);
    assert.deepEqual(await counts(page), before);
    assert.deepEqual(await zonesShown(page), last);
    await allStale(page, true, ['cb-zones', 'cb-map']);
    await page.fill('#cb-setup-pick', '0.1');
    await waitPlotted(page, 'cb-zones', before['cb-zones']);
    assert.equal(await page.getAttribute('#cb-setup-pick', 'aria-invalid'), null);
    await page.screenshot({ path: `${ARTIFACTS}cubic-no-transform.png`, fullPage: true });
  });
});

test('cubic panel on another machine: an A/C trunnion table with its A axis 20 µm low', async () => {
  await withPage({ viewport: { width: 1400, height: 1900 } }, async ({ page, url }) => {
    await page.goto(`${url}#v=2&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    const before = await counts(page);
    await page.selectOption('#cb-preset-menu', await optionValue(page, 'cb-preset-menu', 'A/C trunnion table'));
    await redrawn(page, before);
    await page.waitForFunction(() => document.getElementById('m-errors-E_Z0A')?.value === '-20');
    assert.equal(await page.inputValue('#m-type'), 'CAZ');
    // A shift t of the tilting axis moves the set-up workpiece by P·t − t (the C turn keeps z):
    // every tilted zone by E_Z0A·(1 − cos 30°), ZONE I not at all.
    const { z, hover } = await zonesShown(page);
    const expected = -20 * (1 - Math.cos(rad(30)));
    z.flat().forEach((v, i) => {
      const want = i === 4 ? 0 : expected;
      assert.ok(Math.abs(v - want) < 1e-6, `cell ${i}: ${v} µm vs ${want}`);
    });
    // The axes are this machine's: C and A.
    assert.ok(hover.every((t) => /^ZONE I{1,3}(-\d)?: C = -?[\d.]+°, A = -?[\d.]+°/.test(t)), hover[0]);
  });
});
