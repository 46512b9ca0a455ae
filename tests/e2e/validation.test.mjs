// Input validation on every numeric field of the Machine section and of every panel: text that
// is not a number, nothing (where a value is required), or a value out of range shows a message
// at the field (and aria-invalid for assistive technology); putting the value back clears it.
// While a field is invalid no plot is redrawn: the last good result stays on screen, greyed when
// the machine it came from is invalid. Tabs and fields are found on the page, so new panels and
// fields are covered without editing this file; whether a field may be left empty comes from
// the engine's schema.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { waitIdle, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });

/** Field ids the schema marks optional (empty: the engine's default or the machine's value). */
const OPTIONAL = (() => {
  const schema = fa.schema();
  const prefixes = { nonlinear: 'nl', cubic: 'cb', sshape: 'ss', toolpath: 'tp', volumetric: 'vm', reversal: 'rv', probe: 'pb', ballbar: 'bb', ballbarRotary: 'br', positioning: 'ps', machineSchematic: 'md' };
  const out = new Set(schema.machine.filter((f) => f.optional).map((f) => `m-${f.path.slice('machine.'.length).replace(/\./g, '-')}`));
  const owner = { nonlinear: /^(nonlinear|machineInverse)/, cubic: /^cubic/, sshape: /^sshape/, toolpath: /^toolpath/, volumetric: /^volumetric/, reversal: /^reversal/, probe: /^probe(Design|Identify)$/, ballbar: /^ballbar(?!Rotary)/, ballbarRotary: /^ballbarRotary/, positioning: /^positioning/, machineSchematic: /^machineSchematic$/ };
  for (const [name, fields] of Object.entries(schema.exports)) {
    for (const [panel, re] of Object.entries(owner)) {
      if (!re.test(name)) continue;
      for (const f of fields) if (f.optional && !f.path.startsWith('machine.')) out.add(`${prefixes[panel]}-${f.path.replace(/\./g, '-')}`);
    }
  }
  // The items of a list (the rotary ball-bar tests, `br-tests-<i>-<path>`).
  for (const f of schema.lists.ballbarTests) {
    if (!f.optional) continue;
    for (let i = 0; i < 8; i++) out.add(`br-tests-${i}-${f.path.replace(/\./g, '-')}`);
  }
  return out;
})();

/** Panels whose results do not depend on the machine (their exports take no `machine`): a bad
 *  machine leaves their plots as they are, current. */
const MACHINE_FREE = (() => {
  const exports = fa.schema().exports;
  const panels = { ballbar: ['ballbarEvaluate'], positioning: ['positioningEvaluate'] };
  for (const [panel, names] of Object.entries(panels)) {
    for (const n of names) assert.ok(exports[n] && !exports[n].some((f) => f.path.startsWith('machine')), `${panel}: ${n} takes no machine`);
  }
  return new Set(Object.keys(panels));
})();

/** How often each plot (of a panel, or all on the page) has been drawn. */
const drawCounts = (page, scope = 'body') => page.$$eval(`${scope} .plot`, (gs) => gs.map((g) => `${g.id}:${g.dataset.plotted ?? '0'}`).join());

/** The draw counts once the page is idle (no engine call in flight, no edit waiting, no plot
 *  being drawn). */
async function settle(page, scope) {
  await waitIdle(page);
  return drawCounts(page, scope);
}

/** The numeric fields shown in `scope`. */
const numericFields = (page, scope) =>
  page.$$eval(`${scope} input[data-number]`, (es) => es.filter((e) => !e.closest('[hidden]')).map((e) => e.id));

/**
 * In the page: writes each text into the field as Playwright's `fill` does (focus, the value,
 * an `input` event), waits until the field is marked invalid or valid as expected (or 10 s have
 * passed: the caller's assertion then fails with what the field shows), and returns the field's
 * state and message after each. One call per field instead of a dozen round trips: the check of
 * 170 fields took six minutes with three test files sharing two cores.
 */
function typeInPage([id, steps]) {
  const el = document.getElementById(id);
  const state = () => ({
    invalid: el.getAttribute('aria-invalid') === 'true',
    message: el.closest('.field')?.querySelector('.field-msg')?.textContent ?? '',
  });
  const settled = (invalid) =>
    new Promise((done) => {
      const until = Date.now() + 10_000;
      const poll = () => (state().invalid === invalid || Date.now() > until ? done(state()) : setTimeout(poll, 5));
      poll();
    });
  return (async () => {
    const out = [];
    for (const [text, invalid] of steps) {
      el.focus();
      el.value = text;
      el.dispatchEvent(new InputEvent('input', { bubbles: true, inputType: 'insertText', data: text }));
      out.push(await settled(invalid));
    }
    return out;
  })();
}

/** Bad texts in a field: each gives its message; the original value clears it. */
async function check(page, id) {
  const original = await page.inputValue(`#${id}`);
  // Optional: empty is a value (the default), no message.
  const empty = OPTIONAL.has(id) ? null : /Enter a value/;
  const bad = [['12abc', /not a number/], ['', empty], ['1e12', /between|at most|whole number/]];
  const steps = [...bad.map(([text, expected]) => [text, expected !== null]), [original, false]];
  const shown = await page.evaluate(typeInPage, [id, steps]);
  for (const [i, [text, expected]] of bad.entries()) {
    if (expected === null) {
      assert.deepEqual(shown[i], { invalid: false, message: '' }, `${id}: empty is allowed`);
      continue;
    }
    assert.equal(shown[i].invalid, true, `${id} with "${text}": marked invalid`);
    assert.match(shown[i].message, expected, `${id} with "${text}"`);
  }
  assert.deepEqual(shown[3], { invalid: false, message: '' }, `${id}: the message goes when the value is good again`);
}

test('every numeric field of the machine and of every panel: bad text shows a message that goes when the value is good', async () => {
  await withPage({ viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    let checked = 0;
    const seen = new Set();
    // The machine: as it opens (a table-table B/C machine), then with a head and an A axis, so
    // that the pivot and the A axis's errors show too.
    for (const [kind, type] of [[null, null], ['head-head', 'CAZ']]) {
      if (kind) {
        await page.selectOption('#m-kind', kind);
        await page.selectOption('#m-type', type);
        await page.waitForFunction(() => !document.getElementById('m-errors-E_X0A')?.closest('[hidden]'));
      }
      for (const id of await numericFields(page, '#machine')) {
        if (seen.has(id)) continue;
        seen.add(id);
        await check(page, id);
        checked++;
      }
    }
    assert.ok(['m-geometry-pivotLength', 'm-geometry-rotaryOffset', 'm-errors-E_X0A', 'm-errors-E_C0C', 'm-errors-E_B0Z', 'md-k'].every((id) => seen.has(id)), [...seen].join());
    assert.equal([...seen].filter((id) => id.startsWith('m-errors-')).length, fa.schema().errors.length, 'every error of the table');
    await page.click('#machine-reset');

    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      await page.waitForFunction((tab) => document.querySelector(`#panel-${tab} .js-plotly-plot`), tab, { timeout: 60_000 });
      await settle(page, `#panel-${tab}`);
      // The panel's form and its tolerance at the top of the results (the verdict).
      // A list's items repeat the first item's fields: the first is checked.
      const ids = (await numericFields(page, `#panel-${tab} :is(form.inputs, .verdict)`)).filter((id) => !/^br-tests-[1-9]/.test(id));
      // Every panel has at least two (the toolpath panel: L and the tolerance).
      assert.ok(ids.length >= 2, `${tab}: numeric fields found`);
      for (const id of ids) {
        await check(page, id);
        checked++;
      }
    }
    assert.ok(checked >= 50, `${checked} fields checked`);
  });
});

test('bad text keeps the last good plot: no redraw while a field of the machine or a panel is invalid', async () => {
  await withPage({ viewport: { width: 1300, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    const tabs = await page.$$eval('[role=tab]', (ts) => ts.map((t) => t.dataset.panel));
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
      await page.waitForFunction((tab) => document.querySelector(`#panel-${tab} .js-plotly-plot`), tab, { timeout: 60_000 });
    }
    // The open panel one that depends on the machine (the first tab), the others behind it.
    const open = tabs[0];
    assert.ok(!MACHINE_FREE.has(open), `${open} depends on the machine`);
    await page.click(`#tab-${open}`);
    // The machine: every panel's plots (and the drawing) stay as they were, greyed.
    let before = await settle(page);
    const first = Object.fromEntries(await Promise.all(tabs.map(async (t) => [t, await drawCounts(page, `#panel-${t}`)])));
    let { calls } = await waitIdle(page);
    const machineIds = await numericFields(page, '#machine');
    const originals = await Promise.all(machineIds.map((id) => page.inputValue(`#${id}`)));
    for (const id of machineIds) await page.fill(`#${id}`, 'x');
    assert.equal((await waitIdle(page)).calls, calls, 'no engine call for a bad machine');
    assert.equal(await drawCounts(page), before, 'no plot was redrawn from a bad machine');
    const drawn = await page.$$eval('.panel .plot', (gs) => gs.filter((g) => g.classList.contains('js-plotly-plot')).map((g) => [g.id, !!g.closest('.plot-wrap')?.classList.contains('stale'), g.closest('.panel').id.slice('panel-'.length)]));
    for (const [id, greyed, panel] of drawn) {
      if (MACHINE_FREE.has(panel)) assert.ok(!greyed, `${id} (${panel}) does not depend on the machine: not greyed`);
      else assert.ok(greyed, `${id} greyed while the machine is invalid`);
    }
    for (const [i, id] of machineIds.entries()) await page.fill(`#${id}`, originals[i]);
    // The machine valid again: the open panel is redrawn; a panel on another tab computes but is
    // drawn only when its tab is opened, greyed until then.
    const greyed = (tab) => page.$$eval(`#panel-${tab} .plot-wrap`, (ws) => ws.filter((w) => w.querySelector('.js-plotly-plot') && w.classList.contains('stale')).map((w) => w.querySelector('.plot').id));
    await page.waitForFunction((open) => [...document.querySelectorAll(`#panel-${open} .plot-wrap`)].every((w) => !w.classList.contains('stale') || !w.querySelector('.js-plotly-plot')), open);
    await waitIdle(page);
    assert.notEqual(await drawCounts(page, `#panel-${open}`), first[open], `${open}: the open panel redrawn`);
    const hidden = tabs.filter((t) => t !== open && !MACHINE_FREE.has(t));
    for (const tab of hidden) {
      assert.equal(await drawCounts(page, `#panel-${tab}`), first[tab], `${tab}: not redrawn behind its tab`);
      assert.ok((await greyed(tab)).length > 0, `${tab}: greyed behind its tab until drawn`);
    }
    for (const tab of hidden) {
      await page.click(`#tab-${tab}`);
      assert.notEqual(await settle(page, `#panel-${tab}`), first[tab], `${tab}: drawn when its tab is opened`);
      assert.deepEqual(await greyed(tab), [], `${tab}: every plot current once its tab is opened`);
    }
    // Each panel's own fields (left invalid: a field of the machine's error motions, on the
    // Volumetric tab, greys the panels after it).
    for (const tab of tabs) {
      await page.click(`#tab-${tab}`);
      before = await settle(page, `#panel-${tab}`);
      // A list's items repeat the first item's fields: the first is checked.
      const ids = (await numericFields(page, `#panel-${tab} :is(form.inputs, .verdict)`)).filter((id) => !/^br-tests-[1-9]/.test(id));
      // The first is refused at the field: no engine call from then on.
      await page.fill(`#${ids[0]}`, 'x');
      ({ calls } = await waitIdle(page));
      for (const id of ids.slice(1)) await page.fill(`#${id}`, 'x');
      assert.equal((await waitIdle(page)).calls, calls, `${tab}: no engine call from bad input`);
      assert.equal(await drawCounts(page, `#panel-${tab}`), before, `${tab}: no plot was redrawn from bad input`);
    }
  });
});
