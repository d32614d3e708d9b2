// End-to-end tests of the paths beyond the line (issue 25, item 4): a
// circle from the address, a polyline drawn on the stage with the mouse,
// and a bad path typed or in the address, refused with a message.
// Registered by e2e.mjs (E2E_ONLY=path: runs only these).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { shots, test, open, clean, state, near, pause } from './harness.mjs';

const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]);

test('path: the address ?path=circle:1.2,0.8 loads, runs the circle and closes it', async () => {
  const page = await open('?task=1&method=numerical&feedback=1&path=circle:1.2,0.8');
  await pause(page);
  await page.click('#reset');
  const s0 = await state(page);
  assert.equal(s0.path, 'circle:1.2,0.8');
  assert.equal(await page.inputValue('#path'), 'circle:1.2,0.8', 'the field shows the path');
  const r = dist(s0.ee, [1.2, 0.8]);
  assert.ok(Math.abs(r - 0.416) < 1e-3, `radius ${r}`);
  // Half way the hand is across the circle; at the end back at its start.
  const half = await page.evaluate(() => window.demo.runUntil(5));
  assert.ok(Math.abs(dist(half.reference, [1.2, 0.8]) - r) < 1e-9, 'the reference is on the circle');
  assert.ok(Math.abs(dist(half.ee, s0.ee) - 2 * r) < 1e-3, 'half way: across the circle');
  const s = await page.evaluate(() => window.demo.runUntil(10));
  assert.ok(Math.abs(s.t - 10) < 1e-9, `ran to the end (t = ${s.t})`);
  assert.ok(s.final_error < 1e-3, `back at the start (${s.final_error} m)`);
  assert.ok(dist(s.ee, s0.ee) < 1e-3, 'the hand is back at its start');
  // The target is the line's: neither drawn nor in the legend; the note
  // speaks of the path's end.
  await page.evaluate(() => window.demo.controller.demo.draw());
  await page.waitForTimeout(100);
  assert.doesNotMatch(await page.innerText('#legend'), /target/);
  assert.match(await page.textContent('#run-note'), /path's end/);
  await page.screenshot({ path: join(shots, 'path-circle.png') });
  clean(page);
  await page.close();
});

test('path: a path drawn with the mouse runs and ends near its last point', async () => {
  const page = await open('?task=1&method=numerical&feedback=1');
  await pause(page);
  const s0 = await state(page);
  assert.equal(s0.path, null, 'the line, at first');
  await page.click('#draw-path');
  assert.equal(await page.getAttribute('#draw-path', 'aria-pressed'), 'true');
  const world = [s0.ee, [1.4, 0.8], [1.3, 0.6], [1.1, 0.55], [1.0, 0.7]];
  const px = [];
  for (const w of world) px.push(await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), w));
  await page.mouse.move(px[0].x, px[0].y);
  await page.mouse.down();
  for (let i = 1; i < px.length; i++) await page.mouse.move(px[i].x, px[i].y, { steps: 15 });
  await page.mouse.up();
  const s1 = await state(page);
  assert.ok(s1.path && s1.path.startsWith('points:'), `a points: path (${s1.path})`);
  assert.equal(await page.inputValue('#path'), s1.path, 'the field shows the drawn path');
  assert.equal(await page.getAttribute('#draw-path', 'aria-pressed'), 'false', 'drawing ends with the stroke');
  assert.ok(near(s1.target, s0.target, 1e-12), 'the stroke did not drag the target');
  // Points at least 5 cm apart (the module thinned the stroke).
  const points = s1.path.slice('points:'.length).split(';').map((p) => p.split(',').map(Number));
  assert.ok(points.length >= 4 && points.length <= 64, `${points.length} points`);
  for (let i = 1; i < points.length - 1; i++) assert.ok(dist(points[i - 1], points[i]) >= 0.05 - 1e-9);
  const last = points[points.length - 1];
  assert.ok(near(last, world[world.length - 1], 0.01), `the path ends where the stroke did (${last})`);
  const end = await page.evaluate(() => window.demo.runUntil(window.demo.state().tf));
  assert.ok(near(end.ee, last, 5e-3), `the hand ends at the last point (${end.ee} vs ${last})`);
  assert.ok(end.final_error < 5e-3, `final error ${end.final_error}`);
  assert.ok(new URL(page.url()).searchParams.get('path') === s1.path, 'the address carries path=');
  await page.screenshot({ path: join(shots, 'path-drawn.png') });
  // Escape cancels drawing: the next drag moves the target again.
  await page.click('#draw-path');
  await page.keyboard.press('Escape');
  assert.equal(await page.getAttribute('#draw-path', 'aria-pressed'), 'false', 'Escape cancels');
  clean(page);
  await page.close();
});

test('path: a bad path typed shows an error and loses nothing; a hostile path= is reported', async () => {
  const page = await open('?task=1&method=numerical&path=circle:1.2,0.8');
  await page.evaluate(() => window.demo.runUntil(4));
  await pause(page);
  const before = await state(page);
  for (const bad of ['circle:NaN,1', 'spiral:1,2', 'points:', 'circle:1.2,0.8,0.5']) {
    await page.fill('#path', bad);
    await page.press('#path', 'Enter');
    const text = await page.textContent('#message');
    assert.ok(await page.isVisible('#message'), `a message for ${bad}`);
    assert.match(text, /path/, `the message names the path: ${text}`);
    const after = await state(page);
    assert.equal(after.path, before.path, 'the path stays');
    assert.equal(after.t, before.t, 'the run stays where it was');
    assert.deepEqual(after.theta, before.theta);
    assert.deepEqual(after.obstacles, before.obstacles);
    assert.equal(await page.inputValue('#path'), bad, 'the text typed stays to be corrected');
  }
  // The centre at the hand's start: the core's refusal (radius 0).
  await page.click('#reset');
  const start = (await state(page)).ee;
  await page.fill('#path', `circle:${start[0]},${start[1]}`);
  await page.press('#path', 'Enter');
  assert.match(await page.textContent('#message'), /radius 0/);
  // A good one then applies.
  await page.fill('#path', 'points:1.2,0.4');
  await page.press('#path', 'Enter');
  assert.equal((await state(page)).path, 'points:1.2,0.4');
  clean(page);
  await page.close();

  const hostile = await open(`?task=1&path=${encodeURIComponent('points:1e999,0;' + 'x'.repeat(5000))}`);
  const s = await state(hostile);
  assert.equal(s.path, null, 'the line instead');
  const note = await hostile.textContent('#message');
  assert.match(note, /Ignored in the address: path: /, note);
  clean(hostile);
  await hostile.close();
});
