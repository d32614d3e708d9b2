// The hand's full pose as the task of the page in space: the Hand menu,
// the gizmo's rings dragged by mouse, the keys x, y and z and the roll,
// pitch and yaw fields turn the target as the core reports it (within 1 mm
// and 0.01 rad of what is drawn), a pose run in qp to its end, and its run
// file replayed by the command line's simulate --from to 1e-9; the
// address keeps the pose task. Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test, open, clean, state, shots, nextFrames, axe, saidSoFar, heard } from './harness.mjs';
import { cli, download, close } from './class-helpers.mjs';

/** The angle (rad) between two rotations given by rows (nine numbers or three rows). */
const angle = (a, b) => {
  const [p, q] = [a.flat(), b.flat()];
  // trace(A B^T) = 1 + 2 cos(angle)
  let tr = 0;
  for (let i = 0; i < 3; i++) for (let k = 0; k < 3; k++) tr += p[3 * i + k] * q[3 * i + k];
  return Math.acos(Math.max(-1, Math.min(1, (tr - 1) / 2)));
};

test("pose: the Hand menu makes the task the hand's full pose; the gizmo's rings by mouse, the keys and the fields turn the target as the core reports it; a qp run to its end replays on the command line", async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0');
  assert.equal(await page.isVisible('#target-roll'), false, 'no orientation fields for the position task');
  let said = await saidSoFar(page);
  await page.selectOption('#hand-task', 'pose');
  await nextFrames(page);
  let s = await state(page);
  assert.equal(s.task, 'pose');
  assert.ok(s.target_rpy.every((a, i) => Math.abs(a - s.hand_rpy[i]) < 1e-9), 'the target starts turned as the hand is');
  await heard(page, /full pose/, said);
  assert.equal(await page.isVisible('#target-roll'), true);

  // The gizmo turns the target: its z ring (about world z) dragged by mouse.
  await page.click('#gizmo-turn');
  assert.equal(await page.getAttribute('#gizmo-turn', 'aria-pressed'), 'true');
  await nextFrames(page);
  assert.equal(await page.evaluate(() => window.demo.controller.view3d.three.gizmoMode()), 'rotate');
  const before = s.target_rpy;
  // Look from above so the z ring is a circle on screen; find it around the target.
  await page.evaluate(() => window.demo.controller.demo.setView(0.3, 1.2, 1.6));
  await nextFrames(page);
  const c = await page.evaluate(([x, y, z]) => window.demo.worldToClient(x, y, z), s.target);
  let at = null;
  for (let r = 20; r < 200 && !at; r += 2) {
    for (const a of [0, Math.PI / 2, Math.PI, -Math.PI / 2]) {
      await page.mouse.move(c.x + r * Math.cos(a), c.y + r * Math.sin(a));
      if ((await page.evaluate(() => window.demo.controller.view3d.gizmoAxis())) === 'Z') {
        at = [c.x + r * Math.cos(a), c.y + r * Math.sin(a), a, r];
        break;
      }
    }
  }
  assert.ok(at, "the gizmo's z ring is found around the target");
  said = await saidSoFar(page);
  await page.mouse.down();
  // Along the ring, a quarter of the way round.
  for (let k = 1; k <= 8; k++) {
    const a = at[2] + (k / 8) * 0.8;
    await page.mouse.move(c.x + at[3] * Math.cos(a), c.y + at[3] * Math.sin(a));
  }
  await page.mouse.up();
  await nextFrames(page);
  s = await state(page);
  assert.ok(Math.abs(s.target_rpy[2] - before[2]) > 0.05, `the yaw turned: ${before} -> ${s.target_rpy}`);
  const drawn = await page.evaluate(() => window.demo.controller.view3d.three.gizmoRotation());
  const core = await page.evaluate(() => window.demo.controller.demo.view().target_rotation);
  assert.ok(angle(drawn, core) < 0.01, `the gizmo is turned as the core has the target: ${angle(drawn, core)} rad`);
  const where = await page.evaluate(() => window.demo.controller.view3d.three.gizmoAt());
  assert.ok(Math.hypot(...where.map((d, i) => d - s.target[i])) < 1e-3, 'and sits on it');
  await heard(page, /turned to roll -?\d+, pitch -?\d+, yaw -?\d+ degrees/, said);
  await page.locator('#stage').screenshot({ path: join(shots, 'pose-gizmo.png') });

  // The keys: z turns the target by 15 degrees about world z.
  const keyed0 = await page.evaluate(() => window.demo.controller.demo.view().target_rotation);
  await page.focus('#stage');
  said = await saidSoFar(page);
  await page.keyboard.press('z');
  await nextFrames(page);
  const keyed1 = await page.evaluate(() => window.demo.controller.demo.view().target_rotation);
  assert.ok(Math.abs(angle(keyed0, keyed1) - Math.PI / 12) < 1e-9, `z turned by 15 degrees: ${angle(keyed0, keyed1)}`);
  await heard(page, /^target turned about z: roll/, said);

  // The fields, in degrees: the target as typed, the gizmo following.
  await page.fill('#target-roll', '180');
  await page.fill('#target-pitch', '10');
  await page.fill('#target-yaw', '-20');
  await page.press('#target-yaw', 'Enter');
  await nextFrames(page);
  s = await state(page);
  const want = [180, 10, -20].map((d) => (d * Math.PI) / 180);
  const rpy = (r) => [Math.atan2(r[2][1], r[2][2]), -Math.asin(r[2][0]), Math.atan2(r[1][0], r[0][0])];
  const got = rpy(await page.evaluate(() => window.demo.controller.demo.view().target_rotation));
  // Roll 180 and -180 are one orientation: compare rotations.
  const R = (a) => {
    const [cr, sr, cp, sp, cy, sy] = [Math.cos(a[0]), Math.sin(a[0]), Math.cos(a[1]), Math.sin(a[1]), Math.cos(a[2]), Math.sin(a[2])];
    return [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, -sp, cp * sr, cp * cr];
  };
  assert.ok(angle(R(got), R(want)) < 1e-9, `the fields set the orientation: ${got} against ${want}`);
  const gizmo = await page.evaluate(() => window.demo.controller.view3d.three.gizmoRotation());
  assert.ok(angle(gizmo, R(want)) < 0.01, 'the gizmo follows the fields');
  assert.match(page.url(), /task=pose|target=[^&]*%2C[^&]*%2C[^&]*%2C[^&]*%2C[^&]*%2C/, 'the address keeps the pose');

  // A pose run in qp to its end: it reaches the pose; the command line replays its file to 1e-9.
  await page.fill('#target-roll', String((s.hand_rpy[0] * 180) / Math.PI + 20));
  await page.press('#target-roll', 'Enter');
  await nextFrames(page);
  await page.evaluate(() => window.demo.controller.runUntil(1e9));
  s = await state(page);
  assert.ok(s.ended && s.summary.final_error < 5e-3 && s.summary.final_orientation_error < 5e-3, JSON.stringify(s.summary));
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.equal(run.scene.target.length, 6, 'the run file is the pose run');
  assert.deepEqual(run.robot, { name: 'panda' }, 'of the shipped Panda, as simulate --arm panda --json records it');
  s.theta.forEach((v, i) => close(run.steps.at(-1).theta[i], v, 1e-12, `theta${i + 1}: the file's run is the drawing's`));
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.equal(back.steps.length, run.steps.length);
  back.steps.forEach((st, k) => st.theta.forEach((v, i) => close(v, run.steps[k].theta[i], 1e-9, `step ${k} theta${i + 1}`)));
  // The pose run's figure and plots, drawn in a worker as `figure --from FILE` draws them.
  const figure = await download(page, '#save-figure-svg');
  const rad = run.summary.final_orientation_error.toExponential(1).replace(/e\+?/, 'e');
  assert.ok(figure.text.includes(`QP with dampers, the hand&apos;s pose:`) || figure.text.includes("QP with dampers, the hand's pose:"), 'the figure says the task');
  assert.ok(figure.text.includes(`, ${rad} rad`), `the orientation's final error ${rad} rad in the title`);
  const drawnFigure = `${json.path}.figure.svg`;
  cli(['figure', '--from', json.path, '--every', '5', '--out', drawnFigure]);
  // The command line runs the file's scene again (to 1e-9 of the page's run): the same drawing.
  const texts = (svg) => svg.match(/<text[^>]*>[^<]*</g).length;
  const title = (svg) => /<text[^>]*>\s*([^<]*the hand[^<]*)</.exec(svg)?.[1].trim();
  assert.equal(title(readFileSync(drawnFigure, 'utf8')), title(figure.text), "the command line's title");
  assert.equal(texts(readFileSync(drawnFigure, 'utf8')), texts(figure.text), "the command line's labels");
  const plots = await download(page, '#save-plots-svg');
  assert.match(plots.text, /QP with dampers over time \(the hand(&apos;|')s pose\)/);
  assert.match(plots.text, /orientation \(rad\)/);
  const drawnPlots = `${json.path}.plots.svg`;
  cli(['figure', '--from', json.path, '--plots', '--out', drawnPlots]);
  assert.equal(texts(readFileSync(drawnPlots, 'utf8')), texts(plots.text), "the command line's labels");

  // Hostile calls: each throws the core's reason, and the scene is kept.
  const kept = await page.evaluate(() => window.demo.controller.demo.view().target_rotation);
  const thrown = await page.evaluate(() => {
    const d = window.demo.controller.demo;
    const calls = [
      () => d.setTargetRotation(Float64Array.of(1, 2)),
      () => d.setTargetRotation(new Float64Array(9).fill(NaN)),
      () => d.setTargetOrientation(NaN, 0, 0),
      () => d.turnTarget(7, 0.1),
      () => d.turnTarget(0, Infinity),
      () => d.setOrientationWeight(-1),
      () => d.setTask('elbow'),
    ];
    return calls.map((f) => {
      try {
        f();
        return 'no error';
      } catch (e) {
        return String(e.message ?? e);
      }
    });
  });
  assert.ok(thrown.every((m) => m !== 'no error' && m.length > 10 && !/unreachable|panicked/.test(m)), thrown.join(' | '));
  assert.deepEqual(await page.evaluate(() => window.demo.controller.demo.view().target_rotation), kept, 'nothing changed');

  // Cases 1 and 3 do not run the pose: refused with the reason, qp kept.
  await page.selectOption('#mode', 'case1').catch(() => {});
  await nextFrames(page);
  assert.equal((await state(page)).method, 'qp');
  // Back to the position task: no orientation.
  await page.selectOption('#hand-task', 'position');
  await nextFrames(page);
  s = await state(page);
  assert.equal(s.task, 'position');
  assert.equal(s.target_rpy, null);
  assert.equal(await page.evaluate(() => window.demo.controller.view3d.three.gizmoMode()), 'translate');
  clean(page);
  await page.close();
});

test('pose: an address with six numbers for the target opens the pose task turned so; a bad orientation is refused and said, the rest applied', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0&target=0.45,0.25,0.5,3,0.2,-0.5');
  const s = await state(page);
  assert.equal(s.task, 'pose');
  [3, 0.2, -0.5].forEach((a, i) => assert.ok(Math.abs(s.target_rpy[i] - a) < 1e-9, `rpy ${i}: ${s.target_rpy}`));
  clean(page);
  await page.close();
  const bad = await open('?arm=panda&method=qp&autoplay=0&task=pose&orientation_weight=0');
  const b = await state(bad);
  assert.equal(b.task, 'pose');
  assert.equal(b.orientation_weight, 1);
  assert.match(await bad.textContent('body'), /orientation_weight/);
  clean(bad);
  await bad.close();
});

test("pose: the slice atlas maps the hand's pose task in a worker; Cases 1 and 3 are left out and said", async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0&task=pose');
  assert.equal((await state(page)).task, 'pose');
  const a = await page.evaluate(() => window.demo.atlas({ methods: ['none', 'qp', 'case1', 'case2'], n: 3 }));
  assert.deepEqual(a.methods, ['none', 'qp', 'case2'], 'case1 left out, case2 (v only) mapped with the shipped networks');
  assert.equal(a.cells.length, 9);
  assert.match(await page.textContent('#space-atlas-status'), /^Atlas of the hand's pose on .* Case 1 left out: no network has a Φ for the pose\.$/);
  clean(page);
  await page.close();
});

test('pose: axe finds nothing serious with the pose task on and the gizmo turning; on a 390 px phone the pose fields fit without sideways scroll', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0&task=pose');
  await page.click('#gizmo-turn');
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
  const result = await axe(page, 'the pose task, the rings shown');
  assert.deepEqual(result, [], 'no serious or critical violations');
  clean(page);
  await page.close();
  const phone = await open('?arm=panda&method=qp&autoplay=0&task=pose', { viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true });
  const wide = await phone.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(wide <= 390, `no sideways scroll: ${wide} px`);
  const box = await phone.locator('#pose-fields').boundingBox();
  assert.ok(box && box.x >= 0 && box.x + box.width <= 390, `the pose fields fit: ${JSON.stringify(box)}`);
  await phone.locator('#pose-fields').screenshot({ path: join(shots, 'pose-fields-phone.png') });
  clean(phone);
  await phone.close();
});

test('self-collision: the switch keeps the links apart in qp where the numerical route folds the Panda into itself; the pairs near each other are drawn; the run file replays on the command line', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0&obstacles=&target=0,0.25,0.2&task=pose');
  await page.click('label[for=self-collision]');
  await nextFrames(page);
  let s = await state(page);
  assert.equal(s.self_collision, true);
  assert.ok(s.summary.self_collision_steps > 0, `the numerical route folds the arm into itself: ${JSON.stringify(s.summary)}`);
  assert.match(await page.textContent('#stage-summary'), /two of its links meet/);
  assert.match(page.url(), /self_collision=1/);
  // Where its links overlap most, the view draws the pair red between its closest points.
  const worst = await page.evaluate(() => {
    const c = window.demo.controller;
    const run = JSON.parse(c.runFile());
    const k = run.steps.reduce((b, st, i) => (st.self_clearance < run.steps[b].self_clearance ? i : b), 0);
    c.runUntil(run.steps[k].t);
    return run.steps[k].self_clearance;
  });
  assert.ok(worst < 0, `the links overlap: ${worst}`);
  await nextFrames(page);
  const drawn = await page.evaluate(() => {
    const v = window.demo.controller.demo.view();
    let line = null;
    window.demo.controller.view3d.three.scene.traverse((o) => {
      if (o.name === 'self near') line = o;
    });
    return { near: v.self_near, visible: line?.visible, count: line?.geometry.getAttribute('position')?.count };
  });
  assert.ok(drawn.near.some((n) => n.distance < 0) && drawn.visible && drawn.count === 2 * drawn.near.length, JSON.stringify(drawn));
  await page.locator('#stage').screenshot({ path: join(shots, 'self-collision-numerical.png') });
  // qp keeps them apart; its file replays on the command line with the pairs.
  await page.selectOption('#mode', 'qp');
  await nextFrames(page);
  s = await state(page);
  assert.equal(s.method, 'qp');
  assert.equal(s.summary.self_collision_steps ?? 0, 0, JSON.stringify(s.summary));
  const json = await download(page, '#save-run-json');
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.equal(back.summary.self_collision_steps ?? 0, 0);
  close(back.summary.min_self_clearance, s.summary.min_self_clearance, 1e-9, 'the command line keeps the same distance');
  // Off: no pairs drawn.
  await page.click('label[for=self-collision]');
  await nextFrames(page);
  assert.equal((await state(page)).self_collision, false);
  assert.deepEqual(await page.evaluate(() => window.demo.controller.demo.view().self_near), []);
  clean(page);
  await page.close();
});
