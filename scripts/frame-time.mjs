// The page's frame time while a person works it (issue 29): the Panda with
// two spheres, orbited (a mouse drag on the empty drawing) and then a
// sphere dragged, each for DURATION_MS, and the planar page's target
// dragged as long; prints the median and the 95th percentile of the
// intervals between animation frames, and the share of frames over 1/60 s.
// A measurement on a shared machine: printed, never judged.
//
//   BASE_URL=http://127.0.0.1:8000/ [DURATION_MS=3000] node scripts/frame-time.mjs
//
// `make bench-web` serves www/ and calls it after the benchmark.

import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const DURATION = Number(process.env.DURATION_MS ?? 3000);
const browser = await launchChromium();

async function open(query) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => console.error(`page exception: ${e.message}`));
  await page.goto(`${BASE}${query}`);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  return page;
}

/** Records animation-frame intervals while `move(k)` drags the mouse in a circle; returns them (ms). */
async function during(page, from, radius) {
  await page.evaluate(() => {
    window.__intervals = [];
    let last = performance.now();
    const f = (now) => {
      window.__intervals.push(now - last);
      last = now;
      if (window.__intervals.length < 100000) requestAnimationFrame(f);
    };
    requestAnimationFrame(f);
  });
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  const t0 = Date.now();
  let k = 0;
  while (Date.now() - t0 < DURATION) {
    const a = (k++ / 30) * Math.PI * 2;
    await page.mouse.move(from.x + radius * Math.sin(a), from.y + radius * (1 - Math.cos(a)) * 0.5);
  }
  await page.mouse.up();
  const xs = await page.evaluate(() => window.__intervals.slice(2));
  return xs;
}

function report(what, xs) {
  const s = [...xs].sort((a, b) => a - b);
  const q = (p) => s[Math.min(s.length - 1, Math.floor(p * s.length))];
  const slow = xs.filter((x) => x > 1000 / 60 + 1).length / xs.length;
  console.log(`measure: ${what}: ${xs.length} frames, median ${q(0.5).toFixed(2)} ms, p95 ${q(0.95).toFixed(2)} ms, ${(100 * slow).toFixed(1)}% over 17.7 ms`);
}

const space = await open('?arm=panda&method=qp&obstacles=0.215,0.21,0.7,0.06;0.45,0.05,0.35,0.05');
await space.evaluate(() => window.demo.controller.demo.setRunning(false));
const box = await space.locator('#stage').boundingBox();
report('Panda, two spheres, qp: orbiting', await during(space, { x: box.x + 40, y: box.y + box.height - 80 }, 60));
const c = await space.evaluate(() => window.demo.worldToClient(...window.demo.state().spheres[0]));
report('Panda, two spheres, qp: dragging a sphere (the run recomputed per move)', await during(space, c, 40));
await space.close();

const plane = await open('?task=1&method=case3');
await plane.evaluate(() => window.demo.controller.demo.setRunning(false));
const t = await plane.evaluate(() => window.demo.worldToClient(...window.demo.state().target));
report('the planar page, Task 1, case3: dragging the target', await during(plane, t, 40));
await browser.close();
