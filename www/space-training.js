// Training the networks of an arm in space in the page: the plane's
// training panel (#train-panel) driven for the arm in space. Φ and v are
// trained at once in two workers (src/web/space_training.rs, the recipe of
// `redundant-ik train --arm A`: quick, or the command line's whole-reach
// one), the progress of both in one bar, Cancel ends both; when both are
// done the core checks them against the chain and the learned methods use
// them (SpaceDemo.installNetworks), and Download weights saves the two
// files the command line reads (--phi-weights, --v-weights). The curves of
// both networks' errors per epoch are the plane's (training.js).

import { runWorker } from './jobs.js';
import { describe, spaceTrainingRecipes } from './module.js';
import { saveText } from './download.js';
import { drawCurves } from './training.js';

/**
 * Wires the training panel under `root` for the spatial `demo` of `preset`;
 * `installed()` after networks are installed (the menu's learned methods
 * open), `show` and `say` the page's message and live region.
 */
export function mountSpaceTraining(root, demo, { preset, show, say, installed }) {
  const $ = (id) => root.querySelector('#' + id);
  const panel = $('train-panel');
  if (!panel) return { train: () => Promise.reject(new Error('this page has no training panel')) };
  panel.querySelector('summary').textContent = `Train the networks for the ${preset.label}`;
  const intro = panel.querySelector('p');
  // A robot of the user's travels to the workers as its run file (its chain, start and sphere).
  const own = preset.key === 'robot';
  if (intro) {
    intro.textContent =
      `Adam training of the Φ and v networks of the ${preset.label}, as redundant-ik train ${own ? '--urdf FILE' : `--arm ${preset.key}`} does it, ` +
      'in two workers at once: Φ on poses within the joint limits, v on states of numerical runs with spheres anywhere in the reach' +
      `${own ? " (of the first sphere's radius, from the scene as it is now)" : ''}. ` +
      'When both are done the learned methods (Cases 1-3) use them; Download weights saves the two files the command line reads.';
  }
  const recipe = $('train-preset');
  // The recipes from the module (src/training/space.rs), the default first.
  const recipes = spaceTrainingRecipes();
  const label = (r) => `${r.name}: ${r.hidden.join('-')} networks, Φ on ${r.phi[0]} poses (${r.phi[1]} epochs), v on ${r.v[0]} states (${r.v[1]} epochs)`;
  recipe?.replaceChildren(...recipes.map((r) => new Option(label(r), r.name)));
  // Both networks, always (the core installs the two together); nothing to forget.
  for (const id of ['train-net', 'train-forget']) $(id)?.closest('.field, button')?.setAttribute('hidden', '');
  const run = $('train-run');
  const cancel = $('train-cancel');
  const bar = $('train-progress');
  const status = $('train-status');
  const download = $('train-download');
  const chart = $('train-curves');
  if (download) download.disabled = true;
  let files = null;
  /** Each network's errors per epoch: `{ phi: [{ epoch, train_mse, val_mse }], v: [...] }`. */
  let curves = {};
  let controller = null;
  const tell = (text) => {
    if (status) status.textContent = text;
    say(text);
  };

  /**
   * Trains both networks: `preset` ('quick' or 'reach', the menu's), and
   * `samples`, `epochs` and `seed` to override the recipe (window.demo.train
   * in space). Resolves to `{ phi, v, seconds }` (the weights files' text)
   * once they are installed, or null when cancelled.
   */
  async function train({ preset: recipeName = recipe?.value ?? recipes[0].name, samples, epochs, seed } = {}) {
    controller = new AbortController();
    const done = { phi: 0, v: 0 };
    const total = { phi: 1, v: 1 };
    if (run) run.disabled = true;
    if (cancel) cancel.hidden = false;
    if (bar) {
      bar.hidden = false;
      bar.value = 0;
    }
    curves = {};
    drawCurves(chart, curves);
    const onProgress = (net) => (p) => {
      done[net] = p.done;
      total[net] = Math.max(1, p.total);
      if (bar) bar.value = (done.phi / total.phi + done.v / total.v) / 2;
      if (!p.epoch) return;
      const e = p.epoch;
      (curves[net] ??= []).push({ epoch: e.epoch, train_mse: e.train_mse, val_mse: e.val_mse });
      drawCurves(chart, curves);
      if (chart) chart.dataset.epochs = String(Object.values(curves).reduce((sum, c) => sum + c.length, 0));
      if (status) status.textContent = `Training: Φ epoch ${done.phi} of ${total.phi}, v epoch ${done.v} of ${total.v}…`;
    };
    const started = performance.now();
    tell(`Training the ${preset.label}'s Φ and v networks…`);
    try {
      // The name is for the messages only, which take up to 200 characters of it.
      const arm = own ? { run: demo.runFile(), name: preset.label.slice(0, 200) } : { arm: preset.key };
      const request = (net) => ({ ...arm, net, preset: recipeName, ...(samples && { samples }), ...(epochs && { epochs }), ...(seed !== undefined && { seed }) });
      const [phi, v] = await Promise.all(
        ['phi', 'v'].map((net) => runWorker({ kind: 'space-train', request: request(net) }, { onProgress: onProgress(net), signal: controller.signal }).then((r) => r.result)),
      );
      demo.installNetworks(phi, v, undefined);
      files = { phi, v };
      if (download) download.disabled = false;
      installed();
      const seconds = (performance.now() - started) / 1000;
      const errors = [phi, v].map((text) => JSON.parse(text).nets[0].report.val_mse.toExponential(1));
      tell(`Trained in ${seconds.toFixed(1)} s (validation MSE: Φ ${errors[0]}, v ${errors[1]}); Cases 1-3 now use them.`);
      return { phi, v, seconds };
    } catch (e) {
      if (e?.name === 'AbortError') {
        tell('Training cancelled: the networks in use stay.');
        return null;
      }
      show(`The training failed: ${describe(e)}`, 'error', true, run);
      throw e;
    } finally {
      if (run) run.disabled = false;
      if (cancel) cancel.hidden = true;
      if (bar) bar.hidden = true;
      controller = null;
    }
  }
  run?.addEventListener('click', () => train().catch(() => {}));
  panel.addEventListener('toggle', () => panel.open && drawCurves(chart, curves));
  cancel?.addEventListener('click', () => controller?.abort());
  download?.addEventListener('click', () => {
    if (!files) return;
    const stem = own ? (preset.label.replace(/[^\w.-]+/g, '-').replace(/^-+|-+$/g, '') || 'robot') : preset.key;
    saveText(`phi-${stem}-trained.json`, files.phi, 'application/json');
    saveText(`v-${stem}-trained.json`, files.v, 'application/json');
  });
  return { train };
}
