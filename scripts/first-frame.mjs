// The first usable frame as a newcomer meets it: a fresh browser context
// navigates to the page and waits for the first drawn arm (`data-ready`,
// set right after the first frame is drawn). For each address, LOADS loads
// (5 by default) in turn over every folder given, so two builds of the page
// are compared A/B in one run on this shared machine; prints the medians of
// `window.demo.readyMs` (performance.now() at that frame: from navigation
// start) and of the wall time from `page.goto` to `data-ready`.
//
//   node scripts/first-frame.mjs www                     # today's page
//   node scripts/first-frame.mjs /other/checkout/www www # A/B
//   LOADS=9 ADDRESSES='?task=1&method=numerical,?arm=panda' node scripts/first-frame.mjs www
//
// Needs www/pkg built (make web) and the e2e suite's packages
// (tests/e2e/node_modules: scripts/e2e.sh installs them).

import { resolve } from 'node:path';
import { launchChromium } from '../tests/e2e/chromium.mjs';
import { serve } from '../tests/e2e/serve.mjs';

const dirs = process.argv.slice(2);
if (!dirs.length) {
  console.error('usage: node scripts/first-frame.mjs DIR [DIR ...]');
  process.exit(2);
}
const LOADS = Number(process.env.LOADS ?? 5);
const ADDRESSES = (process.env.ADDRESSES ?? '?task=1&method=numerical,?arm=panda&method=numerical').split(',');
const median = (a) => {
  const b = [...a].sort((x, y) => x - y);
  return b.length % 2 ? b[b.length >> 1] : (b[b.length / 2 - 1] + b[b.length / 2]) / 2;
};

const servers = await Promise.all(dirs.map((d) => serve(resolve(d))));
const browser = await launchChromium();
const results = {};
try {
  for (let i = 0; i < LOADS; i++) {
    for (const address of ADDRESSES) {
      // Alternate the order of the folders from one round to the next.
      const order = i % 2 ? [...servers.keys()].reverse() : [...servers.keys()];
      for (const k of order) {
        const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
        const page = await context.newPage();
        const t0 = performance.now();
        await page.goto(servers[k].url + address);
        await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
        const wall = performance.now() - t0;
        const ready = await page.evaluate(() => window.demo.readyMs);
        await context.close();
        const r = ((results[address] ??= {})[dirs[k]] ??= { ready: [], wall: [] });
        r.ready.push(ready);
        r.wall.push(wall);
      }
    }
  }
} finally {
  await browser.close();
  for (const s of servers) s.stop();
}
for (const [address, byDir] of Object.entries(results)) {
  for (const [dir, r] of Object.entries(byDir)) {
    console.log(
      `measure: first usable frame ${address} from ${dir}: median ${median(r.ready).toFixed(0)} ms after navigation ` +
        `(min ${Math.min(...r.ready).toFixed(0)}, max ${Math.max(...r.ready).toFixed(0)}), ` +
        `goto -> data-ready median ${median(r.wall).toFixed(0)} ms (${r.ready.length} fresh contexts)`,
    );
  }
}
