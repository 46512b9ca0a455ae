// Identification you can trust (issue 13) in Debian's Chromium: the cubic panel identifies the
// errors from measured zones (the engine's own numbers, shown with the file they came from), a
// failed file removes the old results at once and says so at the top of the panel, the test
// designer's zone table is exported (the downloaded file is read back by the engine); the
// S-shape panel's failed upload does the same. Screenshots at 1366 × 768 and 390 × 844.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, optionValue, traceY, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const LI = MACHINES[0].machine;
const SSHAPE = readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8');
/** Li et al.'s Table 5 in ISO names (E = −ε of the paper), degrees for angles. */
const TABLE_5 = { E_X0B: -0.0146, E_Y0B: 0.0089, E_Z0B: 0.0142, E_A0B: 0.0023, E_B0B: -0.0029, E_C0B: 0.00002, E_A0C: 0.00017, E_X0C: -0.0094 };

/** The paper's nine zones measured on Li et al.'s machine with Table 5's errors (the engine's exact planes). */
function measured() {
  const r = fa.cubicTest({ machine: { ...LI, errors: TABLE_5 } });
  return ['zone,height_um,slope_x,slope_y', ...r.zones.map((z) => `${z.name},${(z.height * 1000).toFixed(4)},${z.slopeX.toExponential(6)},${z.slopeY.toExponential(6)}`)].join('\n') + '\n';
}

/** The cubic panel with Li et al.'s machine and Table 5's errors (the panel's preset). */
async function openCubic(page, url) {
  await page.goto(`${url}#v=2&p=cubic`);
  await page.waitForSelector('#panel-cubic[data-ready=true]');
  await page.selectOption('#cb-preset-menu', await optionValue(page, 'cb-preset-menu', 'Paper example: B/C tilting table with the errors its ball bar found'));
  await page.waitForFunction(() => document.getElementById('m-errors-E_X0B')?.value === '-14.6');
}

test('cubic panel: identification from measured zones, a failed file, the designed test exported', async () => {
  await withPage({ viewport: { width: 1366, height: 768 }, acceptDownloads: true }, async ({ page, url }) => {
    await openCubic(page, url);
    // The designer runs at once on the machine of the page.
    await page.waitForFunction(() => /possible/.test(document.getElementById('cb-design-compare')?.textContent ?? ''));
    await waitPlotted(page, 'cb-design-sv');
    const compare = await page.textContent('#cb-design-compare');
    const engine = fa.cubicDesign({ machine: LI });
    assert.match(compare, new RegExp(`${engine.designed.rank} of ${engine.reachableRank} possible`));
    assert.equal(engine.designed.rank, engine.reachableRank);

    // Identification: the paper's zones with Table 5's heights and slopes.
    const csv = measured();
    const file = `${ARTIFACTS}cubic-measured.csv`;
    writeFileSync(file, csv);
    let n = await page.evaluate(() => Number(document.getElementById('cb-fit')?.dataset.plotted ?? 0));
    await page.setInputFiles('#cb-file', file);
    await waitPlotted(page, 'cb-fit', n);
    assert.match(await page.textContent('#cb-source'), /From cubic-measured\.csv \(9 zones\), read at/);
    const f = fa.cubicIdentify({ machine: LI, csv });
    const b0b = f.estimates.find((e) => e.name === 'E_B0B');
    const cell = await page.$eval('#cb-ident-table tr[data-name=E_B0B] td', (td) => td.textContent);
    assert.ok(Math.abs(Number(cell.replace(/[^0-9.e\-−]/g, '').replace('−', '-')) - b0b.value) < 5e-4 * Math.abs(b0b.value) + 1e-12, `${cell} vs ${b0b.value}°`);
    assert.equal(await page.getAttribute('#cb-ident-table tr[data-name=E_Y0B]', 'data-verdict'), 'not-identifiable');
    assert.match(await page.textContent('#cb-groups'), /cannot see it at all/);
    const fitted = await traceY(page, 'cb-fit', 1);
    assert.equal(fitted.length, f.fitted.length);
    await page.screenshot({ path: `${ARTIFACTS}identify-cubic-1366.png`, fullPage: true });

    // A file with a bad line: the old identification goes at once, the top of the panel says so.
    const bad = csv.replace(/^II-1,[^,]*/m, 'II-1,0.0x');
    writeFileSync(`${ARTIFACTS}cubic-bad.csv`, bad);
    await page.setInputFiles('#cb-file', `${ARTIFACTS}cubic-bad.csv`);
    await page.waitForSelector('#cb-alert:not([hidden])');
    assert.match(await page.textContent('#cb-alert'), /No identification from cubic-bad\.csv: line 3: height "0\.0x" is not a number/);
    assert.equal(await page.$$eval('#cb-ident-table', (t) => t.length), 0);
    assert.equal(await page.evaluate(() => document.getElementById('cb-fit')?.data?.length ?? 0), 0);
    // The alert is at the top of the results column, right under the verdict.
    assert.equal(await page.$eval('#panel-cubic .results', (r) => r.firstElementChild?.nextElementSibling?.id), 'cb-alert');
    assert.ok(await page.$eval('#panel-cubic .results', (r) => r.firstElementChild?.classList.contains('verdict')), 'the verdict above it');
    await page.screenshot({ path: `${ARTIFACTS}identify-cubic-failed-1366.png`, fullPage: false });

    // The designed test exported: the download is the engine's zone table, which the engine
    // reads back once heights are filled in.
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#cb-design-export')]);
    const path = `${ARTIFACTS}cubic-designed-test.csv`;
    await download.saveAs(path);
    const text = readFileSync(path, 'utf8');
    const rows = text.split('\n').filter((l) => l && !l.startsWith('#'));
    assert.match(rows[0], /^zone,setup,piece_x_mm,x_mm,y_mm,tilt_deg,azimuth_deg,i,j,k,k_deg,m_deg,height_um,slope_x,slope_y$/);
    const shown = await page.$$eval('#cb-design-zones tbody tr', (rs) => rs.length);
    assert.equal(rows.length - 1, shown);
    const filled = text.replace(/,,,$/gm, ',0,0,0');
    const back = fa.cubicIdentify({ machine: LI, csv: filled });
    assert.equal(back.zones.length, shown);
    assert.equal(back.rank, engine.designed.rank);
  });
});

test('cubic panel on a phone: the designer and the identification fit', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true }, async ({ page, url }) => {
    await openCubic(page, url);
    await waitPlotted(page, 'cb-design-sv');
    await page.fill('#cb-csv', measured());
    await waitPlotted(page, 'cb-fit');
    // Nothing of the identification and the designer reaches past the screen's right edge
    // (their tables scroll in their own boxes).
    const wide = await page.evaluate(() => ['cb-ident', 'cb-design', 'cb-fit', 'cb-design-sv'].flatMap((id) =>
      [document.getElementById(id), ...document.getElementById(id).querySelectorAll('*')]
        .filter((e) => !e.closest('.table-scroll') && e.getBoundingClientRect().right > window.innerWidth + 1)
        .map((e) => `${id}: ${e.tagName} ${(e.textContent ?? '').slice(0, 40)}`)));
    assert.deepEqual(wide, []);
    await page.screenshot({ path: `${ARTIFACTS}identify-cubic-390.png`, fullPage: true });
  });
});

test('S-shape panel: a failed upload removes the last identification at once and says so at the top', async () => {
  await withPage({ viewport: { width: 1366, height: 768 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-sshape');
    await page.waitForSelector('#panel-sshape[data-ready=true]');
    await page.click('#ss-load-sample');
    await waitPlotted(page, 'ss-residuals');
    assert.match(await page.textContent('#ss-source'), /From the sample file sshape-measured\.csv \(100 points\)/);
    assert.ok((await page.$$eval('#ss-ident-table tbody tr', (r) => r.length)) > 0);
    // 41 points missing: the case.
    const missing = SSHAPE.split('\n').slice(0, 68).join('\n');
    writeFileSync(`${ARTIFACTS}missing.csv`, missing);
    await page.setInputFiles('#ss-file', `${ARTIFACTS}missing.csv`);
    await page.waitForSelector('#ss-alert:not([hidden])');
    assert.match(await page.textContent('#ss-alert'), /No identification from missing\.csv: .*points are missing.*The previous results were removed/);
    assert.equal(await page.$$eval('#ss-ident-table', (t) => t.length), 0);
    assert.equal(await page.evaluate(() => document.getElementById('ss-residuals')?.data?.length ?? 0), 0);
    assert.equal(await page.evaluate(() => document.getElementById('ss-fit')?.data?.length ?? 0), 0);
    assert.equal(await page.$eval('#panel-sshape .results', (r) => r.firstElementChild?.nextElementSibling?.id), 'ss-alert');
    assert.ok(await page.$eval('#panel-sshape .results', (r) => r.firstElementChild?.classList.contains('verdict')), 'the verdict above it');
    await page.screenshot({ path: `${ARTIFACTS}identify-sshape-failed-1366.png`, fullPage: false });
  });
});
