// End-to-end tests of the atlas: in its worker, the panel and its layer, the 41 x 41 timing.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { here, shots, test, open, clean, state, near, pause, countFrames, methodsOf, usesNetworks } from './harness.mjs';

test('atlas: computed in a worker while the page draws, equal to the module computed directly', async () => {
  const page = await open('?task=1&method=case3');
  await pause(page);
  await page.click('#atlas-panel summary');
  await countFrames(page);
  const methods = ['none', 'numerical', 'case3', 'distance', 'priority', 'qp'];
  const run = await page.evaluate(async (methods) => {
    const progress = [];
    const t0 = performance.now();
    const r = await window.demo.atlas({ methods, n: 11, onProgress: (p) => progress.push([p.done, p.total]) });
    return { r, progress, seconds: (performance.now() - t0) / 1000, frames: window.__frames };
  }, methods);
  const { r, progress } = run;
  // Progress advances row by row to the whole grid.
  assert.ok(progress.length >= 11, `${progress.length} progress messages`);
  for (let i = 1; i < progress.length; i++) assert.ok(progress[i][0] >= progress[i - 1][0], 'progress never goes back');
  assert.deepEqual(progress.at(-1), [121, 121]);
  assert.ok(run.frames > 10 * run.seconds, `only ${run.frames} frames in ${run.seconds.toFixed(2)} s: the page stalled`);
  // The JSON shape of `redundant-ik atlas --json`, on the default region.
  assert.equal(r.task, 1);
  assert.equal(r.grid.n, 11);
  assert.deepEqual(r.grid.region.map((v) => Math.round(v * 1000) / 1000), [-2.05, 2.05, 0, 2.55]);
  assert.equal(r.radius, 0.05);
  assert.deepEqual(r.methods, methods);
  assert.equal(r.cells.length, 121);
  for (const m of methods) {
    assert.ok(['success', 'collision', 'missed', 'failed', 'path_blocked', 'start_overlap'].includes(r.cells[60].outcomes[m].class));
    assert.equal(Object.values(r.summary[m].counts).reduce((a, b) => a + b, 0), 121);
  }
  // The worker's result equals the module computing the same atlas here.
  const same = await page.evaluate(async ({ methods, expected }) => {
    const m = await import('./pkg/redundant_ik_worker.js');
    const wasm = window.demo.build === 'simd' ? 'redundant_ik_worker_simd_bg.wasm' : 'redundant_ik_worker_bg.wasm';
    await m.default({ module_or_path: `./pkg/${wasm}` });
    // The workers' module carries no weights: hand it the sets, as the page's jobs do.
    const sets = await (await import('./module.js')).networkSetsFor();
    for (const [set, f] of Object.entries(sets)) m.provideBuiltinNetworks(f.phi, f.v, set);
    const job = new m.AtlasJob(window.demo.controller.demo.run(), { methods, n: 11, task: 1 });
    job.advance(1e6);
    const direct = job.finish();
    job.free();
    return JSON.stringify(direct) === JSON.stringify(expected);
  }, { methods, expected: r });
  assert.ok(same, 'the worker and the module computed directly agree');
  clean(page);
  await page.close();
});

test('atlas panel: the map under the arm, its legend, hover numbers, click to replay, cancel and bad options', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  await page.click('#atlas-panel summary');
  await page.selectOption('#atlas-n', '11');
  await page.click('#atlas-run');
  await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
  const methods = await methodsOf(page);
  assert.equal(await page.locator('#atlas-body tr').count(), methods.length, 'one row per method (all ticked)');
  assert.equal(await page.locator('#atlas-agreement li').count(), methods.filter(usesNetworks).length, 'the methods with networks against numerical');
  assert.equal(await page.inputValue('#atlas-show'), 'numerical', 'the numerical map is shown first');
  // A cell in view, away from the target and the obstacle, where the
  // numerical route succeeds: its pixel is the legend's swatch over white.
  const probe = await page.evaluate(() => {
    const key = document.querySelector('#atlas-legend li[data-key="success"] .key');
    return { swatch: getComputedStyle(key).backgroundColor };
  });
  assert.ok(probe.swatch.startsWith('rgba'), `a translucent swatch: ${probe.swatch}`);
  const result = await page.evaluate(() => window.demo.atlasResult());
  const pick = result.cells
    .map((c, k) => ({ ...c, k }))
    .find(
      (c) =>
        c.outcomes.numerical.class === 'success' &&
        c.x > -0.4 && c.x < 2.0 && c.y > 0.2 && c.y < 1.8 &&
        Math.hypot(c.x - 0.5, c.y - 0.5) > 0.2 && Math.hypot(c.x - 0.6, c.y - 0.2) > 0.2 &&
        Math.abs(c.x - Math.round(c.x * 2) / 2) > 0.05 && Math.abs(c.y - Math.round(c.y * 2) / 2) > 0.05,
    );
  assert.ok(pick, 'a successful cell in view');
  const px = await page.evaluate(([x, y]) => {
    const canvas = document.getElementById('stage');
    const dpr = canvas.width / canvas.getBoundingClientRect().width;
    const [cx, cy] = window.demo.controller.demo.worldToCanvas(x + 0.02, y + 0.02);
    return [...canvas.getContext('2d').getImageData(Math.round(cx * dpr), Math.round(cy * dpr), 1, 1).data];
  }, [pick.x, pick.y]);
  const m = probe.swatch.match(/rgba?\(([^)]+)\)/)[1].split(',').map(Number);
  const blended = m.slice(0, 3).map((c) => c * m[3] + 255 * (1 - m[3]));
  assert.ok(px.slice(0, 3).every((v, i) => Math.abs(v - blended[i]) <= 4), `cell pixel ${px} vs swatch ${blended}`);
  assert.equal(await page.locator('#atlas-legend li').count(), 6);
  // Hover: the tip names the cell and every method's outcome.
  await page.evaluate(() => window.scrollTo(0, 0));
  const at = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), [pick.x, pick.y]);
  await page.mouse.move(at.x, at.y);
  await page.waitForSelector('#atlas-tip:not([hidden])');
  const tip = await page.textContent('#atlas-tip');
  assert.match(tip, new RegExp(`obstacle at \\(${pick.x.toFixed(3)}, ${pick.y.toFixed(3)}\\)`), tip);
  assert.match(tip, /Numerical: clear, target reached, smallest link-to-obstacle clearance/, tip);
  assert.equal(await page.getAttribute('#atlas-tip', 'data-cell'), String(pick.k));
  await page.screenshot({ path: join(shots, 'atlas.png') });
  // Click: the obstacle goes to the cell and the task replays.
  await page.mouse.down();
  await page.mouse.up();
  const s = await state(page);
  assert.ok(near(s.obstacle, [pick.x, pick.y], 1e-9), `obstacle at ${s.obstacle}`);
  assert.equal(s.running, true, 'the task replays');
  assert.ok(s.t < 2, `from the start (t = ${s.t})`);
  // The address carries the cell's centre as the fields write it: no floating-point noise.
  const written = new URL(page.url()).searchParams.get('obstacle') ?? '';
  assert.match(written, /^-?\d+\.\d{3,9},-?\d+\.\d{3,9}$/, `obstacle=${written}`);
  // The same outcome as the map says, once run to the end.
  const end = await page.evaluate(() => window.demo.runUntil(10));
  assert.equal(end.collided, false);
  assert.ok(Math.abs(end.min_distance - pick.outcomes.numerical.min_distance) < 1e-9, `${end.min_distance}`);
  // Cancelling a larger atlas keeps the map shown; bad options are refused.
  const cancelled = await page.evaluate(async () => {
    const c = new AbortController();
    const p = window.demo.atlas({ n: 61, signal: c.signal, onProgress: () => c.abort() });
    const outcome = await p.then(() => 'finished', (e) => e.name);
    return { outcome, status: document.getElementById('atlas-status').textContent, n: window.demo.atlasResult().grid.n };
  });
  assert.deepEqual(cancelled, { outcome: 'AbortError', status: 'Cancelled.', n: 11 });
  for (const [options, message] of [
    [{ n: 1 }, /grid points per side/],
    [{ n: 2.5 }, /whole number/],
    [{ methods: ['fast'] }, /unknown method 'fast'/],
    [{ region: [1, 0, 0, 1] }, /empty/],
    [{ region: [0, 1] }, /four numbers/],
    [{ grid: 21 }, /unknown atlas option 'grid'/],
  ]) {
    const e = await page.evaluate((o) => window.demo.atlas(o).then(() => 'finished', (e) => e.message), options);
    assert.match(e, message, JSON.stringify(options));
  }
  assert.equal(await page.evaluate(() => window.demo.atlasResult().grid.n), 11, 'a refused atlas changes nothing');
  // A change of the task (here lambda) marks the map as stale.
  await page.evaluate(() => window.demo.controller.demo.setLambda(6));
  await page.waitForFunction(() => document.getElementById('atlas-status').dataset.stale === 'true');
  assert.match(await page.textContent('#atlas-status'), /task changed since this atlas was computed/);
  clean(page);
  await page.close();
});

test('atlas of 41 x 41 cells in every method, in Chromium', async () => {
  const page = await open('?task=1&method=numerical');
  const r = await page.evaluate(async () => {
    const t0 = performance.now();
    const a = await window.demo.atlas({});
    return {
      wall: (performance.now() - t0) / 1000,
      worker: Number(document.getElementById('atlas-status').dataset.ms) / 1000,
      cells: a.cells.length,
      methods: a.methods.length,
      rates: Object.fromEntries(a.methods.map((m) => [m, a.summary[m].success_rate])),
      build: window.demo.build,
    };
  });
  const count = (await methodsOf(page)).length;
  assert.equal(r.cells, 41 * 41);
  assert.equal(r.methods, count, 'every method ticked by default');
  const rates = Object.entries(r.rates).map(([m, v]) => `${m} ${(100 * v).toFixed(1)}%`).join(', ');
  console.log(
    `measure: atlas of Task 1, 41 x 41 cells, ${count} methods (${r.cells * r.methods} runs) in a worker (${r.build} build): ` +
      `${r.worker.toFixed(2)} s computing, ${r.wall.toFixed(2)} s with the worker's start; success ${rates}`,
  );
  clean(page);
  await page.close();
});
