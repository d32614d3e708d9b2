// The README's two screenshots, taken from the page as `make web` leaves
// it: the paper's planar arm after Task 1 in Case 3 (docs/img/demo.png)
// and the Franka Panda after its task in the QP with dampers
// (docs/img/space.png), each at 1280 x 1000 CSS pixels.
//
//   node scripts/readme-shots.mjs   # needs www/pkg (make web) and tests/e2e/node_modules

import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium } from '../tests/e2e/chromium.mjs';
import { serve } from '../tests/e2e/serve.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const SHOTS = [
  ['?task=1&method=case3', 'docs/img/demo.png'],
  ['?arm=panda&method=qp', 'docs/img/space.png'],
];

const server = await serve(join(root, 'www'));
const browser = await launchChromium();
try {
  for (const [address, file] of SHOTS) {
    const context = await browser.newContext({ viewport: { width: 1280, height: 1000 } });
    const page = await context.newPage();
    await page.goto(server.url + address);
    await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
    await page.evaluate(() => window.demo.runUntil(1e9));
    // Two frames, so the drawing shows the run's end.
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await page.screenshot({ path: join(root, file) });
    console.log(`wrote ${file}`);
    await context.close();
  }
} finally {
  await browser.close();
  server.stop();
}
