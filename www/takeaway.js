// "Save and share" under the drawing: the figure (the stroboscopic drawing
// `redundant-ik figure` draws) and the plots (`figure --plots`) as SVG and
// PNG, the run as CSV and as the JSON of `redundant-ik simulate --json`
// (which `simulate --from` reads back), and the address of the scene. The
// files are made in a Web Worker by the workers' module (runFiles): the
// run of the scene as it is now, from t = 0 to the end of its line, the
// very run the drawing shows unless the scene was changed while it ran.
// Embed shows two snippets of the scene for another page: an iframe of the
// page with embed=1, and the <redundant-ik-demo> element with the scene's
// address keys as attributes (embedSnippets).

import { runWorker } from './jobs.js';
import { saveBlob, saveText, svgToPng, stem } from './download.js';
import { sceneQuery } from './address.js';

/** Text for an HTML attribute's value in double quotes. */
const attribute = (v) => String(v).replace(/&/g, '&amp;').replace(/"/g, '&quot;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
/** Text for an element's content. */
const content = (v) => String(v).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');

/**
 * The two snippets that put the scene of state `s` in another page, from
 * `page` (the page's address): `{ iframe, element }`. The iframe shows the
 * page with the scene's address and embed=1; the element snippet loads
 * redundant-ik-demo.js from beside the page (an absolute URL, so it works
 * when pasted on another site) and sets the same keys as attributes, with
 * a fallback text that shows while (or if) the script cannot run.
 */
export function embedSnippets(s, page = location.href) {
  return snippetsOf(sceneQuery(s), page, 'Redundant-arm simulation');
}

/**
 * The Embed dialog's snippets of the scene whose address keys are `q`
 * (URLSearchParams) on `page`: the iframe titled `title`, and the element
 * with the same keys as its attributes (any arm: the element reads an arm
 * in space from `arm=panda`).
 */
export function snippetsOf(q, page, title) {
  const full = new URL(page);
  full.hash = '';
  full.search = `?${q}`;
  const framed = new URL(full);
  framed.searchParams.set('embed', '1');
  const script = new URL('redundant-ik-demo.js', full).href;
  const iframe =
    `<iframe src="${attribute(framed.href)}" width="900" height="600" loading="lazy" ` +
    `title="${attribute(title)}" style="border: 0; max-width: 100%;"></iframe>`;
  const attrs = [...q].map(([k, v]) => `${k}="${attribute(v)}"`).join(' ');
  const element = [
    `<script type="module" src="${attribute(script)}"></script>`,
    `<redundant-ik-demo ${attrs}>`,
    `  If this text stays, the simulation's script could not load from ${content(new URL('./', full).href)}: that server must send the header`,
    `  Access-Control-Allow-Origin to pages on other sites (docs/embedding.md). <a href="${attribute(full.href)}">Open the demo</a> instead.`,
    `</redundant-ik-demo>`,
  ].join('\n');
  return { iframe, element };
}

/**
 * Wires the Embed dialog under `root` (`#embed-open`, `#embed-dialog`,
 * `#embed-iframe`, `#embed-element`, their `-copy` buttons, `#embed-status`):
 * `snippets()` gives `{ iframe, element }` when it opens; the copy buttons
 * copy (or select) them; closing gives the focus back to the button.
 */
export function wireEmbedDialog(root, snippets) {
  const $ = (id) => root.querySelector('#' + id);
  const dialog = $('embed-dialog');
  const open = $('embed-open');
  const status = $('embed-status');
  if (!dialog || !open) return;
  open.addEventListener('click', () => {
    const { iframe, element } = snippets();
    $('embed-iframe').value = iframe;
    $('embed-element').value = element;
    if (status) status.textContent = '';
    dialog.showModal();
  });
  for (const [button, area, what] of [
    ['embed-iframe-copy', 'embed-iframe', 'The iframe'],
    ['embed-element-copy', 'embed-element', 'The element'],
  ]) {
    $(button)?.addEventListener('click', async () => {
      const box = $(area);
      box.select();
      try {
        await navigator.clipboard.writeText(box.value);
        status.textContent = `${what} is copied: paste it into the other page's HTML.`;
      } catch (_) {
        status.textContent = `${what} is selected: copy it with Ctrl+C (the browser did not let the page copy it).`;
      }
    });
  }
  dialog.addEventListener('close', () => open.focus());
}

/**
 * Wires `#save-figure-svg`, `#save-figure-png`, `#save-plots-svg`,
 * `#save-plots-png`, `#save-run-csv`, `#save-run-json`, `#copy-link`,
 * `#link-text` and the Embed dialog (`#embed-open`, `#embed-dialog`,
 * `#embed-iframe`, `#embed-element`, their `-copy` buttons, `#embed-status`)
 * under `root`. Hooks: `show(text, kind, sticky, near)`,
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

  // ---- one Tab stop for the row (WAI-ARIA's toolbar pattern) -------------
  // The row sits under the drawing and before the controls in the document;
  // as one Tab stop it no longer puts seven buttons between the drawing and
  // the method menu (issue 27). The arrows, Home and End move along it; the
  // button last used keeps the stop.
  const bar = $('takeaway');
  const buttons = bar ? [...bar.querySelectorAll('button')] : [];
  const rove = (to) => {
    for (const b of buttons) b.tabIndex = b === to ? 0 : -1;
  };
  rove(buttons[0]);
  bar?.addEventListener('focusin', (e) => buttons.includes(e.target) && rove(e.target));
  bar?.addEventListener('keydown', (e) => {
    const at = buttons.indexOf(e.target);
    if (at < 0 || e.ctrlKey || e.metaKey || e.altKey) return;
    const last = buttons.length - 1;
    const to = { ArrowRight: at + 1, ArrowDown: at + 1, ArrowLeft: at - 1, ArrowUp: at - 1, Home: 0, End: last }[e.key];
    if (to === undefined) return;
    e.preventDefault();
    buttons[(to + buttons.length) % buttons.length].focus();
  });

  // ---- Embed: the dialog with the two snippets -------------------------
  wireEmbedDialog(root, () => embedSnippets(demo.state()));

  return { files };
}
