// The npm package (make npm) as a user gets it: its tarball installed with
// `npm install ./redundant-ik-X.tgz` into a scratch folder (no runtime
// dependencies, so nothing else is fetched), that folder served, and in
// headless Chromium the element loaded (a) through an import map, (b) by
// its path, (c) as the compat entry, which fetches no .wasm or weights
// file; each reaches data-ready with no console error. Then the notebook
// widget loaded as anywidget loads a module (its text alone, from a Blob
// URL) and rendered with a stand-in for anywidget's model, a trait change
// included. Run by `make test-npm`.

import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { open, root, run, shots, test } from './browser.mjs';
import { serve } from '../e2e/serve.mjs';

const tarball = readdirSync(join(root, 'target/npm')).find((f) => /^redundant-ik-.*\.tgz$/.test(f));
assert.ok(tarball, 'target/npm has no tarball: run make npm');
const scratch = mkdtempSync(join(tmpdir(), 'redundant-ik-npm-'));
writeFileSync(join(scratch, 'package.json'), '{ "private": true }\n');
execFileSync('npm', ['install', join(root, 'target/npm', tarball), '--no-audit', '--no-fund', '--loglevel=error'], { cwd: scratch, stdio: 'inherit' });

const ELEMENT = '<redundant-ik-demo task="1" method="numerical" plots></redundant-ik-demo>';
const page = (script) => `<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,">${script}\n${ELEMENT}\n`;
const pages = {
  'importmap.html': page(`<script type="importmap">{"imports":{"redundant-ik":"./node_modules/redundant-ik/redundant-ik-demo.js","redundant-ik/compat":"./node_modules/redundant-ik/compat.js"}}</script>
<script type="module">import 'redundant-ik';</script>`),
  'direct.html': page('<script type="module" src="./node_modules/redundant-ik/redundant-ik-demo.js"></script>'),
  'compat.html': page(`<script type="importmap">{"imports":{"redundant-ik/compat":"./node_modules/redundant-ik/compat.js"}}</script>
<script type="module">import 'redundant-ik/compat';</script>`),
  'widget.html': '<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,"><div id="out" style="max-width:720px"></div>\n',
};
for (const [name, html] of Object.entries(pages)) writeFileSync(join(scratch, name), html);
// A robot's URDF beside the notebook, for the widget's urdf trait.
writeFileSync(join(scratch, 'ur5e.urdf'), readFileSync(join(root, 'robots/ur5e.urdf')));

const server = await serve(scratch);
const base = server.url;

const READY = 'redundant-ik-demo[data-ready="true"]';
const fetched = (p, re) => p.requests.filter((u) => re.test(u)).map((u) => u.slice(base.length));

test('(a) through an import map: import "redundant-ik"', async () => {
  const p = await open(`${base}importmap.html`, { ready: READY });
  assert.ok(fetched(p, /\.wasm$/).length >= 1, 'the element fetched its .wasm beside it');
  assert.deepEqual(p.problems, []);
  await p.close();
});

test('(b) by its path in node_modules', async () => {
  const p = await open(`${base}direct.html`, { ready: READY });
  assert.deepEqual(fetched(p, /weights\/.*\.json$/), ['node_modules/redundant-ik/weights/phi-equivariant.json', 'node_modules/redundant-ik/weights/v-plain.json']);
  assert.deepEqual(p.problems, []);
  await p.close();
});

test('(c) the compat entry fetches no .wasm or weights file', async () => {
  const p = await open(`${base}compat.html`, { ready: READY });
  assert.deepEqual(fetched(p, /\.(wasm|json)$/), []);
  assert.deepEqual(p.problems, []);
  await p.close();
});

test('the widget: its module text alone renders the element from the traits; a trait change changes the running demo; cleanup removes it', async () => {
  const p = await open(`${base}widget.html`, { ready: null });
  const r = await p.evaluate(async () => {
    // anywidget imports the module's text (a notebook's _esm), so nothing beside it resolves.
    const text = await (await fetch('node_modules/redundant-ik/widget.js')).text();
    const widget = (await import(URL.createObjectURL(new Blob([text], { type: 'text/javascript' })))).default;
    // A stand-in for anywidget's model: get, set, on, off, save_changes.
    const traits = { task: 2, method: 'numerical', lambda: 4, floor: false, plots: true, target: [0.6, 0.2] };
    const pending = new Set();
    const handlers = new Map();
    const model = {
      get: (name) => traits[name],
      set: (name, value) => ((traits[name] = value), pending.add(name)),
      on: (event, fn) => handlers.set(event, [...(handlers.get(event) ?? []), fn]),
      off: (event, fn) => handlers.set(event, (handlers.get(event) ?? []).filter((f) => f !== fn)),
      save_changes: () => {
        for (const name of pending) for (const fn of handlers.get(`change:${name}`) ?? []) fn();
        pending.clear();
      },
    };
    const el = document.getElementById('out');
    const cleanup = await widget.render({ model, el });
    const demo = el.querySelector('redundant-ik-demo');
    await new Promise((resolve) => (demo.dataset.ready ? resolve() : demo.addEventListener('ready', resolve, { once: true })));
    const before = Object.fromEntries(['task', 'method', 'lambda', 'floor', 'plots', 'target', 'obstacles'].map((a) => [a, demo.getAttribute(a)]));
    const running = () => demo.controller.state();
    const first = running();
    model.set('method', 'case3');
    model.set('lambda', 6);
    model.save_changes();
    const after = demo.getAttribute('method');
    // The element applies a changed attribute to its running demo (a MutationObserver: a task later).
    await new Promise((resolve) => setTimeout(resolve, 50));
    const now = running();
    const listening = () => [...handlers.values()].flat().length;
    window.widgetTest = { cleanup, listening };
    return { before, after, listening: listening(), first: [first.method, first.lambda, first.target], now: [now.method, now.lambda] };
  });
  assert.deepEqual(r.before, { task: '2', method: 'numerical', lambda: '4', floor: '0', plots: '', target: '0.6,0.2', obstacles: null });
  assert.equal(r.after, 'case3');
  assert.deepEqual(r.first, ['numerical', 4, [0.6, 0.2]], 'the traits are the running scene');
  assert.deepEqual(r.now, ['case3', 6], 'a trait change changes the running demo');
  assert.ok(r.listening > 0);
  await p.screenshot({ path: join(shots, 'widget.png') });
  // The cleanup render() returned: no element, no handler left.
  const gone = await p.evaluate(() => {
    window.widgetTest.cleanup();
    return { elements: document.querySelectorAll('redundant-ik-demo').length, listening: window.widgetTest.listening() };
  });
  assert.deepEqual(gone, { elements: 0, listening: 0 });
  assert.deepEqual(p.problems, []);
  await p.close();
});

test("the widget in space: arm='panda' renders the 3-D page; a urdf trait opens the user's robot in a new element", async () => {
  const p = await open(`${base}widget.html`, { ready: null });
  const r = await p.evaluate(async () => {
    const text = await (await fetch('node_modules/redundant-ik/widget.js')).text();
    const widget = (await import(URL.createObjectURL(new Blob([text], { type: 'text/javascript' })))).default;
    const traits = { arm: 'panda', method: 'qp', autoplay: false, self_collision: true };
    const handlers = new Map();
    const model = {
      get: (name) => traits[name],
      on: (event, fn) => handlers.set(event, [...(handlers.get(event) ?? []), fn]),
      off: (event, fn) => handlers.set(event, (handlers.get(event) ?? []).filter((f) => f !== fn)),
    };
    const change = (name, value) => {
      traits[name] = value;
      for (const fn of handlers.get(`change:${name}`) ?? []) fn();
    };
    const el = document.getElementById('out');
    await widget.render({ model, el });
    const ready = (demo) => new Promise((resolve, reject) => {
      if (demo.dataset.ready) resolve();
      demo.addEventListener('ready', resolve, { once: true });
      setTimeout(() => reject(new Error(`not ready: ${demo.shadowRoot?.textContent.slice(0, 300)}`)), 30000);
    });
    let demo = el.querySelector('redundant-ik-demo');
    await ready(demo);
    const panda = demo.controller.state();
    change('arm', undefined);
    change('urdf', 'ur5e.urdf');
    demo = el.querySelector('redundant-ik-demo');
    await ready(demo);
    const robot = demo.controller.state();
    return {
      panda: [panda.kind, panda.arm, panda.method, panda.self_collision],
      robot: [robot.kind, robot.arm, robot.arm_label, robot.dof],
      elements: el.querySelectorAll('redundant-ik-demo').length,
    };
  });
  assert.deepEqual(r.panda, ['space', 'panda', 'qp', true]);
  assert.deepEqual(r.robot, ['space', 'robot', 'ur5e', 6]);
  assert.equal(r.elements, 1, 'the element of the Panda gave way to the robot\'s');
  await p.screenshot({ path: join(shots, 'widget-space.png') });
  assert.deepEqual(p.problems, []);
  await p.close();
});

await run('npm', () => {
  server.stop();
  rmSync(scratch, { recursive: true, force: true });
});
