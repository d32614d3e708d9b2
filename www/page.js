// The full page (index.html): loads the module, fills the prose the module
// knows (the methods explained, the limits quoted), mounts the demo on the
// document with the settings of the address (address.js), wires the
// benchmark panel (bench-panel.js) and exposes `window.demo` for scripts
// and tests. If the module cannot start, the page says so and disables its
// controls instead of showing a blank stage.

import { loadModule, describe, methods, methodGroups, fillLimits, moduleBuild, moduleMemoryBytes } from './module.js';
import { bench } from './jobs.js';
import { mount } from './demo.js';
import { readAddress, writeAddress } from './address.js';
import { mountBenchPanel } from './bench-panel.js';

/** The methods, each with what it computes: the "The methods" list of the page. */
function explainMethods(list) {
  if (!list) return;
  for (const g of methodGroups()) {
    const head = document.createElement('dt');
    head.className = 'group';
    head.textContent = g.label;
    list.append(head);
    for (const m of g.methods) {
      const dt = document.createElement('dt');
      dt.textContent = m.label;
      const dd = document.createElement('dd');
      dd.textContent = m.description;
      list.append(dt, dd);
    }
  }
}

async function start() {
  const loading = document.getElementById('loading');
  try {
    await loadModule();
    explainMethods(document.getElementById('modes-explained'));
    fillLimits(document);
    const { problems, ...settings } = readAddress(location.search);
    const controller = await mount(document, {
      ...settings,
      problems,
      problemsLabel: 'Ignored in the address',
      keyboard: document,
      onChange: writeAddress,
    });
    window.demo = {
      state: () => controller.state(),
      worldToClient: (x, y) => controller.worldToClient(x, y),
      runUntil: (t) => controller.runUntil(t),
      bench: (options) => bench(options),
      atlas: (options) => controller.atlas(options),
      useNetworks: (name) => controller.useNetworks(name),
      atlasResult: () => controller.atlasResult(),
      setArm: (arm) => controller.playground.setArm(arm),
      addObstacle: (x, y, r) => controller.playground.addObstacle(x, y, r),
      removeObstacle: (i) => controller.playground.removeObstacle(i),
      obstacles: () => controller.playground.obstacles(),
      train: (options) => controller.playground.train(options),
      exportWeights: () => controller.playground.exportWeights(),
      simulate: (options) => controller.playground.simulate(options),
      methods: () => structuredClone(methods()),
      build: moduleBuild(),
      wasmMemoryBytes: () => moduleMemoryBytes(),
      controller,
      readyMs: performance.now(),
    };
    document.body.dataset.ready = 'true';
  } catch (e) {
    loading.hidden = false;
    loading.classList.add('failed');
    for (const c of document.querySelectorAll('aside button, aside input, aside select')) c.disabled = true;
    document.getElementById('loading-text').textContent =
      `The simulation could not start: ${describe(e)}. ` + 'It needs a current browser with WebAssembly, served over http (make demo).';
    console.warn(e);
  }
}

start();
mountBenchPanel(document);
