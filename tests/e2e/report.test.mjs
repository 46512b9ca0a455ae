// The printed report for a customer: the header (company, customer, machine, serial number,
// operator, date, the panel's tolerance), the panel's verdict, the plots and a line to sign;
// printed to PDF. The header's fields belong to the page state: a reload, a saved case and a
// share link carry them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { ARTIFACTS, waitIdle, waitPlotted, withPage } from './harness.mjs';

const HEADER = {
  'rp-company': 'Präzision Müller GmbH',
  'rp-customer': 'Turbine Blades Ltd',
  'rp-machine': 'DMU 65 monoBLOCK',
  'rp-serial': 'SN 4711-0815',
  'rp-operator': 'A. Schmidt',
  'rp-date': '2026-11-23',
};
const LABELS = { 'rp-company': 'Company', 'rp-customer': 'Customer', 'rp-machine': 'Machine', 'rp-serial': 'Serial number', 'rp-operator': 'Operator', 'rp-date': 'Date' };

/** The printed header as label → value. */
const printedHeader = (page, tab) =>
  page.$$eval(`#panel-${tab} > .report-header table.report-table th`, (ths) => Object.fromEntries(ths.map((th) => [th.textContent, th.nextElementSibling?.textContent ?? null])));

test('report: header, tolerance, verdict, plots and a line to sign, printed to PDF; the header kept with the case', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    await page.click('#report-menu summary');
    for (const [id, v] of Object.entries(HEADER)) await page.fill(`#${id}`, v);
    await page.click('#report-menu summary');

    // The toolpath panel has a tolerance field (tp-tolerance); the sample path is ranked.
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await waitPlotted(page, 'tp-delta');
    await page.fill('#tp-tolerance', '7.5');
    await waitIdle(page);
    const unit = await page.$eval('#tp-tolerance', (e) => e.closest('.field-row')?.querySelector('.unit')?.textContent);
    // The panel's own verdict (the first child of its results), judged against that tolerance.
    await page.waitForSelector('#panel-toolpath .results > .verdict:is([data-verdict=pass], [data-verdict=fail])');
    const judged = await page.$eval('#panel-toolpath .results > .verdict', (v) => v.dataset.verdict);
    await page.emulateMedia({ media: 'print' });
    await page.waitForSelector('#panel-toolpath > .report-header', { state: 'attached' });
    assert.equal(await page.$eval('#panel-toolpath', (s) => s.firstElementChild.classList.contains('report-header')), true, 'the header comes first');
    const header = await printedHeader(page, 'toolpath');
    const want = Object.fromEntries(Object.entries(HEADER).map(([id, v]) => [LABELS[id], v]));
    want.Tolerance = `7.5 ${unit}`;
    assert.deepEqual(header, want);
    assert.match(await page.textContent('#panel-toolpath .report-title'), /^Machine accuracy report: /);
    // The verdict printed once, in the header, without duplicate ids.
    assert.equal(await page.$eval('#panel-toolpath .report-verdict', (v) => getComputedStyle(v).display !== 'none' && v.dataset.verdict), judged);
    assert.match(await page.textContent('#panel-toolpath .report-verdict'), judged === 'pass' ? /PASS/ : /FAIL/);
    assert.equal(await page.$eval('#panel-toolpath .results > .verdict', (v) => getComputedStyle(v).display), 'none');
    assert.equal(await page.$$eval('#panel-toolpath .report-verdict [id]', (es) => es.length), 0, 'the copy has no ids');
    assert.equal(await page.$$eval('#panel-toolpath .report-verdict input', (es) => es.length), 0, 'no tolerance field in the copy');
    // The plots and, at the end, the line to sign.
    assert.ok(await page.$$eval('#panel-toolpath .js-plotly-plot', (gs) => gs.filter((g) => getComputedStyle(g).display !== 'none').length) >= 1);
    assert.deepEqual(await page.$$eval('#panel-toolpath .report-signature .sign-label', (ls) => ls.map((l) => l.textContent)), ['Checked by', 'Date', 'Signature']);
    assert.equal(await page.$eval('#panel-toolpath', (s) => s.lastElementChild.classList.contains('report-signature')), true);
    await page.screenshot({ path: `${ARTIFACTS}report-print.png`, fullPage: true });
    await page.pdf({ path: `${ARTIFACTS}report-toolpath-header.pdf`, format: 'A4', printBackground: true });
    const pdf = readFileSync(`${ARTIFACTS}report-toolpath-header.pdf`);
    assert.equal(pdf.subarray(0, 5).toString(), '%PDF-');
    assert.ok(pdf.length > 20_000, `${pdf.length} bytes`);
    await page.emulateMedia({ media: 'screen' });
    await page.waitForSelector('#panel-toolpath .report-signature', { state: 'detached' });
    await page.waitForSelector('#panel-toolpath > .report-header', { state: 'detached' });

    // Another panel: its own tolerance and verdict; an empty header field is a line to fill in
    // by hand; no date entered: today's.
    await page.click('#tab-nonlinear');
    await page.click('#report-menu summary');
    await page.fill('#rp-operator', '');
    await page.fill('#rp-date', '');
    await page.click('#report-menu summary');
    await page.emulateMedia({ media: 'print' });
    await page.waitForSelector('#panel-nonlinear > .report-header', { state: 'attached' });
    const plain = await printedHeader(page, 'nonlinear');
    const today = await page.evaluate(() => {
      const d = new Date();
      return `${d.getFullYear()}-${String(d.getMonth() + 1).padStart(2, '0')}-${String(d.getDate()).padStart(2, '0')}`;
    });
    const nlTolerance = await page.$eval('#nl-tolerance', (e) => `${e.value} ${e.closest('.field-row')?.querySelector('.unit')?.textContent}`);
    assert.deepEqual(plain, { ...want, Operator: '', Date: today, Tolerance: nlTolerance });
    assert.equal(await page.$$eval('#panel-nonlinear .report-verdict', (v) => v.length), 1);
    await page.emulateMedia({ media: 'screen' });

    // Kept with the page state: a reload, a saved case, a share link.
    await page.waitForFunction(() => /rp-company=/.test(location.hash) && !/rp-operator=/.test(location.hash));
    await page.reload();
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    assert.equal(await page.inputValue('#rp-company'), HEADER['rp-company']);
    assert.equal(await page.inputValue('#rp-serial'), HEADER['rp-serial']);
    await page.click('details.cases summary');
    await page.fill('#case-name', 'Blade job');
    await page.click('#case-save');
    await page.click('details.cases summary');
    await page.click('#report-menu summary');
    await page.fill('#rp-serial', 'another');
    await page.click('#report-menu summary');
    await page.click('details.cases summary');
    await page.click('[aria-label="Load case Blade job"]');
    await page.waitForFunction((v) => document.getElementById('rp-serial')?.value === v, HEADER['rp-serial']);
    const link = await page.evaluate(() => location.href);
    const other = await page.context().newPage();
    await other.goto(link);
    await other.waitForSelector('#panel-nonlinear[data-ready=true]');
    assert.equal(await other.inputValue('#rp-customer'), HEADER['rp-customer']);
    assert.equal(await other.inputValue('#rp-machine'), HEADER['rp-machine']);
    await other.close();
  });
});
