// End-to-end tests of the module: a module or networks that cannot load, the SIMD and baseline builds, names and colours from the module, the embed page.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { shots, BASE, browser, test, open, clean, state, pause, methodsOf, usesNetworks } from './harness.mjs';

test('a module that cannot load gives a readable message, not a blank page', async () => {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const exceptions = [];
  page.on('pageerror', (err) => exceptions.push(err.message));
  await page.route('**/*.wasm', (route) => route.abort());
  await page.goto(BASE + '?task=1&method=numerical');
  const loading = page.locator('#loading.failed');
  await loading.waitFor({ state: 'visible', timeout: 15000 });
  const text = await loading.textContent();
  assert.match(text, /could not start/, text);
  assert.equal(await page.getAttribute('body', 'data-ready'), null, 'never claims to be ready');
  assert.equal(await page.isDisabled('#play'), true, 'dead controls are disabled');
  assert.deepEqual(exceptions, [], 'the failure is handled, not thrown');
  await page.screenshot({ path: join(shots, 'load-failed.png') });
  await context.close();
});

test('built-in networks that cannot be fetched: the page runs the exact methods and says why the others wait', async () => {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (err) => problems.push(err.message));
  await page.route('**/weights/*.json', (route) => route.fulfill({ status: 404, body: 'gone' }));
  await page.goto(BASE);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  const s = await page.evaluate(() => window.demo.state());
  assert.equal(s.method, 'numerical', 'the default method falls back to one without networks');
  assert.equal(s.networks, false);
  const refused = await page.evaluate(() => {
    try {
      window.demo.controller.demo.setMethod('case3');
      return null;
    } catch (e) {
      return e.message;
    }
  });
  assert.match(refused, /networks not available: could not fetch weights\/phi-equivariant\.json \(HTTP 404\)/);
  // The workers are told the same reason: an atlas in Case 3 says it, one in the exact methods runs.
  const inWorker = await page.evaluate(() => window.demo.atlas({ methods: ['case3'], n: 3 }).then(() => null, (e) => e.message));
  assert.match(inWorker ?? '', /networks not available: could not fetch weights\/phi-equivariant\.json \(HTTP 404\)/);
  assert.equal((await page.evaluate(() => window.demo.atlas({ methods: ['numerical'], n: 3 }))).cells.length, 9);
  // The methods without networks are there, the others disabled.
  const options = await page.$$eval('#mode option', (os) => os.map((o) => [o.value, o.disabled]));
  const methods = await methodsOf(page);
  assert.deepEqual(options, methods.map((m) => [m.name, usesNetworks(m)]));
  await page.evaluate(() => window.demo.runUntil(2));
  assert.deepEqual(problems, []);
  await context.close();
});

test('the SIMD build runs where SIMD is available, the baseline build where it is not', async () => {
  // Chromium has wasm SIMD: the page picks the SIMD build.
  const page = await open('?task=1&method=case3');
  assert.equal(await page.evaluate(() => window.demo.build), 'simd');
  clean(page);
  await page.close();
  // A browser with SIMD switched off (hardened modes do that): validation
  // fails, the baseline module loads, and the page works.
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  await context.addInitScript(() => {
    const validate = WebAssembly.validate;
    // Refuse any module with a SIMD opcode (prefix 0xfd), as a browser
    // without SIMD would.
    WebAssembly.validate = (bytes) => (new Uint8Array(bytes).includes(0xfd) ? false : validate(bytes));
  });
  const requested = [];
  const p2 = await context.newPage();
  const problems = [];
  p2.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  p2.on('pageerror', (e) => problems.push(e.message));
  p2.on('request', (r) => r.url().endsWith('.wasm') && requested.push(r.url().split('/').pop()));
  await p2.goto(BASE + '?task=1&method=case3');
  await p2.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  assert.equal(await p2.evaluate(() => window.demo.build), 'baseline');
  assert.deepEqual(requested, ['redundant_ik_bg.wasm'], 'the SIMD module is not even fetched');
  const s = await p2.evaluate(() => window.demo.runUntil(10));
  assert.equal(s.collided, false);
  assert.ok(s.final_error < 5e-3);
  // The workers load the baseline build of their module too.
  const r = await p2.evaluate(() => window.demo.bench({ batchMs: 2 }));
  assert.ok(r.step_ns.case3 > 0);
  const a = await p2.evaluate(() => window.demo.atlas({ n: 5, methods: ['case3'] }));
  assert.equal(a.cells.length, 25);
  assert.deepEqual(requested, ['redundant_ik_bg.wasm', 'redundant_ik_worker_bg.wasm', 'redundant_ik_worker_bg.wasm']);
  assert.deepEqual(problems, []);
  await context.close();
  // If the SIMD module fails to start anyway, the baseline takes over.
  const c3 = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const p3 = await c3.newPage();
  const errors = [];
  p3.on('pageerror', (e) => errors.push(e.message));
  await p3.route('**/redundant_ik_simd_bg.wasm', (route) =>
    route.fulfill({ status: 200, contentType: 'application/wasm', body: Buffer.from('not wasm') }),
  );
  await p3.goto(BASE + '?task=1&method=numerical');
  await p3.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  assert.equal(await p3.evaluate(() => window.demo.build), 'baseline');
  assert.deepEqual(errors, []);
  await c3.close();
});

test('names and colours come from the module: the method menu, and legend swatches that match the drawing', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  // The menu is built from the module's methods(): none is written in the page.
  const options = await page.$$eval('#mode option', (os) => os.map((o) => [o.value, o.textContent]));
  const methods = await methodsOf(page);
  assert.deepEqual(options, methods.map((m) => [m.name, `${m.label}: ${m.description}`]));
  assert.deepEqual(options.slice(0, 5).map((o) => o[0]), ['none', 'numerical', 'case1', 'case2', 'case3'], "the paper's order");
  assert.match(options[2][1], /^Case 1: /);
  // So are the method explanations and the limits quoted in the prose.
  const prose = await page.evaluate(() => ({
    explained: [...document.querySelectorAll('#modes-explained dt:not(.group)')].map((dt) => dt.textContent),
    groups: [...document.querySelectorAll('#modes-explained dt.group')].map((dt) => dt.textContent),
    limits: Object.fromEntries([...document.querySelectorAll('[data-limit]')].map((e) => [e.dataset.limit, e.textContent])),
  }));
  assert.deepEqual(prose.explained, methods.map((m) => m.label));
  assert.deepEqual(prose.groups, ['The paper', 'Beyond the paper']);
  assert.deepEqual(prose.limits, { min_links: '2', max_links: '6', max_obstacles: '8', reach_tolerance: '5', drift_gain: '1', default_radius: '0.05' });
  // Each legend swatch has the colour the renderer draws its element with,
  // read back from the canvas where that element is.
  const probe = await page.evaluate(() => {
    const swatch = (key) => {
      const el = document.querySelector(`#legend li[data-key="${key}"] .key`);
      const cs = getComputedStyle(el);
      return key === 'obstacle' ? cs.backgroundColor : cs.borderTopColor;
    };
    const canvas = document.getElementById('stage');
    const dpr = canvas.width / canvas.getBoundingClientRect().width;
    const ctx = canvas.getContext('2d');
    const pixel = ([x, y]) => {
      const [cx, cy] = window.demo.controller.demo.worldToCanvas(x, y);
      return [...ctx.getImageData(Math.round(cx * dpr), Math.round(cy * dpr), 1, 1).data];
    };
    const s = window.demo.state();
    const [a, b] = [s.joints[1], s.joints[2]];
    const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    const o = s.obstacle;
    // Inside the disc, off its centre dot and off the grid lines through it.
    const inside = [o[0] + 0.55 * s.radius, o[1] + 0.3 * s.radius];
    return {
      keys: [...document.querySelectorAll('#legend li')].map((li) => li.dataset.key),
      arm: { swatch: swatch('arm'), pixel: pixel(mid) },
      obstacle: { swatch: swatch('obstacle'), pixel: pixel(inside) },
      ghost: swatch('ghost'),
      strobe: swatch('strobe'),
      cssArm: getComputedStyle(document.documentElement).getPropertyValue('--arm').trim(),
    };
  });
  assert.deepEqual(probe.keys, ['arm', 'strobe', 'ghost', 'path', 'trail', 'reference', 'target', 'obstacle', 'region', 'dampers', 'floor', 'atlas', 'limits', 'ellipse', 'force']);
  const rgba = (css) => {
    const m = css.match(/rgba?\(([^)]+)\)/);
    const v = m[1].split(',').map(Number);
    return [v[0], v[1], v[2], v.length > 3 ? v[3] : 1];
  };
  const close = (x, y, tol, what) =>
    assert.ok(x.every((v, i) => Math.abs(v - y[i]) <= tol), `${what}: ${x} vs ${y}`);
  // The arm is opaque: the pixel is the swatch.
  const arm = rgba(probe.arm.swatch);
  close(probe.arm.pixel.slice(0, 3), arm.slice(0, 3), 2, 'arm pixel against its swatch');
  // The obstacle disc is translucent over white: blend the swatch likewise.
  const ob = rgba(probe.obstacle.swatch);
  const blended = ob.slice(0, 3).map((c) => c * ob[3] + 255 * (1 - ob[3]));
  close(probe.obstacle.pixel.slice(0, 3), blended, 3, 'obstacle pixel against its swatch');
  // The page's CSS custom properties are the module's palette.
  assert.equal(probe.cssArm, '#1d4e89');
  assert.ok(rgba(probe.ghost)[3] < 1 && rgba(probe.strobe)[3] < 0.5, 'translucent swatches for translucent strokes');
  clean(page);
  await page.close();
});

test('embed page: two independent demos', async () => {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const problems = [];
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(BASE + 'embed.html');
  await page.waitForSelector('#left[data-ready="true"]', { timeout: 15000 });
  await page.waitForSelector('#right[data-ready="true"]', { timeout: 15000 });
  const run = (id) =>
    page.evaluate((id) => {
      const c = document.getElementById(id).controller;
      return c.runUntil(10);
    }, id);
  const left = await run('left');
  const right = await run('right');
  assert.equal(left.method, 'none');
  assert.equal(right.method, 'numerical');
  assert.equal(left.collided, true, 'left (no avoidance) collides');
  assert.equal(right.collided, false, 'right (numerical) does not');
  // Changing one leaves the other alone.
  await page.locator('#left').locator('#mode').selectOption('numerical');
  const l2 = await page.evaluate(() => document.getElementById('left').controller.state());
  const r2 = await page.evaluate(() => document.getElementById('right').controller.state());
  assert.equal(l2.method, 'numerical');
  assert.equal(r2.t, right.t);
  // (The left run had ended: the new method replays it, from t = 0.)
  await page.locator('#right').locator('#reset').click();
  const l3 = await page.evaluate(() => document.getElementById('left').controller.state());
  assert.ok(l3.t >= l2.t && l3.method === 'numerical', 'reset of one demo leaves the other');
  await page.screenshot({ path: join(shots, 'embed.png'), fullPage: true });
  // The attribute's older name, mode, is still read.
  await page.evaluate(() => document.body.insertAdjacentHTML('beforeend', '<redundant-ik-demo id="old" task="2" mode="qp"></redundant-ik-demo>'));
  await page.waitForSelector('#old[data-ready="true"]', { timeout: 15000 });
  assert.equal(await page.evaluate(() => document.getElementById('old').controller.state().method), 'qp');
  assert.deepEqual(problems, []);
  await context.close();
});
