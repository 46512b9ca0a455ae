// The "Probe and sphere" panel (issue 31) in Debian's Chromium: the designed poses appear, each
// within the machine's travel as the preset states it, and export as CSV and NC blocks; the
// sample file, loaded by the file input, gives a verdict and the corrections, and the errors it
// was made with (its header, and stated again here) lie within the intervals the page shows;
// "Use these errors" puts them into the Machine section, keeps the machine's other values, and
// the volumetric map changes; a file with a missing column names its line and greys the last
// result. Screenshots at 1366 × 768 and 390 × 844.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, downloaded, optionValue, traceY, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

const SAMPLE_URL = new URL('../../public/samples/probe-sphere-measured.csv', import.meta.url);
const SAMPLE = readFileSync(SAMPLE_URL, 'utf8');
const MACHINES = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;
const BC = MACHINES.find((p) => p.name.startsWith('B/C tilting table')).machine;
/** The errors the sample was simulated with (scripts/make-probe-sample.mjs): mm and degrees. */
const TRUTH = { E_X0B: 0.012, E_Z0B: -0.008, E_A0B: 0.005, E_C0B: -0.003 };
/** The probe's largest tilt from the table's normal, the panel's default. */
const MAX_TILT = 90;

/** A number as the page writes it ("-8.336 µm", "0.004752°", "−3"). */
const number = (text) => Number(/[-−]?\d+(\.\d+)?(e[-+]?\d+)?/.exec(text)?.[0].replace('−', '-'));
/** mm or degrees from the page's default units (µm for small lengths, degrees for angles). */
const toApi = (name, shown) => (/^E_[XYZ]0/.test(name) ? shown / 1000 : shown);

async function openProbe(page, url) {
  await page.goto(url);
  await page.click('#tab-probe');
  await page.waitForSelector('#panel-probe[data-ready=true]');
  // The sample's set-up: the B/C tilting table, the sphere 100 mm above the table centre.
  await page.selectOption('#pb-preset-menu', await optionValue(page, 'pb-preset-menu', 'Sample file'));
  await page.waitForFunction(() => document.getElementById('m-type')?.value === 'CBZ');
  await page.waitForSelector('#pb-poses-designed tbody tr');
  await waitIdle(page);
}

test('Probe and sphere: designed poses, the sample identified, its errors used on the machine, a bad file', async () => {
  // The header states the errors this test states.
  for (const [name, v] of Object.entries(TRUTH)) {
    const shown = `${name} = ${v > 0 ? '+' : '-'}${Math.abs(v).toFixed(3).replace('.', ',')}`;
    assert.ok(SAMPLE.includes(shown), `the sample's header states ${shown}`);
  }
  await withPage({ viewport: { width: 1366, height: 768 }, acceptDownloads: true }, async ({ page, url }) => {
    await openProbe(page, url);

    // ---- the design: every pose within the travel the preset states, and the tilt limit
    const poses = await page.$$eval('#pb-poses-designed tbody tr', (rs) => rs.map((r) => ({ k: Number(r.dataset.k), m: Number(r.dataset.m), tilt: Number(r.dataset.tilt), cells: [...r.children].map((c) => c.textContent) })));
    assert.ok(poses.length >= 12, `${poses.length} designed poses`);
    const { kFrom, kTo, mFrom, mTo } = BC.rotary;
    for (const p of poses) {
      assert.ok(p.k >= kFrom - 1e-9 && p.k <= kTo + 1e-9, `C ${p.k}° within ${kFrom}…${kTo}`);
      assert.ok(p.m >= mFrom - 1e-9 && p.m <= mTo + 1e-9, `B ${p.m}° within ${mFrom}…${mTo}`);
      // On this table the probe (along Z) leans from the table's normal by B itself.
      assert.ok(Math.abs(p.m) <= MAX_TILT + 1e-9 && Math.abs(p.tilt - Math.abs(p.m)) < 1e-6, `tilt ${p.tilt}° at B ${p.m}°`);
    }
    // The expected centre of a pose at C = c, B = b: the sphere (0, 0, 100) turned by C about Z,
    // then by B about Y (B carries C; both lines through the origin on this preset; a table
    // turning by +b moves the sphere by −b relative to the tool, ISO 841).
    for (const p of poses) {
      const b = (-p.m * Math.PI) / 180;
      const want = [100 * Math.sin(b), 0, 100 * Math.cos(b)];
      const shown = p.cells.slice(3, 6).map(Number);
      for (let a = 0; a < 3; a++) assert.ok(Math.abs(shown[a] - want[a]) < 1e-4, `pose C ${p.k} B ${p.m}: ${shown} vs ${want}`);
    }
    const compare = await page.$$eval('#pb-design-compare tbody tr', (rs) => rs.map((r) => [...r.children].map((c) => c.textContent)));
    const weakest = compare.find((r) => /^Weakest/.test(r[0]));
    assert.ok(Number(weakest[2]) >= Number(weakest[1]), `designed ${weakest[2]} ≥ simple ${weakest[1]}`);
    assert.match(await page.textContent('#pb-visibility'), /E_C0C cannot be seen at all/);
    assert.match(await page.textContent('#pb-second'), /second sphere/i);
    // The downloads: the pose table (read back by the engine once filled in) and NC blocks.
    const [csvDl] = await Promise.all([page.waitForEvent('download'), page.click('#pb-poses-designed-csv')]);
    const csv = readFileSync(await downloaded(csvDl), 'utf8');
    const filled = csv.replace(/,,,$/gm, ',0,0,100');
    const back = fa.probeReadCsv({ machine: BC, csv: filled });
    assert.equal(back.poses.length, poses.length);
    back.poses.forEach((p, i) => assert.ok(Math.abs(p.k - poses[i].k) < 1e-6 && Math.abs(p.m - poses[i].m) < 1e-6, `row ${i + 1}`));
    const [ncDl] = await Promise.all([page.waitForEvent('download'), page.click('#pb-poses-designed-nc')]);
    const blocks = readFileSync(await downloaded(ncDl), 'utf8').split('\n').filter((l) => /^N\d+ /.test(l));
    assert.equal(blocks.length, poses.length);
    blocks.forEach((b, i) => {
      const c = Number(/ C(-?[\d.]+)/.exec(b)?.[1]);
      const bb = Number(/ B(-?[\d.]+)/.exec(b)?.[1]);
      assert.ok(Math.abs(c - poses[i].k) < 6e-4 && Math.abs(bb - poses[i].m) < 6e-4, b);
    });
    assert.equal(await page.getAttribute('#pb-verdict', 'data-verdict'), 'none');
    // Nothing measured yet: no empty plot boxes, no empty summary, no offer.
    for (const sel of ['#pb-centres', '#pb-components', '#pb-summary', '#pb-sample-offer']) {
      assert.ok(await page.$eval(sel, (e) => e.getBoundingClientRect().height === 0), `${sel} not shown`);
    }
    await page.screenshot({ path: `${ARTIFACTS}probe-design-1366.png`, fullPage: true });

    // ---- the volumetric map before: the machine has no errors
    await page.click('#tab-volumetric');
    await page.waitForSelector('#panel-volumetric[data-ready=true]');
    await waitPlotted(page, 'vm-map');
    await waitIdle(page);
    const mapBefore = await page.$eval('#vm-map', (gd) => gd.data[0].z.flat());
    const worstBefore = Number(await page.getAttribute('#vm-verdict', 'data-worst'));

    // ---- the sample file, by the file input
    await page.click('#tab-probe');
    await page.setInputFiles('#pb-file', SAMPLE_URL.pathname);
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.state === 'result');
    await waitPlotted(page, 'pb-centres');
    const engine = fa.probeIdentify({ machine: BC, sphere: { x: 0, y: 0, height: 100 }, csv: SAMPLE });
    const worst = Number(await page.getAttribute('#pb-verdict', 'data-worst'));
    assert.equal(worst, engine.before.max, 'the verdict judges the centres’ largest wander before correction');
    assert.equal(await page.getAttribute('#pb-verdict', 'data-verdict'), worst > 0.01 ? 'fail' : 'pass');
    const sentence = await page.textContent('#pb-verdict-sentence');
    assert.match(sentence, new RegExp(`strays up to ${(worst * 1000).toPrecision(4)} µm`));
    assert.match(sentence, /corrections below would bring it to/);
    assert.match(await page.textContent('#pb-verdict-source'), /probe-sphere-measured\.csv/);
    assert.match(await page.textContent('#pb-source'), /From probe-sphere-measured\.csv \(19 poses\), read at/);
    // The spread before and after, 1σ and largest.
    assert.match(await page.textContent('#pb-sum-before'), /1σ per coordinate, [\d.]+ µm at most/);
    assert.match(await page.textContent('#pb-sum-after'), /1σ per coordinate, [\d.]+ µm at most/);

    // The corrections: exactly the errors the sample was made with, each with what to enter.
    const corrections = await page.$$eval('#pb-corrections-table tbody tr', (rs) => rs.map((r) => ({ name: r.dataset.name, cells: [...r.children].map((c) => c.textContent) })));
    assert.deepEqual(corrections.map((c) => c.name).sort(), Object.keys(TRUTH).sort());
    for (const c of corrections) {
      const [, words, , enter] = c.cells;
      assert.match(words, /the B axis line/);
      const sign = TRUTH[c.name] > 0 ? '+' : '-';
      if (/^E_[XYZ]0/.test(c.name)) assert.match(enter, new RegExp(`add \\${sign}0\\.0\\d+ mm`), `${c.name}: ${enter}`);
      else assert.match(enter, new RegExp(`turn it by \\${sign}0\\.00\\d+°`), `${c.name}: ${enter}`);
    }
    assert.match(await page.textContent('#pb-signs'), /where the axis really is minus where the control believes/);

    // The identified values against the errors the sample was made with: each within the 95 %
    // interval the page shows.
    const identified = {};
    for (const name of Object.keys(TRUTH)) {
      const [value, half, decision] = await page.$$eval(`#pb-ident-table tr[data-name=${name}] td`, (tds) => tds.map((t) => t.textContent));
      const v = toApi(name, number(value));
      const h = toApi(name, number(half));
      identified[name] = v;
      assert.equal(decision, 'present', name);
      assert.ok(Math.abs(v - TRUTH[name]) <= h, `${name}: ${value} ± ${half} does not hold the truth ${TRUTH[name]}`);
      assert.ok(h < Math.abs(TRUTH[name]) / 3, `${name}: interval ± ${half} is tight`);
    }
    // The plot: per pose, the centre's distance before and after (µm), the tolerance line.
    const before = await traceY(page, 'pb-centres', 0);
    const after = await traceY(page, 'pb-centres', 1);
    assert.equal(before.length, 19);
    assert.ok(Math.max(...after) < Math.max(...before) / 3, 'the model explains the wander');
    assert.deepEqual(await page.$eval('#pb-centres', (gd) => gd.data.map((t) => t.name)), ['before correction', 'after correction (predicted)', 'tolerance (10 µm)']);
    // The tolerance: above the worst wander it passes; an invalid one gives no verdict.
    await page.fill('#pb-tolerance', String(Math.ceil(worst * 1000 + 0.5)));
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.verdict === 'pass');
    assert.match(await page.textContent('#pb-verdict-sentence'), /within the \d+ µm tolerance/);
    await page.fill('#pb-tolerance', 'x');
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.state === 'invalid');
    assert.equal(await page.getAttribute('#pb-verdict', 'data-verdict'), 'none');
    await page.fill('#pb-tolerance', '10');
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.verdict === 'fail');
    await page.screenshot({ path: `${ARTIFACTS}probe-identified-1366.png`, fullPage: true });
    await page.$eval('#pb-verdict', (e) => e.scrollIntoView());
    await page.screenshot({ path: `${ARTIFACTS}probe-1366.png` });

    // ---- "Use these errors": into the Machine section, the machine's other values kept
    const kept = {};
    for (const id of ['m-kind', 'm-type', 'm-linear', 'm-rotary-mFrom', 'm-rotary-mTo', 'm-geometry-toolLength']) kept[id] = await page.inputValue(`#${id}`);
    await page.click('#pb-use-errors');
    await page.waitForFunction(() => /Entered in the Machine section/.test(document.getElementById('pb-use-msg')?.textContent ?? ''));
    for (const [name, truth] of Object.entries(TRUTH)) {
      const field = toApi(name, Number(await page.inputValue(`#m-errors-${name}`)));
      assert.ok(Math.abs(field - identified[name]) <= 1e-3 * Math.abs(identified[name]), `${name}: the machine holds ${field}, the page identified ${identified[name]}`);
      assert.ok(Math.sign(field) === Math.sign(truth), name);
      assert.match(await page.textContent('#pb-use-msg'), new RegExp(name));
    }
    for (const [id, v] of Object.entries(kept)) assert.equal(await page.inputValue(`#${id}`), v, `${id} unchanged`);
    await page.waitForFunction(() => /4 errors entered/.test(document.getElementById('machine-summary')?.textContent ?? ''));

    // The volumetric map now runs on the machine as measured.
    await page.click('#tab-volumetric');
    await page.waitForFunction(() => Number(document.getElementById('vm-verdict')?.dataset.worst ?? 0) > 0);
    await waitIdle(page);
    const mapAfter = await page.$eval('#vm-map', (gd) => gd.data[0].z.flat());
    const worstAfter = Number(await page.getAttribute('#vm-verdict', 'data-worst'));
    assert.equal(worstBefore, 0, 'no error entered: no volumetric error');
    assert.ok(worstAfter > 1e-3, `the machine as measured: ${worstAfter} mm`);
    assert.notDeepEqual(mapAfter, mapBefore);
    assert.match(await page.textContent('#vm-sentence'), /E_X0B|E_Z0B|E_A0B|E_C0B/);

    // ---- a bad file: a line with a missing column names its line and greys the last result
    await page.click('#tab-probe');
    const lines = SAMPLE.split('\r\n');
    const k = lines.findIndex((l) => l.startsWith('5;'));
    lines[k] = lines[k].slice(0, lines[k].lastIndexOf(';'));
    const bad = `${ARTIFACTS}probe-bad.csv`;
    writeFileSync(bad, lines.join('\r\n'));
    await page.setInputFiles('#pb-file', bad);
    await page.waitForFunction((line) => new RegExp(`line ${line}:`).test(document.querySelector('#pb-csv')?.closest('.field')?.textContent ?? ''), k + 1);
    assert.match(await page.$eval('#pb-csv', (e) => e.closest('.field').textContent), new RegExp(`line ${k + 1}: expected 6 values like the header, got 5`));
    assert.equal(await page.getAttribute('#pb-csv', 'aria-invalid'), 'true');
    assert.match(await page.textContent('#pb-alert'), new RegExp(`No identification from probe-bad\\.csv: line ${k + 1}:.*greyed: they belong to probe-sphere-measured\\.csv`));
    for (const sel of ['#pb-ident', '#pb-corrections', '#pb-summary']) assert.ok(await page.$eval(sel, (e) => e.classList.contains('stale')), `${sel} greyed`);
    for (const id of ['pb-centres', 'pb-components']) assert.ok(await page.$eval(`#${id}`, (e) => e.closest('.plot-wrap').classList.contains('stale')), `${id} greyed`);
    assert.equal(await page.getAttribute('#pb-verdict', 'data-verdict'), 'none', 'no verdict from a file that could not be read');
    assert.match(await page.textContent('#pb-verdict-sentence'), /probe-bad\.csv could not be used/);
    assert.ok(await page.$eval('#pb-use-errors', (b) => b.disabled), 'nothing to use');
    await page.$eval('#pb-verdict', (e) => e.scrollIntoView());
    await page.screenshot({ path: `${ARTIFACTS}probe-bad-1366.png` });
  });
});

test('Probe and sphere on a phone: the sample loaded, nothing wider than the screen', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await openProbe(page, url);
    await page.click('#pb-load-sample');
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.state === 'result');
    await waitPlotted(page, 'pb-centres');
    await waitIdle(page);
    assert.match(await page.textContent('#pb-source'), /From the sample file probe-sphere-measured\.csv \(19 poses\)/);
    // Nothing reaches past the screen's right edge (tables scroll in their own boxes).
    const wide = await page.evaluate(() => [...document.querySelectorAll('#panel-probe *')]
      .filter((e) => e.offsetParent && !e.closest('.table-scroll') && e.getBoundingClientRect().right > window.innerWidth + 1)
      .slice(0, 5).map((e) => `${e.tagName} ${e.id} ${(e.textContent ?? '').slice(0, 40)}`));
    assert.deepEqual(wide, []);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'no sideways scrolling');
    await page.screenshot({ path: `${ARTIFACTS}probe-390.png`, fullPage: true });
  });
});

test('Probe and sphere: the sample on another machine is refused by its header, and its machine is offered', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-probe');
    await page.waitForSelector('#panel-probe[data-ready=true]');
    await page.selectOption('#m-preset-menu', await optionValue(page, 'm-preset-menu', 'A/C trunnion'));
    await page.waitForFunction(() => document.getElementById('m-type')?.value === 'CAZ');
    await waitIdle(page);
    await page.click('#pb-load-sample');
    // A and C here: the file's B column is not one of this machine's axes.
    await page.waitForFunction(() => !document.getElementById('pb-alert')?.hidden);
    assert.match(await page.textContent('#pb-alert'), /No identification from the sample file probe-sphere-measured\.csv: line 9: unknown column "B \[deg\]"/);
    assert.equal(await page.getAttribute('#pb-verdict', 'data-verdict'), 'none');
    await page.waitForSelector('#pb-sample-offer:not([hidden])');
    assert.match(await page.textContent('#pb-sample-offer'), /measured on “B\/C tilting table/);
    await page.click('#pb-sample-machine');
    await page.waitForFunction(() => document.getElementById('m-type')?.value === 'CBZ');
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.state === 'result');
    // The machine's change and the file's text each start an identification: the first result
    // can show for a moment before the second request; judge the page once it is idle.
    await waitIdle(page);
    await page.waitForFunction(() => document.getElementById('pb-verdict')?.dataset.state === 'result');
    assert.equal(await page.inputValue('#pb-csv'), SAMPLE.replace(/\r\n/g, '\n'));
    assert.match(await page.textContent('#pb-verdict-source'), /the sample file probe-sphere-measured\.csv/);
    assert.ok(await page.$eval('#pb-alert', (e) => e.hidden), 'the message goes with the file read');
  });
});
