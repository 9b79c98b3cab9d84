// The load time of a `texture preview` page in headless chromium (WebGL2 on SwiftShader): from
// navigation start to the page's first drawn frame after its load event (the navigation timing's
// loadEventEnd, then one requestAnimationFrame), in ms, for each query given, each R times.
// Usage: node --experimental-websocket scripts/preview-load-time.mjs PAGE.html R 'QUERY' ['QUERY'...]
//   (QUERY: '' for the page as it opens, 'method=hex' ...). Prints one line per query: the times and their median.
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { evaluatePage } = await import(path.join(here, '../tests/scripts/chromium_eval.mjs'));
const [page, rounds, ...queries] = process.argv.slice(2);
const expression = `document.readyState !== 'complete' ? undefined : new Promise(r => requestAnimationFrame(() =>
  r({ ms: performance.now(), title: document.title, method: (document.getElementById('info') || {}).textContent })))`;
for (const q of queries) {
  const times = [];
  let info = '';
  for (let i = 0; i < Number(rounds); ++i) {
    const r = await evaluatePage(page, { expression, query: q ? '?' + q : '' });
    times.push(r.ms);
    info = r.method;
  }
  const sorted = [...times].sort((a, b) => a - b);
  console.log(`'${q}': ${times.map(t => t.toFixed(0)).join(' ')} ms, median ${sorted[Math.floor(sorted.length / 2)].toFixed(0)} (${info})`);
}
