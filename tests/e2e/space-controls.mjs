// The page in space as a newcomer tries its controls: every control shown
// works, and what is not built for an arm in space yet is not shown (the
// tour, the weights upload); the keys hint names the drawing's own keys;
// Task plays; the comparison fetches the networks of Cases 1-3 or says why
// they are left out; the trained-range note; the plots' time axis is the
// run's. Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { test, open, clean, state, textMatching, shots, nextFrames, here, saidSoFar, heard } from './harness.mjs';

test('space controls: the tour is not shown, the keys hint is the drawing in space\'s, Task plays', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  assert.equal(await page.isVisible('#tour-open'), false, 'no tour in space yet');
  const hint = await page.textContent('#keys-hint');
  assert.match(hint, /orbit/);
  assert.doesNotMatch(hint, /elbow|"Keys"/);
  await page.evaluate(() => window.demo.runUntil(2));
  // The state in the same task as the click (a busy machine's animation
  // could run on before a later read).
  const s = await page.evaluate(() => {
    document.getElementById('task1').click();
    return window.demo.state();
  });
  assert.equal(s.running, true, 'Task loads the task and plays it');
  assert.ok(s.t < 1, `from its start (t = ${s.t})`);
  clean(page);
  await page.close();
});

test('space controls: the comparison fetches the networks first, or says why Cases 1-3 are left out', async () => {
  const panda = await open('?arm=panda&method=numerical&autoplay=0');
  assert.equal((await state(panda)).has_networks, false);
  await panda.click('#compare-panel summary');
  const rows = await panda.evaluate(() => window.demo.compare());
  assert.equal(rows.length, 10, 'every method, the learned ones with the networks fetched');
  assert.equal((await state(panda)).has_networks, true);
  clean(panda);
  await panda.close();
  const iiwa = await open('?arm=iiwa14&method=numerical&autoplay=0');
  await iiwa.click('#compare-panel summary');
  const some = await iiwa.evaluate(() => window.demo.compare());
  assert.equal(some.length, 7, 'the iiwa has no shipped networks');
  await textMatching(iiwa, '#compare-status', /Cases 1-3 are left out: no networks are shipped/);
  clean(iiwa);
  await iiwa.close();
});

test('space controls: the trained-range note shows when a sphere leaves the networks\' box', async () => {
  const page = await open('?arm=panda&method=case3&autoplay=0');
  await page.waitForFunction(() => window.demo.state().method === 'case3', null, { timeout: 60000 });
  assert.equal((await state(page)).in_range, true);
  assert.equal(await page.isVisible('#range-warning'), false);
  await page.evaluate(() => window.demo.controller.demo.setSpheres(Float64Array.from([1.6, 1.6, 1.6, 0.06])));
  await page.waitForFunction(() => !document.getElementById('range-warning').hidden, null, { timeout: 10000 });
  assert.equal((await state(page)).in_range, false);
  assert.match(await page.textContent('#range-warning'), /trained range/);
  clean(page);
  await page.close();
});

test('space controls: the slice atlas shows a cell\'s numbers under the pointer, and a click places the sphere there', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  const a = await page.evaluate(() => window.demo.atlas({ methods: ['none', 'numerical'], n: 11 }));
  assert.equal(a.cells.length, 121);
  // A corner cell, clear of the target and the sphere.
  const pick = async (k) => ({ k, at: await page.evaluate((c) => window.demo.worldToClient(...c), a.cells[k].centre) });
  let cell = null;
  for (const k of [0, 10, 110, 120]) {
    const c = await pick(k);
    const free = await page.evaluate(([x, y]) => {
      const r = document.getElementById('stage').getBoundingClientRect();
      return !window.demo.controller.demo.hover(x - r.left, y - r.top, 4) && x > r.left && x < r.right && y > r.top && y < r.bottom;
    }, [c.at.x, c.at.y]);
    if (free) {
      cell = c;
      break;
    }
  }
  assert.ok(cell, 'a corner cell on screen, clear of the items');
  await page.mouse.move(cell.at.x, cell.at.y);
  const tip = await textMatching(page, '#atlas-tip', /sphere at \(/);
  assert.match(tip, /No avoidance: /);
  assert.match(tip, /Numerical: /);
  assert.equal(await page.getAttribute('#atlas-tip', 'data-cell'), String(cell.k));
  const placed = await saidSoFar(page);
  await page.mouse.down();
  await page.mouse.up();
  const s = await state(page);
  a.cells[cell.k].centre.forEach((v, i) => assert.ok(Math.abs(s.spheres[0][i] - v) < 1e-9, `sphere ${s.spheres[0]} at the cell ${a.cells[cell.k].centre}`));
  assert.match(page.url(), /obstacles=/, 'the address has the placed sphere');
  await heard(page, /placed on the atlas's cell/, placed);
  clean(page);
  await page.close();
});

test('space controls: a path typed or drawn on the stage, the damping switch and the joint weighting, each kept in the address', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  for (const id of ['#path', '#draw-path', '#damping']) assert.equal(await page.isVisible(id), true, `${id} is shown in space`);
  assert.match(await page.getAttribute('#path', 'placeholder'), /CX,CY,CZ,NX,NY,NZ/);
  // Typed: a circle about a point beside the hand's start, in the plane with normal y.
  const start = (await state(page)).hand;
  const circle = `circle:${(start[0] - 0.1).toFixed(3)},${start[1].toFixed(3)},${start[2].toFixed(3)},0,1,0`;
  await page.fill('#path', circle);
  await page.press('#path', 'Enter');
  await page.locator('#path').blur();
  await page.waitForFunction(() => /^circle:/.test(window.demo.state().path ?? ''), null, { timeout: 10000 });
  const typed = (await state(page)).path;
  assert.deepEqual(typed.slice(7).split(',').map(Number), circle.slice(7).split(',').map(Number));
  await page.waitForFunction(() => /path=circle/.test(location.search), null, { timeout: 10000 });
  // Refused with the core's reason, the path kept.
  await page.fill('#path', 'circle:1,2');
  await page.press('#path', 'Enter');
  await textMatching(page, '#message', /path/);
  assert.equal((await state(page)).path, typed);
  // Drawn: a stroke from the hand's start, 160 px right and 80 px up.
  const from = await page.evaluate((p) => window.demo.worldToClient(...p), start);
  await page.click('#draw-path');
  assert.equal(await page.getAttribute('#draw-path', 'aria-pressed'), 'true');
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let k = 1; k <= 16; k++) await page.mouse.move(from.x + 10 * k, from.y - 5 * k);
  await page.mouse.up();
  await page.waitForFunction(() => /^points:/.test(window.demo.state().path ?? ''), null, { timeout: 10000 });
  const s = await state(page);
  const points = s.path.slice('points:'.length).split(';').map((p) => p.split(',').map(Number));
  assert.ok(points.length >= 3 && points.every((p) => p.length === 3), s.path);
  const end = await page.evaluate((p) => window.demo.worldToClient(...p), points.at(-1));
  assert.ok(Math.hypot(end.x - (from.x + 160), end.y - (from.y - 80)) < 3, `the path ends under the stroke's end (${end.x}, ${end.y})`);
  assert.equal((await state(page)).spheres.length, 1, 'the stroke moved nothing');
  await page.screenshot({ path: `${shots}/space-drawn-path.png` });
  // The damping switch.
  assert.equal(s.damping, false);
  await page.click('label[for=damping]');
  await page.waitForFunction(() => window.demo.state().damping === true, null, { timeout: 10000 });
  await page.waitForFunction(() => /damping=1/.test(location.search), null, { timeout: 10000 });
  // The joint weighting, shown for the methods it reaches.
  await page.selectOption('#mode', 'qp');
  await page.waitForFunction(() => document.getElementById('joint-weighting-field').hidden, null, { timeout: 10000 });
  await page.selectOption('#mode', 'numerical');
  await page.waitForFunction(() => !document.getElementById('joint-weighting-field').hidden, null, { timeout: 10000 });
  await page.selectOption('#joint-weighting', 'wln');
  await page.waitForFunction(() => window.demo.state().weighting === 'wln', null, { timeout: 10000 });
  // A reload gives the same scene back.
  const url = page.url();
  const again = await open(url.slice(url.indexOf('?')));
  const t = await state(again);
  assert.equal(t.path, s.path);
  assert.equal(t.damping, true);
  assert.equal(t.weighting, 'wln');
  clean(again);
  await again.close();
  clean(page);
  await page.close();
});

test('space controls: a learned method draws the numerical ghost, and its legend says so', async () => {
  const page = await open('?arm=panda&method=case3&autoplay=0');
  await page.waitForFunction(() => window.demo.state().method === 'case3', null, { timeout: 60000 });
  await page.evaluate(() => window.demo.runUntil(2.5));
  const s = await state(page);
  assert.ok(s.ghost, 'Case 3 has a ghost');
  assert.equal(s.ghost.theta.length, 7);
  assert.notDeepEqual(s.ghost.theta, s.theta, 'the exact route differs from the learned one');
  await page.waitForFunction(() => !document.querySelector('#legend [data-key=ghost]').hidden, null, { timeout: 10000 });
  await page.screenshot({ path: `${shots}/space-ghost.png` });
  await page.selectOption('#mode', 'numerical');
  await page.waitForFunction(() => window.demo.state().ghost === null, null, { timeout: 10000 });
  await page.waitForFunction(() => document.querySelector('#legend [data-key=ghost]').hidden, null, { timeout: 10000 });
  clean(page);
  await page.close();
});

test('space controls: self-motion: the slider and an elbow dragged with the mouse move the arm, the hand held, from a new start', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  assert.equal(await page.isVisible('#self-motion'), true);
  const before = await state(page);
  // The slider, by keyboard: each arrow a step along joint 2's self-motion.
  await page.focus('#self-motion');
  for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
  await page.waitForFunction((t) => window.demo.state().theta.some((v, i) => Math.abs(v - t[i]) > 0.05), before.theta, { timeout: 10000 });
  const slid = await state(page);
  assert.ok(Math.hypot(...slid.hand.map((v, i) => v - before.hand[i])) < 1e-3, `the hand held: ${slid.hand} vs ${before.hand}`);
  assert.equal(slid.t, 0);
  // An elbow (joint 4's origin) dragged 40 px.
  const elbow = await page.evaluate(() => {
    const d = window.demo.controller.demo;
    const r = document.getElementById('stage').getBoundingClientRect();
    for (let x = 0; x < r.width; x += 3) for (let y = 0; y < r.height; y += 3) if (d.hover(x, y, 0) === 'elbow 4') return { x: r.left + x, y: r.top + y };
    return null;
  });
  assert.ok(elbow, 'elbow 4 is on the drawing');
  const said = await saidSoFar(page);
  await page.mouse.move(elbow.x, elbow.y);
  await page.mouse.down();
  for (let k = 1; k <= 10; k++) await page.mouse.move(elbow.x + 4 * k, elbow.y + 2 * k);
  await page.mouse.up();
  const dragged = await state(page);
  assert.ok(dragged.theta.some((v, i) => Math.abs(v - slid.theta[i]) > 0.02), 'the arm moved');
  assert.ok(Math.hypot(...dragged.hand.map((v, i) => v - before.hand[i])) < 2e-3, `the hand held: ${dragged.hand}`);
  assert.equal(dragged.spheres.length, 1);
  assert.deepEqual(dragged.target, before.target, 'the target stayed');
  await heard(page, /elbow 4 moved, the hand held still/, said);
  await page.screenshot({ path: `${shots}/space-self-motion.png` });
  // The new start is in the address: a reload starts from it.
  await page.waitForFunction(() => /theta0=/.test(location.search), null, { timeout: 10000 });
  const url = page.url();
  const again = await open(url.slice(url.indexOf('?')));
  assert.deepEqual((await state(again)).theta0, dragged.theta0);
  clean(again);
  await again.close();
  clean(page);
  await page.close();
});

test('space controls: the manipulability readouts and the legend\'s switches of the velocity and the force ellipsoid', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  const s = await state(page);
  assert.equal(s.singular_values.length, 3);
  assert.ok(Math.abs(s.singular_values.reduce((a, b) => a * b, 1) - s.manipulability) < 1e-9, 'w = σ₁σ₂σ₃');
  assert.equal(await page.isVisible('[data-readout="manipulability"]'), true);
  await textMatching(page, '[data-readout="sigma"]', /^\d\.\d{3}, \d\.\d{3}, \d\.\d{3}$/);
  assert.match(await page.textContent('.readouts div:has([data-readout="sigma"]) dt'), /σ₁, σ₂, σ₃ of J$/);
  // The matrix's name keeps its case where the readouts' labels are lowercased.
  assert.equal(await page.evaluate(() => getComputedStyle(document.querySelector('.readouts div:has([data-readout="sigma"]) dt i')).textTransform), 'none');
  const green = () =>
    page.evaluate(() => {
      const c = window.demo.snapshot();
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 46) < 20 && Math.abs(d[i + 1] - 125) < 20 && Math.abs(d[i + 2] - 50) < 20) n++;
      return n;
    });
  const before = await green();
  const box = page.locator('#legend input[data-toggle="ellipse"]');
  assert.equal(await box.isVisible(), true);
  await box.check();
  await page.waitForFunction((b) => {
    const c = window.demo.snapshot();
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 46) < 20 && Math.abs(d[i + 1] - 125) < 20 && Math.abs(d[i + 2] - 50) < 20) n++;
    return n > b + 200;
  }, before, { timeout: 10000 });
  await page.screenshot({ path: `${shots}/space-ellipsoid.png` });
  await box.uncheck();
  await nextFrames(page);
  assert.ok((await green()) <= before + 20, 'switched off, the ellipsoid is gone');
  // The force ellipsoid, its own switch and colour (#6d4c41).
  const brown = () =>
    page.evaluate(() => {
      const c = window.demo.snapshot();
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 109) < 16 && Math.abs(d[i + 1] - 76) < 16 && Math.abs(d[i + 2] - 65) < 16) n++;
      return n;
    });
  const plain = await brown();
  await page.locator('#legend input[data-toggle="force"]').check();
  await nextFrames(page);
  assert.ok((await brown()) > plain + 200, `the force ellipsoid is drawn (${plain} -> ${await brown()} px)`);
  clean(page);
  await page.close();
});

test('space controls: window.demo.simulate runs a scene off screen with overrides, as the plane\'s, and refuses a bad one', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  const before = await state(page);
  const plain = await page.evaluate(() => window.demo.simulate({ method: 'qp' }));
  const compared = (await page.evaluate(() => window.demo.compare())).find((r) => r.method === 'qp');
  assert.deepEqual(plain, compared.summary, 'the scene in use, as the comparison runs it');
  const moved = await page.evaluate(() => window.demo.simulate({ method: 'qp', target: [0.45, 0.2, 0.5], obstacles: [[0.45, 0.1, 0.7, 0.05]], tf: 3 }));
  assert.equal(moved.steps, 60);
  const objects = await page.evaluate(() => window.demo.simulate({ method: 'qp', target: [0.45, 0.2, 0.5], obstacles: [{ x: 0.45, y: 0.1, z: 0.7 }], tf: 3 }));
  assert.deepEqual(objects, moved, 'a sphere written { x, y, z } has the default radius, 0.05 m');
  const flat = await page.evaluate(() => window.demo.simulate({ method: 'qp', target: [0.45, 0.2, 0.5], obstacles: [0.45, 0.1, 0.7, 0.05], tf: 3 }));
  assert.deepEqual(flat, moved, 'a flat list of numbers, as before');
  const current = await page.evaluate(() => window.demo.simulate({}));
  const numerical = (await page.evaluate(() => window.demo.compare())).find((r) => r.method === 'numerical');
  assert.deepEqual(current, numerical.summary, 'without a method, the method in use');
  for (const bad of [{ method: 'qp', target: [1, 2] }, { method: 'nope' }, { method: 'qp', tf: -1 }, { colour: 'red' }]) {
    const why = await page.evaluate((o) => {
      try {
        window.demo.simulate(o);
        return null;
      } catch (e) {
        return String(e.message ?? e);
      }
    }, bad);
    assert.ok(why, `refused: ${JSON.stringify(bad)}`);
  }
  const after = await state(page);
  assert.deepEqual([after.method, after.target, after.spheres, after.tf], [before.method, before.target, before.spheres, before.tf], 'the stage did not change');
  clean(page);
  await page.close();
});

test('space controls: your own weights files: the Panda\'s installed, refused for the iiwa with the core\'s reason', async () => {
  const files = ['phi', 'v'].map((k) => join(here, '..', '..', 'weights', `${k}-panda-reach.json`));
  const iiwa = await open('?arm=iiwa14&method=numerical&autoplay=0');
  assert.equal(await iiwa.isVisible('#weights-upload'), true);
  await iiwa.click('#weights-upload summary');
  assert.match(await iiwa.textContent('#weights-upload p'), /train --arm iiwa14/);
  await iiwa.setInputFiles('#phi-file', files[0]);
  await iiwa.setInputFiles('#v-file', files[1]);
  await iiwa.click('#load-weights');
  await textMatching(iiwa, '#message', /chain|joint|trained/i);
  assert.equal((await state(iiwa)).has_networks, false, 'refused: the networks in use stay (none)');
  assert.equal(await iiwa.locator('#mode option[value=case3]').isDisabled(), true);
  clean(iiwa);
  await iiwa.close();

  const panda = await open('?arm=panda&method=numerical&autoplay=0');
  await panda.click('#weights-upload summary');
  await panda.setInputFiles('#phi-file', files[0]);
  await panda.setInputFiles('#v-file', files[1]);
  await panda.click('#load-weights');
  await textMatching(panda, '#message', /Loaded phi-panda-reach\.json/);
  const s = await state(panda);
  assert.equal(s.has_networks, true);
  assert.equal(s.network_set, null, 'the user\'s files, not the shipped set by name');
  await panda.selectOption('#mode', 'case3');
  await panda.waitForFunction(() => window.demo.state().method === 'case3', null, { timeout: 10000 });
  clean(panda);
  await panda.close();
});

test('space controls: training in the page gives the iiwa networks for Cases 1-3; Cancel stops it and keeps what was in use', async () => {
  const page = await open('?arm=iiwa14&method=numerical&autoplay=0');
  assert.equal(await page.isVisible('#train-panel'), true);
  await page.click('#train-panel summary');
  assert.match(await page.textContent('#train-panel summary'), /iiwa/);
  assert.equal(await page.isVisible('#train-net'), false, 'both networks, always');
  assert.equal(await page.isVisible('#train-curves'), true, 'the plane\'s training curves');
  // Started from the button and cancelled.
  await page.click('#train-run');
  await page.waitForFunction(() => !document.getElementById('train-cancel').hidden, null, { timeout: 10000 });
  await page.click('#train-cancel');
  await textMatching(page, '#train-status', /cancelled/);
  assert.equal((await state(page)).has_networks, false);
  assert.equal(await page.locator('#mode option[value=case3]').isDisabled(), true);
  // A small training (window.demo.train, the recipe's sampling on few samples): installed, Case 3 runs.
  const trained = await page.evaluate(() => window.demo.train({ samples: 300, epochs: 3 }).then((r) => [JSON.parse(r.phi), JSON.parse(r.v)].map((f) => ({ format: f.format, variant: f.variant, joints: f.arm.rows.length, d1: f.arm.rows[0].d }))));
  // The one weights file of every arm, the iiwa's chain whole in it (its first row's d is the iiwa's 0.36 m).
  assert.deepEqual(trained, [0, 1].map(() => ({ format: 'redundant-ik-weights/2', variant: 'equivariant', joints: 7, d1: 0.36 })));
  await textMatching(page, '#train-status', /Trained in .* Cases 1-3 now use them/);
  // Both networks' curves drew an epoch each (3 epochs each at the most).
  const epochs = Number(await page.getAttribute('#train-curves', 'data-epochs'));
  assert.ok(epochs >= 2 && epochs <= 6, `${epochs} epochs on the curves`);
  await page.locator('#train-panel').screenshot({ path: `${shots}/space-training.png` });
  assert.equal((await state(page)).has_networks, true);
  assert.equal(await page.locator('#mode option[value=case3]').isDisabled(), false);
  await page.selectOption('#mode', 'case3');
  await page.waitForFunction(() => window.demo.state().method === 'case3', null, { timeout: 10000 });
  assert.equal(await page.locator('#train-download').isDisabled(), false);
  clean(page);
  await page.close();
});
