// The 3-D view of an arm in space (three.js, www/view/three-view.js): the
// drawing is the core's (three's matrices read back against the core's
// view at a random pose of each arm), the gizmo moves the target along one
// axis by mouse and the core reports where it is drawn, and a browser
// without WebGL is told so while the run goes on. Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { test, open, clean, state, shots, nextFrames, saidSoFar, heard } from './harness.mjs';

test("3-D view: three's matrices put every link, joint and sphere where the core says, at a random pose of each arm in space", async () => {
  for (const arm of ['panda', 'iiwa14']) {
    const page = await open(`?arm=${arm}&method=numerical&autoplay=0`);
    const worst = await page.evaluate(async () => {
      const c = window.demo.controller;
      const s = c.state();
      // A random start within the limits (a fixed generator: the same pose each run).
      let seed = 7;
      const rand = () => ((seed = (seed * 16807) % 2147483647) / 2147483647);
      const theta = s.joint_limits.map(([lo, hi]) => lo + (0.1 + 0.8 * rand()) * (hi - lo));
      c.demo.setStart(Float64Array.from(theta));
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      const v = c.demo.view();
      const scene = c.view3d.three.scene;
      scene.updateMatrixWorld(true);
      const byName = (name) => {
        let found = null;
        scene.traverse((o) => {
          if (o.name === name && o.visible) found = o;
        });
        if (!found) throw new Error(`no ${name} in the drawing`);
        return found;
      };
      const apply = (m, p) => {
        const e = m.elements;
        return [0, 1, 2].map((i) => e[i] * p[0] + e[4 + i] * p[1] + e[8 + i] * p[2] + e[12 + i]);
      };
      const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      let worst = 0;
      // A link's cylinder is the unit one (along y, from -1/2 to 1/2) in three's matrix.
      v.links.forEach(([a, b], i) => {
        const m = byName(`link ${i + 1}`).matrixWorld;
        worst = Math.max(worst, dist(apply(m, [0, -0.5, 0]), a), dist(apply(m, [0, 0.5, 0]), b));
      });
      v.joints.forEach((p, i) => (worst = Math.max(worst, dist(apply(byName(`joint ${i + 1}`).matrixWorld, [0, 0, 0]), p))));
      v.spheres.forEach((p, i) => (worst = Math.max(worst, dist(apply(byName(`sphere ${i + 1}`).matrixWorld, [0, 0, 0]), p))));
      // The core's view is the pose on screen: the hand the state reports, from the start just set.
      const st = c.state();
      worst = Math.max(worst, dist(v.joints[v.joints.length - 1], st.hand));
      const start = st.theta.map((x, i) => Math.abs(x - theta[i]));
      return { worst, links: v.links.length, joints: v.joints.length, start: Math.max(...start) };
    });
    assert.ok(worst.links >= 4 && worst.joints >= 7, JSON.stringify(worst));
    assert.ok(worst.start < 1e-12, `the pose drawn is the start set: ${worst.start}`);
    assert.ok(worst.worst < 1e-6, `${arm}: the drawing is the core's to ${worst.worst} m`);
    await page.locator('#stage').screenshot({ path: join(shots, `view3d-${arm}-random.png`) });
    clean(page);
    await page.close();
  }
});

test('3-D view: the gizmo dragged along its x arrow by mouse moves the target along x only, the core reports it where it is drawn; the keys and the z field move it too', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0');
  const before = (await state(page)).target;
  const client = (p) => page.evaluate(([x, y, z]) => window.demo.worldToClient(x, y, z), p);
  const c0 = await client(before);
  const c1 = await client([before[0] + 0.1, before[1], before[2]]);
  const n = Math.hypot(c1.x - c0.x, c1.y - c0.y);
  const u = [(c1.x - c0.x) / n, (c1.y - c0.y) / n];
  // Along the x axis's image from the target, the gizmo's x arrow is under the pointer.
  let at = null;
  for (let k = 14; k < 160 && !at; k += 3) {
    await page.mouse.move(c0.x + u[0] * k, c0.y + u[1] * k);
    if ((await page.evaluate(() => window.demo.controller.view3d.gizmoAxis())) === 'X') at = [c0.x + u[0] * k, c0.y + u[1] * k];
  }
  assert.ok(at, "the gizmo's x arrow is found along the x axis's image");
  const said = await saidSoFar(page);
  await page.mouse.down();
  await page.mouse.move(at[0] + u[0] * 50, at[1] + u[1] * 50, { steps: 8 });
  await page.mouse.up();
  await nextFrames(page);
  const after = (await state(page)).target;
  assert.ok(after[0] - before[0] > 0.02, `the target moved along +x: ${before} -> ${after}`);
  assert.ok(Math.abs(after[1] - before[1]) < 1e-9 && Math.abs(after[2] - before[2]) < 1e-9, `and along x only: ${before} -> ${after}`);
  const drawn = await page.evaluate(() => window.demo.controller.view3d.three.gizmoAt());
  assert.ok(Math.hypot(...drawn.map((d, i) => d - after[i])) < 1e-3, `the gizmo is where the core has the target: ${drawn} against ${after}`);
  await heard(page, /^moved: target at x \d\.\d\d, y \d\.\d\d, z \d\.\d\d m$/, said);
  assert.match(page.url(), /target=/, 'the address keeps the moved target');
  // The arrow keys still move the selected item, and the gizmo follows.
  await page.focus('#stage');
  await page.keyboard.press('ArrowUp');
  await nextFrames(page);
  const keyed = (await state(page)).target;
  const drawnAfterKey = await page.evaluate(() => window.demo.controller.view3d.three.gizmoAt());
  assert.ok(Math.hypot(...keyed.map((d, i) => d - after[i])) > 1e-3, 'the key moved the target');
  assert.ok(Math.hypot(...drawnAfterKey.map((d, i) => d - keyed[i])) < 1e-3, 'the gizmo followed the key');
  // Without dragging: the target's z field moves it (WCAG 2.5.7), and the gizmo follows.
  await page.fill('#target-z', '0.4');
  await page.press('#target-z', 'Enter');
  await nextFrames(page);
  const typed = (await state(page)).target;
  assert.ok(Math.abs(typed[2] - 0.4) < 1e-12 && Math.abs(typed[0] - keyed[0]) <= 5e-4, `z typed (x and y kept, to the millimetre the fields show): ${typed}`);
  const drawnAfterField = await page.evaluate(() => window.demo.controller.view3d.three.gizmoAt());
  assert.ok(Math.hypot(...drawnAfterField.map((d, i) => d - typed[i])) < 1e-3, 'the gizmo followed the field');
  assert.equal(await page.inputValue('#target-x'), String(Number(typed[0].toFixed(3))), 'the x field follows the target');
  await page.locator('#stage').screenshot({ path: join(shots, 'view3d-gizmo.png') });
  clean(page);
  await page.close();
});

test('3-D view: a browser without WebGL is told so, and the run, its readouts and the overlay still work', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0', {});
  await page.close();
  const context = await page.context().browser().newContext({ viewport: { width: 1280, height: 900 } });
  await context.addInitScript(() => {
    const get = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (kind, ...rest) {
      return /webgl/.test(kind) ? null : get.call(this, kind, ...rest);
    };
  });
  const p = await context.newPage();
  const errors = [];
  p.on('pageerror', (e) => errors.push(e.message));
  await p.goto(page.url());
  await p.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  await p.waitForFunction(() => /draws no 3-D view/.test(document.body.textContent));
  assert.equal(await p.evaluate(() => document.querySelector('canvas.view-3d')), null, 'no WebGL canvas is left behind');
  await p.evaluate(() => window.demo.runUntil(2));
  assert.ok((await p.evaluate(() => window.demo.state().t)) >= 2, 'the run goes on');
  assert.deepEqual(errors, []);
  await context.close();
});
