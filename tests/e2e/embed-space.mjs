// The element with an arm in space: the Panda page's Embed button gives an
// element whose attributes are the page's address keys; pasted into a
// course page it shows the same scene in perspective, marks nothing on the
// host page, follows attributes changed later and names a bad one.
// Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { join } from 'node:path';
import { test, open, clean, state, shots, browser, BASE } from './harness.mjs';

/** The scene of a spatial state: what an element must reproduce. */
const scene = (s) => ({ kind: s.kind, arm: s.arm, method: s.method, target: s.target, spheres: s.spheres, path: s.path, damping: s.damping, params: s.params, weighting: s.weighting, floor: s.floor });

test('embed in space: the Embed button\'s element shows the Panda\'s scene on a course page, follows its attributes and names a bad one', async () => {
  const q = 'arm=panda&method=qp&target=0.45,0.25,0.55&obstacles=0.4,0.1,0.62,0.05&path=points:0.5,0.1,0.5;0.45,0.2,0.6&damping=1&influence=0.2&autoplay=0';
  const page = await open(`?${q}`);
  const want = await state(page);
  await page.click('#embed-open');
  const element = await page.inputValue('#embed-element');
  const iframe = await page.inputValue('#embed-iframe');
  for (const key of ['arm="panda"', 'method="qp"', 'target="0.45,0.25,0.55"', 'damping="1"', 'influence="0.2"', 'path="points:']) assert.ok(element.includes(key), `the element has ${key}: ${element}`);
  assert.match(iframe, /arm=panda/);
  assert.match(iframe, /embed=1/);
  await page.keyboard.press('Escape');
  clean(page);
  await page.close();

  const context = await browser.newContext({ viewport: { width: 900, height: 900 } });
  const course = await context.newPage();
  const problems = [];
  course.on('pageerror', (e) => problems.push(e.message));
  const html = element.replace('<redundant-ik-demo ', '<redundant-ik-demo id="panda" autoplay="false" plots ');
  await course.route(BASE + 'course-space.html', (r) => r.fulfill({ status: 200, contentType: 'text/html; charset=utf-8', body: `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>A course page</title></head><body><h1>Redundancy in space</h1>${html}</body></html>` }));
  await course.goto(BASE + 'course-space.html');
  await course.waitForSelector('#panda[data-ready="true"]', { timeout: 30000 });
  const got = await course.evaluate(() => document.getElementById('panda').controller.state());
  assert.deepEqual(scene(got), scene(want), 'the element shows the page\'s scene');
  assert.equal(await course.evaluate(() => document.documentElement.hasAttribute('data-space')), false, 'the host page is not marked');
  assert.equal(await course.evaluate(() => document.getElementById('panda').dataset.space), 'panda');
  await course.screenshot({ path: join(shots, 'embed-space.png') });

  // An attribute changed later is applied; a bad one is named, the rest runs.
  await course.evaluate(() => document.getElementById('panda').setAttribute('target', '0.5,0.2,0.5'));
  await course.waitForFunction(() => document.getElementById('panda').controller.state().target.join() === '0.5,0.2,0.5', null, { timeout: 10000 });
  await course.evaluate(() => document.getElementById('panda').setAttribute('obstacles', '0.4,oops'));
  await course.waitForFunction(() => /Not applied: obstacles/.test(document.getElementById('panda').shadowRoot.getElementById('message').textContent), null, { timeout: 10000 });
  assert.deepEqual((await course.evaluate(() => document.getElementById('panda').controller.state())).spheres, want.spheres, 'the spheres stay');
  // Removed: back to the default (the damping off, as the preset's task has it).
  await course.evaluate(() => document.getElementById('panda').removeAttribute('damping'));
  await course.waitForFunction(() => document.getElementById('panda').controller.state().damping === false, null, { timeout: 10000 });
  // A learned method by attribute fetches the Panda's networks.
  await course.evaluate(() => document.getElementById('panda').setAttribute('method', 'case3'));
  await course.waitForFunction(() => document.getElementById('panda').controller.state().method === 'case3', null, { timeout: 60000 });
  assert.deepEqual(problems, []);
  await context.close();
});

test('embed in space: <redundant-ik-demo urdf="URL" tip="..."> shows the robot at that address, its workers started across origins; a host without CORS gives the first shipped arm and says why', async () => {
  const { mkdirSync, readFileSync, writeFileSync } = await import('node:fs');
  const { fileURLToPath } = await import('node:url');
  const { serve } = await import('./serve.mjs');
  const { scratch } = await import('./class-helpers.mjs');
  // The course page and its robot on one host, the demo's files on another that allows it (a
  // page fulfilled by the test itself counts as public to Chromium, which then blocks its fetches
  // from 127.0.0.1), the same robot on a third that does not.
  const root = join(scratch, 'element-host');
  mkdirSync(join(root, 'slider_arm/urdf'), { recursive: true });
  mkdirSync(join(root, 'slider_arm/meshes'), { recursive: true });
  writeFileSync(join(root, 'slider_arm/urdf/slider_arm.urdf'), readFileSync('tests/data/urdf/slider_arm.urdf'));
  writeFileSync(join(root, 'slider_arm/meshes/forearm.stl'), readFileSync('tests/data/urdf/meshes/forearm.stl'));
  const www = fileURLToPath(new URL('../../www', import.meta.url));
  const [site, demo, closed] = await Promise.all([serve(root, ['--cors']), serve(www, ['--cors']), serve(root)]);
  const context = await browser.newContext({ viewport: { width: 900, height: 900 } });
  try {
    const url = `${site.url}slider_arm/urdf/slider_arm.urdf`;
    const blocked = `${closed.url}slider_arm/urdf/slider_arm.urdf`;
    const body = `<redundant-ik-demo id="mine" urdf="slider_arm/urdf/slider_arm.urdf" tip="tool" method="qp" autoplay="false"></redundant-ik-demo><redundant-ik-demo id="blocked" urdf="${blocked}" tip="tool" autoplay="false"></redundant-ik-demo>`;
    writeFileSync(join(root, 'course.html'), `<!doctype html><html lang="en"><head><meta charset="utf-8"><title>My robot</title><script type="module" src="${demo.url}redundant-ik-demo.js"></script></head><body>${body}</body></html>`);
    const course = await context.newPage();
    const problems = [];
    course.on('pageerror', (e) => problems.push(e.message));
    await course.goto(site.url + 'course.html');
    await course.waitForSelector('#mine[data-ready="true"]', { timeout: 30000 });
    await course.waitForSelector('#blocked[data-ready="true"]', { timeout: 30000 });
    const mine = await course.evaluate(() => document.getElementById('mine').controller.state());
    const mineSaid = await course.evaluate(() => document.getElementById('mine').shadowRoot.getElementById('message').textContent);
    assert.deepEqual([mine.arm, mine.arm_label, mine.method], ['robot', 'slider_arm', 'qp'], `${url}: ${mineSaid}`);
    // (Its urdf is relative: read against the course page's address, it is `url`, on the course's host.)
    assert.ok(mine.summary.steps > 0 && !mine.failure, `its task runs in qp: ${JSON.stringify(mine.summary)}`);
    const other = await course.evaluate(() => document.getElementById('blocked').controller.state());
    assert.equal(other.arm, 'panda', 'the first shipped arm instead');
    const said = await course.evaluate(() => document.getElementById('blocked').shadowRoot.getElementById('message').textContent);
    assert.match(said, /urdf: .*could not be fetched: .*CORS/);
    assert.deepEqual(problems, []);
    await course.locator('#mine').screenshot({ path: join(shots, 'embed-robot.png') });
  } finally {
    await context.close();
    site.stop();
    demo.stop();
    closed.stop();
  }
});
