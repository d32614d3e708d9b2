// End-to-end tests of the methods: every one selectable, the menu's groups, Task 1 and Task 2 in each.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { shots, test, open, clean, state, selectMethod, methodsOf, usesNetworks } from './harness.mjs';

test('every method is selectable', async () => {
  const page = await open('?task=1&method=numerical');
  // The page ships the networks: the paper's arm can run every method.
  assert.equal((await state(page)).networks, true, 'the built-in networks are there');
  const methods = await methodsOf(page);
  assert.ok(methods.length >= 5, `the paper's five methods at least: ${methods.map((m) => m.name)}`);
  assert.ok(methods.some(usesNetworks) && methods.some((m) => !usesNetworks(m)), 'methods with and without networks');
  for (const m of methods) {
    await selectMethod(page, m.name);
    const s = await state(page);
    assert.equal(s.method, m.name);
    assert.equal(await page.inputValue('#mode'), m.name);
    assert.deepEqual(s.uses, m.networks, `${m.name}: the state says which networks it uses`);
    await page.evaluate(() => window.demo.runUntil(window.demo.state().t + 1));
    const after = await state(page);
    assert.equal(after.error, null, `${m.name}: steps without error`);
    // A method with networks is compared with the numerical ghost; one without has none.
    assert.equal(Boolean(after.ghost), usesNetworks(m), `${m.name}: ghost arm ${after.ghost ? 'present' : 'absent'}`);
  }
  clean(page);
  await page.close();
});

test("the menu groups the paper's methods and those beyond it; each runs Task 1", async () => {
  const page = await open('?task=1&method=numerical');
  const methods = await methodsOf(page);
  const groups = await page.$$eval('#mode optgroup', (gs) => gs.map((g) => ({ label: g.label, names: [...g.querySelectorAll('option')].map((o) => o.value) })));
  assert.deepEqual(groups.map((g) => g.label), ['The paper', 'Beyond the paper']);
  assert.deepEqual(groups.flatMap((g) => g.names), methods.map((m) => m.name), 'every method once, in menu order');
  assert.deepEqual(groups[0].names, methods.filter((m) => m.group === 'paper').map((m) => m.name));
  assert.ok(groups[1].names.length >= 3, `distance, priority and qp at least: ${groups[1].names}`);
  const outcomes = [];
  for (const m of methods) {
    await selectMethod(page, m.name);
    await page.click('#task1');
    const s = await page.evaluate(() => window.demo.runUntil(10));
    assert.equal(s.error, null, `${m.name}: Task 1 runs`);
    assert.ok(Math.abs(s.t - 10) < 1e-9, `${m.name}: to its end`);
    // Every method that avoids keeps Task 1's arm clear of its obstacle.
    assert.equal(s.collided, !m.avoids, `${m.name}: ${s.collided ? 'collided' : 'clear'}`);
    outcomes.push(`${m.name} ${s.min_distance.toFixed(3)} m, ${(s.final_error * 1000).toFixed(2)} mm`);
    // The sliders of the method's own parameters (beyond λ and δ, and
    // the self-collision dampers' gains, which act only where the page
    // cannot yet switch self-collision on: www/method-params.js).
    const sliders = await page.$$eval('#method-params [data-param]', (fs) => fs.map((f) => f.dataset.param));
    const noSlider = ['lambda', 'delta', 'self_influence', 'self_stop_distance', 'self_damper_gain'];
    assert.deepEqual(sliders, m.params.filter((p) => !noSlider.includes(p)), `${m.name}: its parameters`);
  }
  console.log(`measure: Task 1 in the page: ${outcomes.join('; ')}`);
  // A parameter set on its slider reaches the planner; a refused one changes nothing.
  await selectMethod(page, 'qp');
  await page.fill('#param-influence', '0.2');
  await page.dispatchEvent('#param-influence', 'input');
  assert.equal((await state(page)).params.influence, 0.2);
  const refused = await page.evaluate(() => {
    try {
      window.demo.controller.demo.setParam('stop_distance', 0.5);
      return null;
    } catch (e) {
      return e.message;
    }
  });
  assert.match(refused, /stop distance/);
  assert.equal((await state(page)).params.stop_distance, 0.02);
  await page.screenshot({ path: join(shots, 'qp-dampers.png') });
  clean(page);
  await page.close();
});

for (const task of [1, 2]) {
  test(`#task${task}: collides without avoidance, not with it`, async () => {
    const page = await open('?task=1&method=numerical');
    await selectMethod(page, 'none');
    await page.click(`#task${task}`);
    await page.evaluate(() => window.demo.runUntil(10));
    const none = await state(page);
    assert.equal(none.task, task);
    assert.ok(Math.abs(none.t - 10) < 1e-9, `ran to t = 10 (t = ${none.t})`);
    assert.equal(none.collided, true, `method none collides (min distance ${none.min_distance})`);
    assert.equal(none.running, false, 'the task run stops at t = 10');
    await page.screenshot({ path: join(shots, `task${task}-none.png`) });

    await selectMethod(page, 'numerical');
    // The state in the same task as the click: on a busy machine the
    // animation could run on before a later read (CI saw t = 0.8).
    const fresh = await page.evaluate((id) => {
      document.getElementById(id).click();
      return window.demo.state();
    }, `task${task}`);
    assert.equal(fresh.t, 0, `the task restarts from t = 0 (t = ${fresh.t})`);
    assert.equal(fresh.collided, false, 'loading the task clears the collision flag');
    assert.equal(fresh.method, 'numerical', 'the task keeps the method');
    await page.evaluate(() => window.demo.runUntil(10));
    const num = await state(page);
    assert.equal(num.collided, false, `numerical avoids (min distance ${num.min_distance})`);
    const paper = task === 1 ? 0.2345 : 0.2193;
    assert.ok(Math.abs(num.min_distance - paper) < 2e-3, `min distance ${num.min_distance} matches ${paper}`);
    assert.ok(num.final_error < 1e-4, `reaches the target (${num.final_error})`);
    await page.screenshot({ path: join(shots, `task${task}-numerical.png`) });
    clean(page);
    await page.close();
  });
}
