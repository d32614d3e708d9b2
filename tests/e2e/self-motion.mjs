// End-to-end tests of self-motion: an elbow dragged on the stage (mouse and
// touch) and the slider (keyboard) move the arm in its null space while the
// hand holds still. Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { test, open, clean, state, near, pause, mouseDrag, touchDrag, shots } from './harness.mjs';

test('an elbow dragged with the mouse moves the arm and not the hand', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  const before = await state(page);
  const elbow = before.joints[1];
  const to = [elbow[0] + 0.25, elbow[1] + 0.1];
  await mouseDrag(page, elbow, to, 16);
  const after = await state(page);
  assert.ok(Math.hypot(after.ee[0] - before.ee[0], after.ee[1] - before.ee[1]) < 1e-4, `the hand moved: ${before.ee} -> ${after.ee}`);
  const moved = after.theta.reduce((a, t, i) => Math.max(a, Math.abs(t - before.theta[i])), 0);
  assert.ok(moved > 0.05, `the arm moved by ${moved} rad`);
  assert.ok(near(after.joints[1], to, Math.hypot(to[0] - elbow[0], to[1] - elbow[1])), 'the elbow went toward the pointer');
  assert.equal(after.t, 0);
  assert.equal(after.running, false);
  // The run starts from the new pose.
  await page.evaluate(() => window.demo.runUntil(10));
  const end = await state(page);
  assert.ok(near(end.ee, end.target, 5e-3), `the run from the new start reaches the target: ${end.ee}`);
  await page.screenshot({ path: join(shots, 'self-motion.png') });
  clean(page);
  await page.close();
});

test('an elbow dragged with a finger does the same', async () => {
  const page = await open('?task=2&method=qp', { hasTouch: true, isMobile: true, viewport: { width: 390, height: 844 } });
  await pause(page);
  const before = await state(page);
  const elbow = before.joints[2];
  await touchDrag(page, elbow, [elbow[0] - 0.2, elbow[1] + 0.15]);
  const after = await state(page);
  assert.ok(Math.hypot(after.ee[0] - before.ee[0], after.ee[1] - before.ee[1]) < 1e-4, 'the hand held');
  assert.notDeepEqual(after.theta, before.theta);
  clean(page);
  await page.close();
});

test('the self-motion slider moves the arm from the keyboard, the hand holding still', async () => {
  const page = await open('?task=1&method=numerical');
  await pause(page);
  const before = await state(page);
  await page.focus('#self-motion');
  for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
  const after = await state(page);
  assert.ok(Math.hypot(after.ee[0] - before.ee[0], after.ee[1] - before.ee[1]) < 1e-4, 'the hand held');
  assert.ok(after.theta[1] > before.theta[1], `joint 2 went up: ${before.theta[1]} -> ${after.theta[1]}`);
  assert.equal(await page.inputValue('#self-motion'), '0', 'the slider comes back to the middle');
  clean(page);
  await page.close();
});
