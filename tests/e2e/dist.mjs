// The page as `make dist` builds it, served under a sub-path
// (scripts/test-dist.sh passes BASE_URL, e.g.
// http://127.0.0.1:PORT/courses/robotics/arm/): the page loads, runs Task 1
// and an atlas in a worker; the embed page's elements start; every request,
// the workers' included, stays under the sub-path and succeeds; no console
// errors.

import assert from 'node:assert/strict';
import { launchChromium } from './chromium.mjs';

const BASE = process.env.BASE_URL;
if (!BASE) throw new Error('dist.mjs: BASE_URL is not set (scripts/test-dist.sh sets it)');
const browser = await launchChromium();

/** A page of `path` under BASE that records every request, its failures and console errors. */
async function open(path) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const seen = { requests: [], bad: [], problems: [] };
  context.on('request', (r) => seen.requests.push(r.url()));
  context.on('requestfailed', (r) => seen.bad.push(`${r.url()}: ${r.failure()?.errorText}`));
  context.on('response', (r) => r.status() >= 400 && seen.bad.push(`${r.url()}: HTTP ${r.status()}`));
  page.on('console', (m) => m.type() === 'error' && seen.problems.push(`console error: ${m.text()}`));
  page.on('pageerror', (e) => seen.problems.push(`page exception: ${e.message}`));
  await page.goto(BASE + path);
  return { page, context, seen };
}

/** Nothing failed, nothing left the sub-path, nothing went to the console as an error. */
function clean({ seen }) {
  assert.deepEqual(seen.bad, [], 'no request failed');
  const outside = seen.requests.filter((u) => !u.startsWith(BASE) && !/^(data|blob):/.test(u));
  assert.deepEqual(outside, [], `every request under ${BASE}`);
  assert.deepEqual(seen.problems, [], 'no console errors or page exceptions');
}

const tests = [
  [
    'dist: the page loads, runs Task 1 in Case 3 and an atlas in a worker, under a sub-path',
    async () => {
      const p = await open('?task=1&method=case3');
      await p.page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
      const run = await p.page.evaluate(() => {
        window.demo.controller.demo.setRunning(false);
        return window.demo.runUntil(10);
      });
      assert.equal(run.collided, false);
      assert.ok(run.final_error < 5e-3, `final error ${run.final_error} m`);
      const atlas = await p.page.evaluate(() => window.demo.atlas({ n: 5, methods: ['numerical', 'case3'] }));
      assert.equal(atlas.cells.length, 25);
      const names = p.seen.requests.map((u) => u.slice(BASE.length).split('?')[0]);
      for (const f of ['weights/phi-equivariant.json', 'weights/v-plain.json', 'worker.js']) {
        assert.ok(names.includes(f), `${f} requested (${names.join(', ')})`);
      }
      assert.ok(names.some((f) => /^pkg\/redundant_ik_worker(_simd)?_bg\.wasm$/.test(f)), 'the workers\' module fetched');
      clean(p);
      await p.context.close();
    },
  ],
  [
    'dist: the embed page\'s custom elements start under a sub-path',
    async () => {
      const p = await open('embed.html');
      await p.page.waitForFunction(() => [...document.querySelectorAll('redundant-ik-demo')].every((e) => e.dataset.ready === 'true'), null, { timeout: 15000 });
      clean(p);
      await p.context.close();
    },
  ],
];

let failed = 0;
for (const [name, fn] of tests) {
  const t0 = Date.now();
  try {
    await fn();
    console.log(`ok   ${name} (${Date.now() - t0} ms)`);
  } catch (e) {
    failed++;
    console.log(`FAIL ${name}\n     ${String(e && e.stack ? e.stack : e).split('\n').slice(0, 6).join('\n     ')}`);
  }
}
await browser.close();
console.log(`test-dist: ${tests.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
