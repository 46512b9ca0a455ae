// The first load over a slow link: bytes over the wire on a first visit (the page, its workers
// and the service worker together) and the time until the first result is on screen, through a
// simulated 10 Mbit/s link with 40 ms of round-trip latency. The link is a TCP proxy in front of
// the test's server (scripts/serve.mjs): it delays every packet by half the latency each way,
// sends the responses of all connections through one 10 Mbit/s queue, and counts the bytes it
// carries, so that every request counts whichever part of the browser made it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer, connect } from 'node:net';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serve } from '../../scripts/serve.mjs';
import { ARTIFACTS, LAUNCH_ARGS, guardedPage, waitIdle, waitPlotted } from './harness.mjs';

const MBIT = 10;
const LATENCY_MS = 40;
const BUDGET_BYTES = 1.5e6;
const BUDGET_MS = 1500;

/**
 * A proxy to `port` through the simulated link; `down` and `up` count the bytes carried. The
 * connections share the downstream 10 Mbit/s fairly, as TCP flows through one bottleneck do: a
 * pump sends, every few milliseconds, the link's worth of bytes round-robin from the
 * connections that have data waiting; each piece arrives half the latency after it was sent.
 */
function link(port) {
  const stats = { down: 0, up: 0 };
  const half = LATENCY_MS / 2;
  const TICK = 4; // ms
  const SLICE = 1460; // bytes, one TCP segment
  const flows = new Set(); // { client, queue: Buffer[], ended }
  let last = performance.now();
  const pump = setInterval(() => {
    const now = performance.now();
    let budget = Math.floor(((now - last) * MBIT * 1e3) / 8);
    last = now;
    while (budget > 0) {
      const busy = [...flows].filter((f) => f.queue.length);
      if (!busy.length) break;
      for (const f of busy) {
        const head = f.queue[0];
        const n = Math.min(SLICE, head.length, budget);
        const piece = head.subarray(0, n);
        if (n === head.length) f.queue.shift();
        else f.queue[0] = head.subarray(n);
        budget -= n;
        flows.delete(f); // to the back of the round
        flows.add(f);
        setTimeout(() => f.client.destroyed || f.client.write(piece), half);
        if (!f.queue.length && f.ended) setTimeout(() => f.client.end(), half + 1);
        if (budget <= 0) break;
      }
    }
  }, TICK);
  const proxy = createServer((client) => {
    const server = connect(port, '127.0.0.1');
    client.setNoDelay(true);
    server.setNoDelay(true);
    const flow = { client, queue: [], ended: false };
    flows.add(flow);
    client.on('data', (chunk) => {
      stats.up += chunk.length;
      setTimeout(() => server.write(chunk), half);
    });
    server.on('data', (chunk) => {
      stats.down += chunk.length;
      flow.queue.push(chunk);
    });
    server.on('end', () => {
      flow.ended = true;
      if (!flow.queue.length) setTimeout(() => client.end(), half + 1);
    });
    client.on('end', () => setTimeout(() => server.end(), half));
    client.on('error', () => server.destroy());
    server.on('error', () => client.destroy());
    client.on('close', () => {
      server.destroy();
      flows.delete(flow);
    });
  });
  proxy.on('close', () => clearInterval(pump));
  return new Promise((ok) => proxy.listen(0, '127.0.0.1', () => ok({ proxy, stats, url: `http://localhost:${proxy.address().port}/` })));
}

test('first visit: ≤ 1.5 MB over the wire, first result ≤ 1.5 s at 10 Mbit/s and 40 ms; the engine fetched once', async () => {
  const { server } = await serve(fileURLToPath(new URL('../../dist', import.meta.url)));
  const requests = [];
  let t0 = 0;
  server.on('request', (req, res) => {
    t0 ||= performance.now();
    const start = performance.now() - t0;
    res.on('finish', () => requests.push(`${res.statusCode} ${req.url} (asked at ${start.toFixed(0)} ms, ${res.getHeader('content-length') ?? 0} bytes)`));
  });
  const { proxy, stats, url } = await link(server.address().port);
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', args: LAUNCH_ARGS, headless: true });
  try {
    const context = await browser.newContext({ viewport: { width: 1366, height: 900 } });
    const { page, assertClean } = await guardedPage(context, url);
    // Bytes as the page's own DevTools see them (not the workers' or the service worker's).
    const cdp = await context.newCDPSession(page);
    await cdp.send('Network.enable');
    let pageBytes = 0;
    cdp.on('Network.loadingFinished', (e) => (pageBytes += e.encodedDataLength));
    // The moment the first result appears, from the navigation's start.
    // The first verdict: the default panel's badge says pass or fail (it says "none" while computing).
    const FIRST_RESULT = ':is(.verdict[data-verdict="pass"], .verdict[data-verdict="fail"]) .verdict-sentence';
    await page.addInitScript((selector) => {
      const seen = () => {
        const e = document.querySelector(selector);
        if (e && e.textContent.trim() && !window.__firstResult) window.__firstResult = performance.now();
        return window.__firstResult;
      };
      new MutationObserver((_, o) => seen() && o.disconnect()).observe(document, { childList: true, subtree: true, characterData: true, attributes: true, attributeFilter: ['data-verdict'] });
    }, FIRST_RESULT);

    await page.goto(url);
    await page.waitForFunction(() => window.__firstResult);
    const firstResult = await page.evaluate(() => window.__firstResult);
    for (const id of ['nl-curve', 'nl-sweep-k', 'nl-sweep-m', 'nl-map-max', 'nl-map-u', 'nl-compare', 'machine-schematic']) await waitPlotted(page, id);
    const allDrawn = await page.evaluate(() => performance.now());
    await page.evaluate(async () => {
      await navigator.serviceWorker.ready;
      while (!navigator.serviceWorker.controller || !window.fiveaxis) await new Promise((r) => setTimeout(r, 50));
    });
    // The page idle (no engine call, draw or fetch pending) and its network idle; then, as a
    // measuring window for the workers' and the service worker's requests, until the link has
    // been quiet for 2 s (the bytes are counted, not inferred from the quiet).
    await waitIdle(page);
    await page.waitForLoadState('networkidle');
    for (let before = -1; before !== stats.down; ) {
      before = stats.down;
      await page.waitForTimeout(2000);
    }
    const first = { down: stats.down, up: stats.up, pageBytes };
    await page.screenshot({ path: `${ARTIFACTS}load-first-visit.png` });

    // A second visit costs revalidations only (the assets' names carry their content's hash).
    stats.down = 0;
    await page.reload();
    await waitPlotted(page, 'nl-curve');
    await page.waitForLoadState('networkidle');
    const second = stats.down;

    const wasm = requests.filter((r) => /^200 \S*\.wasm /.test(r));
    console.log(`first visit: ${first.down} bytes over the wire to the browser (${(first.down / 1e6).toFixed(3)} MB; ${first.up} up); ` +
      `DevTools' count for the page's own requests (those the service worker answered count 0 there): ${first.pageBytes} bytes`);
    console.log(`first result on screen at ${firstResult.toFixed(0)} ms, every plot of the panel and the machine drawn at ${allDrawn.toFixed(0)} ms ` +
      `(${MBIT} Mbit/s, ${LATENCY_MS} ms)`);
    console.log(`second visit: ${second} bytes; requests answered on the first visit:\n  ${requests.join('\n  ')}`);
    assert.equal(wasm.length, 1, `the engine is sent once: ${wasm.join(', ')}`);
    assert.ok(first.down <= BUDGET_BYTES, `first visit ${first.down} bytes > ${BUDGET_BYTES}`);
    assert.ok(firstResult <= BUDGET_MS, `first result at ${firstResult.toFixed(0)} ms > ${BUDGET_MS} ms`);
    assertClean();
  } finally {
    await browser.close();
    await new Promise((r) => proxy.close(r));
    await new Promise((r) => server.close(r));
  }
});
