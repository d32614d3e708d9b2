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

/** Every text the live region took, with when (ms since the page started), from now on. */
async function listen(page) {
  await page.evaluate(() => {
    window.__said = [];
    const region = document.getElementById('announcer');
    new MutationObserver(() => window.__said.push({ text: region.textContent, at: performance.now() })).observe(region, { childList: true, characterData: true, subtree: true });
  });
}
const said = (page) => page.evaluate(() => window.__said);

test('a11y: the live region says the first collision of a run, its end and result, a method switch, a task; the drawing has a text summary', async () => {
  const page = await open('?task=1', DESKTOP);
  const list = await page.evaluate(() => window.demo.methods());
  const bare = list.find((m) => m.group === 'paper' && !m.avoids);
  const exact = list.find((m) => m.group === 'paper' && m.avoids && !m.networks.phi && !m.networks.v);
  await page.selectOption('#mode', bare.name);
  await page.selectOption('#speed', '4');
  await listen(page);
  await page.click('#task1');
  await page.waitForFunction(() => window.demo.state().ended, null, { timeout: 20000 });
  await page.waitForFunction(() => window.__said.some((s) => s.text.includes('run ended')), null, { timeout: 5000 });
  // Said one after the other, or together where the end came within 1.5 s of the contact.
  const texts = (await said(page)).flatMap((s) => s.text.split('; '));
  console.log(`measure: heard: ${texts.join(' | ')}`);
  const hits = texts.filter((t) => t.startsWith('collision'));
  assert.equal(hits.length, 1, `the first contact only: ${texts.join(' | ')}`);
  assert.match(hits[0], /^collision: link [1-3] inside obstacle 1 at t = \d+\.\d s$/);
  const end = texts.find((t) => t.startsWith('run ended'));
  assert.match(end, /^run ended at t = 10\.0 s: the hand is .* from the target, smallest distance to an obstacle's centre \d\.\d{3} m, a link hit an obstacle$/);
  // The contact's time is the state's: the link was inside then.
  const s = await state(page);
  assert.equal(s.collided, true);
  // A method switch, then the drawing's summary names it.
  await page.waitForTimeout(1600);
  await page.selectOption('#mode', exact.name);
  await page.waitForFunction((l) => document.getElementById('announcer').textContent === `method: ${l}`, exact.label, { timeout: 3000 });
  const summary = await page.evaluate(() => {
    const canvas = document.getElementById('stage');
    return document.getElementById(canvas.getAttribute('aria-describedby')).textContent;
  });
  assert.match(summary, /^The drawing: a 3-link arm on a 0\.50 m post \(links 0\.60, 0\.85, 0\.60 m\); its hand follows a straight line to the target at \(0\.60, 0\.20\) m; 1 obstacle: 1 at \(.*\) m, radius 0\.05 m; method: /);
  assert.ok(summary.includes(`method: ${exact.label}`), summary);
  await page.evaluate(() => window.demo.addObstacle(1.2, 0.2, 0.1));
  await page.waitForFunction(() => document.getElementById('stage-summary').textContent.includes('2 obstacles'));
  clean(page);
  await page.close();
});

test('a11y: the live region says at most one thing every 1.5 s, the latest', async () => {
  const page = await open('?task=1', DESKTOP);
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
  const list = (await page.evaluate(() => window.demo.methods())).filter((m) => !m.networks.phi && !m.networks.v);
  await page.waitForTimeout(1600);
  await listen(page);
  for (const m of list.slice(0, 3)) await page.selectOption('#mode', m.name);
  await page.waitForTimeout(2000);
  const got = await said(page);
  assert.deepEqual(got.map((s) => s.text), [`method: ${list[0].label}`, `method: ${list[2].label}`], 'the first at once, the last after the gap, the one between dropped');
  const gap = got[1].at - got[0].at;
  assert.ok(gap >= 1450 && gap < 1900, `${gap} ms between them`);
  clean(page);
  await page.close();
});

