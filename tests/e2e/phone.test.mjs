// Phones and small screens: at 360 and 390 px (a phone, touch) no panel makes the page wider than
// the screen, with its results drawn; the tabs are thumb-sized (≥ 44 px) and scroll inside their
// own bar; no plot's title is covered by Plotly's mode bar; no tick reads a number of more than
// 8 digits. Screenshots of every panel at 360,
// 390 and 1366 px go to tests/artifacts/ (phone-<width>-<panel>.png) to be looked at.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ARTIFACTS, withPage, waitIdle } from './harness.mjs';

const TABS = ['nonlinear', 'cubic', 'sshape', 'toolpath', 'volumetric', 'reversal', 'probe', 'ballbar', 'ballbar-rotary', 'positioning'];

/**
 * Waits until the open panel is ready and the page idle: every plot it draws on its own (and
 * the machine's) drawn. The plots of an identification stay empty until a measurement is given.
 */
async function drawn(page, tab) {
  await page.waitForSelector(`#panel-${tab}[data-ready=true]`);
  await waitIdle(page);
}

/** What is wrong with the page's layout now, in words (nothing: an empty list). */
function layoutProblems(page, width) {
  return page.evaluate((width) => {
    const out = [];
    // On a phone a page wider than the screen widens the layout viewport (innerWidth) too, and
    // is shown zoomed out: the screen's width is the measure.
    const w = Math.min(width, window.innerWidth);
    if (document.documentElement.scrollWidth > w || window.innerWidth > width) {
      const wide = [...document.querySelectorAll('body *')]
        .filter((e) => e.getBoundingClientRect().right > w + 1 && !e.closest('nav#tabs, .table-wrap, .table-scroll') && e.offsetParent)
        .slice(0, 5)
        .map((e) => `${e.tagName.toLowerCase()}${e.id ? `#${e.id}` : ''}.${[...e.classList].join('.')} (right ${Math.round(e.getBoundingClientRect().right)})`);
      out.push(`page ${document.documentElement.scrollWidth} px wide (layout viewport ${window.innerWidth}) at ${w}: ${wide.join(', ')}`);
    }
    // A field too narrow for its number (the S-shape preset's E_A0B = 0.018574718760346158°).
    for (const i of document.querySelectorAll('input:not([type=checkbox]):not([type=file]):not([type=hidden])')) {
      if (i.offsetParent && i.scrollWidth > i.clientWidth + 1) out.push(`field ${i.id} cuts its text ${i.value}`);
    }
    for (const gd of document.querySelectorAll('.js-plotly-plot')) {
      if (!gd.offsetParent) continue;
      const bar = gd.querySelector('.modebar');
      const title = gd.querySelector('.gtitle');
      if (!bar || !title || getComputedStyle(bar).display === 'none' || getComputedStyle(bar).visibility === 'hidden') continue;
      const a = bar.getBoundingClientRect();
      const b = title.getBoundingClientRect();
      if (a.width && b.width && a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) out.push(`${gd.id}: the mode bar covers the title`);
    }
    // A number on an axis or a colour bar written with more digits than anyone reads (a colour
    // scale over values equal to 1e-12: "164.70423213582998").
    for (const gd of document.querySelectorAll('.js-plotly-plot')) {
      if (!gd.offsetParent) continue;
      for (const t of gd.querySelectorAll('.xtick text, .ytick text, .colorbar text')) {
        const s = (t.textContent ?? '').replace(/[\s,]/g, '').replace('−', '-');
        const digits = (s.match(/\d/g) ?? []).length;
        if (/^-?\d*\.?\d+$/.test(s) && digits > 8) out.push(`${gd.id}: a tick reads ${t.textContent}`);
      }
    }
    return out;
  }, width);
}

for (const width of [360, 390]) {
  test(`phone at ${width} px: no sideways scrolling on any panel, thumb-sized tabs, titles clear of the mode bar`, async () => {
    await withPage({ viewport: { width, height: 800 }, isMobile: true, hasTouch: true }, async ({ page, url }) => {
      await page.goto(url);
      await page.waitForSelector('#tab-nonlinear');
      const tabs = await page.$$eval('nav#tabs button', (bs) => bs.map((b) => b.getBoundingClientRect().height));
      assert.ok(tabs.every((h) => h >= 44), `tab heights ${tabs.join(', ')} px`);
      const problems = [];
      for (const tab of TABS) {
        await page.click(`#tab-${tab}`);
        await drawn(page, tab);
        if (tab === 'sshape') {
          // Chanal et al.'s machine (its long E_A0B), and the sample measurement drawn.
          await page.waitForFunction(() => document.querySelectorAll('#ss-preset-menu option').length > 1);
          await page.selectOption('#ss-preset-menu', '0');
          await drawn(page, tab);
          await page.click('#ss-load-sample');
          await page.waitForFunction(() => document.getElementById('ss-csv')?.value.split('\n').length > 100);
          await drawn(page, tab);
        }
        problems.push(...(await layoutProblems(page, width)).map((p) => `${tab}: ${p}`));
        await page.screenshot({ path: `${ARTIFACTS}phone-${width}-${tab}.png`, fullPage: true });
      }
      const bar = await page.$eval('nav#tabs', (n) => ({ scroll: n.scrollWidth, client: n.clientWidth, overflow: getComputedStyle(n).overflowX }));
      assert.ok(bar.scroll <= bar.client || bar.overflow === 'auto' || bar.overflow === 'scroll', `the tab bar neither fits nor scrolls: ${JSON.stringify(bar)}`);
      assert.deepEqual(problems, []);
    });
  });
}

test('desktop at 1366 px: screenshots of every panel, no sideways scrolling', async () => {
  const width = 1366;
  await withPage({ viewport: { width: 1366, height: 900 } }, async ({ page, url }) => {
    await page.goto(url);
    const problems = [];
    for (const tab of TABS) {
      await page.click(`#tab-${tab}`);
      await drawn(page, tab);
      problems.push(...(await layoutProblems(page, width)).map((p) => `${tab}: ${p}`));
      await page.screenshot({ path: `${ARTIFACTS}phone-1366-${tab}.png`, fullPage: true });
    }
    assert.deepEqual(problems, []);
  });
});
