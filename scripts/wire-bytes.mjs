// What the page transfers, as Chromium requests it: serves a directory
// (www/ by default, or dist/) on a free port, opens the page in headless
// Chromium (playwright-core, the browser launch of tests/e2e/chromium.mjs)
// and records every request, the workers' included, in four steps: the
// first load (to data-ready and the network idle), a first atlas (11 x 11
// cells), a first training (both networks, 300 samples, 2 epochs) and the
// whole-reach network set chosen. Each file is counted once, in the step
// that first fetched it (a static host's cache serves it afterwards), with
// its size raw and as `gzip -9` gives it (what a host with compression
// sends, near enough). Prints a Markdown table for docs/web.md.
//
//   node scripts/wire-bytes.mjs [DIR]     # after make web (or make dist: DIR=dist)

import { execFileSync } from 'node:child_process';
import { statSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium } from '../tests/e2e/chromium.mjs';
import { serve } from '../tests/e2e/serve.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const dir = resolve(root, process.argv[2] ?? 'www');

const server = await serve(dir);
const base = server.url;

const browser = await launchChromium();
const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
const page = await context.newPage();
const errors = [];
page.on('pageerror', (e) => errors.push(e.message));
let step = 'first load';
const fetched = new Map(); // path -> { step, count }
const requests = new Map(); // step -> requests made in it
context.on('requestfinished', (r) => {
  const url = r.url();
  if (!url.startsWith(base)) return;
  const path = decodeURIComponent(url.slice(base.length).split('?')[0]) || 'index.html';
  const seen = fetched.get(path) ?? { step, count: 0 };
  seen.count += 1;
  fetched.set(path, seen);
  requests.set(step, (requests.get(step) ?? 0) + 1);
});
const settle = () => page.waitForLoadState('networkidle');

await page.goto(base);
await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
await settle();
step = 'first atlas';
await page.evaluate(() => window.demo.atlas({ n: 11 }));
await settle();
step = 'first training';
await page.evaluate(() => window.demo.train({ net: 'both', preset: 'quick', samples: 300, epochs: 2, seed: 1 }));
await settle();
step = "the 'reach' set chosen";
await page.selectOption('#network-set', 'reach');
await page.waitForFunction(() => window.demo.state().network_set === 'reach');
await settle();
await browser.close();
server.stop();
if (errors.length) throw new Error(`page exceptions: ${errors.join('; ')}`);

const gzip = (file) => execFileSync('gzip', ['-9', '-c', file], { maxBuffer: 1 << 26 }).length;
const steps = new Map([...requests.keys()].map((s) => [s, []]));
for (const [path, { step: s, count }] of fetched) {
  const file = join(dir, path);
  const raw = statSync(file).size;
  steps.get(s).push({ path, raw, gz: gzip(file), count });
}
const n = (x) => x.toLocaleString('en-US');
console.log('| step | file | raw | gzip -9 |');
console.log('|---|---|---|---|');
let total = { raw: 0, gz: 0 };
for (const [s, files] of steps) {
  const sum = { raw: 0, gz: 0 };
  for (const f of files.sort((a, b) => b.gz - a.gz)) {
    const again = f.count > 1 ? ` (${f.count} requests in all)` : '';
    console.log(`| ${s} | \`${f.path}\`${again} | ${n(f.raw)} B | ${n(f.gz)} B |`);
    sum.raw += f.raw;
    sum.gz += f.gz;
  }
  const label = `${s}: ${requests.get(s)} requests, ${files.length ? `${files.length} new files` : 'no new file'}`;
  console.log(`| **${label}** | | **${n(sum.raw)} B** | **${n(sum.gz)} B** |`);
  total = { raw: total.raw + sum.raw, gz: total.gz + sum.gz };
}
console.log(`| **all four steps** | | **${n(total.raw)} B** | **${n(total.gz)} B** |`);
