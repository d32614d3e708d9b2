// The page for a class, continued (class.mjs registers these last): the
// legend per method, the tour, the atlas and the comparison, prose that
// follows the arm, the benchmark's download.

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { download, pngSize, parseSvg, close } from './class-helpers.mjs';
import { textMatching } from './harness.mjs';

export function classPanelTests(h) {
  const { test, open, clean, state, shots, mouseDrag, selectMethod, methodsOf, usesNetworks, browser, BASE } = h;

  test('class: the legend lists what is drawn, per method (ghost, trained region, dampers), and a link below the floor', async () => {
    const page = await open('?task=1&method=numerical');
    const visible = () => page.evaluate(() => [...document.querySelectorAll('#legend li')].filter((li) => !li.hidden).map((li) => li.dataset.key));
    const frame = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    for (const m of await methodsOf(page)) {
      await selectMethod(page, m.name);
      await page.click('#task1');
      await page.evaluate(() => window.demo.runUntil(100));
      await frame();
      // The ellipses' entries (legend toggles) are always listed.
      const expected = ['arm', 'strobe', 'path', 'trail', 'reference', 'target', 'obstacle', 'ellipse', 'force'];
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
    await selectMethod(page, 'case3');
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

  test('class: the tour runs its six steps to the end, each one click, and can be skipped; the last opens the Panda', async () => {
    const page = await open('?task=2&method=qp');
    await page.click('#tour-open');
    assert.equal(await page.isVisible('#tour'), true);
    const expect = [
      (s) => s.method === 'none' && s.collided,
      (s) => s.method === 'numerical' && !s.collided && s.final_error < 5e-3,
      (s) => s.method === 'case3' && !s.collided && s.ghost && s.final_error < 5e-3,
      (s) => s.method === 'case3' && Math.hypot(s.obstacle[0] + 0.2, s.obstacle[1] - 0.85) < 1e-9 && s.collided,
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
        assert.ok(expect[k](s), `step ${k + 1}: ${JSON.stringify({ method: s.method, collided: s.collided, obstacle: s.obstacle, in_range: s.in_range })}`);
        if (k === 3) assert.equal(await page.isVisible('.stage-card #range-warning'), true, 'outside the box: the warning shows');
      } else {
        await page.waitForFunction(() => /This atlas \(.*\): Case 3 succeeds/.test(document.getElementById('tour-result').textContent), null, { timeout: 60000 });
        // The figure says what it is of (issue 27: three grids, none labelled).
        const said = await page.textContent('#tour-result');
        assert.match(said, /Task 1, 21 × 21 cells over \[-?[\d.]+, [\d.]+\] × \[-?[\d.]+, [\d.]+\] m, damping near singular poses on/, said);
        assert.match(await page.textContent('#atlas-table caption'), /21 × 21 cells/, 'the table says its grid too');
        assert.equal(await page.inputValue('#atlas-show'), 'case3', 'the map of Case 3');
      }
      await page.screenshot({ path: join(shots, `class-tour-${k + 1}.png`) });
      await page.click('#tour-next');
    }
    // The sixth opens the first arm in space with the numerical route, where a link hits the sphere.
    assert.equal(await page.getAttribute('#tour', 'data-step'), '6');
    assert.equal(await page.textContent('#tour-next'), 'Done');
    await Promise.all([page.waitForNavigation(), page.click('#tour-show')]);
    await page.waitForSelector('body[data-ready="true"]');
    const panda = await page.evaluate(() => window.demo.runUntil(1e9));
    assert.equal(panda.kind, 'space');
    assert.equal(panda.method, 'numerical');
    assert.ok(panda.collided, 'the criterion at its gain lets a link hit the sphere');
    await page.screenshot({ path: join(shots, 'class-tour-6.png') });
    await page.goBack();
    await page.waitForSelector('body[data-ready="true"]');
    assert.equal((await state(page)).kind, undefined, 'back on the plane');
    // Skipped at once: the page goes on as it was.
    await page.click('#tour-open');
    const before = (await state(page)).method;
    await page.click('#tour-close');
    assert.equal(await page.isVisible('#tour'), false);
    assert.equal((await state(page)).method, before);
    clean(page);
    await page.close();
  });

  test('class: the atlas opens on the selected method and says what it counts; the comparison greys out and marks unavoidable hits; both download', async () => {
    const page = await open('?task=1&method=case3');
    await page.click('#atlas-panel summary');
    await page.selectOption('#atlas-n', '11');
    await page.click('#atlas-run');
    await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
    assert.equal(await page.inputValue('#atlas-show'), 'case3', 'the map of the method in use');
    await page.waitForSelector('#legend li[data-key="atlas"]:not([hidden])');
    const heads = await page.$$eval('#atlas-table th', (ths) => ths.map((th) => th.textContent));
    assert.deepEqual(heads, ['method', 'success', 'where it mattered', 'in v box', 'outside', 'smallest clearance']);
    assert.match(await page.textContent('#atlas-counts'), /not on the path, not on the start arm/);
    const none = await page.textContent('#atlas-body tr[data-method="none"] td:nth-child(3)');
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
    assert.equal(crows[0], 'method,label,min_clearance_m,collided,unavoidable,final_error_m,reached,error,limit_steps');
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
    const page = await open('?task=1&method=case3');
    assert.equal(await page.textContent('[data-arm="links"]'), 'three');
    await page.click('#arm-panel summary');
    await page.selectOption('#arm-preset', 'four');
    await page.waitForFunction(() => window.demo.state().arm.links.length === 4);
    // The prose follows the arm on the next frame (describeArm): awaited, not read at once.
    await textMatching(page, '[data-arm="links"]', /^four$/);
    await textMatching(page, '[data-arm="spare"]', /^its two spare degrees of freedom bend$/);
    await textMatching(page, '#what-you-see', /links of 0\.6, 0\.85, 0\.6 and 0\.4 m.*Four joints .* two degrees of freedom spare/);
    await textMatching(page, '#network-note', /trained for the paper's arm, not this one/);
    assert.equal((await state(page)).method, 'numerical');
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
    await textMatching(page, '#network-note', /a few parts in ten thousand/);
    await page.screenshot({ path: join(shots, 'class-four-links.png') });
    clean(page);
    await page.close();
  });

  test('class: the benchmark downloads as CSV', async () => {
    const page = await open('?task=1&method=numerical');
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
