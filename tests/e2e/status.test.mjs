// The four states of a verdict and of the plots it judges (issue 29, "honest status"): a result
// (saying when and from what it was computed), computing, invalid input (naming the field and
// where it is, with a button that goes to it; never "the field marked in red" with nothing
// marked), and an engine error (the engine's own words, as the engine gives them from Node).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fa } from '../papers.mjs';
import { waitIdle, withPage } from './harness.mjs';

const state = (page, panel) =>
  page.$eval(`#panel-${panel} .verdict`, (v) => ({
    state: v.dataset.state,
    verdict: v.dataset.verdict,
    badge: v.querySelector('.verdict-badge').textContent,
    sentence: v.querySelector('.verdict-sentence').textContent,
    source: v.querySelector('.verdict-source').textContent,
    links: [...v.querySelectorAll('.verdict-links button')].map((b) => b.dataset.go),
  }));
const waitState = (page, panel, s) => page.waitForFunction(([panel, s]) => document.querySelector(`#panel-${panel} .verdict`)?.dataset.state === s, [panel, s], { timeout: 60_000 });
const labelOf = (page, id) => page.$eval(`label[for="${id}"]`, (l) => l.textContent.trim());

test('a verdict names the invalid field and where it is, goes to it, and says when and from what a result was computed', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(`${url}#v=2&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    await waitState(page, 'cubic', 'result');
    let v = await state(page, 'cubic');
    assert.match(v.badge, /^(PASS|FAIL)$/);
    assert.match(v.source, /^Computed at \d\d:\d\d:\d\d from the inputs shown\.$/);

    // A field of the Machine section made invalid while the Cubic tab is open.
    const id = 'm-geometry-tableHeight';
    const label = await labelOf(page, id);
    await page.fill(`#${id}`, 'abc');
    await waitState(page, 'cubic', 'invalid');
    v = await state(page, 'cubic');
    assert.equal(v.badge, 'NO VERDICT');
    const message = await page.$eval(`#${id}`, (e) => e.closest('.field').querySelector('.field-msg').textContent.trim());
    assert.ok(message.length > 0, 'the field shows its message');
    assert.ok(v.sentence.includes(`${label} (Machine section)`), `"${v.sentence}" names ${label} in the Machine section`);
    const words = message.replace(/\.$/, '').replace(/^[A-Z](?=[a-z])/, (c) => c.toLowerCase());
    assert.ok(v.sentence.includes(words), `"${v.sentence}" gives the field's message "${message}"`);
    assert.doesNotMatch(v.sentence, /marked in red|inputs marked/);
    assert.deepEqual(v.links, [id]);
    assert.equal(v.source, '', 'no time stamp without a result');
    // The plots greyed say the same field.
    const labels = await page.$$eval('#panel-cubic .stale-label', (ls) => ls.map((l) => l.textContent));
    assert.ok(labels.length > 0);
    for (const l of labels) assert.ok(l.includes(`fix ${label} (Machine section)`), l);

    // The button goes to the field.
    await page.locator('#panel-cubic .verdict-links button').click();
    assert.equal(await page.evaluate(() => document.activeElement?.id), id);

    // Two invalid fields: both named, the panel's own with its tab.
    await page.fill('#cb-tolerance', '-1');
    await page.waitForFunction(() => document.querySelectorAll('#panel-cubic .verdict-links button').length === 2);
    v = await state(page, 'cubic');
    const tab = (await page.textContent('#tab-cubic')).trim();
    assert.ok(v.sentence.includes(`(${tab} tab)`), `"${v.sentence}" names the ${tab} tab`);
    assert.deepEqual(v.links.sort(), ['cb-tolerance', id].sort());

    // Fixed: a result again, with its time stamp.
    await page.fill(`#${id}`, '100');
    await page.fill('#cb-tolerance', '10');
    await waitState(page, 'cubic', 'result');
    assert.match((await state(page, 'cubic')).source, /^Computed at /);
    assert.equal(await page.$$eval('#panel-cubic .stale-label', (ls) => ls.length), 0);
  });
});

test('an engine refusal naming no field is an engine error, in the engine\'s words', async () => {
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(`${url}#v=2&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    await waitState(page, 'cubic', 'result');
    // B may turn between −10° and 10° only: the test's zones at B = ±30° are out of reach.
    await page.fill('#m-rotary-mFrom', '-10');
    await page.fill('#m-rotary-mTo', '10');
    // Independent of the page: the engine from Node refuses the same machine, and says why.
    let words = '';
    try {
      fa.cubicTest({ machine: { kind: 'table-table', type: 'CBZ', geometry: { tableHeight: 100 }, rotary: { mFrom: -10, mTo: 10 } } });
    } catch (e) {
      words = e.message;
    }
    assert.ok(words, 'the engine refuses B within ±10° for the cubic test');
    await waitState(page, 'cubic', 'error');
    const v = await state(page, 'cubic');
    assert.equal(v.badge, 'ENGINE ERROR');
    const core = words.replace(/^machine: /, '');
    assert.ok(v.sentence.includes(core), `"${v.sentence}" has the engine's "${core}"`);
    assert.deepEqual(v.links, []);
    assert.doesNotMatch(v.sentence, /marked/);
  });
});

test('on a phone, the button to an invalid Machine field opens the folded Machine section', async () => {
  await withPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
    await page.goto(`${url}#v=2&p=cubic`);
    await page.waitForSelector('#panel-cubic[data-ready=true]');
    await waitState(page, 'cubic', 'result');
    assert.equal(await page.$eval('#machine-details', (d) => d.open), false, 'folded on a phone');
    // Invalid from a share link's state: the field is in the folded section.
    await page.evaluate(() => {
      const input = document.getElementById('m-geometry-tableHeight');
      input.value = '';
      input.dispatchEvent(new Event('input', { bubbles: true }));
      input.value = 'x';
      input.dispatchEvent(new Event('input', { bubbles: true }));
    });
    await waitState(page, 'cubic', 'invalid');
    await page.locator('#panel-cubic .verdict-links button').click();
    assert.equal(await page.$eval('#machine-details', (d) => d.open), true);
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'm-geometry-tableHeight');
    await waitIdle(page);
  });
});
