// The offline file (dist/redundant-ik.html, `make offline`) opened from
// file:// in headless Chromium, with no server: it reaches data-ready on
// the SIMD build fetching nothing but its own data: URLs, Task 1 runs in
// every method of the menu, the whole-reach networks run, the benchmark,
// an atlas and a quick training complete in their workers, the Panda runs
// Case 3 with its networks inline, a robot of the user's opens through
// "Open robot…" and survives a reload, the built-in
// weights download, and where the browser had no wasm SIMD it says why it
// cannot start. Run by `make test-offline`.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { open, run, root, shots, test } from './browser.mjs';

const FILE = pathToFileURL(join(root, 'dist/redundant-ik.html')).href;

test('opens from file:// on the SIMD build; fetches nothing beside it', async () => {
  const page = await open(`${FILE}?task=1&method=numerical`);
  assert.equal(await page.evaluate(() => window.demo.build), 'simd');
  await page.screenshot({ path: join(shots, 'offline.png') });
  assert.deepEqual(page.requests.filter((u) => u.split('?')[0] !== FILE), [], 'no request but the file itself');
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('Task 1 runs in every method of the menu', async () => {
  const page = await open(FILE);
  const names = await page.$$eval('#mode option', (os) => os.map((o) => o.value));
  assert.deepEqual(names, await page.evaluate(() => window.demo.methods().map((m) => m.name)));
  for (const name of names) {
    await page.selectOption('#mode', name);
    await page.click('#task1');
    const s = await page.evaluate(() => window.demo.runUntil(10));
    assert.equal(s.error, null, `${name}: Task 1 runs`);
    assert.ok(Math.abs(s.t - 10) < 1e-9, `${name}: to its end`);
  }
  assert.deepEqual(page.problems, []);
  await page.close();
});

test("the whole-reach network set, inline too, runs Case 3; the benchmark runs in its worker", async () => {
  const page = await open(`${FILE}?task=1&method=case3`);
  await page.evaluate(() => window.demo.useNetworks('reach'));
  await page.waitForFunction(() => window.demo.state().network_set === 'reach');
  const s = await page.evaluate(() => window.demo.runUntil(10));
  assert.equal(s.error, null, 'Case 3 on the reach set runs Task 1');
  const r = await page.evaluate(() => window.demo.bench({ batchMs: 2 }).then((b) => Object.keys(b.step_ns).length, (e) => e.message));
  assert.ok(typeof r === 'number' && r > 0, `the benchmark: ${r}`);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('an atlas completes in its worker', async () => {
  const page = await open(FILE);
  const r = await page.evaluate(() => window.demo.atlas({ n: 5, methods: ['none', 'numerical'] }).then((a) => ({ keys: Object.keys(a) }), (e) => ({ error: e.message })));
  assert.equal(r.error, undefined, `the atlas: ${r.error}`);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('the built-in weights download; a quick training completes in its workers', async () => {
  const page = await open(FILE);
  await page.click('#train-panel summary');
  const download = page.waitForEvent('download');
  await page.click('#train-download');
  const name = (await download).suggestedFilename();
  assert.match(name, /\.json$/);
  const report = await page.evaluate(() => window.demo.train({ net: 'both', preset: 'quick' }).then((r) => r, (e) => ({ error: e.message })));
  assert.equal(report.error, undefined, `the training: ${report.error}`);
  assert.match(await page.textContent('#train-report'), /Test errors/);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('the Panda opens from the same file, in its 3-D view; its learned method runs with the networks carried inline', async () => {
  const page = await open(`${FILE}?arm=panda&method=case3&autoplay=0`);
  assert.equal((await page.evaluate(() => window.demo.state())).kind, 'space');
  // The 3-D view (three.js) is in the file too, and draws the arm.
  const view = await page.evaluate(() => ({ canvas: Boolean(document.querySelector('canvas.view-3d')), links: window.demo.controller.demo.view().links.length }));
  assert.deepEqual(view, { canvas: true, links: 6 }, 'the 3-D view is drawn from the file');
  await page.evaluate(() => window.demo.networks());
  await page.waitForFunction(() => window.demo.state().method === 'case3', null, { timeout: 60000 });
  const s = await page.evaluate(() => window.demo.runUntil(1e9));
  assert.equal(s.failure, null, 'Case 3 runs the Panda task to its end');
  assert.ok(s.ended);
  assert.deepEqual(page.requests.filter((u) => u.split('?')[0] !== FILE), [], 'no request but the file itself');
  assert.deepEqual(page.problems, []);
  await page.close();
});

test("a robot of the user's opens from the same file through Open robot…, is kept for a reload, and runs qp", async () => {
  const page = await open(FILE);
  await page.click('#arm-panel summary');
  await Promise.all([page.waitForURL(/[?&]robot=[0-9a-f]{16}/, { timeout: 30000 }), page.setInputFiles('#robot-files', join(root, 'robots/ur5e.urdf'))]);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000, state: 'attached' });
  const s = await page.evaluate(() => window.demo.state());
  assert.deepEqual([s.kind, s.arm, s.arm_label, s.dof], ['space', 'robot', 'ur5e', 6]);
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000, state: 'attached' });
  assert.equal((await page.evaluate(() => window.demo.state())).arm_label, 'ur5e', 'kept in this browser');
  await page.selectOption('#mode', 'qp');
  const end = await page.evaluate(() => window.demo.runUntil(1e9));
  assert.equal(end.failure, null);
  assert.ok(end.ended);
  assert.deepEqual(page.requests.filter((u) => u.split('?')[0] !== FILE), [], 'no request but the file itself');
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('without wasm SIMD the file says it carries the SIMD build only', async () => {
  const page = await open(FILE, { ready: '#loading.failed', init: () => (WebAssembly.validate = () => false) });
  assert.match(await page.textContent('#loading-text'), /does not carry pkg\/redundant_ik_bg\.wasm/);
  await page.close();
});

await run('offline');
