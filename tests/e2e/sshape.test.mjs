// The "S-shape test piece" panel in Debian's Chromium: the part and the overcut maps draw; the
// Table 4 preset sets Chanal et al.'s machine and errors in the Machine section and the defect
// plot follows its error fields; the sample measurement file from public/ loads and is
// identified with the paper's eight errors (values and residuals shown, the choice of errors
// followed); a malformed file gets a message naming its line; nothing is logged as an error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, optionValue, traceY, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const SAMPLE = readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8');
const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const CHANAL = MACHINES.find((p) => p.name === 'B swivel head, C rotary table, Y under the table (Chanal et al. 2022)').machine;
/** Chanal et al.'s Table 4 (values for simulation): E_X0B mm, E_A0B 3.2419e-4 rad in degrees. */
const TABLE_4 = { E_X0B: 0.0294, E_A0B: (3.2419e-4 * 180) / Math.PI };
/** The eight errors the paper identifies (Section 5.2). */
const PAPER_PARAMETERS = ['E_C0Y', 'E_A0Z', 'E_B0Z', 'E_A0C', 'E_B0C', 'E_X0B', 'E_A0B', 'E_C0B'];
const checkedParameters = (page) => page.$$eval('#ss-parameters input[type=checkbox]:checked', (es) => es.map((e) => e.value));

test('S-shape panel: part, overcut, defects, identification of the sample file', async () => {
  await withPage({ viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-sshape');
    await page.waitForSelector('#panel-sshape[data-ready=true]');
    for (const id of ['ss-part', 'ss-overcut-a', 'ss-overcut-b', 'ss-defects']) await waitPlotted(page, id);

    // Overcut summary: eq 6, the exact gouge and the paper's values are shown, in µm by default.
    assert.match(await page.textContent('#ss-max-a'), /eq 6 3\d\.\d+ µm.*exact gouge 2\d\.\d+ µm.*paper 38\.7 µm/);
    assert.match(await page.textContent('#ss-max-b-inner'), /eq 6 1[23]\.\d+ µm/);

    // The Table 4 preset: Chanal et al.'s machine (B head, C table, L0 = 499.889 mm) with
    // E_X0B and E_A0B in the Machine section, the paper's eight errors to identify.
    let n = await waitPlotted(page, 'ss-defects');
    const preset = await optionValue(page, 'ss-preset-menu', 'Paper example: B head / C table, B axis 29.4 µm off');
    await page.selectOption('#ss-preset-menu', preset);
    await page.waitForFunction(() => document.getElementById('m-errors-E_X0B')?.value === '29.4');
    await waitPlotted(page, 'ss-defects', n);
    assert.equal(await page.inputValue('#m-kind'), 'head-table');
    assert.equal(await page.inputValue('#m-linear'), 'table-y');
    assert.equal(Number(await page.inputValue('#m-geometry-pivotLength')) + Number(await page.inputValue('#m-geometry-toolLength')), 499.889);
    assert.ok(Math.abs(Number(await page.inputValue('#m-errors-E_A0B')) - TABLE_4.E_A0B) < 1e-12);
    assert.deepEqual((await checkedParameters(page)).sort(), [...PAPER_PARAMETERS].sort());

    // Two contributions and the total; they are the engine's, called directly with the paper's
    // values on the preset machine.
    await page.waitForFunction(() => document.getElementById('ss-defects')?.data?.some((t) => t.name === 'E_A0B'));
    const names = await page.$eval('#ss-defects', (gd) => gd.data.map((t) => t.name));
    assert.deepEqual(names.slice(0, 3), ['E_X0B', 'E_A0B', 'total']);
    const d = fa.sshapeDefects({ machine: { ...CHANAL, errors: TABLE_4 }, tool: { rTool: 10, lTool: 35 } });
    const x0b = await traceY(page, 'ss-defects', 0);
    const total = await traceY(page, 'ss-defects', 2);
    const ix = d.names.indexOf('E_X0B');
    x0b.forEach((v, k) => assert.ok(Math.abs(v - d.contributions[k * d.names.length + ix] * 1000) < 1e-9, `E_X0B at point ${k + 1}`));
    total.forEach((v, k) => assert.ok(Math.abs(v - d.total[k] * 1000) < 1e-9, `total at point ${k + 1}`));
    // E_X0B's line follows its field in the Machine section: twice the value, twice the line.
    n = await waitPlotted(page, 'ss-defects');
    await page.fill('#m-errors-E_X0B', '58.8'); // µm
    await waitPlotted(page, 'ss-defects', n);
    const twice = await traceY(page, 'ss-defects', 0);
    twice.forEach((v, i) => assert.ok(Math.abs(v - 2 * x0b[i]) < 1e-9 * Math.max(1, Math.abs(v)), `point ${i}`));
    // The tool passes along C at four points (13 and 37 of each curve): C undefined there.
    assert.match(await page.textContent('#ss-singular'), /4 of 100 points/);
    await page.fill('#m-errors-E_X0B', '29.4');

    // Identification of the sample file (simulated with E_X0B = 0.0294 mm, E_A0B = 3.2419e-4 rad,
    // a tool 0.02 mm small and 2 µm of noise).
    await page.click('#ss-load-sample');
    await waitPlotted(page, 'ss-residuals');
    assert.equal(await page.inputValue('#ss-csv'), SAMPLE);
    const row = async (name) => page.$eval(`#ss-ident-table tr[data-name=${name}] td`, (td) => td.textContent);
    await page.waitForFunction(() => document.querySelectorAll('#ss-ident-table tbody tr').length === 9);
    const x0bText = await row('E_X0B');
    const x0bUm = Number(x0bText.replace(/[^0-9.\-]/g, ''));
    assert.ok(Math.abs(x0bUm - 29.4) < 1.5, `E_X0B ${x0bText}`);
    const drText = await row('dR');
    assert.ok(Math.abs(Number(drText.replace(/[^0-9.\-]/g, '')) + 20) < 1.5, `dR ${drText}`);
    // The table shows the engine's identification (4 significant digits).
    const f = fa.sshapeIdentify({ machine: CHANAL, tool: { rTool: 10, lTool: 35 }, csv: SAMPLE, parameters: PAPER_PARAMETERS });
    const engineX0B = f.estimates.find((e) => e.name === 'E_X0B').value * 1000;
    assert.ok(Math.abs(x0bUm - engineX0B) <= 5e-4 * Math.abs(engineX0B), `${x0bUm} vs ${engineX0B}`);
    const residuals = await traceY(page, 'ss-residuals');
    assert.equal(residuals.length, 100);
    const rms = Math.sqrt(residuals.reduce((s, r) => s + r * r, 0) / 100);
    assert.ok(rms > 1 && rms < 3, `residual RMS ${rms} µm (the sample's noise is 2 µm)`);
    assert.match(await page.textContent('#ss-ident'), /Rank 9 of 9/);
    await page.screenshot({ path: `${ARTIFACTS}sshape.png`, fullPage: true });

    // The choice of errors: without E_C0B, eight parameters (seven errors and dR).
    n = await waitPlotted(page, 'ss-residuals');
    await page.setChecked('#ss-parameters-E_C0B', false);
    await waitPlotted(page, 'ss-residuals', n);
    await page.waitForFunction(() => /Rank 8 of 8/.test(document.getElementById('ss-ident')?.textContent ?? ''));
    assert.equal(await page.$$eval('#ss-ident-table tr[data-name=E_C0B]', (rs) => rs.length), 0);
    n = await waitPlotted(page, 'ss-residuals');
    await page.setChecked('#ss-parameters-E_C0B', true);
    await waitPlotted(page, 'ss-residuals', n);

    // Eq 14 as printed: E_A0Z and E_A0C act alike but for sign, so do E_B0Z and E_B0C; the two
    // pairs come out as groups of which only the difference (coefficient near 1) is identifiable.
    n = await waitPlotted(page, 'ss-residuals');
    await page.selectOption('#ss-model-reference', 'axesZero');
    await waitPlotted(page, 'ss-residuals', n);
    await page.waitForFunction(() => document.querySelectorAll('#ss-groups li').length === 2);
    const groups = await page.$$eval('#ss-groups li', (ls) => ls.map((l) => l.textContent));
    for (const axis of ['A', 'B']) {
      const pair = [`E_${axis}0C`, `E_${axis}0Z`];
      const g = groups.find((t) => t.includes(pair[0]) && t.includes(pair[1]));
      assert.ok(g, `${pair}: a group in ${groups}`);
      const m = /only this combination is measurable: (E_\w+) − (?:([\d.]+)·)?(E_\w+) = /.exec(g);
      assert.ok(m && [m[1], m[3]].sort().join() === pair.join(), g);
      assert.ok(Math.abs(Number(m[2] ?? 1) - 1) < 0.05, g);
    }

    // A file with a damaged line: the message names the line; the last results go at once (they
    // belong to another file) and the top of the panel says so.
    const bad = SAMPLE.replace('top,3,', 'top,3,x');
    const file = `${ARTIFACTS}sshape-bad.csv`;
    writeFileSync(file, bad);
    await page.setInputFiles('#ss-file', file);
    await page.waitForFunction(() => /line 12/.test(document.querySelector('#ss-csv')?.closest('.field')?.textContent ?? ''));
    assert.equal(await page.getAttribute('#ss-csv', 'aria-invalid'), 'true');
    assert.match(await page.textContent('#ss-alert'), /No identification from sshape-bad\.csv: line 12/);
    assert.equal(await page.evaluate(() => document.getElementById('ss-residuals')?.data?.length ?? 0), 0);

    // Angles in radians: the identified E_A0B is shown in rad.
    await page.fill('#ss-csv', SAMPLE);
    await page.selectOption('#ss-model-reference', 'workOrigin');
    await page.selectOption('#units-angle', 'rad');
    await page.waitForFunction(() => /rad/.test(document.querySelector('#ss-ident-table tr[data-name=E_A0B] td')?.textContent ?? ''));
    const a0b = Number((await row('E_A0B')).replace(/[^0-9.e\-]/g, ''));
    assert.ok(Math.abs(a0b - 3.2419e-4) < 1.5e-5, `E_A0B ${a0b} rad`);
    // The machine's angle fields follow the unit too.
    assert.ok(Math.abs(Number(await page.inputValue('#m-errors-E_A0B')) - 3.2419e-4) < 1e-12, await page.inputValue('#m-errors-E_A0B'));
    await page.screenshot({ path: `${ARTIFACTS}sshape-rad.png`, fullPage: false });
  });
});
