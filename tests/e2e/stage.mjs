// End-to-end tests of the stage: loading, the clock, dragging the target and the obstacle with mouse, keys and touch.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { shots, test, open, clean, state, near, pause, mouseDrag, touchDrag, selectMethod, textMatching } from './harness.mjs';

test('page loads, draws and exposes window.demo', async () => {
  const page = await open();
  const s = await state(page);
  for (const key of ['t', 'method', 'theta', 'ee', 'target', 'obstacle', 'radius', 'distance', 'min_distance', 'collided', 'running', 'solver_ms']) {
    assert.ok(key in s, `state() has ${key}`);
  }
  assert.equal(s.theta.length, 3);
  assert.ok(await page.isHidden('#loading'), 'loading indicator hidden');
  // The canvas has been drawn on: not a blank white backing store.
  const inked = await page.evaluate(() => {
    const c = document.getElementById('stage');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4 * 31) if (d[i] < 200) n++;
    return n;
  });
  assert.ok(inked > 50, `stage has drawing (${inked} dark samples)`);
  await page.evaluate(() => window.demo.runUntil(10));
  await page.screenshot({ path: join(shots, 'index.png'), fullPage: true });
  clean(page);
  await page.close();
});

test('play runs the clock; space pauses; r resets', async () => {
  const page = await open('?task=1&method=numerical');
  await page.waitForFunction(() => window.demo.state().t > 0.3);
  await page.keyboard.press('Space');
  const paused = await state(page);
  assert.equal(paused.running, false);
  await page.waitForTimeout(200);
  assert.equal((await state(page)).t, paused.t, 'clock stopped');
  await page.click('#play');
  await page.waitForFunction((t) => window.demo.state().t > t + 0.2, paused.t);
  assert.equal((await state(page)).running, true);
  await page.keyboard.press('r');
  const reset = await state(page);
  assert.equal(reset.t, 0);
  assert.equal(reset.running, false);
  await page.click('#step');
  assert.ok(Math.abs((await state(page)).t - 0.1) < 1e-9, 'one step of 0.1 s');
  clean(page);
  await page.close();
});

test('drag the target with the mouse: new line, the arm follows', async () => {
  const page = await open('?task=1&method=numerical');
  await page.evaluate(() => window.demo.runUntil(3));
  await pause(page);
  const before = await state(page);
  const goal = [1.1, 0.5];
  await mouseDrag(page, before.target, goal);
  const after = await state(page);
  assert.ok(near(after.target, goal, 0.02), `target moved to ${after.target}`);
  assert.ok(near(after.line.start, before.ee, 1e-9), 'new line starts at the end effector');
  assert.equal(after.line.t0, 0, 'a new run: its line starts at t = 0');
  assert.deepEqual(after.theta0, before.theta, 'from the pose at the drop');
  assert.equal(after.running, true, 'releasing the target starts the clock');
  assert.ok(Math.abs(after.tf - after.line.duration) < 1e-9, 'the run ends with its line');
  await page.evaluate((t) => window.demo.runUntil(t), after.t + after.line.duration + 0.5);
  const end = await state(page);
  assert.ok(near(end.ee, goal, 0.02), `end effector reached the new target (${end.ee})`);
  await page.screenshot({ path: join(shots, 'drag-target.png') });
  clean(page);
  await page.close();
});

test('a target out of reach: damping switches on, the arm stretches, nothing breaks; with damping on, the note says so too', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  await page.click('label[for="damping"]');
  assert.equal((await state(page)).damping, false);
  const before = await state(page);
  const goal = [2.0, 1.6]; // 2.4 m from the post top; the reach is 2.05 m
  await mouseDrag(page, before.target, goal);
  await page.evaluate(() => window.demo.runUntil(window.demo.state().t + 15));
  const s = await state(page);
  assert.equal(s.auto_damping, true, 'the planner switched damping on');
  assert.equal(s.damping, true);
  assert.equal(await page.isChecked('#damping'), true, 'the switch shows it');
  await textMatching(page, '#message', /out of reach/);
  assert.ok(s.theta.every(Number.isFinite), `finite joint angles ${s.theta}`);
  const reach = Math.hypot(s.ee[0], s.ee[1] - 0.5);
  assert.ok(reach > 2.0, `the arm stretches towards the target (${reach.toFixed(3)} m from the post top)`);
  clean(page);
  await page.close();
  // With the damping on already (the page's default), the note says it too (issue 27).
  const on = await open('?task=1&method=numerical');
  await pause(on);
  assert.equal((await state(on)).damping, true);
  await mouseDrag(on, (await state(on)).target, goal);
  const t = await state(on);
  assert.equal(t.out_of_reach, true);
  assert.equal(t.auto_damping, false, 'nothing to switch on');
  await textMatching(on, '#message', /out of reach: the hand stops as close as it can/);
  clean(on);
  await on.close();
});

test('keyboard on the drawing: n selects the target, each obstacle, each elbow; arrows move it (Shift: 5 mm); a adds an obstacle, Delete removes it; Escape leaves placing', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  const before = await state(page);
  await page.focus('#stage');
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowUp');
  let s = await state(page);
  assert.equal(s.selected, 'target');
  assert.ok(near(s.target, [before.target[0] + 0.05, before.target[1] + 0.05], 1e-9), `target ${s.target}`);
  assert.equal(s.running, true, 'a keyboard move starts the clock like a drag');
  assert.match(decodeURIComponent(page.url()), /target=0\.650,0\.250/);
  await pause(page);
  // n: the obstacle; Shift+arrows move it 5 mm.
  await page.keyboard.press('n');
  s = await state(page);
  assert.deepEqual([s.selected, s.selected_index], ['obstacle', 0]);
  await page.keyboard.press('Shift+ArrowLeft');
  assert.ok(near((await state(page)).obstacle, [before.obstacle[0] - 0.005, before.obstacle[1]], 1e-9));
  // n again: the first elbow; an arrow moves the arm, the hand holding still.
  await page.keyboard.press('n');
  s = await state(page);
  assert.deepEqual([s.selected, s.selected_index], ['joint', 1]);
  const hand = s.ee;
  await page.keyboard.press('ArrowLeft');
  const t = await state(page);
  const arc = Math.hypot(...t.theta.map((v, i) => v - s.theta[i]));
  assert.ok(Math.abs(arc - 0.1) < 0.02, `the arm moved 0.1 rad along its self-motion: ${arc}`);
  assert.ok(near(t.ee, hand, 1e-6), `the hand held: ${t.ee} vs ${hand}`);
  // Shift+n back to the obstacle; a adds one in the middle of the view, selected; Delete removes it.
  await page.keyboard.press('Shift+N');
  assert.equal((await state(page)).selected, 'obstacle');
  await page.keyboard.press('a');
  s = await state(page);
  assert.equal(s.obstacles.length, 2, 'added');
  assert.deepEqual([s.selected, s.selected_index], ['obstacle', 1]);
  await page.keyboard.press('Delete');
  s = await state(page);
  assert.equal(s.obstacles.length, 1, 'removed');
  assert.equal(s.selected, 'target');
  // The Add obstacle button from the keyboard adds one at once; with the mouse it waits for a click, and Escape leaves that.
  await page.click('#arm-panel summary');
  await page.focus('#obstacle-add');
  await page.keyboard.press('Enter');
  assert.equal((await state(page)).obstacles.length, 2, 'Enter on Add obstacle adds one');
  await page.click('#obstacle-add');
  assert.equal(await page.getAttribute('#obstacle-add', 'aria-pressed'), 'true', 'waiting for a click');
  await page.keyboard.press('Escape');
  assert.equal(await page.getAttribute('#obstacle-add', 'aria-pressed'), 'false', 'Escape leaves placing');
  // The live region says what the keys hold now (within its 1.5 s gap), not what they held before.
  await textMatching(page, '#announcer', /(^|; )selected: obstacle 2 at \(/);
  await page.focus('#stage');
  await page.keyboard.press('n');
  s = await state(page);
  assert.deepEqual([s.selected, s.selected_index], ['joint', 1], 'after the second obstacle, the first elbow');
  await textMatching(page, '#announcer', /(^|; )selected: elbow 1 \(the hand holds still\)($|; )/);
  await page.screenshot({ path: join(shots, 'keys-selected.png') });
  clean(page);
  await page.close();
});

test('drag the obstacle with the mouse: takes effect at once', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  const before = await state(page);
  const goal = [1.0, 1.25];
  await mouseDrag(page, before.obstacle, goal);
  const after = await state(page);
  assert.ok(near(after.obstacle, goal, 0.02), `obstacle moved to ${after.obstacle}`);
  assert.notEqual(after.distance, before.distance, 'distance follows the obstacle without a step');
  // The avoidance vector now pushes the links away from the new obstacle.
  await page.evaluate(() => window.demo.runUntil(10));
  const end = await state(page);
  assert.ok(end.min_distance > end.radius, 'no collision with the moved obstacle');
  clean(page);
  await page.close();
});

test('the obstacle cannot be dropped onto the post', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  const before = await state(page);
  await mouseDrag(page, before.obstacle, [0.0, 0.25]);
  const after = await state(page);
  assert.ok(Math.hypot(after.obstacle[0], 0) > after.radius, `obstacle stayed off the post (${after.obstacle})`);
  assert.ok(await page.isVisible('#message'), 'a message says why');
  assert.match(await page.textContent('#message'), /post/);
  await page.screenshot({ path: join(shots, 'obstacle-on-post.png') });
  clean(page);
  await page.close();
});

test('touch drag moves the target', async () => {
  const page = await open('?task=1&method=numerical', { hasTouch: true });
  await pause(page);
  const before = await state(page);
  const goal = [0.9, 0.3];
  await touchDrag(page, before.target, goal);
  const after = await state(page);
  assert.ok(near(after.target, goal, 0.03), `target moved by touch to ${after.target}`);
  clean(page);
  await page.close();
});

test("the paper's criterion with several obstacles: a note says why a far one pulls harder; the distance gradient has none", async () => {
  const page = await open('?task=1&method=numerical&obstacles=0.5,0.5,0.05;1.0,1.3,0.05');
  const note = '#criterion-note';
  await page.waitForSelector(`${note}:not([hidden])`);
  assert.match(await page.textContent(note), /an area grows with the distance, so a far obstacle pulls harder/);
  assert.equal(await page.getAttribute(`${note} a`, 'href'), '#modes-explained', 'a link to the methods');
  await selectMethod(page, 'distance');
  await page.waitForSelector(note, { state: 'hidden' });
  await selectMethod(page, 'case3');
  await page.waitForSelector(`${note}:not([hidden])`);
  const one = await open('?task=1&method=numerical');
  await pause(one);
  assert.equal(await one.isVisible(note), false, 'one obstacle: no note');
  clean(page);
  clean(one);
  await page.close();
  await one.close();
});

test('placing without dragging: the target and each obstacle have number fields, kept in step with drags', async () => {
  const page = await open('?task=1&method=numerical&obstacles=0.5,0.5,0.05;1.2,1.4,0.08');
  await pause(page);
  await page.fill('#target-x', '0.7');
  await page.fill('#target-y', '0.25');
  await page.press('#target-y', 'Enter');
  await page.waitForFunction(() => window.demo.state().target.join() === '0.7,0.25');
  // Dragged, the fields follow (to the millimetre).
  const s = await state(page);
  await mouseDrag(page, s.target, [0.9, 0.4]);
  const t = (await state(page)).target;
  assert.equal(await page.inputValue('#target-x'), String(Number(t[0].toFixed(3))));
  assert.equal(await page.inputValue('#target-y'), String(Number(t[1].toFixed(3))));
  // Obstacle 2 typed into place, then dragged: its fields follow.
  await page.click('#arm-panel summary');
  const field = (i, what) => `#obstacle-list li[data-index="${i}"] input[aria-label^="Centre ${what}"]`;
  assert.equal(await page.inputValue(field(1, 'x')), '1.2');
  await page.fill(field(1, 'x'), '1.05');
  await page.press(field(1, 'x'), 'Enter');
  await page.waitForFunction(() => window.demo.state().obstacles[1].centre[0] === 1.05);
  assert.deepEqual((await state(page)).obstacles[1].centre, [1.05, 1.4]);
  await mouseDrag(page, [0.5, 0.5], [0.45, 0.75]);
  const o = (await state(page)).obstacles[0].centre;
  assert.equal(await page.inputValue(field(0, 'y')), String(Number(o[1].toFixed(3))));
  // Each field applies on its own: x = 0 above the post is a place; y = 0.2 then puts it on the post: refused beside the field, nothing moved.
  await page.fill(field(0, 'x'), '0');
  await page.press(field(0, 'x'), 'Enter');
  await page.waitForFunction(() => window.demo.state().obstacles[0].centre[0] === 0);
  const above = (await state(page)).obstacles[0].centre;
  assert.deepEqual(above, [0, Number(o[1].toFixed(3))], "the other coordinate as its field shows it");
  await page.fill(field(0, 'y'), '0.2');
  await page.press(field(0, 'y'), 'Enter');
  assert.deepEqual((await state(page)).obstacles[0].centre, above, 'refused');
  assert.match(await page.textContent('#message'), /post/);
  clean(page);
  await page.close();
});

for (const [arm, address] of [['the planar arm', '?task=1&method=numerical'], ['the Panda', '?arm=panda&method=numerical']]) {
  test(`keys on ${arm}: Space on a focused button presses it, not play; Enter ticks a checkbox; Space on the drawing plays`, async () => {
    const page = await open(address);
    await pause(page);
    // Space on Reset: the button acts (the clock back at 0), the run stays paused.
    await page.evaluate(() => window.demo.runUntil(2));
    await page.focus('#reset');
    await page.keyboard.press('Space');
    let s = await state(page);
    assert.equal(s.running, false, 'Space on a button does not toggle the run');
    assert.equal(s.t, 0, 'it pressed Reset');
    // Enter on the Damping checkbox ticks it.
    const before = s.damping;
    await page.focus('#damping');
    await page.keyboard.press('Enter');
    s = await state(page);
    assert.equal(s.damping, !before, 'Enter changed Damping');
    // A panel's heading opens with Space, the run untouched.
    await page.focus('#atlas-panel summary');
    await page.keyboard.press('Space');
    assert.equal(await page.evaluate(() => document.getElementById('atlas-panel').open), true);
    assert.equal((await state(page)).running, false);
    // On the drawing, Space plays.
    await page.focus('#stage');
    await page.keyboard.press('Space');
    assert.equal((await state(page)).running, true, 'Space on the drawing plays');
    clean(page);
    await page.close();
  });
}

