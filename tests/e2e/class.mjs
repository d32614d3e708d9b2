// The page for a class (issue 20), end to end through the UI as a student
// or a teacher uses it: runs that end and hold still, a scene that stays as
// the user made it, readouts that reset with their run, honest warnings
// beside the drawing, everything taken away (figures, runs, tables) read
// back by the command-line tool, a phone that fits, a legend of what is
// drawn, an atlas and a comparison that explain themselves, prose that
// follows the arm, and the tour. Registered by e2e.mjs with its helpers.

import { readFileSync, writeFileSync, mkdtempSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import assert from 'node:assert/strict';

const CLI = process.env.REDUNDANT_IK ?? 'target/debug/redundant-ik';
const scratch = mkdtempSync(join(tmpdir(), 'redundant-ik-class-'));

/** Runs the command-line tool; its standard output. */
function cli(args) {
  const out = spawnSync(CLI, args, { encoding: 'utf8', maxBuffer: 64 << 20 });
  assert.equal(out.status, 0, `${args.join(' ')}: ${out.stderr}`);
  return out.stdout;
}

/** Clicks `selector` and returns the file it downloads: `{ name, bytes, text }`. */
async function download(page, selector) {
  const [d] = await Promise.all([page.waitForEvent('download', { timeout: 60000 }), page.click(selector)]);
  const bytes = readFileSync(await d.path());
  const name = d.suggestedFilename();
  writeFileSync(join(scratch, name), bytes);
  return { name, bytes, text: bytes.toString('utf8'), path: join(scratch, name) };
}

/** Width and height of a PNG, from its IHDR chunk. */
function pngSize(bytes) {
  assert.deepEqual([...bytes.subarray(1, 4)], [0x50, 0x4e, 0x47], 'a PNG signature');
  return [bytes.readUInt32BE(16), bytes.readUInt32BE(20)];
}

/** The SVG parsed by the browser: its size and its polylines' points, or a parse error. */
function parseSvg(page, text) {
  return page.evaluate((svg) => {
    const doc = new DOMParser().parseFromString(svg, 'image/svg+xml');
    const error = doc.querySelector('parsererror');
    const root = doc.documentElement;
    return {
      error: error ? error.textContent : null,
      size: [Number(root.getAttribute('width')), Number(root.getAttribute('height'))],
      polylines: [...doc.querySelectorAll('polyline')].map((p) => ({
        stroke: p.getAttribute('stroke'),
        width: p.getAttribute('stroke-width'),
        points: p.getAttribute('points').trim().split(/\s+/).map((xy) => xy.split(',').map(Number)),
      })),
      texts: [...doc.querySelectorAll('text')].map((t) => t.textContent.trim()),
    };
  }, text);
}

const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b}`);

export function classTests(h) {
  const { test, open, clean, state, shots, mouseDrag, selectMode, methodsOf, usesNetworks, browser, BASE } = h;
  const waitEnded = (page, timeout = 60000) =>
    page.waitForFunction(() => window.demo.state().ended && !window.demo.state().running, null, { timeout });

  test('class: a dropped target runs its line to the end; the clock stops and the hand holds within 1 mm for 5 s, in every method', async () => {
    const page = await open('?task=1&mode=numerical');
    await page.selectOption('#speed', '8');
    for (const m of await methodsOf(page)) {
      await selectMode(page, m.name);
      await page.click('#task1');
      await waitEnded(page);
      // The drop: (0.3, 1.2), from wherever the hand is now.
      await mouseDrag(page, (await state(page)).target, [0.3, 1.2]);
      const run = await state(page);
      assert.equal(run.mode, m.name);
      assert.ok(run.running && run.t < run.tf, `${m.name}: the drop starts a new run`);
      await waitEnded(page);
      const end = await state(page);
      close(end.t, end.tf, 1e-9, `${m.name}: the clock stopped at the end of the line`);
      close(end.tf, end.line.duration, 1e-9, `${m.name}: the line's end`);
      assert.equal(await page.textContent('#play'), 'Replay');
      assert.match(await page.textContent('#run-note'), /The run ended at t = .* holds still/);
      // 5 s of page time: no clock runs on, the hand stays within 1 mm.
      let worst = 0;
      for (let k = 0; k < 10; k++) {
        await page.waitForTimeout(500);
        const s = await state(page);
        assert.equal(s.t, end.t, `${m.name}: the clock runs on`);
        worst = Math.max(worst, Math.hypot(s.ee[0] - end.ee[0], s.ee[1] - end.ee[1]));
      }
      assert.ok(worst <= 1e-3, `${m.name}: the hand moved ${worst} m after the end`);
    }
    await page.screenshot({ path: join(shots, 'class-run-ended.png') });
    clean(page);
    await page.close();
  });

  test('class: add three obstacles by clicking, press Task 1: all three are there', async () => {
    const page = await open('?task=1&mode=numerical');
    await page.click('#arm-panel summary');
    const added = [[-0.4, 1.4], [1.3, 1.5], [0.2, 1.75]];
    for (const p of added) {
      await page.click('#obstacle-add');
      const at = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), p);
      await page.mouse.click(at.x, at.y);
    }
    const placed = (await state(page)).obstacles.slice(1).map((o) => o.centre);
    assert.equal(placed.length, 3);
    await page.click('#task1');
    const s = await state(page);
    assert.equal(s.obstacles.length, 4, 'the paper obstacle and the three added');
    assert.deepEqual(s.obstacles[0].centre, [0.5, 0.5], "the paper's obstacle");
    assert.deepEqual(s.obstacles.slice(1).map((o) => o.centre), placed, 'the three added stay');
    await page.click('#task2');
    assert.equal((await state(page)).obstacles.length, 4, 'Task 2 keeps them too');
    await page.click('#reset');
    assert.equal((await state(page)).obstacles.length, 4, 'so does reset');
    await page.screenshot({ path: join(shots, 'class-task-keeps-obstacles.png') });
    clean(page);
    await page.close();
  });

  test('class: pause, reset, drag the obstacle next to the arm: "smallest this run" is the distance', async () => {
    const page = await open('?task=1&mode=numerical');
    await page.waitForFunction(() => window.demo.state().t > 1);
    await page.click('#play');
    assert.equal((await state(page)).running, false, 'paused');
    await page.click('#reset');
    const s0 = await state(page);
    const [a, b] = [s0.joints[2], s0.joints[3]];
    const goal = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2 + 0.11];
    await mouseDrag(page, s0.obstacle, goal);
    const s = await state(page);
    assert.ok(s.distance < 0.15, `next to the arm: ${s.distance}`);
    assert.equal(s.min_distance, s.distance);
    const shown = await page.evaluate(() => ['distance', 'min_distance'].map((k) => document.querySelector(`[data-readout="${k}"]`).textContent));
    assert.equal(shown[1], shown[0], `readouts ${shown}`);
    await page.screenshot({ path: join(shots, 'class-readouts-reset.png') });
    clean(page);
    await page.close();
  });

  test('class: moving the obstacle after a run ends replays the run with it there', async () => {
    const page = await open('?task=1&mode=numerical');
    await page.selectOption('#speed', '8');
    await waitEnded(page);
    await mouseDrag(page, (await state(page)).obstacle, [1.05, 0.95]);
    const s = await state(page);
    assert.ok(s.running && s.t < 5, `replaying (t = ${s.t})`);
    await waitEnded(page);
    const end = await state(page);
    assert.ok(Math.hypot(end.obstacle[0] - 1.05, end.obstacle[1] - 0.95) < 0.02);
    clean(page);
    await page.close();
  });

  test('class: take it away: the figure, the plots and the run, each read back (SVG as XML, PNG of the right size, CSV a line per step, JSON by the CLI)', async () => {
    const page = await open('?task=1&mode=case3');
    await page.selectOption('#speed', '8');
    await waitEnded(page);
    const s = await state(page);
    // The run as the JSON of `simulate --json`, read back by the CLI: the
    // same scene, and the same run to rounding (native kernels use FMA).
    const json = await download(page, '#save-run-json');
    assert.match(json.name, /^task1-case3\.json$/);
    const run = JSON.parse(json.text);
    assert.deepEqual(Object.keys(run), ['task', 'mode', 'scene', 'steps', 'summary']);
    assert.equal(run.mode, 'case3');
    assert.deepEqual(run.scene, await page.evaluate(() => window.demo.controller.demo.scene()), 'the page scene');
    const last = run.steps.at(-1);
    s.theta.forEach((v, i) => close(last.theta[i], v, 1e-12, `theta${i + 1}: the file's run is the drawing's`));
    const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
    assert.deepEqual(back.scene, run.scene, 'the CLI reads the same scene');
    assert.equal(back.steps.length, run.steps.length);
    back.steps.forEach((st, k) => st.theta.forEach((v, i) => close(v, run.steps[k].theta[i], 1e-9, `step ${k} theta${i + 1}`)));
    for (const key of ['min_distance', 'min_clearance', 'final_error', 'max_tracking_error']) close(back.summary[key], run.summary[key], 1e-9, key);
    for (const key of ['collided', 'reached', 'steps', 'mode', 'out_of_range_steps']) assert.equal(back.summary[key], run.summary[key], key);
    // The CSV: its header and one line per step, the numbers of the run.
    const csv = await download(page, '#save-run-csv');
    const lines = csv.text.trim().split('\n');
    assert.equal(lines[0], 't,theta1,theta2,theta3,x,y,ref_x,ref_y,tracking_error,clearance,collision');
    assert.equal(lines.length, run.steps.length + 1, 'one line per step');
    const row = lines.at(-1).split(',').map(Number);
    close(row[0], last.t, 0, 't');
    close(row[4], s.ee[0], 1e-12, 'hand x');
    close(row[9], last.clearance, 0, 'clearance');
    // The CLI writes the same CSV for the same file (to rounding).
    const theirs = cli(['simulate', '--from', json.path, '--csv']).trim().split('\n');
    assert.equal(theirs.length, lines.length);
    assert.equal(theirs[0], lines[0]);
    theirs.slice(1).forEach((l, k) => {
      const [a, b] = [l.split(','), lines[k + 1].split(',')];
      a.forEach((x, i) => close(Number(x), Number(b[i]), 1e-9, `CSV line ${k + 2}, column ${lines[0].split(',')[i]}`));
    });
    // The figure: well-formed SVG with the arm's final pose as a polyline,
    // the figure `redundant-ik figure` draws for the same run.
    const svg = await download(page, '#save-figure-svg');
    const fig = await parseSvg(page, svg.text);
    assert.equal(fig.error, null, 'well-formed XML');
    const pose = fig.polylines.find((p) => p.stroke === '#000000' && p.width === '3');
    assert.ok(pose, 'the final pose is drawn');
    assert.equal(pose.points.length, s.joints.length, 'a point per joint');
    const seg = (pts, i) => Math.hypot(pts[i + 1][0] - pts[i][0], pts[i + 1][1] - pts[i][1]);
    const scale = seg(pose.points, 0) / seg(s.joints, 0);
    for (let i = 1; i < s.joints.length - 1; i++) close(seg(pose.points, i) / seg(s.joints, i), scale, 0.03 * scale, `link ${i + 1} in proportion`);
    assert.ok(fig.texts.some((x) => /^Case 3 · Task 1 · λ = 4 · δ = 0 \+ damping near singular poses · radius 0.05 m · open loop/.test(x)), `the caption line: ${fig.texts.join(' | ')}`);
    const mine = join(scratch, 'cli-figure.svg');
    cli(['figure', '--from', json.path, '--out', mine]);
    const cliFig = await parseSvg(page, readFileSync(mine, 'utf8'));
    assert.deepEqual(cliFig.texts, fig.texts, 'the same words as the CLI figure');
    assert.deepEqual(cliFig.size, fig.size);
    assert.equal(cliFig.polylines.length, fig.polylines.length);
    cliFig.polylines.forEach((p, k) => p.points.forEach((xy, j) => {
      close(xy[0], fig.polylines[k].points[j][0], 1, `polyline ${k} point ${j}`);
      close(xy[1], fig.polylines[k].points[j][1], 1, `polyline ${k} point ${j}`);
    }));
    const png = await download(page, '#save-figure-png');
    assert.deepEqual(pngSize(png.bytes), fig.size.map((v) => 2 * v), 'PNG at twice the SVG size');
    // The plots, likewise.
    const plots = await download(page, '#save-plots-svg');
    const pl = await parseSvg(page, plots.text);
    assert.equal(pl.error, null);
    assert.ok(pl.texts.includes('joint angles (rad)') && pl.texts.includes('tracking error (m)'), pl.texts.join(' | '));
    assert.equal(pl.polylines.filter((p) => p.width === '2').length >= 3 + 2, true, 'distance, error and three joint angles');
    const ppng = await download(page, '#save-plots-png');
    assert.deepEqual(pngSize(ppng.bytes), pl.size.map((v) => 2 * v));
    // The built-in networks, for the paper's arm: files the CLI loads.
    await page.click('#train-panel summary');
    const got = [];
    page.on('download', (d) => got.push(d));
    await page.click('#train-download');
    await page.waitForFunction(() => /as shipped/.test(document.getElementById('message').textContent));
    for (let k = 0; k < 50 && got.length < 2; k++) await page.waitForTimeout(100);
    const [w1, w2] = got;
    const names = [w1.suggestedFilename(), w2.suggestedFilename()].sort();
    assert.deepEqual(names, ['phi-equivariant.json', 'v-plain.json']);
    const paths = {};
    for (const d of [w1, w2]) paths[d.suggestedFilename()] = await d.path();
    cli(['simulate', '--mode', 'case3', '--phi-weights', paths['phi-equivariant.json'], '--v-weights', paths['v-plain.json']]);
    await page.screenshot({ path: join(shots, 'class-take-away.png') });
    clean(page);
    await page.close();
  });

  test('class: copy link: the address of the scene, a dropped line included, opens the same scene', async () => {
    const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
    await context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(BASE).origin });
    const page = await context.newPage();
    await page.goto(BASE + '?task=2&mode=distance');
    await page.waitForSelector('body[data-ready="true"]');
    await page.selectOption('#speed', '8');
    await page.click('label[for="damping"]');
    await page.evaluate(() => window.demo.controller.demo.setParam('influence', 0.35));
    await waitEnded(page);
    await mouseDrag(page, (await state(page)).target, [0.95, 0.35]);
    await mouseDrag(page, (await state(page)).obstacle, [0.8, 1.3]);
    const s = await state(page);
    await page.click('#copy-link');
    const url = await page.inputValue('#link-text');
    const copied = await page.evaluate(() => navigator.clipboard.readText());
    assert.equal(copied, url, 'on the clipboard');
    const other = await context.newPage();
    await other.goto(url);
    await other.waitForSelector('body[data-ready="true"]');
    const o = await other.evaluate(() => window.demo.state());
    assert.equal(o.mode, 'distance');
    assert.deepEqual(o.theta0, s.theta0, 'the start pose of the dropped line');
    assert.equal(o.tf, s.tf);
    assert.deepEqual(o.target, s.target);
    assert.deepEqual(o.obstacles, s.obstacles, `${url}: ${JSON.stringify(o.obstacles)} vs ${JSON.stringify(s.obstacles)}`);
    assert.equal(o.damping, false);
    assert.equal(o.params.influence, 0.35);
    // The same run from t = 0 (the obstacle moved while the page's ran).
    await page.click('#reset');
    const end = await other.evaluate(() => window.demo.runUntil(1e3));
    const mine = await page.evaluate(() => window.demo.runUntil(1e3));
    assert.deepEqual(end.ee, mine.ee, 'the same run');
    await context.close();
  });

  test('class: at 390 x 844 with every panel open the page never scrolls sideways; the drawing and the method menu fit the first screen', async () => {
    const page = await open('?task=1&mode=case3', { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, deviceScaleFactor: 2 });
    const first = await page.evaluate(() => {
      const box = (id) => document.getElementById(id).getBoundingClientRect();
      return { stage: box('stage'), mode: box('mode'), height: innerHeight };
    });
    assert.ok(first.stage.bottom <= first.height && first.mode.bottom <= first.height, `stage ends at ${first.stage.bottom}, menu at ${first.mode.bottom} of ${first.height}`);
    assert.ok(first.stage.width >= 340, `the drawing uses the width (${first.stage.width} px)`);
    await page.screenshot({ path: join(shots, 'class-phone.png') });
    // Every panel open, the tour too, and the longest texts in them.
    await page.click('#tour-open');
    await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
    await page.selectOption('#train-preset', 'thorough');
    await page.click('#compare');
    await page.selectOption('#atlas-n', '11');
    await page.click('#atlas-run');
    await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
    await page.waitForTimeout(300);
    const wide = await page.evaluate(() => ({
      scroll: document.documentElement.scrollWidth,
      culprits: [...document.querySelectorAll('body *')].filter((e) => e.getBoundingClientRect().right > 391).map((e) => e.id || e.className || e.tagName).slice(0, 5),
    }));
    assert.ok(wide.scroll <= 390, `scrollWidth ${wide.scroll}: ${wide.culprits}`);
    await page.screenshot({ path: join(shots, 'class-phone-panels.png'), fullPage: true });
    clean(page);
    await page.close();
    // The embed page too: two demos, one under the other, its title in view.
    const context = await browser.newContext({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true });
    const embed = await context.newPage();
    await embed.goto(BASE + 'embed.html');
    await embed.waitForSelector('#right[data-ready="true"]', { timeout: 15000 });
    const e = await embed.evaluate(() => ({ scroll: document.documentElement.scrollWidth, title: document.querySelector('h1').getBoundingClientRect().right }));
    assert.ok(e.scroll <= 390 && e.title <= 390, `embed: scrollWidth ${e.scroll}, title ends at ${e.title}`);
    await embed.screenshot({ path: join(shots, 'class-embed-phone.png'), fullPage: true });
    await context.close();
  });

  test('class: the legend lists what is drawn, per method (ghost, trained region, dampers), and a link below the floor', async () => {
    const page = await open('?task=1&mode=numerical');
    const visible = () => page.evaluate(() => [...document.querySelectorAll('#legend li')].filter((li) => !li.hidden).map((li) => li.dataset.key));
    const frame = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    for (const m of await methodsOf(page)) {
      await selectMode(page, m.name);
      await page.click('#task1');
      await page.evaluate(() => window.demo.runUntil(100));
      await frame();
      const expected = ['arm', 'strobe', 'path', 'trail', 'reference', 'target', 'obstacle'];
      if (usesNetworks(m)) expected.push('ghost');
      if (m.networks.v) expected.push('region');
      if (m.params.includes('influence')) expected.push('dampers');
      assert.deepEqual((await visible()).sort(), expected.sort(), m.name);
    }
    // At the start of a run nothing has been traced yet.
    await page.click('#reset');
    await frame();
    const atStart = await visible();
    assert.ok(!atStart.includes('strobe') && !atStart.includes('trail'), `${atStart}`);
    // The ghost is drawn on top of the arm, in its own colour: where the two
    // agree (at the start) its pixels show on the arm.
    await selectMode(page, 'case3');
    await page.click('#reset');
    await frame();
    const ghost = await page.evaluate(() => {
      const key = getComputedStyle(document.querySelector('#legend li[data-key="ghost"] .key')).borderTopColor;
      const m = key.match(/[\d.]+/g).map(Number);
      const canvas = document.getElementById('stage');
      const dpr = canvas.width / canvas.getBoundingClientRect().width;
      const ctx = canvas.getContext('2d');
      const s = window.demo.state();
      let hits = 0;
      for (let k = 0; k <= 40; k++) {
        const [a, b] = [s.joints[1], s.joints[2]];
        const p = [a[0] + (k / 40) * (b[0] - a[0]), a[1] + (k / 40) * (b[1] - a[1])];
        const [cx, cy] = window.demo.controller.demo.worldToCanvas(p[0], p[1]);
        const d = ctx.getImageData(Math.round(cx * dpr), Math.round(cy * dpr), 1, 1).data;
        if (Math.abs(d[0] - m[0]) < 40 && Math.abs(d[1] - m[1]) < 40 && Math.abs(d[2] - m[2]) < 40) hits++;
      }
      return hits;
    });
    assert.ok(ghost >= 8, `the ghost shows on the arm (${ghost} of 41 points)`);
    // A 4-link arm in Task 1 goes below the floor: drawn, listed and said.
    await page.click('#arm-panel summary');
    await page.selectOption('#arm-preset', 'four');
    await page.click('#task1');
    await page.evaluate(() => window.demo.runUntil(100));
    await frame();
    const s = await state(page);
    assert.ok(s.below_floor_steps > 0);
    assert.ok((await visible()).includes('floor') === s.below_floor, 'listed while a link is below');
    assert.match(await page.textContent('.stage-card #floor-warning'), /below the floor \(y < 0\)/);
    await page.screenshot({ path: join(shots, 'class-floor.png') });
    clean(page);
    await page.close();
  });

  test('class: the tour runs its five steps to the end, each one click, and can be skipped', async () => {
    const page = await open('?task=2&mode=qp');
    await page.click('#tour-open');
    assert.equal(await page.isVisible('#tour'), true);
    const expect = [
      (s) => s.mode === 'none' && s.collided,
      (s) => s.mode === 'numerical' && !s.collided && s.final_error < 5e-3,
      (s) => s.mode === 'case3' && !s.collided && s.ghost && s.final_error < 5e-3,
      (s) => s.mode === 'case3' && Math.hypot(s.obstacle[0] + 0.2, s.obstacle[1] - 0.85) < 1e-9 && s.collided,
      null,
    ];
    for (let k = 0; k < 5; k++) {
      assert.equal(await page.getAttribute('#tour', 'data-step'), String(k + 1));
      const words = (await page.textContent('#tour-text')).split(/(?<=\.)\s+/).filter(Boolean);
      assert.equal(words.length, 2, `step ${k + 1} in two sentences: ${words}`);
      await page.click('#tour-show');
      if (expect[k]) {
        await page.evaluate(() => window.demo.runUntil(100));
        await page.waitForFunction(() => /This run:/.test(document.getElementById('tour-result').textContent), null, { timeout: 20000 });
        const s = await state(page);
        assert.ok(expect[k](s), `step ${k + 1}: ${JSON.stringify({ mode: s.mode, collided: s.collided, obstacle: s.obstacle, in_range: s.in_range })}`);
        if (k === 3) assert.equal(await page.isVisible('.stage-card #range-warning'), true, 'outside the box: the warning shows');
      } else {
        await page.waitForFunction(() => /This atlas: Case 3 succeeds/.test(document.getElementById('tour-result').textContent), null, { timeout: 60000 });
        assert.equal(await page.inputValue('#atlas-show'), 'case3', 'the map of Case 3');
      }
      await page.screenshot({ path: join(shots, `class-tour-${k + 1}.png`) });
      await page.click('#tour-next');
    }
    assert.equal(await page.isVisible('#tour'), false, 'done');
    assert.equal(await page.getAttribute('#tour', 'data-done'), 'true');
    // Skipped at once: the page goes on as it was.
    await page.click('#tour-open');
    const before = (await state(page)).mode;
    await page.click('#tour-close');
    assert.equal(await page.isVisible('#tour'), false);
    assert.equal((await state(page)).mode, before);
    clean(page);
    await page.close();
  });

  test('class: the atlas opens on the selected method and says what it counts; the comparison greys out and marks unavoidable hits; both download', async () => {
    const page = await open('?task=1&mode=case3');
    await page.click('#atlas-panel summary');
    await page.selectOption('#atlas-n', '11');
    await page.click('#atlas-run');
    await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
    assert.equal(await page.inputValue('#atlas-show'), 'case3', 'the map of the method in use');
    await page.waitForSelector('#legend li[data-key="atlas"]:not([hidden])');
    const heads = await page.$$eval('#atlas-table th', (ths) => ths.map((th) => th.textContent));
    assert.deepEqual(heads, ['method', 'success', 'where it mattered', 'in v box', 'outside', 'smallest clearance']);
    assert.match(await page.textContent('#atlas-counts'), /not on the path, not on the start arm/);
    const none = await page.textContent('#atlas-body tr[data-mode="none"] td:nth-child(3)');
    assert.match(none, /^0\.0% of \d+$/, `no avoidance where it mattered: ${none}`);
    const result = await page.evaluate(() => window.demo.atlasResult());
    const json = await download(page, '#atlas-json');
    const back = JSON.parse(json.text);
    assert.deepEqual(back.cells.map((c) => c.outcomes.case3.class), result.cells.map((c) => c.outcomes.case3.class));
    assert.deepEqual(back.summary, result.summary, "the atlas's own JSON");
    const csv = await download(page, '#atlas-csv');
    const rows = csv.text.trim().split('\n');
    assert.equal(rows.length, 11 * 11 + 1);
    assert.ok(rows[0].startsWith('x,y,avoidance_needed,none_class,none_clearance,none_final_error,numerical_class'));
    const svg = await download(page, '#atlas-figure');
    const fig = await parseSvg(page, svg.text);
    assert.equal(fig.error, null);
    assert.ok(fig.texts.some((x) => /^Case 3: \d+% clear and reached/.test(x)), 'the map of Case 3');
    assert.ok(!fig.texts.some((x) => /^Numerical:/.test(x)), 'only the map shown');
    const png = await download(page, '#atlas-figure-png');
    assert.deepEqual(pngSize(png.bytes), fig.size.map((v) => 2 * v));
    await page.screenshot({ path: join(shots, 'class-atlas.png') });
    // Hidden: off the legend too.
    await page.click('#atlas-hide');
    await page.waitForSelector('#legend li[data-key="atlas"][hidden]', { state: 'attached' });
    await page.selectOption('#atlas-show', 'case3');
    // The comparison: an obstacle on the path makes every hit unavoidable.
    await page.click('#compare-panel summary');
    const s = await state(page);
    const mid = [(s.line.start[0] + s.line.end[0]) / 2, (s.line.start[1] + s.line.end[1]) / 2];
    await page.evaluate(([x, y]) => window.demo.controller.demo.setObstacle(x, y), mid);
    await page.click('#compare');
    assert.match(await page.textContent('#compare-status'), /Unavoidable: an obstacle covers the path/);
    const hits = await page.$$eval('#compare-body tr[data-collided="true"]', (trs) => trs.map((tr) => tr.dataset.unavoidable));
    assert.ok(hits.length >= 5 && hits.every((u) => u === 'path_blocked'), `${hits}`);
    assert.equal(await page.getAttribute('#compare-table', 'data-stale'), 'false');
    const ccsv = await download(page, '#compare-csv');
    const crows = ccsv.text.trim().split('\n');
    assert.equal(crows[0], 'method,label,min_clearance_m,collided,unavoidable,final_error_m,reached,error');
    assert.equal(crows.length, (await methodsOf(page)).length + 1);
    // The scene changes: the table greys out and says so.
    await mouseDrag(page, mid, [1.2, 1.5]);
    await page.waitForFunction(() => document.getElementById('compare-table').dataset.stale === 'true');
    assert.match(await page.textContent('#compare-status'), /scene changed/);
    await page.screenshot({ path: join(shots, 'class-compare.png') });
    clean(page);
    await page.close();
  });

  test('class: the prose follows the arm; a switch of method the page makes is announced at the menu; messages appear next to their cause', async () => {
    const page = await open('?task=1&mode=case3');
    assert.equal(await page.textContent('[data-arm="links"]'), 'three');
    await page.click('#arm-panel summary');
    await page.selectOption('#arm-preset', 'four');
    await page.waitForFunction(() => window.demo.state().arm.links.length === 4);
    assert.equal(await page.textContent('[data-arm="links"]'), 'four');
    assert.equal(await page.textContent('[data-arm="spare"]'), 'two spare degrees');
    assert.match(await page.textContent('#what-you-see'), /links of 0\.6, 0\.85, 0\.6 and 0\.4 m.*Four joints .* two degrees of freedom spare/);
    assert.match(await page.textContent('#network-note'), /trained for the paper's arm, not this one/);
    assert.equal((await state(page)).mode, 'numerical');
    const said = await page.evaluate(() => {
      const m = document.getElementById('message');
      return { text: m.textContent, hidden: m.hidden, after: m.previousElementSibling?.contains(document.getElementById('mode')) };
    });
    assert.equal(said.hidden, false);
    assert.match(said.text, /Case 3 needs networks trained for this arm.*switched to Numerical/);
    assert.ok(said.after, 'the message sits under the method menu');
    // "Download weights" with no networks for this arm: the answer under the button.
    await page.click('#train-panel summary');
    await page.click('#train-download');
    const w = await page.evaluate(() => {
      const m = document.getElementById('message');
      return { text: m.textContent, after: m.previousElementSibling?.contains(document.getElementById('train-download')) };
    });
    assert.match(w.text, /train them first/);
    assert.ok(w.after, 'next to the button');
    // A refusal on the drawing: beside the drawing.
    await page.evaluate(() => window.scrollTo(0, 0));
    await mouseDrag(page, (await state(page)).obstacle, [0.0, 0.25]);
    assert.equal(await page.evaluate(() => document.getElementById('message').parentElement.id), 'stage-notes');
    assert.match(await page.textContent('#message'), /post/);
    // Back to the paper's arm: the paper's prose again.
    await page.selectOption('#arm-preset', 'paper');
    await page.waitForFunction(() => window.demo.state().arm.links.length === 3);
    assert.match(await page.textContent('#network-note'), /a few parts in ten thousand/);
    await page.screenshot({ path: join(shots, 'class-four-links.png') });
    clean(page);
    await page.close();
  });

  test('class: the benchmark downloads as CSV', async () => {
    const page = await open('?task=1&mode=numerical');
    await page.click('#bench-panel summary');
    await page.click('#bench');
    await page.waitForSelector('#bench-csv:not([hidden])', { timeout: 120000 });
    const csv = await download(page, '#bench-csv');
    const rows = csv.text.trim().split('\n').map((l) => l.split(','));
    assert.deepEqual(rows[0], ['method', 'build', 'theta_dot_ns', 'step_ns', 'native_step_ns']);
    const shown = await page.$$eval('#bench-body tr', (trs) => trs.length);
    assert.equal(rows.length, 1 + shown + 2, 'each method, and the two forward passes');
    assert.ok(rows.slice(1).every((r) => Number(r[3]) > 0), 'step times');
    clean(page);
    await page.close();
  });
}
