// The "Laser positioning (ISO 230-2)" panel in Debian's Chromium: it opens on the sample runs; a
// small file written here (three targets, three runs each way) is dropped on it and every value
// shown is checked against ISO 230-2's definitions computed here by hand; tolerances give the
// verdict; "Use as error motion" puts the mean bidirectional deviation into the machine as E_XX
// (a table) and the volumetric map changes to what that table gives; a file with a missing
// column names its line at the field and greys the last result; the same runs as a rotary axis
// in arc-seconds; screenshots at 1366 × 768 and 390 × 844.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { ARTIFACTS, drop, waitIdle, waitPlotted, withPage } from './harness.mjs';

const SAMPLE = readFileSync(new URL('../../public/samples/x-laser-runs.csv', import.meta.url), 'utf8');
const number = (text) => Number(/[-−]?\d+(\.\d+)?(e[-+]?\d+)?/.exec(text)?.[0].replace('−', '-'));

/**
 * The runs (µm): three targets, three runs each way, chosen so that the bidirectional R_i at
 * −250 mm (2s↑ + 2s↓ + |B_i| = 2 + 2 + 3 = 7) exceeds both directional repeatabilities (4).
 * By hand:
 *   −250 mm: ↑ 1, 2, 3 → x̄↑ 2, s↑ 1;  ↓ −2, −1, 0 → x̄↓ −1, s↓ 1;  B 3, R 7, x̄ 0.5
 *   0 mm:    ↑ 4, 4, 5 → x̄↑ 4.3333, s↑ √(1/3) = 0.57735;  ↓ 2, 3, 4 → x̄↓ 3, s↓ 1;
 *            B 1.3333, R = 2·0.57735 + 2 + 1.3333 = 4.4880, x̄ 3.6667
 *   250 mm:  ↑ −1, 0, 1 → x̄↑ 0, s↑ 1;  ↓ −3, −3, −3 → x̄↓ −3, s↓ 0;  B 3, R 5, x̄ −1.5
 *   axis: B 3, B̄ 2.4444, R↑ 4, R↓ 4, R 7, E↑ 4.3333, E↓ 6, E 4.3333 − (−3) = 7.3333, M 5.1667,
 *         A↑ 5.4880 − (−2) = 7.4880, A↓ 5 − (−3) = 8, A 5.4880 − (−3) = 8.4880.
 */
const RUNS = {
  '-250': { up: [1, 2, 3], down: [-2, -1, 0] },
  0: { up: [4, 4, 5], down: [2, 3, 4] },
  250: { up: [-1, 0, 1], down: [-3, -3, -3] },
};
const FILE = ['target (mm); direction; run; deviation (µm)']
  .concat(Object.entries(RUNS).flatMap(([t, r]) => ['up', 'down'].flatMap((d) => r[d].map((v, j) => `${t}; ${d}; ${j + 1}; ${v}`))))
  .join('\n');

/** ISO 230-2:2014, clause 3, written out here from the standard's definitions. */
function iso230_2(runs) {
  const mean = (v) => v.reduce((s, x) => s + x, 0) / v.length;
  const sd = (v) => Math.sqrt(v.reduce((s, x) => s + (x - mean(v)) ** 2, 0) / (v.length - 1));
  const targets = Object.entries(runs).map(([t, r]) => {
    const [mu, md, su, sdn] = [mean(r.up), mean(r.down), sd(r.up), sd(r.down)];
    const b = mu - md;
    return { target: Number(t), mu, md, su, sd: sdn, b, r: Math.max(2 * su + 2 * sdn + Math.abs(b), 4 * su, 4 * sdn), m: (mu + md) / 2 };
  }).sort((a, b) => a.target - b.target);
  const max = (f) => Math.max(...targets.map(f));
  const min = (f) => Math.min(...targets.map(f));
  return {
    targets,
    b: max((t) => Math.abs(t.b)),
    bMean: mean(targets.map((t) => t.b)),
    rUp: max((t) => 4 * t.su), rDown: max((t) => 4 * t.sd), r: max((t) => t.r),
    eUp: max((t) => t.mu) - min((t) => t.mu), eDown: max((t) => t.md) - min((t) => t.md),
    e: Math.max(max((t) => t.mu), max((t) => t.md)) - Math.min(min((t) => t.mu), min((t) => t.md)),
    m: max((t) => t.m) - min((t) => t.m),
    aUp: max((t) => t.mu + 2 * t.su) - min((t) => t.mu - 2 * t.su),
    aDown: max((t) => t.md + 2 * t.sd) - min((t) => t.md - 2 * t.sd),
    a: Math.max(max((t) => t.mu + 2 * t.su), max((t) => t.md + 2 * t.sd)) - Math.min(min((t) => t.mu - 2 * t.su), min((t) => t.md - 2 * t.sd)),
  };
}

/** Shown to 4 significant digits: equal to `want` to that precision. */
const close4 = (got, want, what) => assert.ok(Math.abs(got - want) <= 5e-4 * Math.max(Math.abs(want), 1e-3) + 1e-9, `${what}: shown ${got}, by hand ${want}`);

test('Laser positioning panel: values by hand, verdict, Use as error motion changes the volumetric map, bad file', async () => {
  const hand = iso230_2(RUNS);
  // The worked numbers above, so that the hand computation itself is checked too.
  close4(hand.r, 7, 'R');
  close4(hand.e, 22 / 3, 'E');
  close4(hand.a, 2 * Math.sqrt(1 / 3) + 13 / 3 + 3, 'A');
  assert.ok(hand.targets[0].r > 4 * hand.targets[0].su && hand.targets[0].r > 4 * hand.targets[0].sd, 'R_i exceeds both directional');

  await withPage({ viewport: { width: 1366, height: 768 } }, async ({ page, url }) => {
    await page.goto(url);
    // The volumetric map before: no error entered.
    await page.click('#tab-volumetric');
    await page.waitForSelector('#panel-volumetric[data-ready=true]');
    await waitPlotted(page, 'vm-map');
    await waitIdle(page);
    const mapBefore = await page.textContent('#vm-worst');

    await page.click('#tab-positioning');
    await page.waitForSelector('#panel-positioning[data-ready=true]');
    let n = await waitPlotted(page, 'ps-runs');
    assert.equal(await page.inputValue('#ps-csv'), SAMPLE);
    assert.match(await page.textContent('#ps-sum-came'), /^the sample x-laser-runs\.csv \(synthetic\): axis X, 13 targets from -300 to 300 mm, 5 runs each way/);

    // The small file, dropped.
    await drop(page, '#panel-positioning form.inputs', 'x-hand.csv', FILE);
    await page.waitForFunction(() => /^x-hand\.csv: axis X, 3 targets from -250 to 250 mm, 3 runs each way \(file in mm and µm\)/.test(document.getElementById('ps-sum-came')?.textContent ?? ''));
    n = await waitPlotted(page, 'ps-runs', n);
    await waitIdle(page);

    // Each target: x̄↑, x̄↓, s↑, s↓, B_i, R_i, x̄_i (µm).
    const rows = await page.$$eval('#ps-targets-table tbody tr', (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
    assert.equal(rows.length, 3);
    rows.forEach((cells, i) => {
      const t = hand.targets[i];
      assert.equal(number(cells[0]), t.target);
      for (const [k, key] of ['mu', 'md', 'su', 'sd', 'b', 'r', 'm'].entries()) close4(number(cells[k + 1]), t[key], `target ${t.target}: ${key}`);
    });
    // The axis: each way and bidirectional.
    const axisRow = async (name) => page.$$eval(`#ps-axis-table tr[data-name=${name}] td`, (tds) => tds.map((t) => t.textContent));
    for (const [name, up, down, both] of [['A', hand.aUp, hand.aDown, hand.a], ['E', hand.eUp, hand.eDown, hand.e], ['R', hand.rUp, hand.rDown, hand.r]]) {
      const [u, d, b] = await axisRow(name);
      close4(number(u), up, `${name}↑`);
      close4(number(d), down, `${name}↓`);
      close4(number(b), both, name);
    }
    close4(number((await axisRow('M'))[2]), hand.m, 'M');
    const bCell = (await axisRow('B'))[2];
    close4(number(bCell), hand.b, 'B');
    close4(number(bCell.split('=')[1]), hand.bMean, 'B̄');

    // Tolerances: A 9 µm (beside the verdict) passes 8.488; R 6 µm fails 7; then R 8 µm passes.
    await page.fill('#ps-tolerance-a', '9');
    await page.waitForFunction(() => document.getElementById('ps-verdict')?.dataset.verdict === 'pass');
    assert.match(await page.textContent('#ps-verdict-sentence'), /Axis X passes ISO 230-2’s checks entered: A 8\.49 µm ≤ 9 µm/);
    await page.fill('#ps-tolerance-r', '6');
    await page.waitForFunction(() => document.getElementById('ps-verdict')?.dataset.verdict === 'fail');
    const sentence = await page.textContent('#ps-verdict-sentence');
    assert.match(sentence, /fails repeatability r/i);
    assert.match(sentence, /R 7 µm > 6 µm/);
    assert.equal(await page.getAttribute('#ps-verdict', 'data-what'), 'Repeatability R');
    close4(Number(await page.getAttribute('#ps-verdict', 'data-worst')) * 1000, hand.r, 'the worst judged');
    assert.equal(await page.$eval('#ps-axis-table tr[data-name=R]', (tr) => tr.className), 'fail');
    await page.fill('#ps-tolerance-r', '8');
    await page.waitForFunction(() => document.getElementById('ps-verdict')?.dataset.verdict === 'pass');

    // The plot: each run's deviations, each way, and the bands x̄ ± 2s.
    n = await waitPlotted(page, 'ps-runs');
    const plot = await page.$eval('#ps-runs', (gd) => ({ names: gd.data.map((t) => t.name), x: Array.from(gd.data[0].x), data: gd.data.map((t) => Array.from(t.y)), y: gd.layout.yaxis.title.text, xt: gd.layout.xaxis.title.text }));
    assert.equal(plot.xt, 'target X (mm)');
    assert.equal(plot.y, 'positional deviation x (µm)');
    assert.deepEqual(plot.x, [-250, 0, 250]);
    const at = (name) => plot.names.indexOf(name);
    hand.targets.forEach((t, i) => {
      close4(plot.data[at('x̄↑ ± 2s↑')][i], t.mu + 2 * t.su, 'band ↑ top');
      close4(plot.data[at('x̄↓ ± 2s↓') - 1][i], t.md - 2 * t.sd, 'band ↓ bottom');
    });
    assert.equal(plot.names.filter((s) => s === 'runs ↑').length, 3, 'three runs up');
    assert.deepEqual(plot.data[plot.names.indexOf('runs ↓')], hand.targets.map((t) => RUNS[t.target].down[0]));
    await page.screenshot({ path: `${ARTIFACTS}positioning-1366.png`, fullPage: true });

    // Use as error motion: E_XX in the machine as a table of x̄_i (mm), named after the file.
    await page.click('#ps-use-motion');
    await page.waitForFunction(() => /Entered E_XX into the machine/.test(document.getElementById('ps-motion-msg')?.textContent ?? ''));
    assert.match(await page.textContent('#ps-motion-msg'), /x-hand\.csv at 3 points, X from -250 to 250 mm/);
    const stored = JSON.parse(await page.inputValue('#m-motions'));
    assert.deepEqual(Object.keys(stored), ['E_XX']);
    assert.deepEqual(stored.E_XX.position, [-250, 0, 250]);
    hand.targets.forEach((t, i) => close4(stored.E_XX.value[i] * 1000, t.m, `E_XX at ${t.target}`));
    assert.equal(stored.E_XX.file, 'x-hand.csv');
    await page.waitForFunction(() => /1 error motion entered/.test(document.getElementById('machine-summary')?.textContent ?? ''));

    // The volumetric map changes: its worst point is now E_XX's largest |x̄| over X −200…200 mm
    // (linear between the targets): 3.667 µm at X 0 (at ±200 mm: 1.133 and −0.4667 µm).
    await page.click('#tab-volumetric');
    await page.waitForFunction(() => /x-hand\.csv: 3 points/.test(document.getElementById('vm-csv-msg-E_XX')?.textContent ?? ''));
    await page.waitForFunction((before) => (document.getElementById('vm-worst')?.textContent ?? before) !== before, mapBefore);
    await waitIdle(page);
    const mapAfter = await page.textContent('#vm-worst');
    assert.notEqual(mapAfter, mapBefore);
    close4(number(mapAfter.split('=')[1]), hand.targets[1].m, 'worst |Δ|');
    assert.match(mapAfter, /at X 0,/);
    assert.match(await page.textContent('#vm-functions'), /E_XX \(x-hand\.csv, 3 points\)/);

    // A bad file: line N has no deviation. The message names the line at the field; the plot and
    // the tables of the runs before stay, greyed; no verdict; the button is off.
    await page.click('#tab-positioning');
    const lines = FILE.split('\n');
    const k = 5;
    lines[k] = lines[k].split(';').slice(0, 3).join(';');
    const bad = `${ARTIFACTS}positioning-bad.csv`;
    writeFileSync(bad, lines.join('\n'));
    const before = await page.$eval('#ps-runs', (gd) => gd.data.map((t) => Array.from(t.y)));
    await page.setInputFiles('#ps-file', bad);
    await page.waitForFunction((line) => new RegExp(`line ${line}: expected 4 cells, got 3`).test(document.querySelector('#ps-csv')?.closest('.field')?.querySelector('.field-msg')?.textContent ?? ''), k + 1);
    await page.waitForFunction(() => document.getElementById('ps-runs')?.closest('.plot-wrap')?.classList.contains('stale'));
    for (const id of ['ps-axis-results', 'ps-targets']) assert.ok(await page.$eval(`#${id}`, (e) => e.classList.contains('stale')), `${id} greyed`);
    assert.ok(await page.$eval('#ps-summary', (e) => e.classList.contains('stale')), 'the key numbers greyed');
    assert.equal(await page.getAttribute('#ps-verdict', 'data-verdict'), 'none');
    assert.ok(await page.$eval('#ps-use-motion', (b) => b.disabled), 'nothing to enter');
    assert.deepEqual(await page.$eval('#ps-runs', (gd) => gd.data.map((t) => Array.from(t.y))), before, 'the last good plot kept');
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}positioning-bad.png`, fullPage: true });

    // A rotary axis: the same runs as C, targets in degrees and deviations in arc-seconds, shown
    // in ″ (the small-angle unit chosen); its tolerances are angles.
    await page.selectOption('#units-angle', 'arcsec');
    await page.selectOption('#ps-axis', 'C');
    assert.ok(await page.isVisible('#ps-rotaryTolerance-a') && !(await page.isVisible('#ps-tolerance-a')), 'the rotary axis’s tolerance of A shown, the linear one hidden');
    const rotary = FILE.replace('target (mm)', 'target (deg)').replace('deviation (µm)', 'deviation (arcsec)');
    await drop(page, '#panel-positioning form.inputs', 'c-hand.csv', rotary);
    await page.waitForFunction(() => /^c-hand\.csv: axis C, 3 targets from -250 to 250 °/.test(document.getElementById('ps-sum-came')?.textContent ?? ''));
    const rotaryRows = await page.$$eval('#ps-targets-table tbody tr', (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
    rotaryRows.forEach((cells, i) => close4(number(cells[7]), hand.targets[i].m, `C: x̄_i at ${hand.targets[i].target}° (″)`));
    assert.match(await page.textContent('#ps-targets-table thead'), /x̄↑ \(″\)/);
    const drawn = await waitPlotted(page, 'ps-runs');
    await page.fill('#ps-rotaryTolerance-a', '9');
    await page.waitForFunction(() => document.getElementById('ps-verdict')?.dataset.verdict === 'pass');
    await waitPlotted(page, 'ps-runs', drawn);
    assert.equal(await page.getAttribute('#ps-verdict', 'data-quantity'), 'errAngle');
    assert.equal(Number(await page.getAttribute('#ps-verdict', 'data-tolerance')), 9 / 3600);
    assert.match(await page.textContent('#ps-verdict-sentence'), /Axis C passes ISO 230-2’s checks entered: A 8\.49″ ≤ 9″/);
    assert.equal(await page.$eval('#ps-runs', (gd) => gd.layout.yaxis.title.text), 'positional deviation x (″)');
    assert.equal(await page.$eval('#ps-runs', (gd) => gd.layout.xaxis.title.text), 'target C (°)');
  });
});

test('Laser positioning panel on a phone', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await page.goto(url);
    await page.click('#tab-positioning');
    await page.waitForSelector('#panel-positioning[data-ready=true]');
    await waitPlotted(page, 'ps-runs');
    await page.fill('#ps-tolerance-a', '12');
    await page.waitForFunction(() => document.getElementById('ps-verdict')?.dataset.verdict === 'pass');
    await waitIdle(page);
    await page.screenshot({ path: `${ARTIFACTS}positioning-390.png`, fullPage: true });
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= 390), 'no sideways scrolling');
    const w = await page.$eval('#ps-runs', (e) => e.getBoundingClientRect().width);
    assert.ok(w <= 390, `ps-runs: ${w} px`);
  });
});
