// The Atlas panel: the current task run with the obstacle centred on every
// cell of a grid, in the chosen methods, in a Web Worker (worker.js); the
// result drawn under the arm by the module (Demo.setAtlasLayer), a legend,
// a table of success rates, the numbers of the cell under the pointer, and
// a click on a cell to put the obstacle there and replay the task.
//
// `mountAtlas(root, demo, hooks)` wires the elements of `root` that exist
// (`#atlas-modes`, `#atlas-n`, `#atlas-run`, `#atlas-cancel`,
// `#atlas-progress`, `#atlas-status`, `#atlas-result`, `#atlas-show`,
// `#atlas-hide`, `#atlas-legend`, `#atlas-body`, `#atlas-agreement`,
// `#atlas-tip`); hook: `changed()` (after the obstacle moved). The job
// takes the module's run (`Demo.run()`: scene and networks in use) and the
// atlas is stale when the state's `revision.atlas` moves on. Returns
// `{ run(options), hover(x, y), click(x, y), result() }` for the page's
// pointer handlers and for `window.demo.atlas()`. The methods, their labels
// and the default grid come from the module.

import { limits, methods, methodGroups, atlasClasses, describe, paperMethods } from './module.js';
import { runWorker, nativeFigures, showBusy } from './jobs.js';
import { metres, percent, row } from './format.js';
import { saveBlob, saveText, svgToPng } from './download.js';

/** Points per side the panel offers (with the core's default, selected). */
export const RESOLUTIONS = [11, 21, 41, 61];

export function mountAtlas(root, demo, { changed }) {
  const $ = (id) => root.querySelector('#' + id);
  const el = {
    methods: $('atlas-modes'),
    n: $('atlas-n'),
    run: $('atlas-run'),
    cancel: $('atlas-cancel'),
    progress: $('atlas-progress'),
    status: $('atlas-status'),
    result: $('atlas-result'),
    show: $('atlas-show'),
    hide: $('atlas-hide'),
    legend: $('atlas-legend'),
    body: $('atlas-body'),
    agreement: $('atlas-agreement'),
    tip: $('atlas-tip'),
    figure: $('atlas-figure'),
    figurePng: $('atlas-figure-png'),
    csv: $('atlas-csv'),
    json: $('atlas-json'),
  };
  const CLASSES = atlasClasses(); // [{ name, label, colour, swatch }], the layer's indices
  const code = Object.fromEntries(CLASSES.map((c, i) => [c.name, i]));
  const label = Object.fromEntries(methods().map((m) => [m.name, m.label]));
  const avoids = Object.fromEntries(methods().map((m) => [m.name, m.avoids]));
  const defaultGrid = limits().default_grid;

  if (el.methods && !el.methods.querySelector('input')) {
    for (const g of methodGroups()) {
      const head = document.createElement('span');
      head.className = 'group';
      head.textContent = g.label;
      el.methods.append(head);
      for (const m of g.methods) {
        const l = document.createElement('label');
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.value = m.name;
        box.checked = true;
        l.append(box, ` ${m.label}`);
        el.methods.append(l);
      }
    }
  }
  if (el.n && !el.n.options.length) {
    const choices = [...new Set([...RESOLUTIONS, defaultGrid])].sort((a, b) => a - b);
    for (const n of choices) el.n.add(new Option(`${n} × ${n} cells`, String(n), n === defaultGrid, n === defaultGrid));
  }

  let atlas = null; // the last result (the JSON shape of `redundant-ik atlas --json`)
  let shown = null; // the method drawn on the stage
  let running = null; // AbortController of the job under way
  let atlasRevision = null; // the state's revision.atlas it was computed at
  let sceneUsed = null; // that scene itself (Demo.scene()), for the figure

  const status = (text) => el.status && (el.status.textContent = text);

  /** What the atlas depends on, from the state (not the moved obstacle). */

  function show(method) {
    if (!atlas) return;
    shown = method;
    const codes = new Uint8Array(atlas.cells.length);
    atlas.cells.forEach((c, i) => (codes[i] = code[c.outcomes[method].class]));
    demo.setAtlasLayer(atlas.grid.region, atlas.grid.n, codes);
    if (el.show && el.show.value !== method) el.show.value = method;
    fillLegend(method);
    demo.draw();
  }

  function hide() {
    shown = null;
    demo.clearAtlasLayer();
    if (el.tip) el.tip.hidden = true;
    if (el.show) el.show.value = '';
    fillLegend(null);
    demo.draw();
  }

  function fillLegend(method) {
    if (!el.legend) return;
    el.legend.replaceChildren();
    if (!method) return;
    const counts = atlas.summary[method].counts;
    // The class of a joint past its limits only for an arm with limits.
    const limited = Boolean(demo.state().arm.joint_limits);
    // Self-collision only where a cell had it (a chain that checks it).
    for (const c of CLASSES.filter((c) => (limited || !c.limits) && (!c.self_collision || counts[c.name] > 0))) {
      const li = document.createElement('li');
      li.dataset.key = c.name;
      const key = document.createElement('span');
      key.className = 'key key-disc';
      key.style.setProperty('--swatch', c.swatch);
      li.append(key, `${c.label} (${counts[c.name]})`);
      el.legend.append(li);
    }
  }

  /**
   * What an atlas's numbers are of (its task, grid, region and the scene's
   * damping and drift correction): the table's caption and the tour's
   * figure say it, since the same method's rate differs between grids and
   * settings (the README's tables are with damping off, as in the paper).
   */
  function describeAtlas(a = atlas, scene = sceneUsed) {
    const [x0, x1, y0, y1] = a.grid.region;
    const box = `[${x0.toFixed(2)}, ${x1.toFixed(2)}] × [${y0.toFixed(2)}, ${y1.toFixed(2)}] m`;
    // The scene's JSON (Demo.scene(), `simulate --json`'s): a damping schedule or null.
    const damping = scene?.damping ? 'damping near singular poses on' : 'damping off, as in the paper';
    const feedback = scene?.feedback_gain > 0 ? `, drift corrected (K = ${scene.feedback_gain} 1/s)` : '';
    return `Task ${a.task ?? '–'}, ${a.grid.n} × ${a.grid.n} cells over ${box}, ${damping}${feedback}`;
  }

  function fillTable() {
    const table = el.body?.closest('table');
    if (table) table.createCaption().textContent = `${describeAtlas()}.`;
    if (el.body) {
      el.body.replaceChildren(
        ...atlas.methods.map((m) => {
          const s = atlas.summary[m];
          const mattered = s.mattered?.cells ? `${percent(s.mattered.rate)} of ${s.mattered.cells}` : '–';
          const tr = row([
            label[m],
            percent(s.success_rate),
            mattered,
            percent(s.inside_trained_region?.rate),
            percent(s.outside_trained_region?.rate),
            s.clearance ? `${metres(s.clearance.median)} / ${metres(s.clearance.p5)}` : '–',
          ]);
          tr.dataset.method = m;
          return tr;
        }),
      );
    }
    if (el.agreement) {
      el.agreement.replaceChildren(
        ...atlas.methods
          .filter((m) => atlas.summary[m].agreement)
          .map((m) => {
            const g = atlas.summary[m].agreement;
            const li = document.createElement('li');
            li.dataset.method = m;
            li.textContent =
              `${label[m]} fails in ${g.numerical_only} cell${g.numerical_only === 1 ? '' : 's'} where the numerical route succeeds, ` +
              `and succeeds in ${g.method_only} where it fails.`;
            return li;
          }),
      );
    }
  }

  function accept(result, ms, state, scene) {
    atlas = result;
    atlasRevision = state.revision.atlas;
    sceneUsed = scene;
    if (el.status) el.status.dataset.stale = 'false';
    if (el.show) {
      el.show.replaceChildren(new Option('(hidden)', ''));
      for (const m of atlas.methods) el.show.add(new Option(label[m], m));
    }
    fillTable();
    if (el.result) el.result.hidden = false;
    const runs = atlas.cells.length * atlas.methods.length;
    const text = (native) =>
      `${runs.toLocaleString('en')} runs in ${(ms / 1000).toFixed(2)} s here${native}. ` +
      'Hover a cell for its numbers; click one to put the obstacle there and replay.';
    status(text(''));
    if (el.status) el.status.dataset.ms = String(ms);
    // The default atlas (Task 1, the default grid, the paper's methods) is
    // also timed natively (`make bench-native`).
    const paper = paperMethods();
    if (atlas.grid.n === defaultGrid && atlas.task === 1 && atlas.methods.join() === paper.join()) {
      nativeFigures().then((nat) => {
        if (nat?.atlas_ms && atlas === result) status(text(` (native, one core: ${(nat.atlas_ms / 1000).toFixed(2)} s)`));
      });
    }
    // The map of the method in use, where it was mapped.
    const selected = demo.state().method;
    const preferred = atlas.methods.includes(selected)
      ? selected
      : atlas.methods.includes(shown)
        ? shown
        : (atlas.methods.find((m) => avoids[m]) ?? atlas.methods[0]);
    show(preferred);
  }

  /**
   * Computes the atlas of the scene as it is now. `options`: `methods` (names,
   * `modes` read too, its older name;
   * default the panel's ticked ones, or all), `n` (default the panel's
   * choice, or the core's default grid), `region` ([x0, x1, y0, y1]; default the box of the
   * arm's reach), `feedback` (the closed-loop gain K) and `refine`
   * (Newton-Schulz steps on a learned Φ; both default to the scene's),
   * `networks` (a shipped set; default the set in use, or the networks
   * trained or loaded here), `onProgress`, `signal`. Resolves to the JSON
   * shape of `redundant-ik atlas --json`; the map is drawn under the arm.
   */
  async function run(options = {}) {
    const known = ['methods', 'n', 'region', 'feedback', 'refine', 'networks', 'onProgress', 'signal'];
    // `modes`, the older name of `methods`, is read too.
    const unknown = Object.keys(options ?? {}).filter((k) => !known.includes(k) && k !== 'modes');
    if (unknown.length) throw new Error(`unknown atlas option '${unknown[0]}': use ${known.join(', ')}`);
    if (running) running.abort();
    const controller = new AbortController();
    running = controller;
    if (options.signal) {
      if (options.signal.aborted) controller.abort();
      options.signal.addEventListener('abort', () => controller.abort());
    }
    const ticked = el.methods ? [...el.methods.querySelectorAll('input:checked')].map((b) => b.value) : [];
    const names = options.methods ?? options.modes ?? (ticked.length ? ticked : methods().map((m) => m.name));
    const n = options.n ?? (el.n ? Number(el.n.value) : defaultGrid);
    const run = demo.run();
    const scene = run.scene;
    const state = demo.state();
    const { feedback, refine, networks } = options;
    showBusy(el, true);
    status('Computing…');
    try {
      const { result, ms } = await runWorker(
        { kind: 'atlas', run, options: { methods: names, n, region: options.region, feedback, refine, networks } },
        {
          signal: controller.signal,
          onProgress: (p) => {
            if (el.progress) el.progress.value = p.total ? p.done / p.total : 0;
            status(`Computing… ${p.done} of ${p.total} cells`);
            if (options.onProgress) options.onProgress(p);
          },
        },
      );
      accept(result, ms, state, scene);
      return result;
    } catch (e) {
      status(e.name === 'AbortError' ? 'Cancelled.' : `The atlas failed: ${describe(e)}`);
      throw e;
    } finally {
      if (running === controller) running = null;
      showBusy(el, false);
    }
  }

  el.run?.addEventListener('click', () => run().catch(() => {}));

  // The atlas's files: its JSON (the command line's), its cells as CSV,
  // and the map shown as the figure `redundant-ik atlas --out` draws.
  async function files(button) {
    const { result } = await runWorker({ kind: 'atlas-files', atlas, scene: sceneUsed, methods: shown ? [shown] : [] });
    return result;
  }
  const stemOf = () => `atlas-task${atlas.task ?? 0}-${atlas.grid.n}x${atlas.grid.n}${shown ? `-${shown}` : ''}`;
  const saving = (button, save) =>
    button?.addEventListener('click', async () => {
      if (!atlas) return;
      button.disabled = true;
      try {
        await save(await files(button));
      } catch (e) {
        status(`Could not save: ${describe(e)}`);
      } finally {
        button.disabled = false;
      }
    });
  saving(el.figure, (f) => saveText(`${stemOf()}.svg`, f.figure, 'image/svg+xml'));
  saving(el.figurePng, async (f) => saveBlob(`${stemOf()}.png`, await svgToPng(f.figure)));
  saving(el.csv, (f) => saveText(`${stemOf()}.csv`, f.csv, 'text/csv'));
  saving(el.json, (f) => saveText(`${stemOf()}.json`, f.json + '\n', 'application/json'));
  el.cancel?.addEventListener('click', () => running && running.abort());
  el.show?.addEventListener('change', () => (el.show.value ? show(el.show.value) : hide()));
  el.hide?.addEventListener('click', hide);

  /** The cell under canvas CSS pixel (x, y) while a map is shown, outlined. */
  function cellAt(x, y) {
    if (!atlas || !shown) return undefined;
    return demo.atlasCellAt(x, y);
  }

  /** Shows the numbers of the cell under the pointer (or hides them). */
  function hover(x, y) {
    const k = cellAt(x, y);
    if (!el.tip) return k;
    if (k === undefined) {
      el.tip.hidden = true;
      return k;
    }
    const c = atlas.cells[k];
    const lines = [`obstacle at (${c.x.toFixed(3)}, ${c.y.toFixed(3)})`];
    for (const m of atlas.methods) {
      const o = c.outcomes[m];
      const cls = CLASSES[code[o.class]].label;
      const nums =
        o.min_distance === null
          ? ''
          : `, smallest link-to-obstacle clearance ${metres(Math.max(0, o.min_distance - atlas.radius))}${o.min_distance < atlas.radius ? ' (inside)' : ''}, ${metres(o.final_error)} from the target`;
      lines.push(`${label[m]}: ${cls}${nums}`);
    }
    el.tip.textContent = lines.join('\n');
    el.tip.dataset.cell = String(k);
    el.tip.hidden = false;
    // Beside the pointer, on the side where it fits inside the stage.
    const box = el.tip.offsetParent?.getBoundingClientRect();
    const [w, h] = [el.tip.offsetWidth, el.tip.offsetHeight];
    const left = box && x + 14 + w > box.width ? Math.max(0, x - 14 - w) : x + 14;
    const top = box && y + 14 + h > box.height ? Math.max(0, y - 14 - h) : y + 14;
    el.tip.style.left = `${left}px`;
    el.tip.style.top = `${top}px`;
    return k;
  }

  /** A click on a shown cell: the obstacle goes there and the task replays. */
  function click(x, y) {
    const k = cellAt(x, y);
    if (k === undefined) return false;
    const c = atlas.cells[k];
    demo.setObstacle(c.x, c.y);
    demo.runTask();
    changed();
    return true;
  }

  function leave() {
    if (atlas && shown) demo.atlasCellAt(NaN, NaN);
    if (el.tip) el.tip.hidden = true;
  }

  /** Says so when the task changed since the atlas was computed (per frame, cheap). */
  function check(state) {
    if (!atlas || !el.status || running) return;
    const stale = state.revision.atlas !== atlasRevision;
    if (stale !== (el.status.dataset.stale === 'true')) {
      el.status.dataset.stale = String(stale);
      if (stale) status('The task changed since this atlas was computed (target, a parameter or a switch): compute it again to map the new one.');
    }
  }

  return { run, hover, click, leave, check, result: () => atlas, shown: () => shown, describe: () => (atlas ? describeAtlas() : '') };
}
