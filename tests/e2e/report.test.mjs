// The printed report, printed to PDF and read back (Ghostscript's text of each page):
// - the machine's report: a header with no tolerance of its own, a table of every study that
//   gives a verdict (its value, its own tolerance, its badge), the overall verdict (the worst),
//   why studies that pass and fail disagree, then each study with its tolerance beside its
//   verdict; on an A/C trunnion with the C axis's position errors entered, the cubic verdict
//   names them with their values; nothing empty, no internal name, no empty heading; charts and
//   tables never cut by a page nor overlapping, headings on the page of what follows;
// - one study's report;
// - the header's fields kept with the page state.
// Values are compared with the engine called from Node and with the inputs themselves.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fa, preset } from '../papers.mjs';
import { ARTIFACTS, waitIdle, withPage } from './harness.mjs';
import { pdfImages, pdfPages } from './pdftext.mjs';

const HEADER = {
  'rp-company': 'Präzision Müller GmbH',
  'rp-customer': 'Turbine Blades Ltd',
  'rp-machine': 'DMU 65 monoBLOCK',
  'rp-serial': 'SN 4711-0815',
  'rp-operator': 'A. Schmidt',
  'rp-date': '2026-11-23',
};
const LABELS = { 'rp-company': 'Company', 'rp-customer': 'Customer', 'rp-machine': 'Machine', 'rp-serial': 'Serial number', 'rp-operator': 'Operator', 'rp-date': 'Date' };
const TRUNNION_NAME = 'A/C trunnion table';
const TRUNNION = preset(TRUNNION_NAME);
/** Entered on the page in µm; the engine's in mm. */
const ENTERED_UM = { E_X0C: 12, E_Y0C: -8, E_Z0A: 20 };
const ERRORS_MM = Object.fromEntries(Object.entries(ENTERED_UM).map(([k, v]) => [k, v / 1000]));
const PREFIXES = ['nl', 'cb', 'ss', 'tp', 'vm', 'rv', 'rp', 'm', 'md'];
const INTERNAL = new RegExp(`\\b(${PREFIXES.join('|')})-[a-z][a-z0-9-]*`, 'i');
/** A µm value as the page shows it ("2.679 µm") back to mm. */
const mm = (text) => Number(text.replace('−', '-').match(/-?[\d.]+/)[0]) / 1000;
/** Whether `b` is printed within 200 characters of `a` (the badge and the tolerance are side
 *  by side; the text's reading order may put either first). */
function beside(text, a, b) {
  for (let i = text.indexOf(a); i >= 0; i = text.indexOf(a, i + 1)) {
    if (text.slice(Math.max(0, i - 200), i + a.length + 200).includes(b)) return true;
  }
  return false;
}
/** The page's text normalised for searching (Ghostscript keeps the layout's spaces). */
const flat = (t) => t.replace(/\s+/g, ' ');

async function fillHeader(page) {
  await page.click('#report-menu summary');
  for (const [id, v] of Object.entries(HEADER)) await page.fill(`#${id}`, v);
  await page.click('#report-menu summary');
}

async function trunnion(page) {
  const i = await page.$$eval('#m-preset-menu option', (os, name) => os.find((o) => o.textContent.startsWith(name))?.value, TRUNNION_NAME);
  await page.selectOption('#m-preset-menu', i);
  for (const [k, v] of Object.entries(ENTERED_UM)) await page.fill(`#m-errors-${k}`, String(v));
  await page.waitForFunction(() => /3 errors entered/.test(document.getElementById('machine-summary')?.textContent ?? ''));
}

/**
 * Marks, for the PDF, the first and last line of every chart, table and list of inputs printed,
 * and every heading (tiny text a reader of the PDF finds): returns the blocks in document order
 * as {kind, id, heading}.
 */
function markBlocks(page) {
  return page.evaluate(() => {
    const visible = (e) => getComputedStyle(e).display !== 'none' && e.getClientRects().length > 0 && !e.parentElement.closest('details:not([open])');
    const mark = (text, block) => {
      const s = document.createElement('span');
      s.className = 'pdf-mark';
      s.textContent = ` ${text} `;
      // A line of its own across a grid (a list of inputs), unbroken.
      s.style.cssText = `font-size:5px;line-height:5px;color:#fff;white-space:nowrap;${block ? 'display:block;grid-column:1/-1;' : ''}`;
      return s;
    };
    const blocks = [];
    const all = [...document.querySelectorAll('.report-front, .report-study, .report-signature')]
      .flatMap((r) => [r, ...r.querySelectorAll('h2, h3, .plot-wrap, table, .print-inputs dl, .report-machine dl, dl.summary, section.verdict')])
      .filter((e) => !e.matches('.report-front, .report-study, .report-signature') && visible(e))
      // A block inside another block (a table in a verdict) is checked with its parent.
      .filter((e, _, list) => !list.some((o) => o !== e && o.contains(e) && !/^H[23]$/.test(o.tagName)));
    all.forEach((e, i) => {
      const heading = /^H[23]$/.test(e.tagName);
      if (e.tagName === 'TABLE') {
        e.rows[0].cells[0].prepend(mark(`QQB${i}QQ`));
        const last = e.rows[e.rows.length - 1];
        last.cells[last.cells.length - 1].append(mark(`QQE${i}QQ`));
      } else {
        e.prepend(mark(`QQB${i}QQ`, !heading));
        if (!heading) e.append(mark(`QQE${i}QQ`, true));
      }
      if (heading) {
        // The start of what follows the heading.
        let next = e.nextElementSibling;
        while (next && !visible(next)) next = next.nextElementSibling;
        if (next?.tagName === 'TABLE') next.rows[0].cells[0].prepend(mark(`QQN${i}QQ`));
        else if (next) next.prepend(mark(`QQN${i}QQ`, true));
      }
      blocks.push({ i, heading, tag: e.tagName, text: (e.textContent ?? '').slice(0, 60) });
    });
    return blocks;
  });
}

/** The page (1-based) each marker is printed on. */
function markerPages(pages) {
  const at = new Map();
  pages.forEach((t, p) => {
    for (const m of t.matchAll(/QQ([BEN]\d+)QQ/g)) if (!at.has(m[1])) at.set(m[1], p + 1);
  });
  return at;
}

/** Boxes of the printed charts, tables and headings (print media, one long page): pairs that
 *  overlap, neither inside the other. */
function overlaps(page) {
  return page.evaluate(() => {
    const els = [...document.querySelectorAll('.report-front, .report-study')]
      .flatMap((r) => [...r.querySelectorAll('h2, h3, .plot-wrap, table, section.verdict, .print-inputs dl, .report-machine dl, dl.summary')])
      .filter((e) => getComputedStyle(e).display !== 'none' && e.getClientRects().length > 0 && !e.parentElement.closest('details:not([open])'));
    const box = (e) => e.getBoundingClientRect();
    const out = [];
    for (let a = 0; a < els.length; a++) {
      for (let b = a + 1; b < els.length; b++) {
        if (els[a].contains(els[b]) || els[b].contains(els[a])) continue;
        const p = box(els[a]);
        const q = box(els[b]);
        const w = Math.min(p.right, q.right) - Math.max(p.left, q.left);
        const h = Math.min(p.bottom, q.bottom) - Math.max(p.top, q.top);
        if (w > 1 && h > 1) out.push(`${els[a].tagName}.${els[a].className} "${els[a].textContent.slice(0, 40)}" and ${els[b].tagName}.${els[b].className} "${els[b].textContent.slice(0, 40)}" (${w.toFixed(0)} × ${h.toFixed(0)} px)`);
      }
    }
    return out;
  });
}

/** Plots drawn beyond their box (print media): each plot's drawing within its frame. */
function clipped(page) {
  return page.evaluate(() => [...document.querySelectorAll('.report-study .js-plotly-plot')]
    .filter((g) => getComputedStyle(g.closest('.plot-wrap') ?? g).display !== 'none' && g.getClientRects().length > 0)
    .flatMap((g) => {
      const svg = g.querySelector('svg.main-svg')?.getBoundingClientRect();
      const box = (g.closest('.plot-wrap') ?? g).getBoundingClientRect();
      return svg && (svg.bottom > box.bottom + 1 || svg.right > box.right + 1) ? [`${g.id}: drawing ${svg.width.toFixed(0)} × ${svg.height.toFixed(0)} px in a box ending ${(svg.bottom - box.bottom).toFixed(0)} px above its bottom`] : [];
    }));
}

/** Headings printed with nothing under them (text or a drawn plot) before the next heading. */
function emptyHeadings(page) {
  return page.evaluate(() => {
    const shown = (e) => getComputedStyle(e).display !== 'none' && e.getClientRects().length > 0 && !e.parentElement?.closest('details:not([open])');
    const heads = [...document.querySelectorAll('.report-front h2, .report-front h3, .report-study h2, .report-study h3')].filter(shown);
    const order = [...document.querySelectorAll('.report-front, .report-study, .report-front *, .report-study *')];
    return heads.filter((h) => {
      // Up to the next heading of its level or above (a sub-heading is not content).
      const next = heads.slice(heads.indexOf(h) + 1).find((n) => n.tagName <= h.tagName);
      const from = order.indexOf(h);
      const to = next ? order.indexOf(next) : order.length;
      return !order.slice(from + 1, to).some((e) => !h.contains(e) && shown(e) && ((e.children.length === 0 && (e.textContent ?? '').trim() !== '') || e.matches('svg.main-svg')));
    }).map((h) => h.textContent);
  });
}

test('the machine report: every study’s verdict with its own tolerance, the worst overall, why they disagree; printed to PDF, nothing cut or empty', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    await fillHeader(page);
    await trunnion(page);
    await page.click('#tab-cubic');
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    await waitIdle(page);

    // The engine from Node on the same machine: the cubic test cannot see the C axis's position.
    const machine = { ...TRUNNION, errors: ERRORS_MM };
    const cubic = fa.cubicTest({ machine });
    const hidden = Object.keys(ENTERED_UM).filter((n) => cubic.visibility.invisible.includes(n));
    assert.deepEqual(hidden, ['E_X0C', 'E_Y0C']);
    const cubicWorst = Math.max(...cubic.zones.filter((z) => z.name !== 'I').map((z) => Math.abs(z.height)));
    const vol = fa.volumetricMap({ machine, region: {} });
    // Left empty, the map is on the table surface: its height above A plus the tool length.
    assert.equal(vol.at, TRUNNION.geometry.tableHeight + TRUNNION.geometry.toolLength);

    // The cubic verdict on screen names them with the values entered.
    const cubicText = flat(await page.textContent('#cb-verdict'));
    assert.match(cubicText, /The cubic test cannot see E_X0C and E_Y0C \(entered: 12 µm and −8 µm\)\./);

    await page.emulateMedia({ media: 'print' });
    await page.waitForSelector('body[data-report=ready]', { timeout: 120_000 });
    await waitIdle(page);

    // The summary: one row per study whose panel gives a verdict, with that verdict's numbers.
    const verdicts = await page.$$eval('.panel > .panel-grid .results > .verdict', (vs) => vs.map((v) => ({
      panel: v.closest('.panel').id.replace('panel-', ''), verdict: v.dataset.verdict, worst: Number(v.dataset.worst), tolerance: Number(v.dataset.tolerance),
    })));
    const judged = verdicts.filter((v) => v.verdict === 'pass' || v.verdict === 'fail');
    assert.ok(judged.length >= 5, JSON.stringify(verdicts));
    const rows = await page.$$eval('table.report-verdicts tbody tr', (trs) => trs.map((tr) => ({ study: tr.dataset.study, verdict: tr.dataset.verdict, cells: [...tr.cells].map((c) => c.textContent) })));
    assert.deepEqual(rows.map((r) => r.study), judged.map((v) => v.panel));
    for (const r of rows) {
      const [, , value, tolerance, badge] = r.cells;
      const want = mm(value) <= mm(tolerance) ? 'pass' : 'fail';
      assert.equal(r.verdict, want, `${r.study}: ${value} against ${tolerance}`);
      assert.equal(badge, want.toUpperCase());
    }
    // Against the engine: the cubic test passes at its worst zone, the volumetric map fails.
    const cubicRow = rows.find((r) => r.study === 'cubic');
    const volRow = rows.find((r) => r.study === 'volumetric');
    // (shown to 4 significant digits)
    assert.ok(Math.abs(mm(cubicRow.cells[2]) - cubicWorst) <= 5e-4 * cubicWorst, `${cubicRow.cells[2]} vs ${cubicWorst}`);
    assert.ok(Math.abs(mm(volRow.cells[2]) - vol.worst.norm) <= 5e-4 * vol.worst.norm, `${volRow.cells[2]} vs ${vol.worst.norm}`);
    assert.equal(mm(cubicRow.cells[3]), 0.01);
    assert.equal(mm(volRow.cells[3]), 0.02);
    assert.equal(cubicRow.verdict, cubicWorst <= 0.01 ? 'pass' : 'fail');
    assert.equal(volRow.verdict, vol.worst.norm <= 0.02 ? 'pass' : 'fail');
    assert.equal(cubicRow.verdict, 'pass');
    assert.equal(volRow.verdict, 'fail');
    // Overall: the worst.
    const overall = await page.$eval('.report-overall', (o) => ({ verdict: o.dataset.verdict, text: o.textContent }));
    assert.equal(overall.verdict, rows.some((r) => r.verdict === 'fail') ? 'fail' : 'pass');
    assert.match(overall.text, /^FAIL/);
    // Why they disagree: what the cubic test cannot see, with the values entered.
    const why = flat(await page.textContent('.report-disagree'));
    assert.match(why, /Cubic-machining test passes while [^.]*Volumetric error[^.]* fail\. The cubic test cannot see E_X0C and E_Y0C \(entered: 12 µm and −8 µm\)\./);
    // The volumetric section says where Z 0 is and that the map is on the table surface.
    const zero = flat(await page.textContent('#vm-zero'));
    assert.equal(zero, `Z 0 puts the spindle nose at the rotary centre, on the A axis; the tool tip is then ${TRUNNION.geometry.toolLength} mm from it against the spindle (the tool length). ` +
      `The table surface is ${TRUNNION.geometry.tableHeight} mm above the rotary centre: the tool tip touches it at Z ${vol.at} mm. This map: Z ${vol.at} mm, on the table surface.`);

    // Print layout (one long page): charts, tables, verdicts and headings do not overlap; no
    // heading printed without something under it.
    assert.deepEqual(await overlaps(page), []);
    assert.deepEqual(await clipped(page), []);
    assert.deepEqual(await emptyHeadings(page), []);

    const blocks = await markBlocks(page);
    const pdfPath = `${ARTIFACTS}report-machine.pdf`;
    await page.pdf({ path: pdfPath, format: 'A4', printBackground: true });
    pdfImages(pdfPath, `${ARTIFACTS}report-machine-page`);
    const pages = pdfPages(pdfPath);
    assert.ok(pages.length >= judged.length + 1, `${pages.length} pages`);
    const at = markerPages(pages);
    for (const b of blocks) {
      const begin = at.get(`B${b.i}`);
      assert.ok(begin, `block ${b.i} (${b.tag} "${b.text}") is in the PDF`);
      if (b.heading) {
        // Kept with what follows: what follows it starts on its page.
        if (at.has(`N${b.i}`)) assert.equal(at.get(`N${b.i}`), begin, `heading "${b.text}" on page ${begin}, what follows on ${at.get(`N${b.i}`)}`);
      } else {
        assert.equal(at.get(`E${b.i}`), begin, `${b.tag} "${b.text}" starts on page ${begin} and ends on page ${at.get(`E${b.i}`)}`);
      }
    }
    const text = pages.map((p) => flat(p.replace(/QQ[BEN]\d+QQ/g, ''))).join('\n');
    // The header (before the verdicts) has no tolerance of its own.
    const head = flat(pages[0]).split('Verdicts')[0];
    for (const v of Object.values(HEADER)) assert.ok(head.includes(v), `header: ${v}`);
    assert.doesNotMatch(head, /Tolerance/i);
    // Each study's tolerance beside its verdict: the label and value next to the badge, and the
    // sentence judging against the same value, on one page.
    for (const v of judged) {
      const label = await page.$eval(`#${{ nonlinear: 'nl', cubic: 'cb', sshape: 'ss', toolpath: 'tp', volumetric: 'vm', reversal: 'rv', probe: 'pb' }[v.panel]}-verdict .verdict-tolerance label`, (l) => l.textContent.trim());
      const value = `${Number((v.tolerance * 1000).toPrecision(4))} µm`;
      const badge = v.verdict === 'pass' ? 'PASS' : 'FAIL';
      const page1 = pages.findIndex((p) => flat(p).includes(`${label}: ${value}`));
      assert.ok(page1 >= 0, `${v.panel}: "${label}: ${value}" printed`);
      assert.ok(beside(flat(pages[page1]), `${label}: ${value}`, badge), `${v.panel}: tolerance beside the ${badge}`);
    }
    // The cubic verdict names the errors it cannot see.
    assert.match(text, /The cubic test cannot see E_X0C and E_Y0C \(entered: 12 µm and −8 µm\)/);
    // Nothing empty, no internal name.
    assert.doesNotMatch(text, /\(empty\)/);
    assert.doesNotMatch(text, /\b0 lines of data/);
    assert.doesNotMatch(text, INTERNAL);
    assert.doesNotMatch(text, /Identification from measured zones/, 'the cubic identification has no data: no heading');
    await page.emulateMedia({ media: 'screen' });
    await page.waitForSelector('.report-front', { state: 'detached' });
    // Back on screen, a study printed from behind its tab is drawn at its box's width when its
    // tab is opened (not at the page's width the report gave it).
    await page.click('#tab-volumetric');
    await waitIdle(page);
    const widths = await page.$$eval('#panel-volumetric .js-plotly-plot', (gs) => gs.map((g) => [g.id, Number(g.querySelector('svg.main-svg')?.getAttribute('width')), g.clientWidth]));
    assert.ok(widths.length > 0, 'volumetric plots drawn');
    for (const [id, drawn, box] of widths) assert.ok(Math.abs(drawn - box) <= 1, `${id}: drawn ${drawn} px wide in a ${box} px box`);
  });
});

test('one study’s report: its verdict with its tolerance, no tolerance in the header; the header kept with the case', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    await fillHeader(page);
    await page.click('#report-menu summary');
    await page.selectOption('#rp-scope', 'study');
    await page.click('#report-menu summary');
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await page.fill('#tp-tolerance', '7.5');
    await waitIdle(page);
    await page.waitForSelector('#tp-verdict:is([data-verdict=pass], [data-verdict=fail])');
    const judged = await page.$eval('#tp-verdict', (v) => v.dataset.verdict);
    await page.emulateMedia({ media: 'print' });
    await page.waitForSelector('body[data-report=ready]', { timeout: 120_000 });
    const header = await page.$$eval('.report-front table.report-table th', (ths) => Object.fromEntries(ths.map((th) => [th.textContent, th.nextElementSibling?.textContent ?? null])));
    assert.deepEqual(header, Object.fromEntries(Object.entries(HEADER).map(([id, v]) => [LABELS[id], v])));
    assert.match(await page.textContent('.report-title'), /^Machine accuracy report: Toolpath$/);
    // Only this study is printed, with its verdict and its tolerance beside the badge.
    const printed = await page.$$eval('.panel', (ps) => ps.filter((p) => getComputedStyle(p).display !== 'none').map((p) => p.id));
    assert.deepEqual(printed, ['panel-toolpath']);
    assert.equal(await page.$eval('#tp-verdict', (v) => getComputedStyle(v).display !== 'none'), true);
    assert.equal(flat(await page.textContent('#tp-verdict .verdict-printed-tolerance')), 'Tolerance on the tool tip: 7.5 µm');
    assert.match(await page.textContent('.report-scope'), /covers one study, Toolpath/);
    assert.deepEqual(await overlaps(page), []);
    const pdfPath = `${ARTIFACTS}report-toolpath.pdf`;
    await page.pdf({ path: pdfPath, format: 'A4', printBackground: true });
    const pages = pdfPages(pdfPath);
    const text = flat(pages.join('\n'));
    assert.doesNotMatch(flat(pages[0]).split('Toolpath')[0], /Tolerance/);
    assert.ok(beside(text, 'Tolerance on the tool tip: 7.5 µm', judged === 'pass' ? 'PASS' : 'FAIL'), 'the tolerance beside the badge');
    assert.match(text, /Checked by/);
    assert.doesNotMatch(text, INTERNAL);
    await page.emulateMedia({ media: 'screen' });
    await page.waitForSelector('.report-front', { state: 'detached' });

    // Kept with the page state: a reload, a saved case, a share link.
    await page.waitForFunction(() => /rp-company=/.test(location.hash) || document.body.dataset.saved);
    await page.reload();
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    assert.equal(await page.inputValue('#rp-company'), HEADER['rp-company']);
    assert.equal(await page.inputValue('#rp-scope'), 'study');
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
    await other.waitForSelector('#panel-toolpath[data-ready=true]');
    assert.equal(await other.inputValue('#rp-customer'), HEADER['rp-customer']);
    await other.close();
  });
});
