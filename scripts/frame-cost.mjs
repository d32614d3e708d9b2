// The cost of a frame while an obstacle is dragged, in headless Chromium
// (tests/e2e/frame-cost.mjs): calls into the module and JS heap allocated
// per frame during a 5 s drag of the second of two obstacles. Serve a built
// www/ and pass its address:
//
//   python3 scripts/serve.py --dir www --port 8000 &
//   BASE_URL=http://127.0.0.1:8000/ node scripts/frame-cost.mjs
//
// Prints one JSON line: { frames, callsPerFrame, calls, heapBytesPerFrame }
// (docs/web.md quotes them, before and after the page's API of actions).

import { launchChromium } from '../tests/e2e/chromium.mjs';
import { dragCost } from '../tests/e2e/frame-cost.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const browser = await launchChromium();
const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
await page.goto(`${BASE}?task=1&method=numerical&obstacles=0.5,0.5,0.05;1.0,1.3,0.05`);
await page.waitForFunction(() => window.demo && window.demo.state);
await page.evaluate(() => window.demo.controller.demo.setRunning(false));
const cost = await dragCost(page, { from: [1.0, 1.3], seconds: Number(process.env.SECONDS ?? 5) });
console.log(JSON.stringify(cost));
await browser.close();
