// Accessibility (issue 27): axe-core (pinned in package-lock.json) over the
// page in each of its states (every panel open one at a time and all open,
// the tour, the Embed dialog, an atlas computed, a training run, embed=1) at
// 1366 x 768 and 390 x 844: no violation of impact serious or critical. Then
// what a screen reader hears (the live region: a collision, the run's end,
// a method switch, throttled; the drawing's text summary), the phone's
// first screen and tap targets, the first screen at 150% zoom, projector
// mode and reduced motion. Registered by e2e.mjs; screenshots
// a11y-phone.png, a11y-zoom150.png, a11y-projector.png, a11y-atlas-table.png.

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { createRequire } from 'node:module';
import { browser, test, open, clean, state, shots, BASE } from './harness.mjs';

const AXE = createRequire(import.meta.url).resolve('axe-core/axe.min.js');
const DESKTOP = { viewport: { width: 1366, height: 768 } };
const PHONE = { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, deviceScaleFactor: 2 };

/** axe's violations of impact serious or critical on `page` now, each as `rule (impact): where`. */
async function axe(page, where) {
  if (!(await page.evaluate(() => 'axe' in window))) await page.addScriptTag({ path: AXE });
  const found = await page.evaluate(async () => {
    const r = await window.axe.run(document, { resultTypes: ['violations'] });
    return r.violations
      .filter((v) => v.impact === 'serious' || v.impact === 'critical')
      .map((v) => `${v.id} (${v.impact}): ${v.nodes.slice(0, 4).map((n) => n.target.join(' ')).join(', ')}${v.nodes.length > 4 ? ` and ${v.nodes.length - 4} more` : ''}`);
  });
  return found.map((f) => `[${where}] ${f}`);
}

/** Every state of the page axe looks at, on a page opened with `options`; the violations found. */
async function axeStates(options, label) {
  const page = await open('?task=1&method=case3', options);
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
  const found = [...(await axe(page, `${label} closed`))];
  const panels = await page.evaluate(() => [...document.querySelectorAll('details')].map((d, i) => d.id || `details-${i}`));
  for (let i = 0; i < panels.length; i++) {
    await page.evaluate((i) => document.querySelectorAll('details').forEach((d, j) => (d.open = i === j)), i);
    found.push(...(await axe(page, `${label} ${panels[i]} open`)));
  }
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
  await page.click('#tour-open');
  found.push(...(await axe(page, `${label} all panels and the tour open`)));
  // An atlas computed, the comparison run, a short training (its report).
  await page.selectOption('#atlas-n', '11');
  await page.click('#atlas-run');
  await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
  await page.click('#compare');
  await page.waitForFunction(() => document.querySelectorAll('#compare-body tr').length > 0, null, { timeout: 60000 });
  found.push(...(await axe(page, `${label} atlas and comparison`)));
  await page.evaluate(() => window.demo.train({ preset: 'quick', samples: 200, epochs: 2 }).catch(() => {}));
  await page.waitForSelector('#train-report:not([hidden])', { timeout: 120000 });
  found.push(...(await axe(page, `${label} training report`)));
  await page.click('#embed-open');
  await page.waitForSelector('#embed-dialog[open]');
  found.push(...(await axe(page, `${label} Embed dialog`)));
  await page.keyboard.press('Escape');
  clean(page);
  await page.close();
  const embedded = await open('?task=1&method=case3&embed=1', options);
  found.push(...(await axe(embedded, `${label} embed=1`)));
  clean(embedded);
  await embedded.close();
  return found;
}

test('a11y: axe finds no serious or critical violation in any panel state, at 1366 x 768 and 390 x 844', async () => {
  const found = [...(await axeStates(DESKTOP, 'desktop')), ...(await axeStates(PHONE, 'phone'))];
  console.log(`measure: axe serious/critical violations: ${found.length}${found.map((f) => `\n  ${f}`).join('')}`);
  assert.deepEqual(found, [], found.join('\n'));
});
