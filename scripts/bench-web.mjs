// Runs the page's benchmark (window.demo.bench(), a Web Worker) in headless
// Chromium and prints one JSON object per run, then the median of each figure;
// then times the page's default atlas (window.demo.atlas({}): Task 1, 41 x 41
// cells, five modes, in a worker) as often and prints its median:
//
//   BASE_URL=http://127.0.0.1:8000/ RUNS=3 [BUILD=baseline] node scripts/bench-web.mjs
//
// BUILD=baseline makes the page believe wasm SIMD is missing, so it loads the
// baseline module (as a browser with SIMD switched off would).
//
// `make bench-web` serves www/ and calls it. Needs playwright-core (installed
// under tests/e2e by scripts/e2e.sh) and Debian's Chromium.

// playwright-core comes from tests/e2e/node_modules, through the shared launcher.
import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const RUNS = Number(process.env.RUNS ?? 3);
const browser = await launchChromium();
const context = await browser.newContext();
if (process.env.BUILD === 'baseline') {
  await context.addInitScript(() => {
    const validate = WebAssembly.validate;
    WebAssembly.validate = (bytes) => (new Uint8Array(bytes).includes(0xfd) ? false : validate(bytes));
  });
}
const page = await context.newPage();
page.on('pageerror', (e) => console.error(`page exception: ${e.message}`));
await page.goto(`${BASE}?task=1&mode=numerical`);
await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
await page.evaluate(() => window.demo.controller.demo.setRunning(false));
const runs = [];
for (let i = 0; i < RUNS; i++) {
  const r = await page.evaluate(() => window.demo.bench());
  runs.push(r);
  console.log(JSON.stringify(r));
}
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const out = { theta_dot_ns: {}, step_ns: {}, forward_ns: {} };
for (const key of ['theta_dot_ns', 'step_ns', 'forward_ns']) {
  for (const k of Object.keys(runs[0][key])) out[key][k] = median(runs.map((r) => r[key][k]));
}
const build = await page.evaluate(() => window.demo.build);
console.log(`median of ${RUNS} (${build} build): ${JSON.stringify(out)}`);
const atlas = [];
for (let i = 0; i < RUNS; i++) {
  const s = await page.evaluate(async () => {
    await window.demo.atlas({});
    return Number(document.getElementById('atlas-status').dataset.ms) / 1000;
  });
  atlas.push(s);
  console.log(`atlas of Task 1, 41 x 41 cells, five modes (8,405 runs), in a worker: ${s.toFixed(2)} s`);
}
console.log(`median of ${RUNS} (${build} build): atlas ${median(atlas).toFixed(2)} s`);
await browser.close();
