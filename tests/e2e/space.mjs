// End-to-end tests of the page with an arm in space (arm=panda, arm=iiwa14):
// the 3-D stage from the address, orbit and zoom and the drag of a sphere
// and the target with the mouse, a finger and the keys (the sphere stays
// under the pointer within 2 px), every method's run, the comparison, the
// slice atlas against the module's own run of its cells, the run file
// read back by `simulate --from`, a 390 px phone, axe, and screenshots of
// the Panda before, during and after a run from three views. Registered
// by e2e.mjs.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { readFileSync } from 'node:fs';
import { test, open, clean, state, shots, axe, saidSoFar, heard } from './harness.mjs';
import { cli, download, close, parseSvg, pngSize } from './class-helpers.mjs';

const client = (page, p) => page.evaluate(([x, y, z]) => window.demo.worldToClient(x, y, z), p);
const paused = async (page) => {
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
};

test('space: the Panda and the iiwa open from the address on the 3-D stage', async () => {
  for (const [arm, dof, label] of [
    ['panda', 7, /Panda/],
    ['iiwa14', 7, /iiwa/],
  ]) {
    const page = await open(`?arm=${arm}&method=qp`);
    const s = await state(page);
    assert.equal(s.kind, 'space');
    assert.equal(s.arm, arm);
    assert.equal(s.dof, dof);
    assert.equal(s.method, 'qp');
    assert.match(s.arm_label, label);
    assert.equal(await page.getAttribute('html', 'data-space'), arm);
    // The plane's own controls are hidden (its second task); the method menu, Play, the target's three fields and the readouts are there.
    assert.equal(await page.isVisible('#task2'), false);
    assert.equal(await page.isVisible('#target-z'), true, "the target's x, y and z fields");
    assert.ok(await page.isVisible('#mode'));
    assert.match(await page.textContent('#task1'), /Task/);
    // The drawing is not blank: the arm's colour is on it (the 3-D view with the overlay over it).
    const inked = await page.evaluate(() => {
      const c = window.demo.snapshot();
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 120 && d[i + 2] > 100) n++;
      return n;
    });
    assert.ok(inked > 500, `the arm is drawn (${inked} px)`);
    assert.match(page.url(), new RegExp(`arm=${arm}`));
    clean(page);
    await page.close();
  }
});

test("space: one module holds every arm; the page in space fetches no planar networks, the planar page no script of the page in space", async () => {
  const loaded = (page) =>
    page.evaluate(() => performance.getEntriesByType('resource').map((e) => new URL(e.name).pathname.split('/').pop()).filter((n) => /\.(wasm|json)$/.test(n)));
  const space = await open('?arm=panda&method=numerical');
  const files = await loaded(space);
  assert.ok(files.some((f) => /^redundant_ik(_simd)?_bg\.wasm$/.test(f)), files.join(' '));
  assert.ok(!files.some((f) => f.includes('space')), `no second module: ${files.join(' ')}`);
  // The 3-D view (three.js, bundled by make web) is loaded, and draws with WebGL.
  assert.ok(await space.evaluate(() => performance.getEntriesByType('resource').some((e) => e.name.endsWith('/pkg/three-view.js'))), 'three-view.js is loaded');
  assert.equal(await space.evaluate(() => Boolean(document.querySelector('canvas.view-3d')?.getContext('webgl2'))), true, 'the 3-D view has its WebGL canvas');
  // The planar networks' weights files are not fetched on the page in space.
  const planarWeights = await space.evaluate(() => import('./module.js').then((m) => m.builtinWeightsFiles('paper')));
  assert.ok(!files.some((f) => planarWeights.includes(f)), files.join(' '));
  // The same module holds the planar demo.
  const demo = await space.evaluate(() => import('./module.js').then((m) => { try { new m.Demo(document.createElement('canvas'), undefined, 1).free(); return 'constructed'; } catch (e) { return String(e); } }));
  assert.equal(demo, 'constructed');
  clean(space);
  await space.close();
  const plane = await open('?arm=iiwa-planar&method=numerical');
  const planeFiles = await loaded(plane);
  assert.deepEqual(
    planeFiles.filter((f) => f.endsWith('.wasm')).sort(),
    files.filter((f) => f.endsWith('.wasm')).sort(),
    'both pages load the same module',
  );
  // Nor the scripts of the page in space (page.js imports them only for an arm in space).
  const scripts = await plane.evaluate(() => performance.getEntriesByType('resource').map((e) => new URL(e.name).pathname.split('/').pop()).filter((n) => n.endsWith('.js')));
  assert.ok(!scripts.some((f) => /^(space-(demo|input|panels|atlas|view)|three-view)\.js$/.test(f)), `no script of the page in space, nor three.js: ${scripts.join(' ')}`);
  assert.notEqual((await state(plane)).kind, 'space', 'the planar page');
  const preset = await plane.evaluate(() => import('./module.js').then((m) => m.limits().arm_presets.find((p) => p.key === 'iiwa-planar')));
  assert.deepEqual((await state(plane)).arm.joint_limits, preset.joint_limits);
  clean(plane);
  await plane.close();
});

test('space: a sphere dragged with the mouse stays under the pointer within 2 px, and the run follows it', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  await paused(page);
  const s0 = await state(page);
  const c = await client(page, s0.spheres[0]);
  const said = await saidSoFar(page);
  await page.mouse.move(c.x, c.y);
  await page.mouse.down();
  for (const [dx, dy] of [
    [20, -10],
    [45, 12],
    [-30, 25],
  ]) {
    await page.mouse.move(c.x + dx, c.y + dy, { steps: 6 });
    const s = await state(page);
    const at = await client(page, s.spheres[0]);
    assert.ok(Math.hypot(at.x - (c.x + dx), at.y - (c.y + dy)) <= 2, `the sphere is at (${at.x}, ${at.y}), the pointer at (${c.x + dx}, ${c.y + dy})`);
    assert.equal(s.dragging, 'sphere 1');
  }
  await page.mouse.up();
  const s1 = await state(page);
  assert.notDeepEqual(s1.spheres[0], s0.spheres[0]);
  assert.ok(s1.run_revision > s0.run_revision, 'the run was computed again');
  assert.match(page.url(), /obstacles=/, 'the address has the moved sphere');
  await heard(page, /moved: sphere 1 at x/, said);
  clean(page);
  await page.close();
});

test('space: the empty drawing orbits with the mouse, the wheel zooms, the keys orbit, zoom, reset and move the selected item', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  await paused(page);
  const box = await page.locator('#stage').boundingBox();
  const [yaw0, pitch0, d0] = (await state(page)).view;
  await page.mouse.move(box.x + 30, box.y + box.height - 60);
  await page.mouse.down();
  await page.mouse.move(box.x + 130, box.y + box.height - 90, { steps: 8 });
  await page.mouse.up();
  const [yaw1, pitch1] = (await state(page)).view;
  assert.ok(Math.abs(yaw1 - yaw0) > 0.5, `the yaw turned (${yaw0} -> ${yaw1})`);
  assert.ok(pitch1 < pitch0, 'dragging up lowers the eye');
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.wheel(0, -300);
  assert.ok((await state(page)).view[2] < d0, 'the wheel zooms in');
  await page.focus('#stage');
  await page.keyboard.press('0');
  assert.deepEqual((await state(page)).view, [yaw0, pitch0, d0], '0 resets the view');
  let said = await saidSoFar(page);
  await page.keyboard.press('o');
  close((await state(page)).view[0], yaw0 + Math.PI / 12, 1e-9, 'o orbits by 15 degrees');
  await heard(page, /view from \d+ degrees round/, said);
  await page.keyboard.press('n');
  assert.equal((await state(page)).selected, 'sphere 1');
  const before = (await state(page)).spheres[0];
  said = await saidSoFar(page);
  await page.keyboard.press('ArrowRight');
  const after = (await state(page)).spheres[0];
  close(Math.hypot(after[0] - before[0], after[1] - before[1], after[2] - before[2]), 0.05, 2e-4, 'an arrow moves it 5 cm');
  await heard(page, /sphere 1 at x/, said);
  await page.keyboard.press('n');
  assert.equal((await state(page)).selected, 'target');
  const t0 = (await state(page)).target;
  await page.keyboard.press('Shift+ArrowUp');
  const t1 = (await state(page)).target;
  close(Math.hypot(t1[0] - t0[0], t1[1] - t0[1], t1[2] - t0[2]), 0.005, 2e-4, 'Shift+arrow moves the target 5 mm');
  clean(page);
  await page.close();
});

test('space: touch: one finger drags the target under it, two fingers orbit and zoom', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0', { hasTouch: true, isMobile: true, viewport: { width: 390, height: 800 } });
  await paused(page);
  const s0 = await state(page);
  const a = await client(page, s0.target);
  const cdp = await page.context().newCDPSession(page);
  const pt = (id, x, y) => ({ x, y, id, radiusX: 4, radiusY: 4, force: 1 });
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [pt(1, a.x, a.y)] });
  for (let i = 1; i <= 6; i++) await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [pt(1, a.x + 4 * i, a.y - 3 * i)] });
  const mid = await state(page);
  const at = await client(page, mid.target);
  assert.ok(Math.hypot(at.x - (a.x + 24), at.y - (a.y - 18)) <= 2, 'the target is under the finger');
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  const [yaw0, , d0] = (await state(page)).view;
  const box = await page.locator('#stage').boundingBox();
  const [cx, cy] = [box.x + box.width / 2, box.y + box.height / 2];
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [pt(1, cx - 40, cy), pt(2, cx + 40, cy)] });
  for (let i = 1; i <= 6; i++) {
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [pt(1, cx - 40 - 8 * i + 10 * i, cy), pt(2, cx + 40 + 8 * i + 10 * i, cy)] });
  }
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await cdp.detach();
  const [yaw1, , d1] = (await state(page)).view;
  assert.ok(d1 < d0, `two fingers spread zoom in (${d0} -> ${d1})`);
  assert.ok(Math.abs(yaw1 - yaw0) > 0.1, 'their midpoint moving orbits');
  // A phone never scrolls sideways.
  const wide = await page.evaluate(() => document.documentElement.scrollWidth - document.documentElement.clientWidth);
  assert.ok(wide <= 0, `no sideways scroll (${wide} px)`);
  await page.screenshot({ path: join(shots, 'space-phone.png'), fullPage: false });
  clean(page);
  await page.close();
});

test('space: every method runs the Panda task to its end, the learned ones with the shipped networks; the comparison agrees', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  await page.evaluate(() => window.demo.networks());
  const names = await page.evaluate(() => [...document.querySelectorAll('#mode option')].filter((o) => !o.disabled).map((o) => o.value));
  assert.equal(names.length, 10, `every method is offered: ${names}`);
  const summaries = {};
  for (const m of names) {
    await page.selectOption('#mode', m);
    const s = await page.evaluate(() => window.demo.runUntil(1e9));
    assert.equal(s.method, m);
    assert.equal(s.failure, null, `${m} ran to the end`);
    assert.ok(s.ended);
    close(s.t, s.tf, 1e-9, `${m} reached tf`);
    summaries[m] = s.summary;
  }
  await page.click('#compare-panel summary');
  await page.click('#compare');
  const rows = await page.evaluate(() => window.demo.compare());
  assert.equal(rows.length, 10);
  for (const r of rows) assert.deepEqual(r.summary, summaries[r.method], `${r.method}: the comparison is the stage's run`);
  assert.ok(summaries.numerical.collision_steps > 0, 'the paper criterion collides on this task');
  assert.equal(summaries.qp.collision_steps ?? 0, 0, 'the QP does not');
  assert.equal(await page.locator('#compare-body tr').count(), 10);
  clean(page);
  await page.close();
});

test('space: the run saved from the page reads back with simulate --from, step for step', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0&target=0.45,0.28,0.55');
  await paused(page);
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.equal(run.format, 'redundant-ik-run/2', 'the one run file of every arm');
  assert.ok(run.scene.arm.rows.length === 7, 'the file carries the chain');
  assert.equal(run.method, 'qp');
  assert.deepEqual(run.scene.target, [0.45, 0.28, 0.55]);
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.equal(back.steps.length, run.steps.length);
  back.steps.forEach((s, k) => s.theta.forEach((v, i) => close(v, run.steps[k].theta[i], 1e-9, `step ${k} theta${i + 1}`)));
  const csv = await download(page, '#save-run-csv');
  assert.equal(csv.text.trim().split('\n').length, run.steps.length + 1);
  assert.match(csv.text, /^t,theta1,.*,theta7,x,y,z,ref_x,ref_y,ref_z,tracking_error,clearance,collision\n/, 'the one run CSV of every arm');
  // The view's PNG is the 3-D drawing with the overlay over it: decoded in the page, the arm's blue and the floor's white are in it.
  const png = await download(page, '#save-figure-png');
  const pixels = await page.evaluate(async (b64) => {
    const img = await createImageBitmap(await (await fetch(`data:image/png;base64,${b64}`)).blob());
    const c = new OffscreenCanvas(img.width, img.height);
    const ctx = c.getContext('2d');
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, img.width, img.height).data;
    let arm = 0;
    let white = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] < 120 && d[i + 2] > 100) arm++;
      if (d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250) white++;
    }
    return { arm, white, pixels: d.length / 4 };
  }, png.bytes.toString('base64'));
  assert.ok(pixels.arm > 500 && pixels.white > pixels.pixels / 4, `the PNG is the 3-D view: ${JSON.stringify(pixels)}`);
  // The figure as the command line draws it from the same file.
  const svg = await download(page, '#save-figure-svg');
  assert.match(svg.text, /^<svg|<\?xml/);
  assert.match(svg.text, /Franka Panda/);
  // The plots as SVG, as figure --from FILE --plots draws them from the same file.
  const plots = await download(page, '#save-plots-svg');
  assert.equal(plots.name, 'redundant-ik-panda-qp-plots.svg');
  assert.match(plots.text, /Franka Panda \(7 joints, in space\), QP with dampers over time/);
  assert.match(plots.text, /θ7/);
  const drawn = `${json.path}.plots.svg`;
  cli(['figure', '--from', json.path, '--plots', '--out', drawn]);
  const own = readFileSync(drawn, 'utf8');
  assert.equal(own.match(/<text/g).length, plots.text.match(/<text/g).length, 'the same labels as the command line draws');
  clean(page);
  await page.close();
});

test('space: with precision=f32 the Panda\'s networks compute in f32, and simulate --from replays the run in f32', async () => {
  const page = await open('?arm=panda&method=case3&precision=f32&autoplay=0');
  await page.waitForFunction(() => window.demo.state().method === 'case3' && window.demo.state().precision === 'f32', null, { timeout: 60000 });
  assert.equal(await page.isVisible('#precision'), true);
  assert.equal(await page.inputValue('#precision'), 'f32');
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.equal(run.precision, 'f32');
  assert.deepEqual(run.networks, { set: 'panda-reach' });
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.equal(back.precision, 'f32');
  assert.equal(back.steps.length, run.steps.length);
  back.steps.forEach((s, k) => s.theta.forEach((v, i) => close(v, run.steps[k].theta[i], 1e-9, `step ${k} theta${i + 1}`)));
  await page.selectOption('#precision', 'f64');
  await page.waitForFunction(() => window.demo.state().precision === 'f64');
  assert.doesNotMatch(page.url(), /precision=/);
  clean(page);
  await page.close();
});

test('space: axe finds nothing serious on the Panda page', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0');
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
  const result = await axe(page, 'the Panda page');
  assert.deepEqual(result, [], 'no serious or critical violations');
  clean(page);
  await page.close();
});

test('space: screenshots of the Panda before, during and after a run, from three views', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0&obstacles=0.215,0.21,0.7,0.06;0.45,0.05,0.35,0.05');
  await paused(page);
  const views = { front: [0, 0.2], side: [Math.PI / 2, 0.25], above: [0.45, 1.2] };
  for (const [name, [yaw, pitch]] of Object.entries(views)) {
    for (const [when, t] of [
      ['before', 0],
      ['during', 2.5],
      ['after', 5],
    ]) {
      await page.evaluate(([yaw, pitch, t]) => {
        const d = window.demo.controller.demo;
        d.setView(yaw, pitch, window.demo.state().view[2]);
        d.reset();
        window.demo.runUntil(t);
      }, [yaw, pitch, t]);
      await page.locator('#stage').screenshot({ path: join(shots, `space-panda-${name}-${when}.png`) });
    }
  }
  clean(page);
  await page.close();
});

test("space: the slice atlas in a worker equals the page module's own runs of its cells, and its map lies on its plane", async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0');
  await paused(page);
  await page.click('#atlas-panel summary');
  const atlas = await page.evaluate(() => window.demo.atlas({ n: 5, methods: ['numerical', 'qp'] }));
  assert.ok(atlas, 'the atlas finished');
  assert.equal(atlas.cells.length, 25);
  assert.deepEqual(atlas.methods, ['numerical', 'qp']);
  assert.match(await page.textContent('#space-atlas-status'), /25 cells x 2 methods/);
  assert.equal(await page.locator('#space-atlas-table tbody tr').count(), 2);
  // The success rate is over the cells where avoidance is possible, as `atlas --arm A` counts it.
  const avoidable = atlas.cells.filter((c) => !['start_overlap', 'path_blocked'].includes(c.outcomes[0].class)).length;
  const rates = await page.$$eval('#space-atlas-table tbody tr', (trs) => trs.map((tr) => tr.lastElementChild.textContent));
  atlas.methods.forEach((m, k) => {
    const won = atlas.cells.filter((c) => c.outcomes[k].class === 'success').length;
    assert.equal(rates[k], `${((100 * won) / avoidable).toFixed(1)}%`, `${m}: ${won} of the ${avoidable} avoidable cells`);
  });
  // Its files, as `atlas --arm panda --json`, `--csv` and `--out` write them: the map of the method shown.
  const json = await download(page, '#space-atlas-json');
  assert.deepEqual(JSON.parse(json.text), atlas, "the atlas's own JSON");
  const csv = (await download(page, '#space-atlas-csv')).text.trim().split('\n');
  assert.equal(csv.length, 26);
  assert.equal(csv[0], 'x,y,z,numerical,numerical_clearance,numerical_final_error,qp,qp_clearance,qp_final_error');
  const svg = await download(page, '#space-atlas-figure');
  assert.match(svg.name, /^atlas-panda-yz\d+mm-5x5-numerical\.svg$/);
  const fig = await parseSvg(page, svg.text);
  assert.equal(fig.error, null);
  assert.ok(fig.texts.some((x) => /^Franka Panda \(7 joints, in space\): where the arm stays clear, sphere .* 5 x 5 cells of the slice yz:/.test(x)), fig.texts.join(' | '));
  assert.ok(fig.texts.some((x) => /^Numerical: \d+% clear and reached/.test(x)), 'the map of the method shown');
  assert.ok(!fig.texts.some((x) => /^QP with dampers:/.test(x)), 'only that map');
  const png = await download(page, '#space-atlas-figure-png');
  assert.deepEqual(pngSize(png.bytes), fig.size.map((v) => 2 * v));
  const radius = (await state(page)).spheres[0][3];
  for (const k of [0, 7, 12, 18, 24]) {
    const cell = atlas.cells[k];
    if (cell.outcomes.every((o) => o.class === 'start_overlap' || o.class === 'path_blocked')) continue;
    const rows = await page.evaluate(([c, r]) => {
      window.demo.controller.demo.setSpheres(Float64Array.of(c[0], c[1], c[2], r));
      return window.demo.compare();
    }, [cell.centre, radius]);
    for (const [i, m] of atlas.methods.entries()) {
      const o = cell.outcomes[i];
      const row = rows.find((r) => r.method === m);
      if (o.class === 'start_overlap' || o.class === 'path_blocked') continue;
      close(row.summary.min_clearance, o.min_clearance, 1e-9, `cell ${k} ${m}: min clearance`);
      assert.equal(row.summary.collision_steps > 0, o.class === 'collision', `cell ${k} ${m}: ${o.class}`);
    }
  }
  // The map of the first method is drawn on the plane: pixels of the atlas colours appear.
  await page.locator('#stage').screenshot({ path: join(shots, 'space-atlas.png') });
  // One method alone: the cells it fails in still count against it.
  const one = await page.evaluate(() => window.demo.atlas({ n: 5, methods: ['numerical'] }));
  const fair = one.cells.filter((c) => !['start_overlap', 'path_blocked'].includes(c.outcomes[0].class));
  const won = fair.filter((c) => c.outcomes[0].class === 'success').length;
  assert.ok(won < fair.length, 'the numerical route fails in a cell of this slice');
  const rate = await page.textContent('#space-atlas-table tbody tr td:last-child');
  assert.equal(rate, `${((100 * won) / fair.length).toFixed(1)}%`, `${won} of ${fair.length}`);
  clean(page);
  await page.close();
});

test("space: the benchmark panel times the Panda's step in every method, in a worker, while the page draws", async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  await page.click('#bench-panel summary');
  await page.click('#bench');
  await page.waitForFunction(() => /Per RK4 step/.test(document.getElementById('bench-result').textContent), null, { timeout: 120000 });
  const rows = await page.locator('#bench-body tr').count();
  assert.equal(rows, 10, 'a row per method that runs in space');
  const d = await page.evaluate(() => ({ ...document.getElementById('bench-result').dataset }));
  assert.ok(Number(d.learnedNs) > 0 && Number(d.exactNs) > 0);
  console.log(`measure: the Panda in the page's benchmark: ${d.learned} ${(d.learnedNs / 1000).toFixed(2)} us, ${d.exact} ${(d.exactNs / 1000).toFixed(2)} us per RK4 step`);
  // The networks' f32 kernels, as `redundant-ik bench --precision f32`.
  const f32 = await page.evaluate(() => window.demo.bench({ arm: 'panda', methods: ['case3'], precision: 'f32' }));
  assert.equal(f32.precision, 'f32');
  assert.ok(f32.step_ns.case3 > 0 && f32.forward_ns.phi > 0 && f32.forward_ns.v > 0, JSON.stringify(f32));
  clean(page);
  await page.close();
});
