// End-to-end tests of what a run is (the module's Demo.run(): scene,
// method, networks and their arithmetic): the files to take away and the
// weights download follow the network set in use, a run in f32 replays in
// f32, and the atlas and the comparison tell
// staleness by the state's revisions. Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { test, open, clean, state, pause, mouseDrag, nextFrames } from './harness.mjs';
import { cli, download, close } from './class-helpers.mjs';
import { dragCost } from './frame-cost.mjs';

test('runs: with networks=reach the run file names the reach set and the CLI replays it with them; Download weights gives the reach files', async () => {
  const page = await open('?task=1&method=case3&networks=reach&refine=2&feedback=1');
  await page.waitForFunction(() => window.demo.state().network_set === 'reach');
  await page.selectOption('#speed', '8');
  await page.click('#task1');
  await page.waitForFunction(() => window.demo.state().ended && !window.demo.state().running, null, { timeout: 60000 });
  const s = await state(page);
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.deepEqual(run.networks, { set: 'reach' }, 'the file names the set in use');
  assert.equal(run.scene.params.refine, 2);
  s.theta.forEach((v, i) => close(run.steps.at(-1).theta[i], v, 1e-12, `theta${i + 1}: the file's run is the drawing's`));
  // The command line replays it with the reach networks, as it ran.
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.deepEqual(back.networks, { set: 'reach' });
  back.steps.forEach((st, k) => st.theta.forEach((v, i) => close(v, run.steps[k].theta[i], 1e-9, `step ${k} theta${i + 1}`)));
  // With the paper's networks it would be another run: the files differ.
  const paper = JSON.parse(cli(['simulate', '--method', 'case3', '--refine', '2', '--feedback', '1', '--json']));
  assert.notEqual(paper.summary.final_error, run.summary.final_error);
  // The weights download gives the set in use.
  await page.click('#train-panel summary');
  const got = [];
  page.on('download', (d) => got.push(d));
  await page.click('#train-download');
  await page.waitForFunction(() => /as shipped/.test(document.getElementById('message').textContent));
  for (let k = 0; k < 50 && got.length < 2; k++) await page.waitForTimeout(100);
  assert.deepEqual(got.map((d) => d.suggestedFilename()).sort(), ['phi-reach.json', 'v-reach.json']);
  assert.match(await page.textContent('#message'), /whole/i, 'the message names the set');
  clean(page);
  await page.close();
});

test('runs: with precision=f32 the networks compute in f32: the selector and the address say so, the run file names it and the CLI replays it in f32', async () => {
  const page = await open('?task=1&method=case3&precision=f32');
  await page.waitForFunction(() => window.demo.state().precision === 'f32');
  assert.equal(await page.isVisible('#precision'), true, 'the Arithmetic selector shows with a learned method');
  assert.equal(await page.inputValue('#precision'), 'f32');
  await page.selectOption('#speed', '8');
  await page.click('#task1');
  await page.waitForFunction(() => window.demo.state().ended && !window.demo.state().running, null, { timeout: 60000 });
  assert.match(page.url(), /precision=f32/);
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.equal(run.precision, 'f32', 'the file names the arithmetic');
  // The f32 kernels give the same bits in the page's SIMD build and natively: the replay is the run.
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.equal(back.precision, 'f32');
  back.steps.forEach((st, k) => st.theta.forEach((v, i) => close(v, run.steps[k].theta[i], 1e-9, `step ${k} theta${i + 1}`)));
  // In f64 it is another run, within 1e-5 m at the end.
  const f64 = JSON.parse(cli(['simulate', '--method', 'case3', '--json']));
  assert.equal(f64.precision, undefined);
  assert.notEqual(f64.summary.final_error, run.summary.final_error);
  close(f64.summary.final_error, run.summary.final_error, 1e-5, 'final error, f64 against f32');
  // Back to f64 with the selector: the state, the address and the next file follow.
  await page.selectOption('#precision', 'f64');
  await page.waitForFunction(() => window.demo.state().precision === 'f64');
  assert.doesNotMatch(page.url(), /precision=/);
  assert.equal(JSON.parse((await download(page, '#save-run-json')).text).precision, undefined, 'an f64 run file leaves it out');
  // A method without networks has no arithmetic to choose.
  await page.selectOption('#mode', 'numerical');
  await nextFrames(page);
  assert.equal(await page.isVisible('#precision'), false);
  clean(page);
  await page.close();
});

test('runs: moving a second obstacle marks the atlas and the comparison stale; choosing a cell (the first obstacle) leaves the atlas current', async () => {
  const page = await open('?task=1&method=numerical&obstacles=0.5,0.5,0.05;1.0,1.3,0.05');
  await pause(page);
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
  await page.evaluate(() => window.demo.atlas({ n: 5, methods: ['numerical'] }));
  await page.click('#compare');
  const stale = () =>
    page.evaluate(() => ({
      atlas: document.getElementById('atlas-status').dataset.stale,
      compare: document.getElementById('compare-table').dataset.stale,
    }));
  await page.waitForTimeout(100);
  assert.deepEqual(await stale(), { atlas: 'false', compare: 'false' });
  const r0 = (await state(page)).revision;
  // The first obstacle is what the atlas moves over its grid.
  await mouseDrag(page, [0.5, 0.5], [0.55, 0.45]);
  await page.waitForTimeout(100);
  const r1 = (await state(page)).revision;
  assert.equal(r1.atlas, r0.atlas, 'the atlas does not depend on the first obstacle');
  assert.ok(r1.scene > r0.scene && r1.run > r0.run);
  assert.deepEqual(await stale(), { atlas: 'false', compare: 'true' });
  // The second obstacle: every cell changed.
  await mouseDrag(page, [1.0, 1.3], [1.1, 1.2]);
  await page.waitForTimeout(100);
  assert.ok((await state(page)).revision.atlas > r1.atlas);
  assert.deepEqual(await stale(), { atlas: 'true', compare: 'true' });
  // The method is not a result's input for either.
  await page.evaluate(() => window.demo.atlas({ n: 5, methods: ['numerical'] }));
  await page.click('#compare');
  await page.selectOption('#mode', 'qp');
  await page.waitForTimeout(100);
  assert.deepEqual(await stale(), { atlas: 'false', compare: 'false' });
  clean(page);
  await page.close();
});

test('page actions: a drag costs at most two calls into the module per frame and rebuilds no list; a radius typed changes that obstacle alone', async () => {
  const page = await open('?task=1&method=numerical&obstacles=0.5,0.5,0.05;1.0,1.3,0.05');
  await pause(page);
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
  const items = () => page.$$('#obstacle-list li');
  const before = await items();
  const cost = await dragCost(page, { from: [1.0, 1.3], seconds: 2 });
  console.log(`measure: dragging an obstacle: ${cost.callsPerFrame.toFixed(2)} calls into the module per frame (${JSON.stringify(cost.calls)}), ${(cost.heapBytesPerFrame / 1024).toFixed(1)} KB of JS heap per frame, ${cost.frames} frames`);
  assert.ok(cost.frames > 30, `${cost.frames} frames drawn`);
  assert.ok(cost.callsPerFrame <= 2, `${cost.callsPerFrame} calls per frame: ${JSON.stringify(cost.calls)}`);
  const after = await items();
  assert.equal(after.length, 2);
  for (let i = 0; i < 2; i++) assert.ok(await page.evaluate(([a, b]) => a === b, [before[i], after[i]]), `entry ${i + 1} kept, not rebuilt`);
  const moved = (await state(page)).obstacles[1].centre;
  const fields = await after[1].$$eval('input', (inputs) => inputs.slice(0, 2).map((i) => Number(i.value)));
  assert.deepEqual(fields, moved.map((v) => Number(v.toFixed(3))), 'its fields follow the drag');
  // The second obstacle's radius, typed: that one changes, in the module.
  await page.fill('#obstacle-list li[data-index="1"] input[aria-label^="Radius"]', '0.12');
  await page.press('#obstacle-list li[data-index="1"] input[aria-label^="Radius"]', 'Enter');
  await page.waitForFunction(() => window.demo.state().obstacles[1].radius === 0.12);
  const s = await state(page);
  assert.deepEqual(s.obstacles.map((o) => o.radius), [0.05, 0.12]);
  assert.deepEqual(s.obstacles[1].centre, moved, 'its centre stays');
  // Out of bounds: refused next to the field, nothing changed.
  await page.fill('#obstacle-list li[data-index="0"] input[aria-label^="Radius"]', '-1');
  await page.press('#obstacle-list li[data-index="0"] input[aria-label^="Radius"]', 'Enter');
  assert.equal((await state(page)).obstacles[0].radius, 0.05);
  clean(page);
  await page.close();
});

test('controls a method does not read are hidden: the network-set selector for a method without networks, the gain λ for one that reads none', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  assert.equal(await page.isVisible('#network-set'), false, 'no networks, no selector');
  assert.equal(await page.isVisible('#lambda'), true, 'the numerical route reads λ');
  await page.selectOption('#mode', 'priority');
  await page.waitForFunction(() => window.demo.state().method === 'priority');
  await page.waitForTimeout(100);
  assert.equal(await page.isVisible('#lambda'), false, 'task priority reads no λ');
  await page.selectOption('#mode', 'case3');
  await page.waitForFunction(() => window.demo.state().method === 'case3');
  await page.waitForTimeout(100);
  assert.equal(await page.isVisible('#network-set'), true, 'Case 3 runs networks: the selector shows');
  clean(page);
  await page.close();
});
