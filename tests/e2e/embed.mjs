// Embedding from the page (issue 26, part 3): the <redundant-ik-demo>
// element takes every key of the page's address as an attribute (the same
// state as the page opened with that address; attributes changed later
// change the running demo; a bad one is named and the rest runs); the Embed
// dialog's two snippets reproduce the scene (the iframe with embed=1, the
// element on a blank page); a course page on another origin shows the
// element's fallback text where the server sends no CORS header and runs
// where it does; a module that cannot be fetched is said in the element;
// index.html and embed.html opened from file:// say how to serve them;
// embed=1 shows the stage and the essential controls only, nothing hidden
// focusable, at 390 px without sideways scroll. Registered by e2e.mjs;
// screenshots embed-dialog.png, embed-mode.png, embed-mode-phone.png,
// embed-fallback.png, embed-load-failed.png, embed-file.png.

import { join } from 'node:path';
import { mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import assert from 'node:assert/strict';
import { browser, test, open, clean, state, shots, BASE, here, textMatching } from './harness.mjs';
import { serve } from './serve.mjs';

/** What a scene is (the settings an address or attributes give), not where the run is. */
const scene = (s) => ({
  task: s.task,
  method: s.method,
  lambda: s.lambda,
  feedback: s.feedback,
  damping: s.damping,
  weighting: s.weighting,
  floor: s.floor,
  precision: s.precision,
  arm: s.arm_text,
  limits: s.arm.joint_limits,
  rates: s.arm.rate_limits,
  obstacles: s.obstacles,
  target: s.target,
  path: s.path,
  params: s.params,
  network_set: s.network_set,
  own_start: s.own_start,
  theta0: s.theta0,
  tf: s.tf,
});

/** A page that records console errors and exceptions, without waiting for the full page's data-ready. */
async function blank(contextOptions = {}) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, ...contextOptions });
  const page = await context.newPage();
  page.problems = [];
  page.on('console', (m) => m.type() === 'error' && page.problems.push(`console error: ${m.text()}`));
  page.on('pageerror', (e) => page.problems.push(`page exception: ${e.message}`));
  page.on('close', () => context.close().catch(() => {}));
  return page;
}

/** HTML of a page that holds `body` (a course page). */
const course = (body) => `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>A course page</title></head><body><h1>A course page</h1>${body}</body></html>`;

/** Serves `html` at `url` for `page` (a page of any origin, through Playwright's router). */
async function serveAt(page, url, html) {
  await page.route(url, (route) => route.fulfill({ status: 200, contentType: 'text/html; charset=utf-8', body: html }));
}

/**
 * Whether the light-DOM text `words` inside an element is drawn (a box on
 * screen): Playwright's isVisible() asks about the text's element, the
 * host, which shows either way.
 */
const drawn = (page, words) =>
  page.evaluate((words) => {
    const walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    for (let n = walk.nextNode(); n; n = walk.nextNode()) {
      if (!n.textContent.includes(words)) continue;
      const range = document.createRange();
      range.selectNodeContents(n);
      if ([...range.getClientRects()].some((r) => r.width > 0 && r.height > 0)) return true;
    }
    return false;
  }, words);

/** The element's state once ready. */
const elementState = (page, id) => page.evaluate((id) => document.getElementById(id).controller.state(), id);
const ready = (page, id) => page.waitForSelector(`#${id}[data-ready="true"]`, { timeout: 20000 });

/** Attributes of an element from an address's query. */
const attributes = (query) =>
  [...new URLSearchParams(query)].map(([k, v]) => `${k}="${v.replace(/&/g, '&amp;').replace(/"/g, '&quot;')}"`).join(' ');

/** Waits until the state `pick` of `read()` holds (a shipped set fetched, a change applied). */
async function until(read, ok, what) {
  for (let i = 0; i < 100; i++) {
    const s = await read();
    if (ok(s)) return s;
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error(`timed out waiting for ${what}`);
}

/** The two scenes of the tests: the lab's arm with every switch, and the paper's arm with the reach networks. */
async function scenes() {
  const first = await open('?arm=iiwa-planar');
  const theta0 = (await state(first)).theta0.map((t) => (t + 0.05).toFixed(4)).join(',');
  await first.close();
  return [
    `task=1&method=qp&arm=iiwa-planar&obstacles=0.9,0.9,0.08;1.4,0.5,0.06&target=1.1,0.6&influence=0.25&weighting=wln&floor=1&path=circle:1.1,1.0&theta0=${theta0}&tf=6`,
    'task=2&method=case3&lambda=5&obstacle=0.95,0.75&networks=reach&precision=f32&feedback=1&damping=0&refine=1',
  ];
}

test('embed: the element with every setting has the page\'s state for the same address; attributes changed later change it; a bad one is named and the rest runs', async () => {
  const queries = await scenes();
  const page = await blank();
  await page.goto(BASE + 'embed.html');
  for (const [i, q] of queries.entries()) {
    const full = await open(`?${q}`);
    const want = await until(() => state(full), (s) => !q.includes('networks=') || s.network_set === 'reach', 'the page to fetch the reach set');
    // No problem with the address (the circle leaves the iiwa's reach, which the page says).
    const said = await full.evaluate(() => { const m = document.getElementById('message'); return m.hidden ? '' : m.textContent; });
    assert.ok(said === '' || /^The path leaves the arm's reach/.test(said), `the page took the whole address ${q}: ${said}`);
    clean(full);
    await full.close();
    await page.evaluate(([i, a]) => document.body.insertAdjacentHTML('beforeend', `<redundant-ik-demo id="e${i}" ${a}>fallback ${i}</redundant-ik-demo>`), [i, attributes(q)]);
    await ready(page, `e${i}`);
    const got = await until(() => elementState(page, `e${i}`), (s) => !q.includes('networks=') || s.network_set === 'reach', 'the element to fetch the reach set');
    assert.deepEqual(scene(got), scene(want), `the element has the page's scene for ${q}`);
    const message = page.locator(`#e${i}`).locator('#message');
    assert.ok((await message.isHidden()) || /^The path leaves the arm's reach/.test(await message.textContent()), 'no problem shown');
    assert.equal(await drawn(page, `fallback ${i}`), false, 'the shadow root hides the fallback text');
  }
  // Changed after ready: applied to the running demo, the module not reloaded.
  const arm = (await elementState(page, 'e0')).arm_text;
  const loads = [];
  page.on('request', (r) => r.url().endsWith('.wasm') && loads.push(r.url()));
  await page.evaluate(() => {
    const e = document.getElementById('e0');
    e.setAttribute('method', 'numerical');
    e.setAttribute('weighting', 'none');
    e.removeAttribute('floor');
    e.setAttribute('influence', '0.35');
    e.setAttribute('lambda', '6');
    e.setAttribute('path', 'line');
  });
  const changed = await until(() => elementState(page, 'e0'), (s) => s.method === 'numerical' && s.lambda === 6, 'the changes to apply');
  assert.equal(changed.weighting, 'none');
  assert.equal(changed.floor, false, 'floor removed: back to its default');
  assert.equal(changed.params.influence, 0.35);
  assert.ok(!changed.path, `back on the line (path ${changed.path})`);
  assert.equal(changed.arm_text, arm, 'the arm stays');
  await page.evaluate(() => document.getElementById('e1').setAttribute('task', '1'));
  const task1 = await until(() => elementState(page, 'e1'), (s) => s.task === 1, 'the task to change');
  assert.equal(task1.method, 'case3', 'the other attributes hold over the new task');
  assert.equal(task1.lambda, 5);
  assert.deepEqual(loads, [], 'no module fetched again');
  // A bad attribute is named in the element; the rest runs.
  await page.evaluate(() =>
    document.body.insertAdjacentHTML('beforeend', '<redundant-ik-demo id="bad" task="2" method="numerical" lambda="lots" weighting="wln" target="1,2,3">fallback</redundant-ik-demo>'),
  );
  await ready(page, 'bad');
  const message = await page.locator('#bad').locator('#message').textContent();
  assert.match(message, /lambda: expected a number, got 'lots'/);
  assert.match(message, /target: expected two numbers x,y, got '1,2,3'/);
  const bad = await elementState(page, 'bad');
  assert.equal(bad.task, 2);
  assert.equal(bad.method, 'numerical');
  assert.equal(bad.weighting, 'wln', 'the attributes that parse apply');
  await page.evaluate(() => document.getElementById('bad').setAttribute('method', '<b>nope</b>'));
  await until(() => page.locator('#bad').locator('#message').textContent(), (t) => /method: unknown method '<b>nope<\/b>'/.test(t), 'the bad method to be named');
  assert.equal((await elementState(page, 'bad')).method, 'numerical', 'the method stays');
  // A megabyte of markup: named in a few words, nothing thrown.
  await page.evaluate(() => document.getElementById('bad').setAttribute('obstacles', '<img src=x onerror=alert(1)>'.repeat(40000)));
  const long = await until(() => page.locator('#bad').locator('#message').textContent(), (t) => /obstacles:/.test(t), 'the long attribute to be named');
  assert.ok(long.length < 600, `a short message (${long.length} characters)`);
  assert.equal(await page.locator('#bad').locator('img').count(), 0, 'no markup made');
  await page.evaluate(() => document.getElementById('bad').removeAttribute('obstacles'));
  await page.evaluate(() => document.getElementById('bad').setAttribute('lambda', '3'));
  await page.evaluate(() => document.getElementById('bad').removeAttribute('target'));
  await page.evaluate(() => document.getElementById('bad').setAttribute('method', 'qp'));
  const fixed = await until(() => elementState(page, 'bad'), (s) => s.method === 'qp' && s.lambda === 3, 'the fixed attributes');
  assert.ok(fixed, 'fixed attributes apply');
  assert.equal(await page.locator('#bad').locator('#message').isHidden(), true, `no problem left to show: ${await page.locator('#bad').locator('#message').textContent()}`);
  // The methods listed in embed.html are the module's.
  const listed = await page.$$eval('#method-list code', (cs) => cs.map((c) => c.textContent));
  assert.deepEqual(listed, await page.evaluate(async () => (await import('./module.js')).methods().map((m) => m.name)));
  clean(page);
  await page.close();
});

test('embed: an element taken off the page stops its clock, a planar arm\'s and the Panda\'s', async () => {
  const page = await blank();
  await page.goto(BASE + 'embed.html');
  for (const [id, attrs] of [['gone-plane', 'task="1" method="numerical" autoplay="0"'], ['gone-space', 'arm="panda" method="numerical" autoplay="0"']]) {
    await page.evaluate(([id, a]) => document.body.insertAdjacentHTML('beforeend', `<redundant-ik-demo id="${id}" ${a}>fallback</redundant-ik-demo>`), [id, attrs]);
    await ready(page, id);
    await page.evaluate((id) => document.getElementById(id).controller.demo.setRunning(true), id);
    const t = () => page.evaluate((id) => (window.__kept?.[id] ?? document.getElementById(id).controller).state().t, id);
    const start = await t();
    await page.waitForFunction(([id, t0]) => document.getElementById(id).controller.state().t > t0, [id, start], { timeout: 10000 });
    // Off the page: its controller kept aside, the clock must not move.
    await page.evaluate((id) => {
      const e = document.getElementById(id);
      window.__kept = { ...window.__kept, [id]: e.controller };
      e.remove();
    }, id);
    const removed = await t();
    await page.evaluate(() => new Promise((r) => setTimeout(r, 400)));
    assert.equal(await t(), removed, `${id}: no frame ran after the element left the page`);
  }
  clean(page);
  await page.close();
});

test('embed: the Embed button shows an iframe and an element of the scene, each reproduces it', async () => {
  const [q] = await scenes();
  const page = await open(`?${q}`);
  const want = await state(page);
  await page.click('#embed-open');
  const dialog = page.locator('#embed-dialog');
  assert.ok(await dialog.isVisible(), 'the dialog opens');
  assert.equal(await dialog.getAttribute('aria-labelledby'), 'embed-title');
  assert.equal(await page.evaluate(() => document.getElementById('embed-dialog').contains(document.activeElement)), true, 'the focus is in the dialog');
  const iframe = await page.inputValue('#embed-iframe');
  const element = await page.inputValue('#embed-element');
  // The arm as its text (the address's form), with the preset's limits.
  const arm = want.arm_text;
  for (const key of [`arm=${encodeURIComponent(arm)}`, 'limits=', 'weighting=wln', 'floor=1', 'influence=0.25', 'theta0=', 'embed=1']) assert.ok(iframe.includes(key), `the iframe has ${key}: ${iframe}`);
  for (const key of [`arm="${arm}"`, 'limits="', 'weighting="wln"', 'floor="1"', 'influence="0.25"', 'method="qp"', 'path="circle:1.1,1"']) assert.ok(element.includes(key), `the element has ${key}: ${element}`);
  assert.match(iframe, /loading="lazy"/);
  assert.match(iframe, /title="/);
  assert.match(element, new RegExp(`<script type="module" src="${BASE}redundant-ik-demo.js"></script>`));
  assert.match(element, /If this text stays/);
  await page.screenshot({ path: join(shots, 'embed-dialog.png') });
  await page.click('#embed-iframe-copy');
  await textMatching(page, '#embed-status', /iframe/);
  await page.keyboard.press('Escape');
  assert.equal(await dialog.isVisible(), false, 'Escape closes');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'embed-open', 'the focus goes back to the button');
  clean(page);
  await page.close();

  // The iframe's src, opened: the scene in embed mode.
  const src = iframe.match(/src="([^"]*)"/)[1].replace(/&amp;/g, '&');
  const framed = await blank();
  await framed.goto(src);
  await framed.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  assert.deepEqual(scene(await state(framed)), scene(want), 'the iframe shows the scene');
  assert.equal(await framed.isVisible('.masthead'), false, 'embed mode: no header');
  clean(framed);
  // In an iframe of a course page, too.
  await serveAt(framed, BASE + 'course-iframe.html', course(iframe));
  await framed.goto(BASE + 'course-iframe.html');
  const inner = framed.frameLocator('iframe');
  await inner.locator('body[data-ready="true"]').waitFor({ timeout: 15000 });
  assert.equal(await inner.locator('#play').isVisible(), true);
  clean(framed);
  await framed.close();

  // The element's snippet, pasted into a blank page of the same server.
  const blankPage = await blank();
  await serveAt(blankPage, BASE + 'course-element.html', course(element.replace('<redundant-ik-demo ', '<redundant-ik-demo id="pasted" ')));
  await blankPage.goto(BASE + 'course-element.html');
  await ready(blankPage, 'pasted');
  assert.deepEqual(scene(await elementState(blankPage, 'pasted')), scene(want), 'the element shows the scene');
  assert.equal(await drawn(blankPage, 'If this text stays'), false, 'the fallback text hides once the element runs');
  clean(blankPage);
  await blankPage.close();
});


test('embed: a course page on another origin shows the fallback text without CORS and runs the element with it; a module that cannot be fetched is said', async () => {
  // The course pages, served on a port of their own (another origin than www/'s).
  const dir = mkdtempSync(join(tmpdir(), 'course-'));
  const snippet = (base) =>
    `<script type="module" src="${base}redundant-ik-demo.js"></script>` +
    `<redundant-ik-demo id="far" task="1" method="numerical">If this text stays, the demo's script could not load: its server must send Access-Control-Allow-Origin.</redundant-ik-demo>`;
  const www = join(here, '../../www');
  const [site, cors] = await Promise.all([serve(dir), serve(www, ['--cors'])]);
  try {
    writeFileSync(join(dir, 'plain.html'), course(snippet(BASE)));
    writeFileSync(join(dir, 'cors.html'), course(snippet(cors.url)));
    const page = await blank();
    await page.goto(site.url + 'plain.html');
    await page.waitForTimeout(1500);
    assert.equal(await drawn(page, 'If this text stays'), true, 'without CORS: the fallback text shows');
    assert.equal(await page.evaluate(() => Boolean(customElements.get('redundant-ik-demo'))), false, 'nothing of ours ran');
    assert.ok(page.problems.some((p) => /CORS/.test(p)), `blocked by CORS: ${page.problems.join(' | ')}`);
    await page.screenshot({ path: join(shots, 'embed-fallback.png') });
    await page.close();

    const page2 = await blank();
    await page2.goto(site.url + 'cors.html');
    await ready(page2, 'far');
    assert.equal((await elementState(page2, 'far')).method, 'numerical', 'with CORS: the element runs');
    assert.equal(await drawn(page2, 'If this text stays'), false, 'with CORS: the fallback text hides');
    clean(page2);
    await page2.close();
  } finally {
    site.stop();
    cors.stop();
    rmSync(dir, { recursive: true, force: true });
  }

  // The element's script runs but its module cannot be fetched: said in the element.
  const page3 = await blank();
  await page3.route('**/pkg/*.wasm', (route) => route.fulfill({ status: 404, body: 'not here' }));
  await page3.goto(BASE + 'embed.html');
  const box = page3.locator('#left').locator('#loading');
  await until(() => box.getAttribute('class'), (c) => c === 'failed', 'the loading box to fail');
  const text = await box.textContent();
  assert.match(text, /could not load its files from http:\/\/127\.0\.0\.1:\d+\//);
  assert.match(text, /Access-Control-Allow-Origin/);
  assert.match(text, /application\/wasm/);
  assert.equal(page3.problems.filter((p) => p.startsWith('page exception')).length, 0, 'handled, not thrown');
  await page3.screenshot({ path: join(shots, 'embed-load-failed.png') });
  await page3.close();
});

test('embed: index.html and embed.html opened from file:// say how to serve them', async () => {
  const page = await blank();
  await page.goto('file://' + join(here, '../../www/index.html'));
  const text = await page.textContent('#loading-text');
  assert.match(text, /python3 -m http\.server/);
  assert.match(text, /redundant-ik\.html/);
  assert.doesNotMatch(text, /Loading/);
  await page.screenshot({ path: join(shots, 'embed-file.png') });
  await page.goto('file://' + join(here, '../../www/embed.html'));
  assert.ok(await page.isVisible('#file-note'));
  assert.match(await page.textContent('#file-note'), /python3 -m http\.server/);
  await page.close();
});

test('embed: embed=1 shows the stage and the essential controls, nothing hidden is focusable, 390 px without sideways scroll', async () => {
  const page = await open('?task=2&method=numerical&embed=1');
  for (const id of ['stage', 'mode', 'play', 'reset']) assert.ok(await page.isVisible(`#${id}`), `#${id} shows`);
  assert.ok(await page.isVisible('[data-readout="clearance"]'), 'the readouts show');
  for (const sel of ['.masthead', '.explain', '.foot', '#takeaway', '#plots', '#lambda', '#step', '#task1', '#arm-panel', '#tour-open'])
    assert.equal(await page.isVisible(sel), false, `${sel} is hidden`);
  // Every stop of the Tab key is visible.
  const stops = [];
  for (let i = 0; i < 25; i++) {
    await page.keyboard.press('Tab');
    stops.push(await page.evaluate(() => {
      const a = document.activeElement;
      return { id: a.id || a.tagName, visible: a === document.body || a.checkVisibility() };
    }));
  }
  assert.deepEqual(stops.filter((s) => !s.visible), [], `only what shows takes the focus: ${stops.map((s) => s.id).join(' ')}`);
  // A change keeps embed=1 in the address.
  await page.selectOption('#mode', 'qp');
  assert.equal(await page.evaluate(() => new URLSearchParams(location.search).get('embed')), '1');
  await page.screenshot({ path: join(shots, 'embed-mode.png') });
  await page.setViewportSize({ width: 390, height: 844 });
  await page.waitForTimeout(300);
  const wide = await page.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(wide <= 390, `scrollWidth ${wide} at 390 px`);
  assert.ok(await page.isVisible('#play'));
  await page.screenshot({ path: join(shots, 'embed-mode-phone.png'), fullPage: true });
  console.log(`measure: embed=1 at 390 px: scrollWidth ${wide}; Tab stops ${stops.map((s) => s.id).join(' ')}`);
  clean(page);
  await page.close();
});
