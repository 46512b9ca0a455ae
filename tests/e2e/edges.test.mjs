// Input edges and the phone (issue 29): a number beyond a double's range is "out of range";
// full-width digits, the minus sign U+2212 and a decimal comma give the result of the ASCII
// number; a file that is not UTF-8 is read as Windows-1252 and says so; an image or a PDF is
// refused by its first bytes and the results it would replace are greyed; at 390 px the toolbar's
// pop-ups stay on the screen and the active tab is scrolled into the tab strip; signed fields
// get the full keyboard (inputmode text and a pattern), the others the decimal keypad.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
const SHOTS = '/work/shots/edges/';
mkdirSync(SHOTS, { recursive: true });

/** A 1 × 1 PNG image (signature, IHDR, IDAT, IEND). */
const PNG = Buffer.from('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg==', 'base64');

const message = (page, id) => page.$eval(`#${id}`, (e) => e.closest('.field')?.querySelector('.field-msg')?.textContent ?? '');

/** What the nonlinear panel computed: its verdict's worst value (mm) and sentence. */
const nonlinearResult = (page) => page.$eval('#nl-verdict', (v) => ({ state: v.dataset.verdict, worst: v.dataset.worst, sentence: v.querySelector('.verdict-sentence').textContent }));

/** Types `text` into field `id` and waits for the computation it starts. */
async function typeIn(page, id, text) {
  await page.fill(`#${id}`, text);
  await waitIdle(page);
}

test('a number beyond the range of a double says "out of range", not "not a number"', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    for (const [id, text] of [['nl-tolerance', '1e400'], ['nl-end-k', '-1e400'], ['m-geometry-toolLength', '1E+999']]) {
      await page.fill(`#${id}`, text);
      await page.waitForFunction((id) => document.getElementById(id)?.getAttribute('aria-invalid') === 'true', id);
      const m = await message(page, id);
      assert.match(m, /out of range/, `${id} = ${text}: ${m}`);
      assert.doesNotMatch(m, /not a number/, `${id} = ${text}`);
    }
  });
});

test('full-width digits, the minus sign U+2212 and a decimal comma give the result of the ASCII number', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    await waitIdle(page);
    const before = await nonlinearResult(page);
    // The end of the move on K: the ASCII text first, then its look-alikes.
    const cases = [
      ['-12.5', ['−12.5', '－１２．５', '–12.5', '-12,5', '−１２，５']],
      ['7.25', ['７．２５', '7,25', '７，２５', '＋7.25']],
      ['12', ['１２']],
    ];
    const seen = new Set();
    for (const [ascii, others] of cases) {
      await typeIn(page, 'nl-end-k', ascii);
      const expected = await nonlinearResult(page);
      assert.notEqual(expected.state, 'none', `${ascii}: a verdict`);
      assert.notDeepEqual(expected, before, `${ascii} changes the result (the field matters)`);
      seen.add(JSON.stringify(expected));
      for (const text of others) {
        await typeIn(page, 'nl-end-k', text);
        assert.equal(await page.getAttribute('#nl-end-k', 'aria-invalid'), null, `${text} accepted`);
        assert.equal(await message(page, 'nl-end-k'), '', `${text}: no message`);
        assert.deepEqual(await nonlinearResult(page), expected, `${text} gives the result of ${ascii}`);
      }
    }
    assert.equal(seen.size, cases.length, 'the three numbers give three results');
    // A decimal comma in an unsigned field and in a machine field, against the point.
    for (const [id, comma, point] of [['nl-tolerance', '2,5', '2.5'], ['m-geometry-toolLength', '87,5', '87.5']]) {
      await typeIn(page, id, point);
      const expected = await nonlinearResult(page);
      await typeIn(page, id, comma);
      assert.equal(await page.getAttribute(`#${id}`, 'aria-invalid'), null, `${id} = ${comma} accepted`);
      assert.deepEqual(await nonlinearResult(page), expected, `${id}: ${comma} gives the result of ${point}`);
    }
  });
});

test('a file that is not UTF-8 is read as Windows-1252 (µ as 0xB5) and the page says so beside it', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    // An error-motion table as German measuring software writes it: "Abweichung (µm)", µ the
    // byte 0xB5, `;` between cells and a decimal comma.
    await page.click('#tab-volumetric');
    await page.waitForSelector('#panel-volumetric[data-ready=true]');
    await waitIdle(page);
    const table = Buffer.concat([Buffer.from('X (mm);Abweichung ('), Buffer.from([0xb5]), Buffer.from('m)\r\n-300;0\r\n0;2,5\r\n300;-4\r\n')]);
    assert.throws(() => new TextDecoder('utf-8', { fatal: true }).decode(table), 'the bytes are not UTF-8');
    await page.setInputFiles('#vm-csv-E_XX', { name: 'abweichung.csv', mimeType: 'text/csv', buffer: table });
    await page.waitForFunction(() => /abweichung\.csv/.test(document.getElementById('vm-csv-msg-E_XX')?.textContent ?? ''));
    await waitIdle(page);
    const msg = await page.textContent('#vm-csv-msg-E_XX');
    assert.match(msg, /^abweichung\.csv \(read as Windows-1252: not valid UTF-8\): 3 points/);
    // The values as the file gives them, in µm (the page's unit).
    await waitPlotted(page, 'vm-table-E_XX');
    assert.deepEqual(await page.$eval('#vm-table-E_XX', (gd) => Array.from(gd.data[0].y)), [0, 2.5, -4]);
    assert.deepEqual(await page.$eval('#vm-table-E_XX', (gd) => Array.from(gd.data[0].x)), [-300, 0, 300]);

    // The same on the toolpath panel (read in a worker): a CSV path with a comment in Windows-1252.
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await waitPlotted(page, 'tp-delta');
    const rows = ['# Werkzeug ', '6 mm, Toleranz 5 ', 'm\n', 'x,y,z,i,j,k\n', '0,0,0,0,0,1\n', '10,0,0,0,0.1,0.995\n', '20,0,0,0,0.2,0.98\n'];
    const path = Buffer.concat([Buffer.from(rows[0]), Buffer.from([0xd8]), Buffer.from(rows[1]), Buffer.from([0xb5]), ...rows.slice(2).map((r) => Buffer.from(r))]);
    await page.setInputFiles('#tp-file', { name: 'bahn.csv', mimeType: 'text/csv', buffer: path });
    await page.waitForFunction(() => /^Read bahn\.csv/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    assert.match(await page.textContent('#tp-file-msg'), /^Read bahn\.csv \(read as Windows-1252: not valid UTF-8\): 3 points/);
    // A UTF-8 file says nothing of the kind.
    await page.setInputFiles('#tp-file', { name: 'bahn-utf8.csv', mimeType: 'text/csv', buffer: Buffer.from(`# Werkzeug Ø6 mm, Toleranz 5 µm\n${rows.slice(3).join('')}`) });
    await page.waitForFunction(() => /^Read bahn-utf8\.csv/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    assert.doesNotMatch(await page.textContent('#tp-file-msg'), /Windows-1252/);
    await waitIdle(page);
  });
});

test('an image or a PDF is refused by its first bytes, with a sentence, and the results it would replace are greyed', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await waitPlotted(page, 'tp-delta');
    await waitIdle(page);
    const plotted = await page.$eval('#tp-delta', (e) => e.dataset.plotted);
    assert.ok(!(await page.$eval('#tp-delta', (e) => e.closest('.plot-wrap').classList.contains('stale'))), 'the sample path is current');
    await page.setInputFiles('#tp-file', { name: 'drawing.png', mimeType: 'image/png', buffer: PNG });
    await page.waitForFunction(() => /drawing\.png/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await waitIdle(page);
    const said = await page.textContent('#tp-file-msg');
    assert.match(said, /^drawing\.png is a PNG image, not a program or a table of numbers\./);
    assert.match(said, /still those of impeller-swarf\.apt/);
    assert.equal(await page.getAttribute('#tp-verdict', 'data-verdict'), 'none');
    assert.match(await page.textContent('#tp-verdict-sentence'), /drawing\.png is a PNG image/);
    for (const sel of ['#tp-delta', '#tp-path']) assert.ok(await page.$eval(sel, (e) => e.closest('.plot-wrap').classList.contains('stale')), `${sel} greyed`);
    assert.ok(await page.$eval('#tp-ranking', (e) => e.classList.contains('stale')), 'the ranking greyed');
    assert.equal(await page.$eval('#tp-delta', (e) => e.dataset.plotted), plotted, 'nothing drawn from the image');
    assert.equal(await page.$eval('#tp-read', (e) => e.textContent), '', 'no reading report for the image');
    await page.screenshot({ path: `${SHOTS}refused-png-1366.png` });

    // The S-shape panel: a PDF chosen as the measurement file; the identification goes.
    await page.click('#tab-sshape');
    await page.waitForSelector('#panel-sshape[data-ready=true]');
    await page.click('#ss-load-sample');
    await page.waitForFunction(() => document.getElementById('ss-fit')?.dataset.plotted);
    await waitIdle(page);
    const pdf = Buffer.from('%PDF-1.7\n%\xe2\xe3\xcf\xd3\n1 0 obj\n<<>>\nendobj\n', 'latin1');
    await page.setInputFiles('#ss-file', { name: 'report.pdf', mimeType: 'application/pdf', buffer: pdf });
    await page.waitForFunction(() => /report\.pdf/.test(document.getElementById('ss-file-msg')?.textContent ?? ''));
    await waitIdle(page);
    assert.equal(await page.textContent('#ss-file-msg'), 'report.pdf is a PDF document, not a program or a table of numbers.');
    assert.match(await page.textContent('#ss-ident'), /No identification: report\.pdf is a PDF document/);
  });
});

test('phone at 390 px: the toolbar pop-ups stay on the screen, the active tab is scrolled into the tab strip', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true]');
    await waitIdle(page);
    const inside = (box, what) => {
      assert.ok(box.left >= 0 && box.right <= 390 && box.width > 0, `${what}: ${JSON.stringify(box)} within 0–390 px`);
    };
    const box = (sel) => page.$eval(sel, (e) => {
      const r = e.getBoundingClientRect();
      return { left: r.left, right: r.right, top: r.top, bottom: r.bottom, width: r.width };
    });
    for (const [summary, body, button] of [['details.cases > summary', '.cases-body', '#case-save'], ['#report-menu > summary', '.report-body', '#rp-date']]) {
      await page.tap(summary);
      await page.waitForSelector(`${body}:visible`);
      inside(await box(body), body);
      inside(await box(button), button);
      await page.screenshot({ path: `${SHOTS}popup-390-${body.slice(1)}.png` });
      // The Save button can be pressed where it is.
      if (button === '#case-save') {
        await page.fill('#case-name', 'Phone case');
        await page.tap('#case-save');
        await page.waitForFunction(() => /Saved “Phone case”/.test(document.querySelector('.cases-body p.field-hint')?.textContent ?? ''));
      }
      await page.tap(summary);
    }

    // The last tab chosen without the browser scrolling to it (a click from a script).
    const strip = () => page.$eval('nav#tabs', (nav) => {
      const n = nav.getBoundingClientRect();
      const t = nav.querySelector('[aria-selected=true]').getBoundingClientRect();
      return { id: nav.querySelector('[aria-selected=true]').id, nav: [n.left, n.right], tab: [t.left, t.right], scroll: nav.scrollWidth > nav.clientWidth };
    });
    assert.ok((await strip()).scroll, 'the tabs are wider than the strip at 390 px');
    const last = await page.$eval('nav#tabs', (nav) => [...nav.querySelectorAll('[role=tab]')].at(-1).id);
    await page.$eval(`#${last}`, (b) => b.click());
    await page.waitForSelector(`#panel-${last.slice(4)}[data-ready=true]`);
    const s = await strip();
    assert.equal(s.id, last);
    assert.ok(s.tab[0] >= s.nav[0] - 0.5 && s.tab[1] <= s.nav[1] + 0.5, `the active tab ${JSON.stringify(s.tab)} within the strip ${JSON.stringify(s.nav)}`);
    await waitIdle(page);
    await page.screenshot({ path: `${SHOTS}tabs-390-last.png` });
    // On load: the page opens on the last tab, scrolled into the strip.
    await page.reload();
    await page.waitForSelector(`#panel-${last.slice(4)}[data-ready=true]`);
    const again = await strip();
    assert.equal(again.id, last, 'the page reopens on the last tab');
    assert.ok(again.tab[0] >= again.nav[0] - 0.5 && again.tab[1] <= again.nav[1] + 0.5, `on load: ${JSON.stringify(again)}`);
    await waitIdle(page);
  });
});

/** Every number field's id → its declared minimum, from the engine's schema (not the page). */
function declaredMinimums() {
  const s = fa.schema();
  const out = new Map();
  // (Longest first: an export's name is matched by its start.)
  const prefixes = { nonlinear: 'nl', cubic: 'cb', sshape: 'ss', toolpath: 'tp', volumetric: 'vm', reversal: 'rv', probe: 'pb', ballbarrotary: 'br', ballbar: 'bb', positioning: 'ps' };
  for (const [name, list] of Object.entries(s.exports)) {
    const prefix = Object.entries(prefixes).find(([p]) => name.toLowerCase().startsWith(p))?.[1];
    for (const f of list) {
      if (f.kind !== 'number' && f.kind !== 'count') continue;
      const path = f.path.replace(/\./g, '-');
      if (f.path.startsWith('machine.')) out.set(`m-${path.slice('machine-'.length)}`, f.min);
      else if (prefix) out.set(`${prefix}-${path}`, f.min);
    }
  }
  // The items of a list (the rotary ball-bar tests).
  for (const f of s.lists.ballbarTests) {
    if (f.kind !== 'number') continue;
    for (let i = 0; i < 8; i++) out.set(`br-tests-${i}-${f.path.replace(/\./g, '-')}`, f.min);
  }
  for (const e of s.errors) out.set(`m-errors-${e.name}`, -e.limit);
  for (const e of s.motions) out.set(`m-motions-${e.name}`, -e.limit);
  return out;
}

test('signed number fields offer a minus sign (inputmode text and a pattern); the others the decimal keypad', async () => {
  const declared = declaredMinimums();
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
    }
    await waitIdle(page);
    const shown = await page.$$eval('input[data-number]', (es) => es.map((e) => ({ id: e.id, mode: e.getAttribute('inputmode'), pattern: e.getAttribute('pattern') })));
    let signed = 0;
    let unsigned = 0;
    for (const f of shown) {
      if (!declared.has(f.id)) continue;
      if (declared.get(f.id) < 0) {
        signed++;
        assert.equal(f.mode, 'text', `${f.id} (from ${declared.get(f.id)}) gets the full keyboard`);
        assert.ok(f.pattern, `${f.id} has a pattern`);
      } else {
        unsigned++;
        assert.equal(f.mode, 'decimal', `${f.id} (from ${declared.get(f.id)}) keeps the decimal keypad`);
        assert.equal(f.pattern, null, `${f.id} has no pattern`);
      }
    }
    assert.ok(signed >= 40 && unsigned >= 20, `${signed} signed and ${unsigned} unsigned fields checked`);
    // The pattern compiles in the browser and tells numbers from text.
    await page.click('#tab-nonlinear');
    for (const [text, ok] of [['-3.5', true], ['−3.5', true], ['－３．５', true], ['12,5', true], ['1e-3', true], ['abc', false], ['1,', false]]) {
      await page.fill('#nl-end-k', text);
      assert.equal(await page.$eval('#nl-end-k', (e) => !e.validity.patternMismatch), ok, `the pattern on "${text}"`);
    }
  });
});
