// The "S-shape test piece" panel in Debian's Chromium: the part and the overcut maps draw, the
// defect plot follows the error fields, the sample measurement file from public/ loads and is
// identified (values and residuals shown), a malformed file gets a message naming its line, and
// nothing is logged as an error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { ARTIFACTS, traceY, waitPlotted, withPage } from './harness.mjs';

const SAMPLE = readFileSync(new URL('../../public/samples/sshape-measured.csv', import.meta.url), 'utf8');

test('S-shape panel: part, overcut, defects, identification of the sample file', async () => {
  await withPage({ viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-sshape');
    await page.waitForSelector('#panel-sshape[data-ready=true]');
    for (const id of ['ss-part', 'ss-overcut-a', 'ss-overcut-b', 'ss-defects']) await waitPlotted(page, id);

    // Overcut summary: eq 6, the exact gouge and the paper's values are shown, in µm by default.
    assert.match(await page.textContent('#ss-max-a'), /eq 6 3\d\.\d+ µm.*exact gouge 2\d\.\d+ µm.*paper 38\.7 µm/);
    assert.match(await page.textContent('#ss-max-b-inner'), /eq 6 1[23]\.\d+ µm/);

    // Default errors (Table 4: E_X0B, E_A0B): two contributions and the total; E_X0B alone
    // follows its own field.
    const names = await page.$eval('#ss-defects', (gd) => gd.data.map((t) => t.name));
    assert.deepEqual(names.slice(0, 3), ['E_X0B', 'E_A0B', 'total']);
    const x0b = await traceY(page, 'ss-defects', 0);
    let n = await waitPlotted(page, 'ss-defects');
    await page.fill('#ss-ex0b', '58.8'); // µm: twice the default
    await waitPlotted(page, 'ss-defects', n);
    const twice = await traceY(page, 'ss-defects', 0);
    twice.forEach((v, i) => assert.ok(Math.abs(v - 2 * x0b[i]) < 1e-9 * Math.max(1, Math.abs(v)), `point ${i}`));
    assert.match(await page.textContent('#ss-singular'), /4 of 100 points/);

    // Identification of the sample file (simulated with E_X0B = 0.0294 mm, E_A0B = 3.2419e-4 rad,
    // a tool 0.02 mm small and 2 µm of noise).
    await page.click('#ss-load-sample');
    await waitPlotted(page, 'ss-residuals');
    assert.equal(await page.inputValue('#ss-csv'), SAMPLE);
    const row = async (name) => page.$eval(`#ss-ident-table tr[data-name=${name}] td`, (td) => td.textContent);
    const x0bText = await row('E_X0B');
    const x0bUm = Number(x0bText.replace(/[^0-9.\-]/g, ''));
    assert.ok(Math.abs(x0bUm - 29.4) < 1.5, `E_X0B ${x0bText}`);
    const drText = await row('dR');
    assert.ok(Math.abs(Number(drText.replace(/[^0-9.\-]/g, '')) + 20) < 1.5, `dR ${drText}`);
    const residuals = await traceY(page, 'ss-residuals');
    assert.equal(residuals.length, 100);
    const rms = Math.sqrt(residuals.reduce((s, r) => s + r * r, 0) / 100);
    assert.ok(rms > 1 && rms < 3, `residual RMS ${rms} µm (the sample's noise is 2 µm)`);
    assert.match(await page.textContent('#ss-ident'), /Rank 9 of 9/);
    await page.screenshot({ path: `${ARTIFACTS}sshape.png`, fullPage: true });

    // Eq 14 as printed: the two pairs come out as groups with their identifiable difference.
    n = await waitPlotted(page, 'ss-residuals');
    await page.selectOption('#ss-reference', 'axesZero');
    await waitPlotted(page, 'ss-residuals', n);
    await page.waitForFunction(() => document.querySelectorAll('#ss-groups li').length === 2);
    assert.match(await page.textContent('#ss-groups'), /E_A0Z, E_A0C.*only E_A0Z − (\d\.\d+·)?E_A0C/);

    // A file with a damaged line: the message names the line, the last good results stay.
    const before = await traceY(page, 'ss-residuals');
    const bad = SAMPLE.replace('top,3,', 'top,3,x');
    const file = `${ARTIFACTS}sshape-bad.csv`;
    writeFileSync(file, bad);
    await page.setInputFiles('#ss-file', file);
    await page.waitForFunction(() => /line 12/.test(document.querySelector('#ss-csv')?.closest('.field')?.textContent ?? ''));
    assert.equal(await page.getAttribute('#ss-csv', 'aria-invalid'), 'true');
    assert.deepEqual(await traceY(page, 'ss-residuals'), before);

    // Angles in radians: the identified E_A0B is shown in rad.
    await page.fill('#ss-csv', SAMPLE);
    await page.selectOption('#ss-reference', 'workOrigin');
    await page.selectOption('#units-angle', 'rad');
    await page.waitForFunction(() => /rad/.test(document.querySelector('#ss-ident-table tr[data-name=E_A0B] td')?.textContent ?? ''));
    const a0b = Number((await row('E_A0B')).replace(/[^0-9.e\-]/g, ''));
    assert.ok(Math.abs(a0b - 3.2419e-4) < 1.5e-5, `E_A0B ${a0b} rad`);
    await page.screenshot({ path: `${ARTIFACTS}sshape-rad.png`, fullPage: false });
  });
});
