// The arm's joint limits on the page: the address's limits= and rates= in
// the command line's syntax (read and written by the module), the arm
// designer's two fields (checked by the core, refusals next to the field,
// nothing changed), and each joint's range drawn (its legend entry shown
// only then). Registered by e2e.mjs with its helpers.

import { join } from 'node:path';
import assert from 'node:assert/strict';

const LIMITS = '-2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944';

export function limitsTests(h) {
  const { test, open, clean, state, shots } = h;
  const frame = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const legendShown = (page) => page.evaluate(() => !document.querySelector('#legend li[data-key="limits"]')?.hidden);
  const address = (page) => page.evaluate(() => Object.fromEntries(new URLSearchParams(location.search)));

  test('limits: the address carries the arm\'s limits in the command line\'s syntax, the designer shows them and the drawing their ranges', async () => {
    const page = await open(`?task=2&method=numerical&limits=${LIMITS}&rates=1.5,1.5,2`);
    const s = await state(page);
    assert.deepEqual(s.arm.joint_limits, [[-2.0944, 2.0944], [-2.0944, 2.0944], [-2.0944, 2.0944]]);
    assert.deepEqual(s.arm.rate_limits, [1.5, 1.5, 2]);
    assert.equal(s.task, 2, "Task 2's scene stays");
    assert.equal(await page.inputValue('#arm-limits'), LIMITS);
    assert.equal(await page.inputValue('#arm-rates'), '1.5,1.5,2');
    await frame(page);
    assert.ok(await legendShown(page), 'the ranges are drawn and in the legend');
    await page.locator('#stage').screenshot({ path: join(shots, 'limits.png') });
    const q = await address(page);
    assert.equal(q.limits, LIMITS, 'written back as read');
    assert.equal(q.rates, '1.5,1.5,2');
    clean(page);
    await page.close();
  });

  test('limits: the designer\'s fields set and clear the limits; the core refuses bad ones next to the field, changing nothing', async () => {
    const page = await open('?task=1&method=numerical');
    await frame(page);
    assert.equal(await legendShown(page), false, 'no limits, no ranges drawn');
    assert.equal((await address(page)).limits, undefined);
    await page.click('#arm-panel summary');
    const set = async (id, text) => {
      await page.fill(id, text);
      await page.dispatchEvent(id, 'change');
    };
    for (const [id, text, why] of [
      ['#arm-limits', '-1:1,-1:1,-1:1', /start pose theta0: theta_2 \(joint 2's limits\) must lie between -1 and 1/],
      ['#arm-limits', '1:-1,-2:2,-2:2', /joint 1's limits 1:-1 are empty/],
      ['#arm-limits', '-2:2,-2:2', /joint limits has 2 entries, expected 3/],
      ['#arm-limits', 'nan:1,-2:2,-2:2', /not a finite number/],
      ['#arm-rates', '1,0,1', /rate limit of joint 2 must be positive/],
    ]) {
      await set(id, text);
      const message = page.locator('#message');
      assert.ok(await message.isVisible(), `${text}: a message`);
      assert.match(await message.textContent(), why, text);
      const placed = await page.evaluate(() => document.querySelector('#message').previousElementSibling?.contains(document.querySelector('#arm-limits')));
      assert.ok(placed, `${text}: the message is next to the fields`);
      const s = await state(page);
      assert.equal(s.arm.joint_limits ?? null, null, `${text}: nothing changed`);
      assert.equal(s.arm.rate_limits ?? null, null, `${text}: nothing changed`);
      await page.fill('#arm-limits', '');
      await page.fill('#arm-rates', '');
    }
    await set('#arm-limits', LIMITS);
    assert.deepEqual((await state(page)).arm.joint_limits[1], [-2.0944, 2.0944]);
    await frame(page);
    assert.ok(await legendShown(page));
    assert.equal((await address(page)).limits, LIMITS);
    // Another length keeps the limits; blank clears them.
    await page.fill('#arm-post', '0.45');
    await page.dispatchEvent('#arm-post', 'change');
    assert.equal((await state(page)).arm.joint_limits.length, 3, 'the limits stay with other lengths');
    await set('#arm-limits', '');
    assert.equal((await state(page)).arm.joint_limits ?? null, null);
    await frame(page);
    assert.equal(await legendShown(page), false);
    assert.equal((await address(page)).limits, undefined);
    await page.close();
  });

  test('limits: limits in the address that do not parse are named, and the page starts unlimited', async () => {
    const page = await open('?task=1&limits=1:-1,-1:1,-1:1&rates=1,abc,1');
    const text = await page.locator('#message').textContent();
    assert.match(text, /^Ignored in the address: /, text);
    assert.match(text, /limits: joint limits '1:-1,-1:1,-1:1': joint 1's limits 1:-1 are empty/, text);
    assert.match(text, /rates: rate limits '1,abc,1': 'abc' is not a finite number/, text);
    const s = await state(page);
    assert.equal(s.arm.joint_limits ?? null, null);
    assert.equal(s.arm.rate_limits ?? null, null);
    await page.close();
  });
}
