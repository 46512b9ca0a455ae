// The shared Machine section in Debian's Chromium: every input the engine's schema declares
// appears on the page with its label, unit and limits; changing the machine once changes every
// panel; a share link carries the machine; the drawing follows the machine's kind.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as fa from '../../wasm/pkg/fiveaxis.js';
import { ARTIFACTS, guardedPage, startBrowser, waitIdle, waitPlotted, withPage } from './harness.mjs';

fa.initSync({ module: readFileSync(new URL('../../wasm/pkg/fiveaxis_bg.wasm', import.meta.url)) });
const schema = fa.schema();
const presets = JSON.parse(readFileSync(new URL('../../public/presets/machines.json', import.meta.url), 'utf8')).presets;

/** The panels, their field prefixes and the exports whose inputs they render. */
const PANELS = [
  { tab: 'nonlinear', prefix: 'nl', exports: ['nonlinearMove', 'nonlinearSweepM', 'nonlinearGrid', 'machineInverse'] },
  { tab: 'cubic', prefix: 'cb', exports: ['cubicTest', 'cubicHeightMap'] },
  { tab: 'sshape', prefix: 'ss', exports: ['sshapeDefects', 'sshapeOvercut', 'sshapeIdentify'] },
  { tab: 'probe', prefix: 'pb', exports: ['probeDesign', 'probeIdentify'] },
  // Last: the error motions' fields, checked after this list, sit on the Volumetric panel.
  { tab: 'volumetric', prefix: 'vm', exports: ['volumetricMap'] },
];
const id = (prefix, path) => `${prefix}-${path.replace(/\./g, '-')}`;
/** The default machine's letters: C (K) and B (M), a vertical spindle (face X, Y). */
const fill = (text) => text.replace(/\{K\}/g, 'C').replace(/\{M\}/g, 'B').replace(/\{U\}/g, 'X').replace(/\{V\}/g, 'Y');
/** The unit shown with the default preferences (µm and degrees for small quantities). */
const UNIT = { length: 'mm', smallLength: 'µm', angle: '°', smallAngle: '°' };
/** API units to the units shown by default. */
const SHOWN = { length: 1, smallLength: 1000, angle: 1, smallAngle: 1 };

/** What the page shows for a field: label, unit, the limits it enforces, hidden or not. */
const fieldOnPage = (page, fid) =>
  page.evaluate((fid) => {
    const e = document.getElementById(fid);
    if (!e) return null;
    const root = e.closest('.field, fieldset.names');
    const label = document.querySelector(`label[for="${fid}"]`)?.textContent ?? root?.querySelector('legend')?.textContent ?? null;
    return {
      label,
      unit: root?.querySelector('.unit')?.textContent ?? null,
      min: e.dataset.min ?? null,
      max: e.dataset.max ?? null,
      hidden: !!e.closest('[hidden]'),
    };
  }, fid);

const message = (page, fid) => page.$eval(`#${fid}`, (e) => e.closest('.field')?.querySelector('.field-msg')?.textContent ?? '');

test('every field of the schema is on the page with its label, unit and limits', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    let checked = 0;
    const check = async (prefix, f) => {
      const fid = id(prefix, f.path);
      const shown = await fieldOnPage(page, fid);
      assert.ok(shown, `${f.path}: a field #${fid}`);
      assert.equal(shown.label?.trim(), fill(f.label), `${f.path}: label`);
      if (f.kind === 'number') {
        assert.equal(shown.unit, UNIT[f.quantity] ?? '', `${f.path}: unit`);
        assert.equal(Number(shown.min), f.min, `${f.path}: lower limit`);
        assert.equal(Number(shown.max), f.max, `${f.path}: upper limit`);
      }
      checked++;
      return shown;
    };
    // The machine: its own fields (those of another kind hidden), the drawing's pose.
    // (Its errors and error motions are tables: checked below.)
    for (const f of schema.machine.filter((f) => f.kind !== 'errors' && f.kind !== 'motions')) {
      const s = await check('m', { ...f, path: f.path.slice('machine.'.length) });
      assert.equal(s.hidden, f.kinds.length > 0 && !f.kinds.includes('table-table'), `${f.path} hidden on a table-table machine`);
    }
    for (const f of schema.exports.machineSchematic.filter((f) => f.shown && !f.path.startsWith('machine.'))) await check('md', f);
    // Every error of the table: its ISO name, unit and limit; those of the B and C axes and the
    // squareness errors shown on the default B/C machine, the A axis's hidden.
    for (const e of schema.errors) {
      const fid = `m-errors-${e.name}`;
      const s = await fieldOnPage(page, fid);
      assert.ok(s, e.name);
      assert.ok(s.label.startsWith(`${e.name}: `), `${e.name} label ${s.label}`);
      assert.equal(s.unit, e.quantity === 'smallAngle' ? '°' : 'µm', `${e.name} unit`);
      assert.equal(s.hidden, e.axis === 'A', `${e.name} hidden`);
      checked++;
    }
    // An out-of-range value is refused at the field with the limits in the unit shown.
    await page.fill('#m-errors-E_X0B', '6000');
    await page.waitForFunction(() => /between -5000 µm and 5000 µm/.test(document.querySelector('#m-errors-E_X0B')?.closest('.field')?.textContent ?? ''));
    await page.fill('#m-errors-E_X0B', '0');
    // Every panel: the shown fields of its exports (the machine's are the section's).
    for (const p of PANELS) {
      await page.click(`#tab-${p.tab}`);
      await page.waitForSelector(`#panel-${p.tab}[data-ready=true]`);
      const seen = new Set();
      for (const name of p.exports) {
        for (const f of schema.exports[name]) {
          if (!f.shown || f.path.startsWith('machine.') || seen.has(f.path)) continue;
          seen.add(f.path);
          await check(p.prefix, f);
        }
      }
      assert.ok(seen.size >= 3, `${p.tab}: fields`);
    }
    // Every error motion of the table, on the Volumetric panel: its ISO name and unit; those of
    // X, Y, Z and of the default machine's B and C shown, the A axis's hidden.
    for (const e of schema.motions) {
      const s = await fieldOnPage(page, `m-motions-${e.name}`);
      assert.ok(s, e.name);
      assert.ok(s.label.startsWith(`${e.name}: `), `${e.name} label ${s.label}`);
      assert.equal(s.unit, e.quantity === 'smallAngle' ? '°' : 'µm', `${e.name} unit`);
      assert.equal(s.hidden, e.axis === 'A', `${e.name} hidden`);
      checked++;
    }
    // A field of another kind appears when the machine is of that kind.
    await page.selectOption('#m-kind', 'head-table');
    await page.waitForFunction(() => !document.getElementById('m-geometry-pivotLength')?.closest('[hidden]'));
    assert.ok(await page.$eval('#m-geometry-rotaryOffset', (e) => !!e.closest('[hidden]')), 'no offset between a table axis and a head axis');
    assert.ok(checked > 60, `${checked} fields checked`);
  });
});

/** The y (or z) data of every trace of a plot. */
const plotData = (page, pid) => page.$eval(`#${pid}`, (gd) => gd.data.map((t) => Array.from(t.z ? t.z.flat() : t.y ?? [])));

/** Waits until the page is idle (nothing computed, waiting or drawn any more); `ids` must exist. */
async function settle(page, ids) {
  for (const i of ids) await page.waitForSelector(`#${i}`, { state: 'attached' });
  await waitIdle(page);
}

test('changing the machine once changes every panel; a share link carries the machine', async () => {
  const b = await startBrowser();
  try {
    const ctx = await b.browser.newContext({ viewport: { width: 1400, height: 1000 } });
    const { page, assertClean } = await guardedPage(ctx, b.url);
    await page.goto(b.url);
    await page.waitForSelector('#machine[data-ready=true]');
    // A plot of each panel; a panel is drawn while its tab is open (one on another tab when it
    // is opened), so each is opened before its plot is read.
    const opened = { 'nl-curve': 'nonlinear', 'cb-zones': 'cubic', 'ss-defects': 'sshape' };
    const plots = Object.keys(opened);
    const openAll = async (page, count = {}) => {
      for (const pid of plots) {
        await page.click(`#tab-${opened[pid]}`);
        await page.waitForSelector(`#panel-${opened[pid]}[data-ready=true]`);
        await waitPlotted(page, pid, count[pid]);
      }
      await settle(page, plots);
    };
    for (const p of PANELS) {
      await page.click(`#tab-${p.tab}`);
      await page.waitForSelector(`#panel-${p.tab}[data-ready=true]`);
    }
    await openAll(page);
    const before = await page.$eval('#nl-summary #nl-max', (e) => e.textContent);
    const count = Object.fromEntries(await Promise.all(plots.map(async (p) => [p, await waitPlotted(page, p)])));

    // One change in the Machine section: the table 150 mm above the rotary centre and the B axis
    // line 20 µm towards +X.
    await page.fill('#m-geometry-tableHeight', '150');
    await page.fill('#m-errors-E_X0B', '20');
    // Both edits computed (one machine or two, as the debounce took them) before any is read.
    await waitIdle(page);
    await openAll(page, count);

    // Nonlinear: L is the machine's table height (the default machine is a table-table one), and
    // δ is proportional to L: the maximum grows by 150/100.
    const m100 = Number(before.split(' ')[0]);
    const m150 = Number((await page.$eval('#nl-summary #nl-max', (e) => e.textContent)).split(' ')[0]);
    assert.ok(Math.abs(m150 / m100 - 1.5) < 1e-6, `${m100} → ${m150}`);
    // Cubic: E_X0B = −δxBY of Li et al., whose II-1 height is −sin 30° per mm of δxBY: +10 µm
    // (first order; the vertical set-up does not enter it).
    const zones = await page.$eval('#cb-zones', (gd) => gd.data[0].z.map((r) => Array.from(r)));
    const ii1 = zones[1][0]; // row 0 (middle), column −1 (left)
    assert.ok(Math.abs(ii1 - 10) < 0.01, `II-1 ${ii1} µm`);
    // S-shape: the defect plot shows the engine's defects for this machine.
    const machine = {
      kind: 'table-table', type: 'CBZ', linear: 'spindle-xyz',
      geometry: { rotaryOffset: 0, tableHeight: 150, toolLength: 100 },
      rotary: { kFrom: -360, kTo: 360, kReversed: false, mFrom: -120, mTo: 120, mReversed: false },
      errors: { E_X0B: 0.02 },
    };
    const d = fa.sshapeDefects({ machine });
    const shown = await page.$eval('#ss-defects', (gd) => Array.from(gd.data.find((t) => t.name === 'total').y));
    shown.forEach((v, i) => assert.ok(Math.abs(v - d.total[i] * 1000) < 1e-9, `point ${i + 1}: ${v} vs ${d.total[i] * 1000}`));
    const expected = Object.fromEntries(await Promise.all(plots.map(async (p) => [p, await plotData(page, p)])));

    // The share link carries the machine: a fresh browser shows the same machine and plots.
    await page.click('#copy-link');
    await page.waitForFunction(() => document.getElementById('share-link')?.value.includes('#v=2'));
    const link = await page.inputValue('#share-link');
    assert.match(link, /m-geometry-tableHeight=150/);
    assertClean();
    const fresh = await b.browser.newContext({ viewport: { width: 1400, height: 1000 } });
    const other = await guardedPage(fresh, b.url);
    await other.page.goto(link);
    await other.page.waitForSelector('#machine[data-ready=true]');
    assert.equal(await other.page.inputValue('#m-geometry-tableHeight'), '150');
    assert.equal(await other.page.inputValue('#m-errors-E_X0B'), '20');
    await openAll(other.page);
    for (const pid of plots) assert.deepEqual(await plotData(other.page, pid), expected[pid], pid);
    other.assertClean();
    await fresh.close();
  } finally {
    await b.close();
  }
});

test('the drawing follows the machine: three kinds', async () => {
  await withPage({ viewport: { width: 1400, height: 1000 } }, async ({ page, url }) => {
    await page.goto(url);
    await page.waitForSelector('#machine[data-ready=true]');
    const cases = [
      { file: 'table-table', preset: 'A/C trunnion table', rotary: ['C (K), in the table', 'A (M), in the table'] },
      { file: 'head-table', preset: 'B swivel head, C rotary table', rotary: ['C (K), in the table', 'B (M), in the head'] },
      { file: 'head-head', preset: 'A/C fork head', rotary: ['C (K), in the head', 'A (M), in the head'] },
    ];
    for (const c of cases) {
      const i = presets.findIndex((p) => p.name.startsWith(c.preset));
      const before = await waitPlotted(page, 'machine-schematic');
      await page.selectOption('#m-preset-menu', String(i));
      await page.fill('#md-m', '30');
      await waitPlotted(page, 'machine-schematic', before);
      await page.waitForFunction(() => /at 30°/.test(document.getElementById('machine-schematic')?.getAttribute('aria-label') ?? ''));
      const names = await page.$eval('#machine-schematic', (gd) => gd.data.map((t) => t.name));
      for (const n of c.rotary) assert.ok(names.includes(n), `${c.file}: ${n} in ${names}`);
      // M at 30° tilts the spindle by 30° on a head; on a table-table machine the spindle stays
      // vertical and the table tilts by 30° instead.
      const [tool, table] = await page.$eval('#machine-schematic', (gd) => {
        const t = gd.data.find((d) => d.name === 'tool');
        const p = gd.data.find((d) => d.name === 'table');
        const e = (i) => [p.x[i] - p.x[0], p.y[i] - p.y[0], p.z[i] - p.z[0]];
        const [a, b] = [e(1), e(3)];
        return [[t.x[1] - t.x[0], t.y[1] - t.y[0], t.z[1] - t.z[0]], [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]];
      });
      const tilt = (v) => (Math.acos(Math.abs(v[2]) / Math.hypot(...v)) * 180) / Math.PI;
      const [toolTilt, tableTilt] = c.file === 'table-table' ? [0, 30] : [30, 0];
      assert.ok(Math.abs(tilt(tool) - toolTilt) < 1e-6, `${c.file}: tool tilt ${tilt(tool)}`);
      assert.ok(Math.abs(tilt(table) - tableTilt) < 1e-6, `${c.file}: table tilt ${tilt(table)}`);
      await page.locator('#machine-schematic').screenshot({ path: `${ARTIFACTS}schematic-${c.file}.png` });
      assert.match(await page.textContent('#machine-summary'), new RegExp(c.file));
    }
    await page.screenshot({ path: `${ARTIFACTS}machine.png`, fullPage: true });
  });
});
