// End-to-end tests of the page around the drawing: the address, the drift switch, high-DPI and narrow screens, warnings, weights files, the comparison and the benchmark.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { shots, BASE, test, open, clean, state, near, pause, mouseDrag, countFrames, selectMethod, methodsOf } from './harness.mjs';

test('the state lives in the URL', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  await page.click('#task2');
  await pause(page);
  await page.fill('#lambda', '6');
  await page.dispatchEvent('#lambda', 'input');
  const s0 = await state(page);
  await mouseDrag(page, s0.obstacle, [0.9, 1.0]);
  const s = await state(page);
  const url = page.url();
  assert.match(url, /task=2/);
  assert.match(url, /method=numerical/);
  assert.match(url, /lambda=6/);
  const copy = await open(url.slice(BASE.length));
  const c = await state(copy);
  assert.equal(c.task, 2);
  assert.equal(c.method, 'numerical');
  assert.equal(c.lambda, 6);
  assert.ok(near(c.obstacle, s.obstacle, 2e-3), 'obstacle restored');
  assert.ok(near(c.target, s.target, 2e-3), 'target restored');
  clean(page);
  clean(copy);
  await page.close();
  await copy.close();
});

test('older names still work: mode= in the address, { mode } and { modes } in window.demo', async () => {
  // Addresses written before "method" said mode=; where both are given, method= wins.
  const old = await open('?task=2&mode=qp');
  assert.equal((await state(old)).method, 'qp');
  // The address is written back on the first change, with method=.
  await old.fill('#lambda', '6');
  await old.dispatchEvent('#lambda', 'input');
  assert.match(old.url(), /[?&]method=qp(&|$)/);
  assert.doesNotMatch(old.url(), /[?&]mode=/);
  const both = await open('?task=1&method=case3&mode=qp');
  assert.equal((await state(both)).method, 'case3');
  // The playground's simulate({ mode }) and atlas({ modes }) as with the new names.
  const r = await both.evaluate(async () => {
    const d = window.demo;
    const atlas = await d.atlas({ n: 3, modes: ['none', 'numerical'] });
    return { old: d.simulate({ mode: 'numerical' }), new: d.simulate({ method: 'numerical' }), methods: atlas.methods, inUse: d.simulate({}), case3: d.simulate({ method: 'case3' }) };
  });
  assert.deepEqual(r.old, r.new);
  assert.deepEqual(r.inUse, r.case3, 'simulate without a method runs the one in use');
  assert.deepEqual(r.methods, ['none', 'numerical']);
  for (const p of [old, both]) {
    clean(p);
    await p.close();
  }
});

test('the drift switch closes the loop in Case 3, and the URL keeps it', async () => {
  const page = await open('?task=1&method=case3');
  await page.evaluate(() => window.demo.runUntil(10));
  const open_ = await state(page);
  assert.equal(open_.feedback, 0, "the paper's open loop by default");
  await page.click('label[for="feedback"]');
  assert.equal(await page.isChecked('#feedback'), true);
  await page.click('#task1');
  await page.evaluate(() => window.demo.runUntil(10));
  const closed = await state(page);
  assert.equal(closed.feedback, 1);
  assert.equal(closed.collided, false);
  assert.ok(
    closed.final_error < open_.final_error / 5,
    `closed loop ${closed.final_error} m against open loop ${open_.final_error} m`,
  );
  assert.match(page.url(), /feedback=1/);
  const copy = await open(page.url().slice(BASE.length));
  assert.equal((await state(copy)).feedback, 1);
  assert.equal(await copy.isChecked('#feedback'), true);
  clean(page);
  clean(copy);
  await page.close();
  await copy.close();
});

test('sharp on high-DPI screens', async () => {
  const page = await open('?task=1&method=numerical', { deviceScaleFactor: 2 });
  const size = await page.evaluate(() => {
    const c = document.getElementById('stage');
    const r = c.getBoundingClientRect();
    return { w: c.width, cssW: r.width };
  });
  assert.ok(Math.abs(size.w - 2 * size.cssW) <= 1, `backing store ${size.w} px for ${size.cssW} CSS px`);
  clean(page);
  await page.close();
});

test('narrow screen layout', async () => {
  const page = await open('?task=2&method=numerical', { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, deviceScaleFactor: 2 });
  await page.evaluate(() => window.demo.runUntil(10));
  await page.screenshot({ path: join(shots, 'mobile.png'), fullPage: true });
  clean(page);
  await page.close();
});

test('network cases warn outside the trained range', async () => {
  const page = await open('?task=1&method=numerical');
  assert.equal((await state(page)).networks, true, 'the built-in networks are there');
  await selectMethod(page, 'case3');
  await pause(page);
  assert.ok(await page.isHidden('#range-warning'), 'no warning on the paper task');
  const s = await state(page);
  assert.ok(s.trained_range, 'state() describes the trained range');
  await mouseDrag(page, s.obstacle, [2.0, 1.75]);
  await page.click('#step');
  await page.waitForSelector('#range-warning', { state: 'visible' });
  assert.equal((await state(page)).in_range, false);
  await page.screenshot({ path: join(shots, 'out-of-range.png') });
  clean(page);
  await page.close();
});

test('bad weights files give a readable message', async () => {
  const page = await open('?task=1&method=numerical');
  const msg = await page.evaluate(() => {
    try {
      window.demo.controller.demo.loadNetworks('{"not": "weights"}', 'nonsense');
      return null;
    } catch (e) {
      return e.message;
    }
  });
  assert.match(msg ?? '', /bad network weights/);
  clean(page);
  await page.close();
});

test('compare panel: every method on a moved obstacle', async () => {
  const page = await open('?task=2&method=numerical');
  await pause(page);
  const s0 = await state(page);
  await mouseDrag(page, s0.obstacle, [0.65, 0.55]);
  await page.click('#compare-panel summary');
  await page.click('#compare');
  await page.waitForSelector('#compare-body tr[data-method="case3"]');
  const rows = await page.$$eval('#compare-body tr', (trs) => trs.map((tr) => ({ ...tr.dataset })));
  assert.deepEqual(rows.map((r) => r.method), (await methodsOf(page)).map((m) => m.name), 'one row per method, in menu order');
  const by = Object.fromEntries(rows.map((r) => [r.method, r]));
  // Moved next to the path, the obstacle is still one the numerical route
  // avoids; Case 3 must avoid it too.
  assert.equal(by.numerical.collided, 'false', `the numerical route avoids: ${JSON.stringify(by.numerical)}`);
  assert.equal(by.case3.collided, 'false', `Case 3 avoids where numerical does: ${JSON.stringify(by.case3)}`);
  assert.equal(by.none.collided, 'true', 'no avoidance hits the obstacle moved next to the path');
  assert.equal(by.qp.collided, 'false', `the QP with dampers avoids: ${JSON.stringify(by.qp)}`);
  console.log(
    'measure: compare at obstacle (0.65, 0.55), Task 2: ' +
      rows.map((r) => `${r.method} ${Number(r.minDistance).toFixed(3)} m`).join(', '),
  );
  await page.locator('#compare-panel').screenshot({ path: join(shots, 'compare.png') });
  clean(page);
  await page.close();
});

test('in-page benchmark: every method, in a worker, while the page keeps drawing', async () => {
  const page = await open('?task=1&method=numerical');
  await page.click('#bench-panel summary');
  // Count animation frames while the benchmark runs.
  await countFrames(page);
  const t0 = Date.now();
  await page.click('#bench');
  await page.waitForFunction(() => document.getElementById('bench-result').dataset.learnedNs, null, {
    timeout: 120000,
  });
  const seconds = (Date.now() - t0) / 1000;
  const frames = await page.evaluate(() => window.__frames);
  assert.ok(frames > 10 * seconds, `only ${frames} frames in ${seconds.toFixed(1)} s: the page stalled`);
  const r = await page.evaluate(() => ({ ...document.getElementById('bench-result').dataset }));
  // The verdict compares the learned route with the exact one it imitates (the workers' benchVerdict()).
  assert.deepEqual([r.learned, r.exact], ['case3', 'numerical']);
  for (const k of ['learnedNs', 'exactNs', 'thetaDotLearnedNs', 'thetaDotExactNs']) {
    assert.ok(Number(r[k]) > 0 && Number.isFinite(Number(r[k])), `${k} = ${r[k]}`);
  }
  assert.equal(await page.locator('#bench-body tr').count(), 5, "one row per method timed: the paper's five");
  assert.match(await page.textContent('#bench-result'), /Per RK4 step, Case 3 .* than Numerical/);
  console.log(
    `measure: in-page benchmark (Task 1, median of 7 batches after warm-up, in a worker): ` +
      `theta_dot ${r.exact} ${Number(r.thetaDotExactNs).toFixed(0)} ns, ${r.learned} ${Number(r.thetaDotLearnedNs).toFixed(0)} ns; ` +
      `RK4 step ${r.exact} ${(Number(r.exactNs) / 1000).toFixed(2)} us, ${r.learned} ${(Number(r.learnedNs) / 1000).toFixed(2)} us ` +
      `(${(Number(r.learnedNs) / Number(r.exactNs)).toFixed(2)}x); ${frames} frames drawn in ${seconds.toFixed(1)} s`,
  );
  await page.locator('#bench-panel').screenshot({ path: join(shots, 'benchmark.png') });
  // The same measurement through window.demo.bench(), and cancelling it.
  const api = await page.evaluate(async () => {
    const r = await window.demo.bench({ batchMs: 2 });
    return { methods: Object.keys(r.step_ns), thetaDot: Object.keys(r.theta_dot_ns), phi: r.forward_ns.phi, verdict: r.verdict };
  });
  // `redundant-ik bench`'s methods: the paper's five, in menu order.
  const paper = (await methodsOf(page)).filter((m) => m.group === 'paper').map((m) => m.name);
  assert.deepEqual(api.methods, paper);
  assert.deepEqual(api.thetaDot, api.methods);
  assert.deepEqual(api.verdict, ['case3', 'numerical']);
  assert.ok(api.phi > 0);
  const cancelled = await page.evaluate(async () => {
    const c = new AbortController();
    const p = window.demo.bench({ signal: c.signal });
    setTimeout(() => c.abort(), 50);
    try {
      await p;
      return 'finished';
    } catch (e) {
      return e.name;
    }
  });
  assert.equal(cancelled, 'AbortError');
  clean(page);
  await page.close();
});
