// The 3-D view's frame rate in headless Chromium (the machine's WebGL is
// SwiftShader, on the CPU): the Panda's page opened fresh (the time to the
// page's data-ready), then its target dragged round a circle for SECONDS
// (5), one pointer move a frame (the calls the stage's pointer handlers
// make), while the run replans at each move and plays: frames a second
// (requestAnimationFrame callbacks), the median and 95th percentile of the
// frame interval, and the time each 3-D draw takes (SpaceDemo.view() read
// and three's render). Five fresh pages; prints one
// JSON line each and the medians. Serve a built www/ and pass its address:
//
//   python3 scripts/serve.py --dir www --port 8000 &
//   BASE_URL=http://127.0.0.1:8000/ node scripts/view-fps.mjs
//
// ADDRESS overrides the page's query (default arm=panda&method=qp).

import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const SECONDS = Number(process.env.SECONDS ?? 5);
const ADDRESS = process.env.ADDRESS ?? 'arm=panda&method=qp';
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const quantile = (xs, q) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(q * xs.length))];

const browser = await launchChromium();
const rows = [];
for (let round = 0; round < Number(process.env.ROUNDS ?? 5); round++) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const t0 = Date.now();
  await page.goto(`${BASE}?${ADDRESS}`);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  const ready = Date.now() - t0;
  const firstFrame = await page.evaluate(() => performance.getEntriesByName('first-contentful-paint')[0]?.startTime ?? null);
  // Wrap the view's draw to time it.
  await page.evaluate((skip) => {
    const v = window.demo.controller.view3d;
    const draw = v.draw.bind(v);
    window.__draws = [];
    v.draw = () => {
      const a = performance.now();
      if (!skip) draw();
      window.__draws.push(performance.now() - a);
    };
    window.__frames = [];
    const tick = (now) => {
      window.__frames.push(now);
      if (!window.__stop) requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }, Boolean(process.env.SKIP3D));
  // The drag: one pointer move a frame, in the page (what the stage's
  // pointer handlers call), so the driver's round trips do not set the rate.
  const { frames, draws, moves, running } = await page.evaluate(async (seconds) => {
    const c = window.demo.controller;
    const [x, y, z] = c.state().target;
    const stage = document.getElementById('stage').getBoundingClientRect();
    const at = c.worldToClient(x, y, z);
    const [px, py] = [at.x - stage.left, at.y - stage.top];
    c.demo.setRunning(true);
    c.demo.pointerDown(px, py, 4);
    let moves = 0;
    const t0 = performance.now();
    await new Promise((done) => {
      const move = (now) => {
        const a = ((now - t0) / 1000) * Math.PI;
        c.demo.pointerMove(px + 40 * Math.sin(a), py + 40 * (1 - Math.cos(a)));
        moves++;
        if (now - t0 < seconds * 1000) requestAnimationFrame(move);
        else done();
      };
      requestAnimationFrame(move);
    });
    c.demo.pointerUp();
    window.__stop = true;
    return { frames: window.__frames, draws: window.__draws, moves, running: c.state().running };
  }, SECONDS);
  const gaps = frames.slice(1).map((t, i) => t - frames[i]);
  const span = (frames[frames.length - 1] - frames[0]) / 1000;
  const row = {
    readyMs: ready,
    firstContentfulPaintMs: firstFrame === null ? null : Math.round(firstFrame),
    fps: Number((gaps.length / span).toFixed(1)),
    frameMsMedian: Number(median(gaps).toFixed(1)),
    frameMsP95: Number(quantile(gaps, 0.95).toFixed(1)),
    drawMsMedian: Number(median(draws).toFixed(2)),
    draws: draws.length,
    moves,
    running,
  };
  console.log(JSON.stringify(row));
  rows.push(row);
  await context.close();
}
const keys = ['readyMs', 'fps', 'frameMsMedian', 'frameMsP95', 'drawMsMedian'];
console.log(JSON.stringify({ medians: Object.fromEntries(keys.map((k) => [k, median(rows.map((r) => r[k]))])) }));
await browser.close();
