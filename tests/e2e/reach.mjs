// End-to-end tests of networks over the whole workspace (docs/learning.md): network sets, refinement, whole-reach training.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { here, shots, BASE, browser, test, open, clean, state, pause, selectMethod } from './harness.mjs';

// ---- networks over the whole workspace (docs/learning.md) ------------------

/** Moves a range input to `value` as a user does (input event). */
async function slide(page, selector, value) {
  await page.$eval(
    selector,
    (el, v) => {
      el.value = String(v);
      el.dispatchEvent(new Event('input', { bubbles: true }));
    },
    value,
  );
}

test('network sets: the whole-reach networks fetched when chosen, refined and drift-corrected Case 3 ends at the target, the URL keeps both', async () => {
  const page = await open('?task=1&method=case3');
  const fetched = [];
  page.on('request', (r) => r.url().includes('/weights/') && fetched.push(r.url().split('/').pop()));
  assert.equal(await page.isVisible('#network-set'), true, 'the selector shows for a method with networks');
  const options = await page.$$eval('#network-set option', (os) => os.map((o) => [o.value, o.disabled]));
  assert.deepEqual(options.map((o) => o[0]), ['paper', 'reach', 'own']);
  assert.equal((await state(page)).network_set, 'paper');
  await pause(page);
  await page.selectOption('#network-set', 'reach');
  await page.waitForFunction(() => window.demo.state().network_set === 'reach');
  assert.deepEqual(fetched.sort(), ['phi-reach.json', 'v-reach.json'], 'fetched when first chosen');
  const s = await state(page);
  assert.equal(s.trained_range.phi_variant, 'equivariant');
  assert.ok(s.trained_range.phi.names.includes('sin theta2'), 'angle features');
  // The refinement slider belongs to Case 3 (and Case 1), not to Case 2.
  await slide(page, '#param-refine', 2);
  await page.click('label[for="feedback"]');
  await page.click('#task1');
  await page.evaluate(() => window.demo.runUntil(10));
  const run = await state(page);
  assert.equal(run.params.refine, 2);
  assert.equal(run.collided, false);
  assert.ok(run.final_error < 5e-3, `final error ${run.final_error} m`);
  await page.screenshot({ path: join(shots, 'reach-set.png') });
  await selectMethod(page, 'case2');
  assert.equal(await page.$('#param-refine'), null, 'Case 2 runs the exact Φ: nothing to refine');
  await selectMethod(page, 'case3');
  assert.match(page.url(), /networks=reach/);
  assert.match(page.url(), /refine=2/);
  const copy = await open(page.url().slice(BASE.length));
  await copy.waitForFunction(() => window.demo.state().network_set === 'reach');
  const c = await state(copy);
  assert.equal(c.params.refine, 2);
  assert.equal(await copy.inputValue('#network-set'), 'reach');
  // Back to the paper's set: no new fetch, the paper's networks again.
  await page.selectOption('#network-set', 'paper');
  await page.waitForFunction(() => window.demo.state().network_set === 'paper');
  assert.equal(fetched.length, 2);
  clean(page);
  clean(copy);
  await page.close();
  await copy.close();
});

test('a network set that cannot be fetched: a readable message, the networks in use stay, a later try works', async () => {
  const page = await open('?task=1&method=case3');
  let block = true;
  await page.route('**/weights/v-reach.json', (route) => (block ? route.fulfill({ status: 404, body: 'gone' }) : route.continue()));
  await page.selectOption('#network-set', 'reach');
  await page.waitForFunction(() => !document.querySelector('#message').hidden && /could not/.test(document.querySelector('#message').textContent));
  assert.match(await page.textContent('#message'), /reach.*could not be loaded.*v-reach\.json.*404/);
  assert.equal((await state(page)).network_set, 'paper', 'the paper networks stay');
  assert.equal(await page.inputValue('#network-set'), 'paper');
  // A job in a worker that needs the set says why it cannot have it (the workers' module carries no weights).
  const why = await page.evaluate(() => window.demo.atlas({ methods: ['case3'], n: 3, networks: 'reach' }).then(() => null, (e) => e.message));
  assert.match(why ?? '', /networks not available: could not fetch weights\/v-reach\.json \(HTTP 404\)/);
  block = false;
  await page.selectOption('#network-set', 'reach');
  await page.waitForFunction(() => window.demo.state().network_set === 'reach');
  page.problems.splice(0); // the 404 is logged by the browser, as it should be
  clean(page);
  await page.close();
});

test('window.demo.simulate and atlas take refine, feedback and networks; bad values are refused with a reason', async () => {
  const page = await open('?task=1&method=case3&networks=reach');
  await page.waitForFunction(() => window.demo.state().network_set === 'reach');
  const runs = await page.evaluate(() => ({
    plain: window.demo.simulate({ method: 'case3' }),
    refined: window.demo.simulate({ method: 'case3', refine: 2, feedback: 1 }),
  }));
  assert.ok(runs.refined.final_error < 5e-3 && !runs.refined.collided, JSON.stringify(runs.refined));
  assert.ok(runs.plain.final_error > 10 * runs.refined.final_error, 'unrefined open loop drifts');
  for (const bad of [{ refine: 1.5 }, { refine: 9 }, { feedback: -1 }]) {
    const why = await page.evaluate((b) => {
      try {
        window.demo.simulate({ method: 'case3', ...b });
        return null;
      } catch (e) {
        return e.message;
      }
    }, bad);
    assert.match(why ?? '', /refine|feedback/, JSON.stringify(bad));
  }
  const atlas = await page.evaluate(() =>
    window.demo.atlas({ methods: ['numerical', 'case3'], n: 11, refine: 2, feedback: 1, networks: 'reach' }),
  );
  const a = atlas.summary.case3.agreement;
  assert.ok(a.both / (a.both + a.numerical_only) >= 0.95, JSON.stringify(a));
  const refused = await page.evaluate(() => window.demo.atlas({ methods: ['case3'], n: 5, networks: 'nope' }).then(() => null, (e) => e.message));
  assert.match(refused ?? '', /network set/);
  clean(page);
  await page.close();
});

test('a short whole-reach training in the page swaps angle-feature networks in', async () => {
  const page = await open('?task=1&method=case3');
  const report = await page.evaluate(() =>
    window.demo.train({ net: 'both', preset: 'reach', samples: 300, epochs: 15, seed: 1 }),
  );
  assert.ok(report.phi && report.v, 'both trained');
  // So short a training fails its own check: kept out until the user says
  // to use them anyway.
  if (!report.verdict.passed) {
    assert.equal((await state(page)).network_set, 'paper', 'the networks in use stay');
    await page.click('#verdict-use');
  }
  const s = await state(page);
  assert.equal(s.network_set, null, 'trained here, no shipped set');
  assert.ok(s.trained_range.phi.names.includes('sin theta2'));
  assert.equal(await page.inputValue('#network-set'), 'own');
  const files = await page.evaluate(() => window.demo.exportWeights());
  assert.equal(JSON.parse(files.phi).encoding, 'angles');
  assert.equal(JSON.parse(files.v).training.sampling.sign_smoothing, 0.1);
  clean(page);
  await page.close();
});
