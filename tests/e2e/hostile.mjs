// End-to-end tests of reliability: hostile input through every door, nothing lost.
// Registered in order by e2e.mjs, which runs them (scripts/e2e.sh).

import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import assert from 'node:assert/strict';
import { here, BASE, browser, test, open, clean, state, pause, countFrames } from './harness.mjs';

// ---- reliability: hostile input through every door, nothing lost --------

/** What a refusal must not look like: a wasm trap, a panic, a JS slip. */
const CRASHY = /unreachable|RuntimeError|panicked|is not a function|Cannot read prop|undefined \(reading|null pointer|recursive use/i;

/** The page still works: finite state, the clock steps, frames are drawn. */
async function stillWorks(page) {
  const s = await page.evaluate(() => window.demo.runUntil(window.demo.state().t + 1));
  for (const v of [s.t, ...s.theta, ...s.ee, s.tracking_error]) assert.ok(Number.isFinite(v), `finite state: ${JSON.stringify(s)}`);
  // Frames keep coming (a page that froze draws none): a few, within 5 s on a loaded machine.
  await countFrames(page);
  await page.waitForFunction(() => window.__frames > 3, null, { timeout: 5000 }).catch(() => {});
  const frames = await page.evaluate(() => window.__frames);
  assert.ok(frames > 3, `the page keeps drawing (${frames} frames)`);
  return s;
}

const HOSTILE_URLS = [
  ['task=NaN', [/task: the paper has tasks 1 and 2/]],
  ['task=2e308', [/task:/]],
  ['lambda=NaN', [/lambda: expected a number, got 'NaN'/]],
  ['lambda=Infinity', [/lambda: expected a number/]],
  ['lambda=1e308', [/lambda: .*lambda/]],
  ['feedback=-1', [/feedback: .*feedback/]],
  ['target=1e308,0', [/target: target x must lie within/]],
  ['target=NaN,NaN', [/target: expected two numbers/]],
  ['target=1,2,3', [/target: expected two numbers/]],
  ['obstacle=0.5', [/obstacle: expected two numbers/]],
  ['obstacles=0.5,0.5,-1', [/obstacles: .*radius/]],
  ['obstacles=0.5,0.5,1e308', [/obstacles: .*radius/]],
  ['obstacles=1,2,3,4', [/obstacles: obstacle '1,2,3,4': expected x,y or x,y,r, got 4 numbers/]],
  ['obstacles=0.5,abc', [/obstacles: obstacle '0.5,abc': 'abc' is not a finite number/]],
  // 40 KB of address (the test server, like many, takes lines up to 64 KB):
  // it parses, and the core refuses so many.
  [`obstacles=${'0.5,0.5;'.repeat(5000)}`, [/obstacles: number of obstacles must lie between 0 and 8 \(got 5000\)/]],
  ['arm=0.5:', [/arm: arm '0.5:': '' is not a finite number/]],
  ['arm=0.5', [/arm: arm '0.5': expected POST:L1/]],
  ['arm=0.5:0.6', [/arm: arm '0.5:0.6': an arm needs 2 to \d+ links .*\(got 1\)/]],
  [`arm=0.5:${Array(100).fill('0.1').join(',')}`, [/arm: arm '0\.5:0\.1,0\.1,.*…': an arm needs 2 to \d+ links .*\(got 100\)/]],
  // A well-formed arm of 7 links: the session takes 2 to 6.
  [`arm=0.5:${Array(7).fill('0.2').join(',')}`, [/arm: an arm needs 2 to 6 links to position a planar end effector \(got 7\)/]],
  ['arm=0.5:0.6,abc,0.6', [/arm: .*'abc' is not a finite number/]],
  ['arm=-1:0.6,0.6', [/arm: .*post/]],
  ['arm=0.5:1e308,1', [/arm: .*link length L1 must lie within/]],
  ['path=spiral:1,2', [/path: path 'spiral:1,2': expected line, circle/]],
  ['path=circle:NaN,1', [/path: .*'NaN' is not a finite number/]],
  [`path=points:${'1,1;'.repeat(5000)}`, [/path: path 'points:1,1;1,1;.*…': expected 1 to 64 points/]],
  ['method=%3Cscript%3Ealert(1)%3C%2Fscript%3E', [/method: unknown method '<script>/]],
  ['method=case9&lambda=abc&target=x,y&arm=zzz', [/method: unknown method/, /lambda: expected a number/, /target: expected two numbers/, /arm: arm 'zzz'/]],
  ['task=%00%FF&%E2%80=1&lambda=%F0%9F%92%A5', [/task:/, /lambda: expected a number/]],
  // The lab's switches (issue 25).
  ['weighting=qp', [/weighting: unknown joint weighting 'qp': use none or wln/]],
  ['weighting=%3Cb%3Ewln&floor=yes', [/weighting: unknown joint weighting '<b>wln'/, /floor: expected 0 or 1, got 'yes'/]],
  [`weighting=${'w'.repeat(5000)}`, [/weighting: unknown joint weighting 'w{40}…'/]],
  ['method=case3&precision=f16', [/precision: unknown arithmetic 'f16': use f64 or f32/]],
];

test('hostile URL parameters: each is named in one readable message and the page runs from its defaults', async () => {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  // Three addresses at a time, each on its own page: the loads wait on the
  // network and the module more than on the two cores (56 s one by one).
  const queue = [...HOSTILE_URLS];
  const one = async ([query, expected]) => {
    const page = await context.newPage();
    const problems = [];
    page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
    page.on('pageerror', (e) => problems.push(e.message));
    const label = query.length > 60 ? `${query.slice(0, 60)}…` : query;
    await page.goto(`${BASE}?${query}`);
    await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 }).catch((e) => {
      throw new Error(`${label}: the page did not start: ${e.message}`);
    });
    const text = await page.locator('#message').textContent();
    const shown = await page.isVisible('#message');
    assert.ok(shown, `${label}: a message is shown`);
    assert.match(text, /^Ignored in the address: /, `${label}: ${text}`);
    for (const re of expected) assert.match(text, re, `${label}: ${text}`);
    assert.doesNotMatch(text, CRASHY, `${label}: ${text}`);
    assert.ok(text.length < 600, `${label}: the message stays readable (${text.length} characters)`);
    await stillWorks(page);
    assert.deepEqual(problems, [], `${label}: no console errors`);
    await page.close();
  };
  const lane = async () => {
    for (let next = queue.shift(); next; next = queue.shift()) await one(next);
  };
  try {
    await Promise.all([lane(), lane(), lane()]);
  } finally {
    await context.close();
  }
});

test('window.demo with wrong types and out-of-range values: readable errors, nothing changes, the page keeps working', async () => {
  const page = await open('?task=1&method=case3');
  await pause(page);
  const v = readFileSync(join(here, '../../weights/v-plain.json'), 'utf8');
  const phi = readFileSync(join(here, '../../weights/phi-equivariant.json'), 'utf8');
  const r = await page.evaluate(async ({ v, phi }) => {
    const d = window.demo;
    const m = d.controller.demo;
    const before = d.state();
    const sim0 = d.simulate({ method: 'case3' });
    // A weights file for a 4-link arm (the page's paper arm has 3).
    const other = JSON.parse(v);
    other.arm.links = [0.6, 0.85, 0.6, 0.4];
    const calls = {
      'runUntil("abc")': () => d.runUntil('abc'),
      'runUntil(NaN)': () => d.runUntil(NaN),
      'setArm(null)': () => d.setArm(null),
      'setArm("0.5:1,1")': () => d.setArm('0.5:1,1'),
      'setArm(post NaN)': () => d.setArm({ post: NaN, links: [1, 1] }),
      'setArm(no links)': () => d.setArm({ post: 0.5, links: [] }),
      'setArm(100 links)': () => d.setArm({ post: 0.5, links: Array(100).fill(0.1) }),
      'setArm(text links)': () => d.setArm({ post: 0.5, links: ['a', 'b', 'c'] }),
      'setArm(1e308)': () => d.setArm({ post: 0.5, links: [1e308, 1, 1] }),
      'setArm(negative)': () => d.setArm({ post: 0.5, links: [-1, 1, 1] }),
      'addObstacle("x", {}, null)': () => d.addObstacle('x', {}, null),
      'addObstacle(radius -1)': () => d.addObstacle(1.0, 1.0, -1),
      'addObstacle(1e308)': () => d.addObstacle(1e308, 0, 0.1),
      'addObstacle(on the post)': () => d.addObstacle(0, 0.2, 0.05),
      'removeObstacle(-1)': () => d.removeObstacle(-1),
      'removeObstacle(NaN)': () => d.removeObstacle(NaN),
      'removeObstacle("a")': () => d.removeObstacle('a'),
      'removeObstacle(1e9)': () => d.removeObstacle(1e9),
      'removeObstacle(0.5)': () => d.removeObstacle(0.5),
      'simulate(null)': () => d.simulate(null),
      'simulate(method warp)': () => d.simulate({ method: 'warp' }),
      'simulate(method 5)': () => d.simulate({ method: 5 }),
      'simulate(target NaN)': () => d.simulate({ method: 'numerical', target: [NaN, 0] }),
      'simulate(target "ab")': () => d.simulate({ method: 'numerical', target: 'ab' }),
      'simulate(tf -1)': () => d.simulate({ method: 'numerical', tf: -1 }),
      'simulate(tf 1e12)': () => d.simulate({ method: 'numerical', tf: 1e12 }),
      'simulate(theta0 short)': () => d.simulate({ method: 'numerical', theta0: [1, 2] }),
      'simulate(obstacles "x")': () => d.simulate({ method: 'numerical', obstacles: 'x' }),
      'simulate(9 obstacles)': () => d.simulate({ method: 'numerical', obstacles: Array(9).fill([1, 1, 0.05]) }),
      'simulate(bogus option)': () => d.simulate({ method: 'numerical', speed: 2 }),
      'train("x")': () => d.train('x'),
      'train(preset huge)': () => d.train({ preset: 'huge' }),
      'train(net x)': () => d.train({ net: 'x' }),
      'train(samples 1e9)': () => d.train({ samples: 1e9 }),
      'train(samples 1.5)': () => d.train({ samples: 1.5 }),
      'train(epochs -1)': () => d.train({ epochs: -1 }),
      'train(bogus option)': () => d.train({ rate: 1 }),
      'atlas(n 1e9)': () => d.atlas({ n: 1e9 }),
      'atlas(n "abc")': () => d.atlas({ n: 'abc' }),
      'atlas(region short)': () => d.atlas({ n: 5, region: [0, 1] }),
      'atlas(region NaN)': () => d.atlas({ n: 5, region: [0, NaN, 0, 1] }),
      'atlas(methods x)': () => d.atlas({ n: 5, methods: ['x'] }),
      'atlas(bogus option)': () => d.atlas({ n: 5, size: 3 }),
      'setLambda("x")': () => m.setLambda('x'),
      'setLambda(1e308)': () => m.setLambda(1e308),
      'setTarget(NaN)': () => m.setTarget(NaN, 0, 10),
      'setTarget(Infinity)': () => m.setTarget(Infinity, 0, 10),
      'setMethod(<b>)': () => m.setMethod('<b>'),
      'setSpeed(1e308)': () => m.setSpeed(1e308),
      'setFeedback(Infinity)': () => m.setFeedback(Infinity),
      'setWeighting("qp")': () => m.setWeighting('qp'),
      'setWeighting(<b>wln)': () => m.setWeighting('<b>wln'),
      'setWeighting(huge)': () => m.setWeighting('w'.repeat(1 << 20)),
      'setObstacles(odd length)': () => m.setObstacles(Float64Array.from([1, 1])),
      'setObstacle(NaN)': () => m.setObstacle(NaN, NaN),
      'loadNetworks(huge)': () => m.loadNetworks('x'.repeat(9 << 20), v),
      'loadNetworks(truncated)': () => m.loadNetworks(phi.slice(0, phi.length / 2), v),
      'loadNetworks(NaN)': () => m.loadNetworks(phi.replace(/("weights":\s*\[\s*)[-\d.e+]+/, '$1NaN'), v),
      'loadNetworks(1e999)': () => m.loadNetworks(phi.replace(/("weights":\s*\[\s*)[-\d.e+]+/, '$11e999'), v),
      'loadNetworks(another arm)': () => m.loadNetworks(phi, JSON.stringify(other)),
      'loadNetworks(swapped)': () => m.loadNetworks(v, phi),
      'loadNetworks(non-string)': () => m.loadNetworks({}, 12),
    };
    const out = {};
    for (const [name, call] of Object.entries(calls)) {
      try {
        const r = call();
        if (r && typeof r.then === 'function') await r;
        out[name] = { threw: false };
      } catch (e) {
        out[name] = { threw: true, message: String(e && e.message) };
      }
    }
    return { out, before, after: d.state(), sim0, sim1: d.simulate({ method: 'case3' }) };
  }, { v, phi });
  for (const [name, o] of Object.entries(r.out)) {
    assert.ok(o.threw, `${name} is refused`);
    assert.ok(o.message.length > 10, `${name}: a message (${o.message})`);
    assert.doesNotMatch(o.message, CRASHY, `${name}: ${o.message}`);
  }
  assert.match(r.out['loadNetworks(huge)'].message, /at most 8 MB/);
  assert.match(r.out['loadNetworks(truncated)'].message, /not a valid weights file/);
  assert.match(r.out['loadNetworks(NaN)'].message, /not a valid weights file/);
  assert.match(r.out['loadNetworks(another arm)'].message, /arm/);
  assert.match(r.out['removeObstacle(NaN)'].message, /whole number/);
  assert.match(r.out['setWeighting(huge)'].message, /^unknown joint weighting 'w{40}…': use none or wln$/);
  // Nothing changed: the same scene, and the same run from it.
  for (const k of ['arm', 'obstacles', 'target', 'method', 'lambda', 'feedback', 'speed', 'theta', 't', 'weighting', 'floor']) {
    assert.deepEqual(r.after[k], r.before[k], `${k} unchanged`);
  }
  assert.deepEqual(r.sim1, r.sim0, 'the networks in use are unchanged');
  await stillWorks(page);
  clean(page);
  await page.close();
});

test('weights files through the file picker: too large, truncated, for another arm: refused, the networks in use stay', async () => {
  const page = await open('?task=1&method=case3');
  await pause(page);
  const v = readFileSync(join(here, '../../weights/v-plain.json'), 'utf8');
  const phi = readFileSync(join(here, '../../weights/phi-equivariant.json'), 'utf8');
  const other = JSON.parse(v);
  other.arm.links = [0.6, 0.85, 0.6, 0.4];
  const before = await page.evaluate(() => window.demo.simulate({ method: 'case3' }));
  const file = (name, text) => ({ name, mimeType: 'application/json', buffer: Buffer.from(text) });
  const cases = [
    ['too large', file('phi.json', ' '.repeat((8 << 20) + 1)), file('v.json', v), /phi\.json has 8\.0 MB; weights files are at most 8 MB/],
    ['truncated', file('phi.json', phi.slice(0, 5000)), file('v.json', v), /not a valid weights file/],
    ['another arm', file('phi.json', phi), file('v.json', JSON.stringify(other)), /arm/],
    ['binary', file('phi.json', '\u0000\u00ff\u0001garbage'), file('v.json', v), /not a valid weights file/],
  ];
  for (const [name, p, q, re] of cases) {
    await page.locator('#phi-file').setInputFiles(p);
    await page.locator('#v-file').setInputFiles(q);
    await page.evaluate(() => {
      document.getElementById('message').textContent = '';
    });
    await page.evaluate(() => document.getElementById('load-weights').click());
    await page.waitForFunction(() => document.getElementById('message').textContent !== '', null, { timeout: 10000 });
    const text = await page.locator('#message').textContent();
    assert.match(text, re, `${name}: ${text}`);
    assert.doesNotMatch(text, CRASHY, `${name}: ${text}`);
  }
  const after = await page.evaluate(() => window.demo.simulate({ method: 'case3' }));
  assert.deepEqual(after, before, 'the networks in use are unchanged');
  await stillWorks(page);
  clean(page);
  await page.close();
});

test('nothing lost: a refused atlas keeps the last map, a refused training keeps the networks', async () => {
  const page = await open('?task=1&method=case3');
  await pause(page);
  const r = await page.evaluate(async () => {
    const d = window.demo;
    await d.atlas({ n: 5, methods: ['numerical'] });
    const map = d.atlasResult();
    const sim = d.simulate({ method: 'case3' });
    const errors = [];
    for (const bad of [{ n: 1 }, { n: 5, methods: [] }, { n: 5, region: [1, 0, 0, 1] }]) {
      try {
        await d.atlas(bad);
      } catch (e) {
        errors.push(e.message);
      }
    }
    for (const bad of [{ samples: 3 }, { epochs: 1e9 }]) {
      try {
        await d.train(bad);
      } catch (e) {
        errors.push(e.message);
      }
    }
    return { map, after: d.atlasResult(), errors, sim, simAfter: d.simulate({ method: 'case3' }) };
  });
  assert.equal(r.errors.length, 5, `every bad job is refused: ${r.errors.join(' | ')}`);
  for (const e of r.errors) assert.doesNotMatch(e, CRASHY, e);
  assert.deepEqual(r.after, r.map, 'the last atlas stays');
  assert.deepEqual(r.simAfter, r.sim, 'the networks stay');
  await stillWorks(page);
  clean(page);
  await page.close();
});

test('weights kept in the browser that are corrupt: dropped with a message, the built-in networks run', async () => {
  const page = await open('?task=1&method=case3');
  await pause(page);
  const shipped = await page.evaluate(() => window.demo.simulate({ method: 'case3' }));
  const key = 'redundant-ik:weights:0.5:0.6,0.85,0.6';
  // Entries that are JSON but do not load say so; one that is not JSON at
  // all is not an entry the page wrote, and is dropped without a word.
  for (const [junk, said] of [
    ['{"phi": "{\\"format\\": 1", "v": 12}', /could not be loaded and were dropped/],
    ['not json at all', /^$/],
    ['{"phi": null}', /could not be loaded and were dropped/],
  ]) {
    await page.evaluate(([k, v]) => localStorage.setItem(k, v), [key, junk]);
    await page.reload();
    await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
    await pause(page);
    const r = await page.evaluate((k) => ({
      message: document.getElementById('message').textContent,
      kept: localStorage.getItem(k),
      sim: window.demo.simulate({ method: 'case3' }),
      method: window.demo.state().method,
    }), key);
    assert.equal(r.kept, null, `${junk}: the corrupt entry is dropped`);
    assert.deepEqual(r.sim, shipped, `${junk}: the built-in networks run`);
    assert.equal(r.method, 'case3');
    assert.match(r.message, said, `${junk}: ${r.message}`);
    assert.doesNotMatch(r.message, CRASHY, `${junk}: ${r.message}`);
  }
  await stillWorks(page);
  clean(page);
  await page.close();
});
