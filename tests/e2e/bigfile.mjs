// A toolpath CSV of `n` points made in the page (a helix tilting between 11° and 29°), as
// `window.bigFile` named million.csv: 70 MB through the test's connection would take longer than
// the page does. For `page.evaluate(makeBigFile, n)` in the 10⁶-point test and the bench.
export function makeBigFile(n) {
  const lines = new Array(n);
  for (let i = 0; i < n; i++) {
    const t = (i / n) * 40 * Math.PI;
    const tilt = 0.3 + 0.2 * Math.sin(t / 7);
    lines[i] = `${(50 * Math.cos(t)).toFixed(4)},${(50 * Math.sin(t)).toFixed(4)},${((i / n) * 10).toFixed(4)},${(Math.sin(tilt) * Math.cos(t)).toFixed(6)},${(Math.sin(tilt) * Math.sin(t)).toFixed(6)},${Math.cos(tilt).toFixed(6)}`;
  }
  window.bigFile = new File([lines.join('\n')], 'million.csv', { type: 'text/plain' });
}
