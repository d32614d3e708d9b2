// What an idle page costs the machine: each page (the planar page on Task 1,
// the page in space with the Panda, and a blank page whose animation loop
// does nothing, the floor) is opened in headless Chromium, paused, left
// 1.5 s to settle, and then the CPU time of every Chromium process (the
// browser, the renderer, the GPU and utility processes: the canvas is
// rasterised in software here) is read from /proc over DURATION_MS and
// printed as a share of one core. On two cores, that is what the page's
// own benchmark worker competes with. Linux only (/proc). A measurement on
// a shared machine: printed, never judged.
//
//   BASE_URL=http://127.0.0.1:8000/ [DURATION_MS=5000] node scripts/idle-cpu.mjs
//
// `make bench-web` serves www/ and calls it after the frame times.

import { readdirSync, readFileSync } from 'node:fs';
import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const DURATION = Number(process.env.DURATION_MS ?? 5000);
/** Clock ticks per second of /proc/PID/stat's utime and stime (USER_HZ, 100 on Linux). */
const HZ = 100;

/** CPU time (s) of every process whose name says Chromium. */
function chromiumSeconds() {
  let ticks = 0;
  for (const pid of readdirSync('/proc')) {
    if (!/^\d+$/.test(pid)) continue;
    try {
      if (!/chrom/i.test(readFileSync(`/proc/${pid}/comm`, 'utf8'))) continue;
      // Fields after the command's closing parenthesis: utime and stime are the 12th and 13th.
      const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      ticks += Number(fields[11]) + Number(fields[12]);
    } catch (_) {
      // The process ended between the listing and the read.
    }
  }
  return ticks / HZ;
}

const BLANK = 'data:text/html,<canvas width=640 height=480></canvas><script>const f=()=>requestAnimationFrame(f);f()</script>';
const pages = [
  ['a blank page with an empty animation loop (the floor)', BLANK],
  ['the planar page, Task 1, paused', `${BASE}?task=1&method=numerical`],
  ['the page in space, the Panda, paused', `${BASE}?arm=panda`],
];

const browser = await launchChromium();
for (const [label, url] of pages) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => console.error(`page exception: ${e.message}`));
  await page.goto(url);
  if (url !== BLANK) {
    await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
    await page.evaluate(() => window.demo.controller.demo.setRunning(false));
  }
  await page.waitForTimeout(1500);
  const before = chromiumSeconds();
  await page.waitForTimeout(DURATION);
  const share = (chromiumSeconds() - before) / (DURATION / 1000);
  console.log(`idle: ${label}: ${(share * 100).toFixed(1)}% of a core (all Chromium processes, ${DURATION / 1000} s)`);
  await context.close();
}
await browser.close();
