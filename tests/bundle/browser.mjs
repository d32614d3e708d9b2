// What the tests of the bundled builds share (tests/bundle/offline.mjs,
// tests/bundle/npm.mjs): headless Chromium as tests/e2e starts it (its
// playwright-core, installed by scripts/e2e.sh's npm ci), a page that
// records console errors and page exceptions, and a tiny test runner.

import { launchChromium } from '../e2e/chromium.mjs';
import { mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const root = join(dirname(fileURLToPath(import.meta.url)), '../..');
export const shots = join(root, 'target/screenshots');
mkdirSync(shots, { recursive: true });
export const browser = await launchChromium();

/** A fresh page at `url` recording problems (`page.problems`) and every request that is not `data:` (`page.requests`). */
export async function open(url, { ready = 'body[data-ready="true"]', init } = {}) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, acceptDownloads: true });
  if (init) await context.addInitScript(init);
  const page = await context.newPage();
  page.problems = [];
  page.requests = [];
  page.on('console', (m) => m.type() === 'error' && page.problems.push(`console error: ${m.text()}`));
  page.on('pageerror', (e) => page.problems.push(`page exception: ${e.message}`));
  page.on('request', (r) => !r.url().startsWith('data:') && page.requests.push(r.url()));
  page.on('close', () => context.close().catch(() => {}));
  await page.goto(url);
  if (ready) await page.waitForSelector(ready, { timeout: 20000, state: 'attached' });
  return page;
}

const tests = [];
export const test = (name, fn) => tests.push({ name, fn });

/** Runs the tests in order, then `after()`; exits non-zero if any failed. */
export async function run(what, after = () => {}) {
  let failed = 0;
  for (const { name, fn } of tests) {
    const t0 = Date.now();
    try {
      await fn();
      console.log(`ok   ${name} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
    } catch (e) {
      failed++;
      console.log(`FAIL ${name}\n     ${String(e.stack ?? e).split('\n').slice(0, 6).join('\n     ')}`);
    }
  }
  await browser.close();
  after();
  console.log(`${what}: ${tests.length - failed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}
