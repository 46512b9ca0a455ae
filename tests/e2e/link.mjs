// A simulated network link for the page's first-load tests and benchmark: a TCP proxy in front
// of the test's server (scripts/serve.mjs) that delays every packet by half the latency each way,
// sends the responses of all connections through one queue of MBIT Mbit/s, and counts the bytes
// it carries, so that every request counts whichever part of the browser made it.
import { createServer, connect } from 'node:net';

export const MBIT = 10;
export const LATENCY_MS = 40;

/**
 * A proxy to `port` through the simulated link; `down` and `up` count the bytes carried. The
 * connections share the downstream 10 Mbit/s fairly, as TCP flows through one bottleneck do: a
 * pump sends, every few milliseconds, the link's worth of bytes round-robin from the
 * connections that have data waiting; each piece arrives half the latency after it was sent.
 */
export function link(port) {
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

/**
 * An init script for the page: records in `window.__firstResult` the moment (ms from the
 * navigation's start) the first verdict is on screen, the default panel's badge saying pass or
 * fail (it says "none" while computing).
 */
export function watchFirstResult() {
  const selector = ':is(.verdict[data-verdict="pass"], .verdict[data-verdict="fail"]) .verdict-sentence';
  const seen = () => {
    const e = document.querySelector(selector);
    if (e && e.textContent.trim() && !window.__firstResult) window.__firstResult = performance.now();
    return window.__firstResult;
  };
  new MutationObserver((_, o) => seen() && o.disconnect()).observe(document, { childList: true, subtree: true, characterData: true, attributes: true, attributeFilter: ['data-verdict'] });
}
