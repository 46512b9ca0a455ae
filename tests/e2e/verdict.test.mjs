// The verdict at the top of every panel's results, in Debian's Chromium: for each panel a case
// that passes and one that fails (a preset, or the tolerance changed), the badge consistent with
// the worst value shown and the tolerance field, the expected outcome derived independently (the
// engine called from Node, or a closed count of the split), the tolerance carried by a share
// link, an invalid tolerance giving no verdict (never a stale one), and no paper-only symbol in a
// headline.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fa, preset, T5_ISO } from '../papers.mjs';
import { ARTIFACTS, optionValue, withPage } from './harness.mjs';

const PREFIX = { nonlinear: 'nl', cubic: 'cb', sshape: 'ss', toolpath: 'tp', volumetric: 'vm', reversal: 'rv', probe: 'pb' };
/** Symbols only a reader of the papers knows: never in a headline. */
const PAPER_ONLY = /u\*|\beq\b|\beqs?\s*\d|Σ|M_WC|KMH/i;

/** The verdict of a panel as shown. */
const verdictOf = (page, panel) =>
  page.$eval(`#panel-${panel} .verdict`, (v) => ({
    status: v.dataset.verdict,
    worst: v.dataset.worst === undefined ? null : Number(v.dataset.worst),
    tolerance: v.dataset.tolerance === undefined ? null : Number(v.dataset.tolerance),
    badge: v.querySelector('.verdict-badge')?.textContent,
    sentence: v.querySelector('.verdict-sentence')?.textContent ?? '',
    first: v.parentElement?.firstElementChild === v,
  }));

/** Waits for a verdict (pass or fail) judged against `tolMm`, and returns it. */
async function judged(page, panel, tolMm) {
  await page.waitForFunction(
    ([panel, tol]) => {
      const v = document.querySelector(`#panel-${panel} .verdict`);
      return v && v.dataset.verdict !== 'none' && Math.abs(Number(v.dataset.tolerance) - tol) < 1e-12 && !v.classList.contains('stale');
    },
    [panel, tolMm],
    { timeout: 90_000 },
  );
  return verdictOf(page, panel);
}

/** Every length written in a text ("3292 µm", "0.012 mm"), in mm. */
const lengths = (text) => [...text.matchAll(/(-?[\d.]+(?:e[-+]?\d+)?) (µm|mm)\b/g)].map((m) => Number(m[1]) / (m[2] === 'µm' ? 1000 : 1));

/** The badge, the worst value in the sentence and the tolerance field agree; returns the verdict. */
async function consistent(page, panel, v, expected) {
  assert.ok(v.first, `${panel}: the verdict is the first thing in the results`);
  const field = Number(await page.inputValue(`#${PREFIX[panel]}-tolerance`)) / 1000; // µm shown
  assert.ok(Math.abs(field - v.tolerance) < 1e-12, `${panel}: judged against the tolerance in the field (${field} mm vs ${v.tolerance})`);
  assert.equal(v.status, v.worst <= v.tolerance ? 'pass' : 'fail', `${panel}: ${v.status} for ${v.worst} mm against ${v.tolerance} mm`);
  assert.equal(v.badge, v.status.toUpperCase());
  if (v.worst > 0) {
    // The worst value is written in the sentence (4 significant digits), so is the tolerance.
    const written = lengths(v.sentence);
    assert.ok(written.some((x) => Math.abs(x - v.worst) <= 5e-4 * v.worst + 1e-9), `${panel}: ${v.worst} mm in "${v.sentence}"`);
    assert.ok(written.some((x) => Math.abs(x - v.tolerance) <= 1e-9), `${panel}: the tolerance in "${v.sentence}"`);
  }
  assert.doesNotMatch(v.sentence, PAPER_ONLY, `${panel}: a paper-only symbol in the headline`);
  if (expected) assert.equal(v.status, expected, `${panel}: ${v.sentence}`);
  return v;
}

async function setTolerance(page, panel, um) {
  await page.fill(`#${PREFIX[panel]}-tolerance`, String(um));
  return judged(page, panel, um / 1000);
}

/** An invalid tolerance: no verdict, a message at the field, no badge of the last inputs. */
async function invalidTolerance(page, panel) {
  const id = `${PREFIX[panel]}-tolerance`;
  await page.fill(`#${id}`, 'abc');
  await page.waitForFunction((p) => document.querySelector(`#panel-${p} .verdict`)?.dataset.verdict === 'none', panel);
  const v = await verdictOf(page, panel);
  assert.equal(v.badge, 'NO VERDICT');
  assert.equal(v.worst, null, `${panel}: no worst value of earlier inputs`);
  assert.match(v.sentence, /No verdict/);
  assert.match(await page.$eval(`#${id}`, (e) => e.closest('.field').querySelector('.field-msg').textContent), /not a number/);
  assert.equal(await page.getAttribute(`#${id}`, 'aria-invalid'), 'true');
  await page.fill(`#${id}`, '0');
  await page.waitForFunction((id) => /greater than 0/.test(document.getElementById(id)?.closest('.field')?.textContent ?? ''), id);
  assert.equal((await verdictOf(page, panel)).status, 'none');
}

async function open(page, panel) {
  await page.click(`#tab-${panel}`);
  await page.waitForSelector(`#panel-${panel}[data-ready=true] .verdict[data-verdict]`);
  // No headline of the panel (its heading) speaks in the papers' symbols either.
  assert.doesNotMatch(await page.textContent(`#panel-${panel} h2`), PAPER_ONLY);
}

async function choose(page, panel, start) {
  const menu = `${PREFIX[panel]}-preset-menu`;
  await page.selectOption(`#${menu}`, await optionValue(page, menu, start));
}

test('verdict: nonlinear and toolpath (tolerance inputs of the engine), share link, invalid tolerance', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url, context }) => {
    await page.goto(url);
    await page.waitForSelector('#panel-nonlinear[data-ready=true] .verdict[data-verdict]');
    // Default machine (table-table CBZ, L = 100 mm) and move (0°, 10°) → (30°, 25°): 3.29 mm.
    const machine = { type: 'CBZ', geometry: { tableHeight: 100 } };
    const start = { k: 0, m: 10 };
    const end = { k: 30, m: 25 };
    const exact = fa.nonlinearMove({ machine, start, end }).max;
    let v = await consistent(page, 'nonlinear', await judged(page, 'nonlinear', 0.01), exact <= 0.01 ? 'pass' : 'fail');
    assert.ok(Math.abs(v.worst - exact) < 1e-12, `δ ${v.worst} vs the engine's ${exact}`);
    // The split the sentence gives: n equal steps each within 10 µm, n − 1 not (each step a
    // move of its own, called on the engine from Node).
    const n = Number(/into (\d+) equal steps/.exec(v.sentence)?.[1]);
    assert.ok(n > 1, v.sentence);
    const worstOf = (steps) => Math.max(...Array.from({ length: steps }, (_, i) => {
      const at = (u) => ({ k: start.k + u * (end.k - start.k), m: start.m + u * (end.m - start.m) });
      return fa.nonlinearMove({ machine, start: at(i / steps), end: at((i + 1) / steps) }).max;
    }));
    assert.ok(worstOf(n) <= 0.01, `${n} steps: ${worstOf(n)} mm`);
    assert.ok(worstOf(n - 1) > 0.01, `${n - 1} steps: ${worstOf(n - 1)} mm`);
    assert.match(v.sentence, new RegExp(`of ${Number((30 / n).toPrecision(3))}° on C and ${Number((15 / n).toPrecision(3))}° on B each`));
    // A tolerance above δ passes; one below fails again.
    v = await consistent(page, 'nonlinear', await setTolerance(page, 'nonlinear', 5000), 'pass');
    assert.match(v.sentence, /within the 5000 µm tolerance as one move/);
    await invalidTolerance(page, 'nonlinear');
    await consistent(page, 'nonlinear', await setTolerance(page, 'nonlinear', 4000), 'pass');
    // The paper's approximations are one level down, in a closed <details>.
    assert.equal(await page.$eval('#nl-approx', (e) => e.closest('details')?.open), false);

    // The tolerance survives a share link (with the cubic panel's, a field of the page's own).
    await open(page, 'cubic');
    await consistent(page, 'cubic', await setTolerance(page, 'cubic', 3), 'pass');
    await page.click('#copy-link');
    await page.waitForFunction(() => document.getElementById('share-link')?.value.includes('cb-tolerance'));
    const link = await page.inputValue('#share-link');
    const other = await context.newPage();
    await other.goto(link);
    await other.waitForSelector('#panel-cubic[data-ready=true] .verdict[data-verdict]');
    assert.equal(await other.inputValue('#cb-tolerance'), '3');
    await judged(other, 'cubic', 0.003);
    await other.click('#tab-nonlinear');
    await other.waitForSelector('#panel-nonlinear[data-ready=true]');
    assert.equal(await other.inputValue('#nl-tolerance'), '4000');
    await consistent(other, 'nonlinear', await judged(other, 'nonlinear', 4), 'pass');
    await other.close();

    // Toolpath: the impeller on CBZ; its largest segment error from the engine decides.
    await open(page, 'toolpath');
    v = await consistent(page, 'toolpath', await judged(page, 'toolpath', 0.01));
    const largest = Number(/([\d.]+) µm \(segment/.exec(await page.textContent('#tp-summary'))?.[1]) / 1000;
    assert.ok(Math.abs(v.worst - largest) <= 5e-4 * largest, `${v.worst} vs the summary's ${largest}`);
    const tight = Math.round(v.worst * 1000 * 0.5 * 1000) / 1000; // µm, half the worst
    await consistent(page, 'toolpath', await setTolerance(page, 'toolpath', tight), 'fail');
    assert.match((await verdictOf(page, 'toolpath')).sentence, /segments are above it/);
    await consistent(page, 'toolpath', await setTolerance(page, 'toolpath', Math.ceil(v.worst * 2000)), 'pass');
    await invalidTolerance(page, 'toolpath');
  });
});

test('verdict: cubic, S-shape, volumetric, reversal with presets that pass and fail', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(`${url}#v=2&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true] .verdict[data-verdict]');
    // No errors: said plainly, and passed.
    let v = await consistent(page, 'cubic', await judged(page, 'cubic', 0.01), 'pass');
    assert.match(v.sentence, /No errors entered: every zone at 0/);
    // Table 5: the worst zone (ZONE I, the set-up's, never named) from the engine called from Node.
    await choose(page, 'cubic', 'Paper example: B/C tilting table with the errors its ball bar found');
    await page.waitForFunction(() => /Worst zone/.test(document.getElementById('cb-verdict-sentence')?.textContent ?? ''));
    const r = fa.cubicTest({ machine: { ...preset('B/C tilting table, vertical spindle (Li et al. 2021)'), errors: T5_ISO } });
    const zones = r.zones.filter((z) => z.name !== 'I');
    const worst = zones.reduce((a, z) => (Math.abs(z.height) > Math.abs(a.height) ? z : a));
    v = await consistent(page, 'cubic', await judged(page, 'cubic', 0.01), Math.abs(worst.height) <= 0.01 ? 'pass' : 'fail');
    assert.ok(Math.abs(v.worst - Math.abs(worst.height)) < 1e-12);
    assert.match(v.sentence, new RegExp(`^Worst zone ${worst.name} is [\\d.]+ µm ${worst.height < 0 ? 'low' : 'high'}`));
    assert.doesNotMatch(v.sentence, /zone I\b/);
    // The first contributor is the error with the largest effect alone on that zone.
    const zi = r.zones.indexOf(worst);
    const n = r.errorNames.length;
    const top = r.errorNames.reduce((a, name, e) => (Math.abs(r.single[zi * n + e]) > Math.abs(r.single[zi * n + r.errorNames.indexOf(a)]) ? name : a));
    assert.equal(await page.$eval('#cb-verdict-contrib li', (li) => li.dataset.name), top);
    assert.match(v.sentence, new RegExp(`comes from ${top}, the `));
    assert.ok(await page.$eval('#cb-verdict-contrib li b', (b) => /ISO 230-1/.test(b.title)), 'a tooltip with the ISO name');
    await consistent(page, 'cubic', await setTolerance(page, 'cubic', Math.floor(Math.abs(worst.height) * 1000) - 1), 'fail');
    assert.doesNotMatch(await page.textContent('#cb-high'), /(^|\/ )I( |$)/, 'ZONE I is not named highest or lowest');
    await invalidTolerance(page, 'cubic');
    await page.screenshot({ path: `${ARTIFACTS}verdict-test-cubic.png` });

    // S-shape: Table 4's simulation values, far above 20 µm; a tolerance above the worst passes.
    await open(page, 'sshape');
    await choose(page, 'sshape', 'Paper example: B head / C table, B axis 29.4 µm off');
    await page.waitForFunction(() => /Worst point/.test(document.getElementById('ss-verdict-sentence')?.textContent ?? ''), null, { timeout: 90_000 });
    v = await judged(page, 'sshape', 0.02);
    const total = await page.$eval('#ss-defects', (gd) => Array.from(gd.data.find((t) => t.name === 'total').y));
    const shown = Math.max(...total.map(Math.abs)) / 1000; // µm plotted
    assert.ok(Math.abs(v.worst - shown) < 1e-9, `${v.worst} vs the plot's ${shown}`);
    await consistent(page, 'sshape', v, shown <= 0.02 ? 'pass' : 'fail');
    await consistent(page, 'sshape', await setTolerance(page, 'sshape', Math.ceil(shown * 1000) + 1), 'pass');
    await invalidTolerance(page, 'sshape');

    // Volumetric: the calibrated machine's worst point, shown in the summary, against 20 µm, then 5 µm.
    await open(page, 'volumetric');
    await choose(page, 'volumetric', 'Laser-calibrated X/Y/Z');
    await page.waitForFunction(() => /Worst point/.test(document.getElementById('vm-verdict-sentence')?.textContent ?? ''), null, { timeout: 90_000 });
    v = await judged(page, 'volumetric', 0.02);
    const norm = Number(/\|Δ\| = ([\d.]+) µm/.exec(await page.textContent('#vm-worst'))?.[1]) / 1000;
    assert.ok(Math.abs(v.worst - norm) <= 5e-4 * norm, `${v.worst} vs the summary's ${norm}`);
    await consistent(page, 'volumetric', v, norm <= 0.02 ? 'pass' : 'fail');
    await consistent(page, 'volumetric', await setTolerance(page, 'volumetric', 5), norm <= 0.005 ? 'pass' : 'fail');
    assert.ok((await page.$$eval('#vm-verdict-contrib li', (l) => l.length)) >= 3, 'the budget ranked under the verdict');
    await invalidTolerance(page, 'volumetric');

    // Reversal: Table 1's r = 25 mm and r = 50 mm cases; the dent depth in the summary decides.
    await open(page, 'reversal');
    const statuses = [];
    for (const [start, tolUm] of [['Paper example: feed 1000 mm/min, circle 25 mm off the C axis', 10], ['Paper example: feed 1000 mm/min, circle 50 mm off the C axis', 10]]) {
      await choose(page, 'reversal', start);
      await page.fill('#rv-tolerance', String(tolUm));
      await page.waitForFunction((r) => (document.getElementById('rv-sum-came')?.textContent ?? '').includes(`r ${r} mm`), start.includes('25 mm') ? 25 : 50, { timeout: 90_000 });
      v = await judged(page, 'reversal', tolUm / 1000);
      const dent = Number(/^([\d.]+) µm deep/.exec(await page.textContent('#rv-sum-dent'))?.[1]) / 1000;
      assert.ok(Math.abs(v.worst - dent) <= 5e-4 * dent, `${v.worst} vs the summary's ${dent}`);
      statuses.push((await consistent(page, 'reversal', v, dent <= tolUm / 1000 ? 'pass' : 'fail')).status);
    }
    assert.deepEqual(statuses, ['pass', 'fail'], 'the dent grows with the circle’s offset from C: 10 µm passes r = 25 mm, not r = 50 mm');
    await invalidTolerance(page, 'reversal');
  });
});

test('presets are named in plain words, the paper’s reference in parentheses', () => {
  for (const panel of ['nonlinear', 'cubic', 'sshape', 'volumetric', 'reversal', 'probe']) {
    const { presets } = JSON.parse(readFileSync(new URL(`../../public/presets/${panel}.json`, import.meta.url), 'utf8'));
    for (const { name } of presets) {
      let outside = name;
      for (let prev = ''; prev !== outside;) (prev = outside), (outside = outside.replace(/\([^()]*\)/g, ''));
      assert.doesNotMatch(outside, /\b(Fig|Figs|Table|Section|eq)\b|Δθ|θ[km]|δ[xyz][BC]|[αβγ][BC][YB]|Group|u\*|Σ|M_WC|KMH/, `${panel}: "${name}"`);
    }
  }
});

test('a worst value exactly at the tolerance passes; the next double below it fails', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    // Lengths shown in mm: the tolerance typed is the worst value's own decimal form, which reads
    // back as the same double (factor 1), so the comparison meets the boundary exactly.
    await page.selectOption('#units-length', 'mm');
    await page.waitForSelector('#panel-nonlinear[data-ready=true] .verdict[data-verdict]');
    const machine = { type: 'CBZ', geometry: { tableHeight: 100 } };
    const exact = fa.nonlinearMove({ machine, start: { k: 0, m: 10 }, end: { k: 30, m: 25 } }).max;
    await page.fill('#nl-tolerance', String(exact));
    const at = await judged(page, 'nonlinear', exact);
    assert.equal(at.worst, exact, 'the engine\'s δ, to the last bit');
    assert.equal(at.tolerance, exact);
    assert.equal(at.status, 'pass', `δ = tolerance = ${exact} mm: ${at.sentence}`);
    // The largest double below: now the worst is above the tolerance.
    const below = exact - Math.abs(exact) * Number.EPSILON;
    assert.ok(below < exact);
    await page.fill('#nl-tolerance', String(below));
    const under = await judged(page, 'nonlinear', below);
    assert.equal(under.status, 'fail', `δ ${exact} mm > tolerance ${below} mm: ${under.sentence}`);
  });
});
