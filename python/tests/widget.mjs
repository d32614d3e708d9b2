// The Python package's Widget in headless Chromium: its front end (the
// module text anywidget loads, the Widget's _esm) rendered with a stand-in
// for anywidget's model holding the Widget's synced state, both written
// by test_widget.py into the folder given. Prints what the element shows
// as JSON; exits non-zero on a page error.
//
//   node python/tests/widget.mjs DIR

import { launchChromium } from '../../tests/e2e/chromium.mjs';
import { serve } from '../../tests/e2e/serve.mjs';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';

const dir = process.argv[2];
writeFileSync(join(dir, 'index.html'), '<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,"><div id="out" style="max-width:720px"></div>\n');
const server = await serve(dir);
const browser = await launchChromium();
const problems = [];
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(`${server.url}index.html`);
  const shown = await page.evaluate(async () => {
    const text = await (await fetch('widget.js')).text();
    const state = await (await fetch('state.json')).json();
    const widget = (await import(URL.createObjectURL(new Blob([text], { type: 'text/javascript' })))).default;
    const handlers = new Map();
    const model = {
      get: (name) => state[name],
      set: (name, value) => (state[name] = value),
      on: (event, fn) => handlers.set(event, [...(handlers.get(event) ?? []), fn]),
      off: () => {},
      save_changes: () => {},
    };
    const el = document.getElementById('out');
    await widget.render({ model, el });
    const demo = el.querySelector('redundant-ik-demo');
    await new Promise((resolve) => (demo.dataset.ready ? resolve() : demo.addEventListener('ready', resolve, { once: true })));
    const s = demo.controller.state();
    return {
      attributes: Object.fromEntries([...demo.attributes].map((a) => [a.name, a.value])),
      method: s.method,
      lambda: s.lambda,
      target: s.target,
    };
  });
  console.log(JSON.stringify({ shown, problems }));
} finally {
  await browser.close();
  server.stop();
}
process.exit(problems.length ? 1 : 0);
