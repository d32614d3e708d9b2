// Times the page's training job (window.demo.train({net: 'both', preset,
// seed: 1}), in the workers' module in a Web Worker) in headless Chromium:
// RUNS runs of each preset, alternating between the pages of BASE_URLS (so
// a build before and after a change share the machine's state), then the
// median of each. These are measurements on a shared machine: printed,
// never judged.
//
//   BASE_URLS=http://127.0.0.1:8000/,http://127.0.0.1:8001/ PRESETS=quick,thorough RUNS=3 node scripts/train-web.mjs
//
// `scripts/train-web.sh` serves www/ (and BEFORE_DIR, if given) and calls it.
// Needs playwright-core (installed under tests/e2e by scripts/e2e.sh).

import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASES = (process.env.BASE_URLS ?? 'http://127.0.0.1:8000/').split(',');
const PRESETS = (process.env.PRESETS ?? 'quick').split(',');
const RUNS = Number(process.env.RUNS ?? 3);
const browser = await launchChromium();

async function open(base) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => console.error(`page exception: ${e.message}`));
  await page.goto(`${base}?task=1&method=numerical`);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
  return { page, context };
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

const times = {};
for (const preset of PRESETS) {
  for (let run = 0; run < RUNS; run++) {
    for (const base of BASES) {
      const { page, context } = await open(base);
      const r = await page.evaluate(async (preset) => {
        const t0 = performance.now();
        const report = await window.demo.train({ net: 'both', preset, seed: 1 });
        const seconds = (performance.now() - t0) / 1000;
        return { seconds, worker_s: report.worker_ms / 1000, phi: report.phi_error?.median, build: window.demo.build };
      }, preset);
      await context.close();
      const key = `${preset} ${base}`;
      (times[key] ??= []).push(r.seconds);
      console.log(JSON.stringify({ preset, base, run, ...r }));
    }
  }
}
for (const [key, xs] of Object.entries(times)) {
  console.log(`median of ${xs.length}: ${key}: ${median(xs).toFixed(2)} s`);
}
await browser.close();
