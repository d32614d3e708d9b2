// "Save and share" under the drawing: the figure (the stroboscopic drawing
// `redundant-ik figure` draws) and the plots (`figure --plots`) as SVG and
// PNG, the run as CSV and as the JSON of `redundant-ik simulate --json`
// (which `simulate --from` reads back), and the address of the scene. The
// files are made in a Web Worker by the workers' module (runFiles): the
// run of the scene as it is now, from t = 0 to the end of its line, the
// very run the drawing shows unless the scene was changed while it ran.

import { runWorker } from './jobs.js';
import { saveBlob, saveText, svgToPng, stem } from './download.js';

/**
 * Wires `#save-figure-svg`, `#save-figure-png`, `#save-plots-svg`,
 * `#save-plots-png`, `#save-run-csv`, `#save-run-json`, `#copy-link` and
 * `#link-text` under `root`. Hooks: `show(text, kind, sticky, near)`,
 * `link()` (the address
 * of the scene). Returns `{ files() }`: a Promise of `{ json, csv, figure,
 * plots }` for the scene as it is now.
 */
export function mountTakeaway(root, demo, { show, link }) {
  const $ = (id) => root.querySelector('#' + id);
  let cache = null; // { key, files }

  async function files() {
    // The module's run (its scene, method and networks), cached by its revision.
    const key = demo.state().revision.run;
    if (cache?.key === key) return cache.files;
    const { result } = await runWorker({ kind: 'run-files', run: demo.run() });
    cache = { key, files: result };
    return result;
  }

  /** Says so when the drawing's run is not the file's (the scene changed while it ran). */
  function checkSame(json, near) {
    const s = demo.state();
    if (!s.ended) return;
    const last = JSON.parse(json).steps.at(-1);
    const off = Math.hypot(last.ee[0] - s.ee[0], last.ee[1] - s.ee[1]);
    if (off > 1e-9) {
      show(
        `The scene changed while this run went on, so the file holds the run of the scene as it is now, from t = 0 (its hand ends ${(off * 1000).toFixed(1)} mm from where the drawing's did). Press Replay to see that run.`,
        'info',
        true,
        near,
      );
    }
  }

  const name = (ext) => {
    const s = demo.state();
    return `${stem(s)}.${ext}`;
  };
  const saving = (id, save) => {
    const button = $(id);
    button?.addEventListener('click', async () => {
      button.disabled = true;
      try {
        await save(await files(), button);
      } catch (e) {
        show(`Could not save: ${e.message ?? e}`, 'error', false, button);
      } finally {
        button.disabled = false;
      }
    });
  };
  saving('save-figure-svg', (f) => saveText(name('svg'), f.figure, 'image/svg+xml'));
  saving('save-figure-png', async (f) => saveBlob(name('png'), await svgToPng(f.figure)));
  saving('save-plots-svg', (f) => saveText(name('plots.svg'), f.plots, 'image/svg+xml'));
  saving('save-plots-png', async (f) => saveBlob(name('plots.png'), await svgToPng(f.plots)));
  saving('save-run-csv', (f, b) => {
    saveText(name('csv'), f.csv, 'text/csv');
    checkSame(f.json, b);
  });
  saving('save-run-json', (f, b) => {
    saveText(name('json'), f.json + '\n', 'application/json');
    checkSame(f.json, b);
  });

  const copy = $('copy-link');
  const text = $('link-text');
  copy?.addEventListener('click', async () => {
    const url = link();
    if (text) {
      text.value = url;
      text.hidden = false;
      text.select();
    }
    try {
      await navigator.clipboard.writeText(url);
      show('The address of this scene is copied: paste it to share the scene.', 'info', false, copy);
    } catch (_) {
      show('Copy the address above (the browser did not let the page copy it).', 'info', false, copy);
    }
  });

  return { files };
}
