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
import { browser, test, open, clean, state, shots, BASE, pause, axe, saidSoFar, said } from './harness.mjs';

const DESKTOP = { viewport: { width: 1366, height: 768 } };
const PHONE = { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true, deviceScaleFactor: 2 };

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

/** The texts the live region took from mark `from` on (harness.mjs, `listen`), with when (ms since the page started). */
const saidAt = (page, from) => page.evaluate((k) => window.__said.slice(k), from);

test('a11y: the live region says the first collision of a run, its end and result, a method switch, a task; the drawing has a text summary', async () => {
  const page = await open('?task=1', DESKTOP);
  const list = await page.evaluate(() => window.demo.methods());
  const bare = list.find((m) => m.group === 'paper' && !m.avoids);
  const exact = list.find((m) => m.group === 'paper' && m.avoids && !m.networks.phi && !m.networks.v);
  await page.selectOption('#mode', bare.name);
  await page.selectOption('#speed', '4');
  const from = await saidSoFar(page);
  await page.click('#task1');
  await page.waitForFunction(() => window.demo.state().ended, null, { timeout: 20000 });
  await page.waitForFunction(() => window.__said.some((s) => s.text.includes('run ended')), null, { timeout: 5000 });
  // Said one after the other, or together where the end came within 1.5 s of the contact.
  const texts = await said(page, from);
  console.log(`measure: heard: ${texts.join(' | ')}`);
  const hits = texts.filter((t) => t.startsWith('collision'));
  assert.equal(hits.length, 1, `the first contact only: ${texts.join(' | ')}`);
  assert.match(hits[0], /^collision: link [1-3] inside obstacle 1 at t = \d+\.\d s$/);
  const end = texts.find((t) => t.startsWith('run ended'));
  assert.match(end, /^run ended at t = 10\.0 s: the hand is .* from the target, smallest clearance to an obstacle -?\d\.\d{3} m, a link hit an obstacle$/);
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
  const mark = await saidSoFar(page);
  for (const m of list.slice(0, 3)) await page.selectOption('#mode', m.name);
  await page.waitForTimeout(2000);
  const got = await saidAt(page, mark);
  assert.deepEqual(got.map((s) => s.text), [`method: ${list[0].label}`, `method: ${list[2].label}`], 'the first at once, the last after the gap, the one between dropped');
  const gap = got[1].at - got[0].at;
  assert.ok(gap >= 1450 && gap < 1900, `${gap} ms between them`);
  clean(page);
  await page.close();
});

/** The boxes of every visible button, menu, check box's label and panel heading shorter than `min` px. */
const small = (page, min) =>
  page.evaluate((min) => {
    const targets = [...document.querySelectorAll('button, select, summary, label')].filter((e) => e.tagName !== 'LABEL' || e.querySelector('input[type="checkbox"]'));
    return targets
      .map((e) => ({ e, r: e.getBoundingClientRect() }))
      .filter(({ e, r }) => r.width > 0 && r.height > 0 && r.height < min - 0.5 && getComputedStyle(e).visibility !== 'hidden')
      .map(({ e, r }) => `${e.id || e.textContent.trim().slice(0, 24)} ${Math.round(r.height)} px`);
  }, min);

test('a11y: the phone: a one-line introduction with More, the plots right under the drawing, tap targets of 44 px', async () => {
  const page = await open('?task=1&method=case3', PHONE);
  const first = await page.evaluate(() => {
    const box = (sel) => document.querySelector(sel).getBoundingClientRect();
    return { short: box('.lede-short'), full: box('#lede-text'), line: parseFloat(getComputedStyle(document.querySelector('.lede')).lineHeight), stage: box('#stage'), card: box('.stage-card'), plots: box('.plots-card'), height: innerHeight };
  });
  assert.ok(first.short.height > 0 && first.short.height <= first.line + 1, `the lede is one line (${first.short.height} px of ${first.line})`);
  assert.equal(first.full.height, 0, 'the rest is behind More');
  assert.ok(first.stage.bottom <= first.height, `the drawing fits the first screen (ends at ${first.stage.bottom})`);
  assert.ok(first.plots.top - first.card.bottom <= 20 && first.plots.top < first.height, `the plots start ${first.plots.top - first.card.bottom} px under the drawing's card, at ${first.plots.top}`);
  await page.screenshot({ path: join(shots, 'a11y-phone.png') });
  await page.click('#lede-more');
  assert.ok((await page.locator('#lede-text').boundingBox()).height > 40, 'More shows the introduction');
  assert.equal(await page.getAttribute('#lede-more', 'aria-expanded'), 'true');
  // Every panel open, the tour too: nothing to tap is under 44 px.
  await page.click('#tour-open');
  const count = await page.evaluate(() => {
    const c = document.getElementById('tour-count');
    const range = document.createRange();
    range.selectNodeContents(c);
    const tops = new Set([...range.getClientRects()].map((r) => Math.round(r.top)));
    return { text: c.textContent, lines: tops.size };
  });
  assert.deepEqual(count, { text: '1 of 6', lines: 1 }, 'the count on one line');
  await page.evaluate(() => document.querySelectorAll('details').forEach((d) => (d.open = true)));
  await page.selectOption('#atlas-n', '11');
  await page.click('#atlas-run');
  await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
  assert.deepEqual(await small(page, 44), [], 'tap targets of at least 44 px');
  clean(page);
  await page.close();
});

test('a11y: at 150% zoom on 1366 x 768 the first screen shows the whole drawing', async () => {
  const page = await open('?task=1&method=case3', { viewport: { width: 911, height: 512 }, deviceScaleFactor: 1.5 });
  const r = await page.evaluate(() => ({ stage: document.getElementById('stage').getBoundingClientRect().toJSON(), height: innerHeight }));
  assert.ok(r.stage.bottom <= r.height && r.stage.height >= 200, `the drawing ${Math.round(r.stage.top)}-${Math.round(r.stage.bottom)} of ${r.height} px`);
  await page.screenshot({ path: join(shots, 'a11y-zoom150.png') });
  clean(page);
  await page.close();
});

test('a11y: the atlas table scrolls inside its panel, focusable, with a cue', async () => {
  const page = await open('?task=1&method=case3', DESKTOP);
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
  await page.click('#atlas-panel summary');
  await page.selectOption('#atlas-n', '11');
  await page.click('#atlas-run');
  await page.waitForSelector('#atlas-result:not([hidden])', { timeout: 60000 });
  const box = page.locator('#atlas-table-scroll');
  await box.scrollIntoViewIfNeeded();
  const before = await box.evaluate((e) => ({ scroll: e.scrollWidth, width: e.clientWidth, left: e.scrollLeft, tab: e.tabIndex, role: e.getAttribute('role'), label: e.getAttribute('aria-label') }));
  assert.ok(before.scroll > before.width, `it scrolls (${before.scroll} > ${before.width})`);
  assert.equal(before.tab, 0);
  assert.equal(before.role, 'region');
  assert.ok(before.label);
  await box.screenshot({ path: join(shots, 'a11y-atlas-table.png') });
  await box.focus();
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('End');
  await page.waitForTimeout(200);
  assert.ok((await box.evaluate((e) => e.scrollLeft)) > 0, 'the keyboard scrolls it');
  clean(page);
  await page.close();
});

test('a11y: projector mode: the header switch and projector=1, larger text; the element takes the attribute', async () => {
  const page = await open('?task=1&method=case3&projector=1', DESKTOP);
  const on = await page.evaluate(() => ({ attr: document.documentElement.hasAttribute('data-projector'), pressed: document.getElementById('projector').getAttribute('aria-pressed'), font: getComputedStyle(document.body).fontSize, label: getComputedStyle(document.querySelector('label[for="mode"]')).fontSize, url: location.search }));
  assert.deepEqual({ attr: on.attr, pressed: on.pressed }, { attr: true, pressed: 'true' });
  assert.ok(parseFloat(on.font) >= 18 && parseFloat(on.label) >= 18, `text ${on.font}, labels ${on.label}`);
  await page.screenshot({ path: join(shots, 'a11y-projector.png') });
  await page.click('#projector');
  const off = await page.evaluate(() => ({ attr: document.documentElement.hasAttribute('data-projector'), pressed: document.getElementById('projector').getAttribute('aria-pressed'), url: location.search, font: getComputedStyle(document.body).fontSize }));
  assert.deepEqual({ attr: off.attr, pressed: off.pressed, font: off.font }, { attr: false, pressed: 'false', font: '15px' });
  assert.ok(!off.url.includes('projector'), off.url);
  // The drawing's strokes and text grow too (the module's setProjector): more ink on the same frame.
  const ink = () =>
    page.evaluate(async () => {
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      const c = document.getElementById('stage');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 120 && d[i + 1] < 120) n++;
      return n;
    });
  await pause(page);
  await page.evaluate(() => window.demo.runUntil(3));
  const thin = await ink();
  await page.click('#projector');
  assert.ok((await page.evaluate(() => location.search)).includes('projector=1'));
  const thick = await ink();
  assert.ok(thick > 1.3 * thin, `the drawing's dark ink grows in projector mode: ${thin} -> ${thick} px`);
  clean(page);
  await page.close();
  // The element: the attribute, and a change of it later.
  const context = await browser.newContext(DESKTOP);
  const embed = await context.newPage();
  embed.problems = [];
  embed.on('console', (m) => m.type() === 'error' && embed.problems.push(`console error: ${m.text()}`));
  embed.on('pageerror', (e) => embed.problems.push(`page exception: ${e.message}`));
  await embed.goto(BASE + 'embed.html');
  await embed.waitForSelector('#right[data-ready="true"]', { timeout: 15000 });
  await embed.evaluate(() => document.getElementById('right').setAttribute('projector', '1'));
  await embed.waitForFunction(() => document.getElementById('right').hasAttribute('data-projector'));
  await embed.evaluate(() => document.getElementById('right').removeAttribute('projector'));
  await embed.waitForFunction(() => !document.getElementById('right').hasAttribute('data-projector'));
  clean(embed);
  await context.close();
});

test('a11y: reduced motion: the run waits for Play, no transitions', async () => {
  const page = await open('?task=1&method=case3&target=0.9,0.3', { ...DESKTOP, reducedMotion: 'reduce' });
  await page.waitForTimeout(600);
  const s = await state(page);
  assert.deepEqual({ running: s.running, t: s.t }, { running: false, t: 0 });
  assert.match(await page.textContent('#run-note'), /Ready at the start/);
  const motion = await page.evaluate(() => getComputedStyle(document.querySelector('.switch .track')).transitionDuration);
  assert.equal(motion, '0s');
  await page.click('#play');
  await page.waitForFunction(() => window.demo.state().t > 0);
  clean(page);
  await page.close();
});

test('a11y: networks swapped in after training restart the run on screen', async () => {
  const page = await open('?task=1&method=case3', DESKTOP);
  await page.evaluate(() => window.demo.runUntil(6));
  assert.ok((await state(page)).t >= 6);
  // A tiny training: whether or not it passes its check, the networks are put in use.
  const r = await page.evaluate(() => window.demo.train({ preset: 'quick', samples: 200, epochs: 2 }));
  if (!r.installed) await page.click('#verdict-use');
  const s = await state(page);
  assert.equal(s.network_set, null, 'the trained networks are in use');
  assert.ok(s.t < 1 && s.running, `the run restarted (t = ${s.t}, running ${s.running})`);
  assert.match(await page.textContent('#train-status'), /restarted/);
  clean(page);
  await page.close();
});

test('a11y: the element has the live region and the drawing summary too', async () => {
  const context = await browser.newContext(DESKTOP);
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(BASE + 'embed.html');
  await page.waitForSelector('#right[data-ready="true"]', { timeout: 15000 });
  const got = await page.evaluate(() => {
    const root = document.getElementById('right').shadowRoot;
    const canvas = root.getElementById('stage');
    return { summary: root.getElementById(canvas.getAttribute('aria-describedby'))?.textContent, region: root.getElementById('announcer')?.getAttribute('aria-live') };
  });
  assert.equal(got.region, 'polite');
  assert.match(got.summary ?? '', /^The drawing: a 3-link arm/);
  assert.deepEqual(problems, []);
  await context.close();
});

/** One finger from `a` to `b` (client px) through the DevTools protocol, optionally held still first. */
async function finger(page, a, b, { steps = 12, holdMs = 0 } = {}) {
  const cdp = await page.context().newCDPSession(page);
  const at = ([x, y]) => [{ x, y, id: 1, radiusX: 4, radiusY: 4, force: 1 }];
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: at(a) });
  if (holdMs) await page.waitForTimeout(holdMs);
  for (let i = 1; i <= steps && (a[0] !== b[0] || a[1] !== b[1]); i++) {
    const f = i / steps;
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: at([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]) });
  }
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await cdp.detach();
}

test('a11y: the phone: a swipe that starts on the empty drawing scrolls the page; one on the target drags it; a finger held on an atlas cell shows its numbers', async () => {
  const page = await open('?task=1&method=numerical', PHONE);
  await pause(page);
  const client = (p) => page.evaluate(([x, y]) => window.demo.worldToClient(x, y), p).then((c) => [c.x, c.y]);
  const view = () => page.evaluate(() => JSON.stringify(window.demo.controller.demo.worldToCanvas(0, 0)));
  // On nothing (left of the base, above the floor): the page scrolls, the view stays.
  const empty = await client([-1.6, 0.25]);
  const before = { view: await view(), target: (await state(page)).target };
  await finger(page, empty, [empty[0], empty[1] - 220]);
  await page.waitForTimeout(300);
  const scrolled = await page.evaluate(() => scrollY);
  assert.ok(scrolled > 100, `the page scrolled ${scrolled} px`);
  assert.equal(await view(), before.view, 'one finger on nothing does not pan the view');
  assert.deepEqual((await state(page)).target, before.target);
  // On the target: the target follows, the page stays.
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.waitForTimeout(100);
  const s = await state(page);
  const grab = await client(s.target);
  await finger(page, grab, [grab[0], grab[1] - 60]);
  await page.waitForTimeout(200);
  assert.equal(await page.evaluate(() => scrollY), 0, 'a drag does not scroll the page');
  assert.ok((await state(page)).target[1] > s.target[1] + 0.2, `the target moved up to ${(await state(page)).target}`);
  // Touch and hold on an atlas cell: the tip with that cell's numbers, and no obstacle moved; the next touch hides it.
  const atlas = await page.evaluate(() => window.demo.atlas({ methods: ['numerical'], n: 11 }));
  await page.evaluate(() => window.scrollTo(0, 0));
  const obstacle = (await state(page)).obstacle;
  const k = atlas.cells.findIndex((c) => c.x < -0.5 && c.y > 0.4 && c.y < 1.5);
  assert.ok(k >= 0, 'a cell left of the base');
  const cell = await client([atlas.cells[k].x, atlas.cells[k].y]);
  await finger(page, cell, cell, { holdMs: 900 });
  await page.waitForSelector('#atlas-tip:not([hidden])', { timeout: 3000 });
  assert.equal(await page.getAttribute('#atlas-tip', 'data-cell'), String(k));
  assert.match(await page.textContent('#atlas-tip'), /^obstacle at/);
  assert.deepEqual((await state(page)).obstacle, obstacle, 'a hold is not a tap: the obstacle stays');
  const inside = await page.evaluate(() => {
    const [t, s] = ['atlas-tip', 'stage'].map((id) => document.getElementById(id).getBoundingClientRect());
    return t.left >= s.left - 1 && t.right <= s.right + 1;
  });
  assert.ok(inside, 'the numbers stay within the drawing');
  await page.screenshot({ path: join(shots, 'a11y-phone-hold.png') });
  // (A tap: a finger that stays down 600 ms is a hold, so no moves that a loaded machine could stretch.)
  await finger(page, empty, empty);
  assert.equal(await page.isHidden('#atlas-tip'), true, 'the next touch hides the tip');
  clean(page);
  await page.close();
});

test('a11y: Save and share is one Tab stop (arrows move along it), and it does not move while a run plays', async () => {
  const page = await open('?task=1&method=qp&arm=iiwa-planar&obstacles=0.9,0.9,0.08;1.4,0.5,0.06&target=1.1,0.6&influence=0.25&weighting=wln&floor=1&path=circle:1.1,1.0&tf=6', DESKTOP);
  // Where the row's last button is, sampled while the run plays and ends (the notes beside the drawing come and go).
  const seen = new Set();
  for (let i = 0; i < 40 && seen.size < 4; i++) {
    seen.add(await page.evaluate(() => { const r = document.getElementById('embed-open').getBoundingClientRect(); return `${Math.round(r.x)},${Math.round(r.y + scrollY)}`; }));
    await page.waitForTimeout(200);
  }
  assert.equal((await state(page)).ended, true, 'the run ended while sampled');
  assert.equal(seen.size, 1, `the Embed button stayed put: ${[...seen].join(' ')}`);
  // Tab from the drawing: the row once, then the method menu within a few stops.
  await page.focus('#stage');
  const stops = [];
  for (let i = 0; i < 6 && stops.at(-1) !== 'mode'; i++) {
    await page.keyboard.press('Tab');
    stops.push(await page.evaluate(() => document.activeElement.id || document.activeElement.tagName));
  }
  assert.equal(stops.filter((id) => /^save-|^copy-link$|^embed-open$/.test(id)).length, 1, `one stop in the row: ${stops.join(' ')}`);
  assert.ok(stops.includes('mode'), `the method menu follows: ${stops.join(' ')}`);
  await page.focus('#save-figure-svg');
  await page.keyboard.press('ArrowRight');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'save-figure-png');
  await page.keyboard.press('End');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'embed-open');
  await page.keyboard.press('ArrowRight');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'save-figure-svg', 'the arrows wrap');
  // The button last used keeps the stop; Enter still does what it does.
  await page.keyboard.press('End');
  await page.focus('#mode');
  await page.keyboard.press('Shift+Tab');
  const back = [];
  for (let i = 0; i < 4 && back.at(-1) !== 'embed-open'; i++) {
    back.push(await page.evaluate(() => document.activeElement.id || document.activeElement.tagName));
    if (back.at(-1) !== 'embed-open') await page.keyboard.press('Shift+Tab');
  }
  assert.equal(back.at(-1), 'embed-open', `Shift+Tab comes back to the last used button: ${back.join(' ')}`);
  await page.keyboard.press('Enter');
  assert.equal(await page.isVisible('#embed-dialog'), true, 'Enter opens the dialog');
  await page.keyboard.press('Escape');
  clean(page);
  await page.close();
});
