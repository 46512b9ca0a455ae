// The "Toolpath" panel on files written outside the page, in Debian's Chromium: a Heidenhain
// program (M128, rapids, a C arc) on the A/C trunnion, and an NX CLSF in inches without UNITS/.
// The page says the dialect and the unit and why, ranks the cutting moves with the rapids listed
// apart (the numbers are the engine's, called here in Node on the same file and machine), and a
// change of the unit reads the file again: the path scales by 25.4.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, downloaded, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const PRESETS = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const TRUNNION = PRESETS.findIndex((p) => p.name.startsWith('A/C trunnion table'));

/** Written from the TNC 620 and iTNC 530 manuals: L with FMAX and F, M128, CC and C DR+. */
const HEIDENHAIN = `0 BEGIN PGM DEMO MM
1 BLK FORM 0.1 Z X-50 Y-50 Z-30
2 BLK FORM 0.2 X+50 Y+50 Z+0
3 TOOL CALL 1 Z S8000
4 M128
5 L X+0 Y+0 Z+50 A+0 C+0 R0 FMAX
6 L A-30 C+90 R0 FMAX
7 L Z+5 R0 FMAX
8 L X+10 Y+0 Z+0 A-30 C+100 R0 F1500
9 L X+20 A-35 C+120
10 CC X+0 Y+0
11 C X+0 Y+20 DR+
12 L Z+50 R0 FMAX
13 M30
14 END PGM DEMO MM
`;

/** NX CLSF as NX writes it (TOOL PATH/, MSYS/, RAPID, FEDRAT/IPM), in inches, no UNITS/. */
const CLSF = `TOOL PATH/FINISH,TOOL,T1
TLDATA/MILL,0.5000,0.0000,3.0000,0.0000,0.0000
MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000
$$ centerline data
PAINT/PATH
LOAD/TOOL,1,ADJUST,1
RAPID
GOTO/1.0000,0.0000,2.0000,0.0000000,0.0000000,1.0000000
RAPID
GOTO/1.0000,0.0000,0.1000
FEDRAT/IPM,20.0000
GOTO/1.0000,0.0000,0.0000
GOTO/2.0000,0.5000,0.0000,0.1736482,0.0000000,0.9848078
GOTO/3.0000,1.0000,0.0000,0.3420201,0.0000000,0.9396926
RAPID
GOTO/3.0000,1.0000,2.0000
END-OF-PATH
`;

/** Drops `text` as a file named `name` on the toolpath panel's file box. */
async function drop(page, name, text) {
  const dt = await page.evaluateHandle(([text, name]) => {
    const d = new DataTransfer();
    d.items.add(new File([text], name, { type: 'text/plain' }));
    return d;
  }, [text, name]);
  await page.dispatchEvent('#tp-file', 'drop', { dataTransfer: dt });
}

/** The largest x of the 3D path's cutting trace. */
const maxX = (page) => page.evaluate(() => Math.max(...document.getElementById('tp-path').data[0].x.filter((v) => v !== null)));

test('toolpath panel: a Heidenhain program and an inch CLSF, read and ranked as the machine reads them', async () => {
  await withPage({ acceptDownloads: true, viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await page.waitForFunction(() => /751 points \(APT/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await page.selectOption('#m-preset-menu', String(TRUNNION));
    await waitIdle(page);

    // The Heidenhain program.
    await drop(page, 'demo.h', HEIDENHAIN);
    await page.waitForFunction(() => /^Read demo\.h/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    assert.equal(await page.textContent('#tp-read-dialect'), 'Heidenhain conversational, 15 blocks, tool-centre-point control: M128 on line 5.');
    assert.equal(await page.textContent('#tp-read-unit'), 'Unit: millimetres: BEGIN PGM … MM on line 1.');
    await page.waitForFunction(() => document.querySelector('#tp-ranking caption')?.textContent?.startsWith('demo.h') && !document.getElementById('tp-ranking').classList.contains('stale'));
    await waitIdle(page);
    // The engine in Node, on the same file and machine: the machine's own row follows the
    // program's commands; its headline is a cutting segment's, the rapids apart.
    const machine = PRESETS[TRUNNION].machine;
    const parsed = fa.toolpathParse(HEIDENHAIN, { machine });
    assert.equal(parsed.path.readFor, 'CAZ');
    const a = fa.toolpathAnalyse({ machine, tolerance: 0.01 }, parsed.path);
    assert.ok(a.summary.commanded);
    assert.equal(a.summary.rapids.count, 3);
    assert.ok(a.summary.rapids.max > a.summary.max, 'the rapid swing at the pole would have been the headline');
    const worst = Number(await page.getAttribute('#tp-verdict', 'data-worst'));
    assert.ok(Math.abs(worst - a.summary.max) <= 1e-12 * Math.max(1, a.summary.max), `${worst} vs ${a.summary.max}`);
    const own = await page.$eval('#tp-ranking tr.own', (tr) => [...tr.cells].map((c) => c.textContent));
    assert.equal(own[1], "CAZ (this machine, the program's commands)");
    assert.equal(own[9].split(',')[0], '3');
    assert.match(await page.textContent('#tp-rapids-line'), /^3 rapid moves on CAZ, /);
    // The largest rapid is listed with its line (block 6: A −30°, C +90° from the pole).
    const firstRapid = await page.$$eval('#tp-rapids table tbody tr', (trs) => [...trs[0].cells].map((c) => c.textContent));
    assert.equal(firstRapid[0], String(parsed.lines[a.rapidMoves.reduce((m, r) => (r.excursion > m.excursion ? r : m)).segment + 1]));
    // δ along the path: the cutting trace has no value where a rapid is, the rapid trace only there.
    await waitPlotted(page, 'tp-delta');
    const [cut, rapid] = await page.evaluate(() => {
      const d = document.getElementById('tp-delta').data;
      return [d[0].y, d.find((t) => /^rapid/.test(t.name)).y].map((y) => Array.from(y, (v) => v === null));
    });
    for (const i of a.rapids) assert.ok(cut[i] && !rapid[i], `segment ${i}`);
    // Its CSV: every value with its quantity and unit, in µm as drawn (the rapids' axis shows mm
    // ticks: 18 mm), equal to the engine's δ.
    const [csv] = await Promise.all([page.waitForEvent('download'), page.locator('#tp-delta ~ .plot-tools button[data-export=csv]').click()]);
    const rows = readFileSync(await downloaded(csv), 'utf8').trim().split('\n').map((l) => l.split(/,(?=(?:[^"]*"[^"]*")*[^"]*$)/));
    assert.deepEqual(rows[0], ['trace', 'segment (from point n to n + 1)', 'value', 'quantity (unit)']);
    const values = (name) => rows.filter((r) => r[0].replace(/"/g, '') === name).map((r) => [Number(r[1]) - 1, Number(r[2]), r[3].replace(/"/g, '')]);
    const cutting = values('δ, cutting');
    assert.equal(cutting.length, a.delta.length - a.rapids.length);
    for (const [i, v, unit] of cutting) {
      assert.equal(unit, 'δ, cutting (µm)');
      assert.ok(Math.abs(v - a.delta[i] * 1000) < 1e-9 * Math.max(1, v), `segment ${i}: ${v} µm vs ${a.delta[i]} mm`);
    }
    const rapids = values('rapid, tip excursion (right axis; not cutting, not judged)');
    assert.deepEqual(rapids.map((r) => r[0]), a.rapids);
    for (const [i, v, unit] of rapids) {
      assert.equal(unit, 'rapid tip excursion (µm)');
      assert.ok(Math.abs(v - a.delta[i] * 1000) < 1e-9 * Math.max(1, v));
    }
    await page.screenshot({ path: `${ARTIFACTS}toolpath-heidenhain.png`, fullPage: true });

    // The inch CLSF: inches from its feed unit, as the page says; the path in inches.
    await drop(page, 'finish.cls', CLSF);
    await page.waitForFunction(() => /^Read finish\.cls/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    assert.match(await page.textContent('#tp-read-dialect'), /^APT CL data, \d+ blocks\.$/);
    assert.equal(await page.textContent('#tp-read-unit'), 'Unit: inches: FEDRAT/IPM (a feed in inches) on line 11 (the file states no length unit; change it beside the file if this is wrong).');
    await waitPlotted(page, 'tp-path');
    await waitIdle(page);
    const inch = await maxX(page);
    assert.ok(Math.abs(inch - 3 * 25.4) < 1e-9, `${inch}`);
    // Millimetres chosen: the file is read again and the path is 25.4 times smaller.
    const drawn = Number(await page.getAttribute('#tp-path', 'data-plotted'));
    await page.selectOption('#tp-unit', 'mm');
    await page.waitForFunction(() => /millimetres: the unit chosen/.test(document.getElementById('tp-read-unit')?.textContent ?? ''));
    await waitPlotted(page, 'tp-path', drawn);
    await waitIdle(page);
    const mm = await maxX(page);
    assert.ok(Math.abs(inch / mm - 25.4) < 1e-9, `${inch} / ${mm}`);

    // At phone width nothing scrolls sideways once the plots have followed the new width.
    await page.setViewportSize({ width: 390, height: 900 });
    await page.waitForFunction(() => document.documentElement.scrollWidth <= 390);
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}toolpath-clsf-phone.png`, fullPage: true });
  });
});

const BC = PRESETS.findIndex((p) => p.name.startsWith('B/C tilting table'));

test('toolpath panel: the file chosen last is the one the fields and the machine read, refused or not', async () => {
  await withPage({ viewport: { width: 1400, height: 1800 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-toolpath');
    await page.waitForSelector('#panel-toolpath[data-ready=true]');
    await page.waitForFunction(() => /751 points \(APT/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    const msg = () => page.textContent('#tp-file-msg');
    const verdictText = () => page.textContent('#tp-verdict');

    // The B/C preset has no table height and no tool length: the verdict says what to enter,
    // and no plot spins for ever.
    await page.selectOption('#m-preset-menu', String(BC));
    await page.waitForFunction(() => /enter L/.test(document.getElementById('tp-verdict')?.textContent ?? ''));
    for (const id of ['tp-delta', 'tp-path']) {
      assert.ok(await page.$eval(`#${id}`, (p) => Boolean(p.dataset.plotted) || Boolean(p.closest('.plot-wrap')?.querySelector('.plot-note')?.textContent)), id);
    }

    // A/C: the Heidenhain program is read and judged.
    await page.selectOption('#m-preset-menu', String(TRUNNION));
    await drop(page, 'demo.h', HEIDENHAIN);
    await page.waitForFunction(() => /^Read demo\.h/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await page.waitForFunction(() => ['pass', 'fail'].includes(document.getElementById('tp-verdict')?.dataset.verdict ?? ''));
    await page.click('#tp-refine');
    await page.waitForFunction(() => !document.getElementById('tp-export').disabled);

    // B/C: the program (A words) is refused; everything of its last result is greyed, the
    // refined path dropped, the reason in the verdict and in the error style at the file.
    await page.selectOption('#m-preset-menu', String(BC));
    await page.waitForFunction(() => /^demo\.h could not be read/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    assert.match(await msg(), /expected a rotary axis of this machine \(C or B\), got A.*\. The results below are still those of demo\.h\.$/);
    assert.ok(await page.$eval('#tp-file-msg', (e) => e.classList.contains('error')));
    assert.match(await verdictText(), /demo\.h could not be read: .*got A/);
    assert.ok(await page.$eval('#tp-rapids', (e) => e.classList.contains('stale')));
    assert.ok(await page.$eval('#tp-export', (e) => e.disabled));
    assert.equal(await page.$('#tp-read-dialect'), null, 'no report of the file refused');

    // A/C again: the program is read again, its report back, the refusal gone.
    await page.selectOption('#m-preset-menu', String(TRUNNION));
    await page.waitForFunction(() => /^Read demo\.h/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    assert.ok(!(await page.$eval('#tp-file-msg', (e) => e.classList.contains('error'))));
    assert.match(await page.textContent('#tp-read-dialect'), /^Heidenhain conversational/);
    await page.waitForFunction(() => ['pass', 'fail'].includes(document.getElementById('tp-verdict')?.dataset.verdict ?? ''));

    // A file refused after a good one: a reading field reads the refused file again, not the
    // one before it, and a tolerance edit brings no verdict of the old file back.
    await drop(page, 'macro.nc', 'G90 G21\nG65 P1000 A1\n');
    await page.waitForFunction(() => /^macro\.nc could not be read/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await page.selectOption('#tp-format', 'nc');
    await page.waitForFunction(() => /^(Reading )?macro\.nc/.test(document.getElementById('tp-file-msg')?.textContent ?? ''));
    await waitIdle(page);
    assert.match(await msg(), /^macro\.nc could not be read: line 2, column 1: G65\/G66 call a macro/);
    await page.fill('#tp-tolerance', '0.02');
    await page.dispatchEvent('#tp-tolerance', 'input');
    await waitIdle(page);
    assert.equal(await page.getAttribute('#tp-verdict', 'data-verdict'), 'none');
    assert.match(await verdictText(), /macro\.nc could not be read/);
  });
});
