// The page for the lab (issue 25): the joint weighting of eq. (7) and the
// floor and post as obstacles, in the controls and the address (read back,
// kept across a reload); a preset named in the address (iiwa-planar, with
// its limits and its own task); the legend's switches for the ellipses at
// the hand, which change what is drawn; the note of a joint past its
// limits; the methods of the lab run Task 1. Registered by e2e.mjs with
// its helpers; screenshots of the ellipse and the warning on a laptop and a
// phone.

import { join } from 'node:path';
import assert from 'node:assert/strict';

export function labTests(h) {
  const { test, open, clean, state, shots } = h;
  const frame = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const address = (page) => page.evaluate(() => Object.fromEntries(new URLSearchParams(location.search)));
  const LIMITS = '-2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944';
  /** A legend entry's bit in drawn (its index in the module's legend()). */
  const drawnBit = (page, key) =>
    page.evaluate((key) => {
      const items = [...document.querySelectorAll('#legend li')];
      const i = items.findIndex((li) => li.dataset.key === key);
      return (window.demo.state().drawn & (1 << i)) !== 0;
    }, key);

  test('lab: weighting=wln and floor=1 load from the address, show in the controls and survive a reload', async () => {
    const page = await open(`?task=1&method=numerical&limits=${LIMITS}&weighting=wln&floor=1`);
    const check = async (why) => {
      const s = await state(page);
      assert.equal(s.weighting, 'wln', why);
      assert.equal(s.floor, true, why);
      assert.equal(await page.inputValue('#joint-weighting'), 'wln', why);
      assert.ok(await page.isChecked('#floor'), why);
      assert.ok(await page.isVisible('#joint-weighting'), `${why}: the weighting reaches numerical`);
      const q = await address(page);
      assert.equal(q.weighting, 'wln', why);
      assert.equal(q.floor, '1', why);
    };
    await check('loaded');
    await page.reload();
    await page.waitForSelector('body[data-ready="true"]');
    await check('after a reload');
    // The choices are the module's; the field shows only where the method says the weighting reaches it.
    const options = await page.$$eval('#joint-weighting option', (o) => o.map((x) => x.value));
    const { joint_weightings: choices } = await page.evaluate(() => import('./module.js').then((m) => m.limits()));
    assert.deepEqual(options, choices.map(([name]) => name));
    const methods = await page.evaluate(() => window.demo.methods());
    for (const m of methods) {
      await page.selectOption('#mode', m.name);
      await frame(page);
      assert.equal(await page.isVisible('#joint-weighting'), m.weighting, `${m.name}: shown iff the weighting reaches it`);
    }
    await page.selectOption('#mode', 'numerical');
    await page.selectOption('#joint-weighting', choices[0][0]);
    await page.click('label[for="floor"]');
    const q = await address(page);
    assert.equal(q.weighting, undefined, 'the default is not written');
    assert.equal(q.floor, undefined);
    const s = await state(page);
    assert.equal(s.weighting, choices[0][0]);
    assert.equal(s.floor, false);
    clean(page);
    await page.close();
  });

  test('lab: a change of weighting or floor makes the comparison and the atlas stale (the revisions move)', async () => {
    const page = await open(`?task=1&method=numerical&limits=${LIMITS}`);
    const before = (await state(page)).revision;
    await page.selectOption('#joint-weighting', 'wln');
    const mid = (await state(page)).revision;
    assert.ok(mid.scene > before.scene && mid.atlas > before.atlas, JSON.stringify([before, mid]));
    await page.click('label[for="floor"]');
    const after = (await state(page)).revision;
    assert.ok(after.scene > mid.scene && after.atlas > mid.atlas, JSON.stringify([mid, after]));
    clean(page);
    await page.close();
  });

  test('lab: ?arm=iiwa-planar gives the preset with its limits and its own task; the designer shows it', async () => {
    const page = await open('?arm=iiwa-planar&method=numerical');
    const preset = await page.evaluate(() => import('./module.js').then((m) => m.limits().arm_presets.find((p) => p.key === 'iiwa-planar')));
    const s = await state(page);
    assert.deepEqual(s.arm.links, preset.links);
    assert.deepEqual(s.arm.joint_limits, preset.joint_limits);
    assert.deepEqual(s.arm.rate_limits, preset.rate_limits);
    assert.deepEqual(s.theta0, preset.task.theta0, 'its own start pose');
    assert.deepEqual(s.target, preset.task.target, 'its own target');
    assert.equal(await page.inputValue('#arm-preset'), 'iiwa-planar');
    // Any change writes the arm back as its text with its limits: the same arm on reload.
    await page.selectOption('#mode', 'none');
    const q = await address(page);
    assert.equal(q.arm, s.arm_text);
    assert.ok(q.limits && q.rates, 'its limits written back');
    await page.reload();
    await page.waitForSelector('body[data-ready="true"]');
    const again = await state(page);
    assert.deepEqual(again.arm, s.arm);
    assert.deepEqual(again.target, s.target);
    clean(page);
    await page.close();
  });

  test('lab: the legend switches the manipulability and force ellipses, and the drawing changes', async () => {
    const page = await open('?task=1&method=numerical');
    await frame(page);
    for (const key of ['ellipse', 'force']) {
      assert.ok(await page.isVisible(`#legend li[data-key="${key}"]`), `${key}: listed`);
      assert.equal(await drawnBit(page, key), false, `${key}: off at first`);
    }
    const before = await page.locator('#stage').screenshot();
    await page.check('#legend input[data-toggle="ellipse"]');
    await frame(page);
    assert.ok(await drawnBit(page, 'ellipse'), 'drawn once on');
    const on = await page.locator('#stage').screenshot();
    assert.notDeepEqual(on, before, 'the drawing changed');
    await page.check('#legend input[data-toggle="force"]');
    await frame(page);
    assert.ok(await drawnBit(page, 'force'));
    await page.uncheck('#legend input[data-toggle="ellipse"]');
    await page.uncheck('#legend input[data-toggle="force"]');
    await frame(page);
    assert.equal(await drawnBit(page, 'ellipse'), false, 'off again');
    assert.equal(await drawnBit(page, 'force'), false);
    // The singular values: their product is the manipulability.
    const s = await state(page);
    const [a, b] = s.singular_values;
    assert.ok(a >= b && Math.abs(a * b - s.manipulability) < 1e-9, JSON.stringify(s.singular_values));
    assert.match(await page.textContent('[data-readout="sigma"]'), /^\d\.\d{3}, \d\.\d{3}$/);
    clean(page);
    await page.close();
  });

  for (const [name, viewport, shot] of [
    ['laptop', { width: 1366, height: 768 }, 'lab-limit-laptop.png'],
    ['phone', { width: 390, height: 844 }, 'lab-limit-phone.png'],
  ]) {
    test(`lab: a joint past its limit is named beside the drawing, with the ellipse (${name})`, async () => {
      // Limits tight around Task 1's start pose: its joints leave them.
      const first = await open('?task=1&method=none');
      const theta0 = (await state(first)).theta0;
      await first.close();
      const limits = theta0.map((t) => `${(t - 0.05).toFixed(4)}:${(t + 0.05).toFixed(4)}`).join(',');
      const page = await open(`?task=1&method=numerical&limits=${limits}`, { viewport });
      await page.evaluate(() => window.demo.runUntil(10));
      await page.check('#legend input[data-toggle="ellipse"]');
      await frame(page);
      const s = await state(page);
      assert.ok(s.limit_steps > 0, 'the run went past a limit');
      const note = page.locator('#limit-warning');
      assert.ok(await note.isVisible(), 'the note is shown');
      const text = await note.textContent();
      if (s.past_limits.length) assert.match(text, new RegExp(`Joint ${s.past_limits[0]} is past its limit \\(-?\\d+° to -?\\d+°\\)`), text);
      assert.match(text, new RegExp(`${s.limit_steps} steps of this run`), text);
      await page.screenshot({ path: join(shots, shot) });
      // Back inside, with no limits: no note.
      await page.click('#arm-panel summary');
      await page.fill('#arm-limits', '');
      await page.dispatchEvent('#arm-limits', 'change');
      await frame(page);
      assert.equal(await note.isVisible(), false);
      clean(page);
      await page.close();
    });
  }

  test('lab: the methods of the lab (manipulability, jointrange) are listed and run Task 1 in the page', async () => {
    const page = await open(`?task=1&limits=${LIMITS}`);
    const names = await page.$$eval('#mode option', (o) => o.map((x) => x.value));
    for (const m of ['manipulability', 'jointrange']) {
      assert.ok(names.includes(m), `${m} in the menu`);
      await page.selectOption('#mode', m);
      const s = await page.evaluate(() => window.demo.runUntil(10));
      assert.equal(s.method, m);
      assert.equal(s.error ?? null, null, `${m}: no error`);
      assert.ok(s.t >= 9.99, `${m}: ran to the end (${s.t})`);
      for (const v of [...s.theta, ...s.ee]) assert.ok(Number.isFinite(v));
      assert.ok(s.final_error < 0.05, `${m}: reached (${s.final_error})`);
    }
    clean(page);
    await page.close();
  });

  test('lab: the comparison table shows the steps past a joint limit where a method had any', async () => {
    const first = await open('?task=1&method=none');
    const theta0 = (await state(first)).theta0;
    await first.close();
    const limits = theta0.map((t) => `${(t - 0.05).toFixed(4)}:${(t + 0.05).toFixed(4)}`).join(',');
    const page = await open(`?task=1&method=numerical&limits=${limits}`);
    const rows = await page.evaluate(() => window.demo.controller.demo.compareMethods());
    assert.ok(rows.some((r) => r.summary?.limit_steps > 0), 'some method went past a limit');
    await page.click('#compare-panel summary');
    await page.click('#compare');
    await page.waitForSelector('#compare-body tr[data-limit-steps]', { timeout: 15000 });
    const shown = await page.$$eval('#compare-body tr[data-limit-steps]', (t) => t.map((r) => [r.dataset.method, Number(r.dataset.limitSteps), r.textContent]));
    for (const [m, n, text] of shown) {
      const r = rows.find((r) => r.method === m);
      assert.equal(n, r.summary.limit_steps, m);
      assert.match(text, new RegExp(`${n} steps? past a joint limit`), text);
    }
    clean(page);
    await page.close();
  });

  test('lab: the atlas legend lists the class of a joint past its limits only for an arm with limits', async () => {
    for (const [query, limited] of [['', false], [`&limits=${LIMITS}`, true]]) {
      const page = await open(`?task=1&method=numerical${query}`);
      await page.evaluate(() => window.demo.controller.demo.setRunning(false));
      await page.click('#atlas-panel summary');
      await page.selectOption('#atlas-n', '11');
      await page.click('#atlas-run');
      await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
      const keys = await page.$$eval('#atlas-legend li', (l) => l.map((li) => li.dataset.key));
      const classes = await page.evaluate(() => import('./module.js').then((m) => m.atlasClasses()));
      // A planar arm never self-collides: its legend leaves that class out.
      const expected = classes.filter((c) => (limited || !c.limits) && !c.self_collision).map((c) => c.name);
      assert.deepEqual(keys, expected, query || 'unlimited');
      assert.equal(keys.length, classes.length - (limited ? 0 : 1) - 1);
      clean(page);
      await page.close();
    }
  });
}
