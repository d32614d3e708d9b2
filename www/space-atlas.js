// The slice atlas of an arm in space, in the Atlas panel (html[data-space]):
// the sphere moved over a grid on a plane (the vertical one through the
// line by default, or xy, xz, yz at a height or offset the panel takes), each
// cell run whole in every method ticked, in a Web Worker (jobs.js
// spaceAtlas: progress and cancel), then its table of outcomes by method and
// the map of one method drawn on its plane in the view (SpaceDemo's
// setAtlasLayer), the same cells `redundant-ik atlas --arm A --json` gives;
// its files to take away (the map shown as SVG or PNG, the cells as CSV,
// the JSON), made in a worker as `atlas --arm A --out`, `--csv`, `--json`.

import { atlasClasses, methods, describe, spaceNetworkSets, assetUrl } from './module.js';
import { spaceAtlas, runWorker } from './jobs.js';
import { metres } from './format.js';
import { saveBlob, saveText, svgToPng } from './download.js';

const pct = (x) => `${(100 * x).toFixed(1)}%`;

/** An atlas's plane (`{ Xz: 0.2 }` in its JSON) as its axes and offset: `['xz', 0.2]`. */
const planeOf = (a) => {
  const [axes, at] = Object.entries(a.plane)[0];
  return [axes.toLowerCase(), at];
};

/** Wires the spatial Atlas panel; returns { sync(state), run(options), result() }. */
export function mountSpaceAtlas(root, demo, { show, say, preset, changed }) {
  const panel = root.querySelector('#atlas-panel');
  if (!panel) return { sync() {}, run: async () => null, result: () => null };
  const summary = panel.querySelector('summary');
  panel.replaceChildren(summary);
  summary.textContent = 'Slice atlas: where a sphere on a plane makes each method fail';
  const intro = document.createElement('p');
  intro.textContent = `Moves the sphere over a grid on a plane (by default the vertical plane through the hand's line), runs the ${preset.label}'s task from t = 0 in each method ticked for every cell, in the background, and draws the chosen method's map on that plane in the view.`;
  const form = document.createElement('div');
  form.className = 'row';
  const plane = document.createElement('input');
  Object.assign(plane, { id: 'space-atlas-plane', type: 'text', value: '', placeholder: 'through the line, or xz:0.2, xy:0.5, yz:0.4', spellcheck: false });
  const planeLabel = document.createElement('label');
  planeLabel.append('Plane ', plane);
  const n = document.createElement('select');
  n.id = 'space-atlas-n';
  for (const k of [11, 21, 31]) n.append(new Option(`${k} x ${k}`, String(k), k === 21, k === 21));
  const nLabel = document.createElement('label');
  nLabel.append('Grid ', n);
  form.append(planeLabel, nLabel);
  const boxes = document.createElement('fieldset');
  boxes.className = 'atlas-modes';
  boxes.id = 'space-atlas-methods';
  const legend = document.createElement('legend');
  legend.textContent = 'Methods';
  boxes.append(legend);
  for (const m of methods()) {
    const l = document.createElement('label');
    const b = document.createElement('input');
    Object.assign(b, { type: 'checkbox', value: m.name, checked: true });
    b.dataset.networks = String(Boolean(m.networks.phi || m.networks.v));
    l.append(b, ` ${m.label}`);
    boxes.append(l);
  }
  const buttons = document.createElement('p');
  buttons.className = 'row buttons';
  const go = Object.assign(document.createElement('button'), { type: 'button', id: 'space-atlas-run', textContent: 'Compute the atlas' });
  const cancel = Object.assign(document.createElement('button'), { type: 'button', id: 'space-atlas-cancel', textContent: 'Cancel', hidden: true });
  const progress = Object.assign(document.createElement('progress'), { id: 'space-atlas-progress', max: 1, value: 0, hidden: true });
  buttons.append(go, cancel, progress);
  const status = Object.assign(document.createElement('p'), { id: 'space-atlas-status' });
  status.setAttribute('role', 'status');
  const showRow = document.createElement('p');
  showRow.className = 'row';
  const which = Object.assign(document.createElement('select'), { id: 'space-atlas-show' });
  const hide = Object.assign(document.createElement('button'), { type: 'button', id: 'space-atlas-hide', textContent: 'Hide the map' });
  const whichLabel = document.createElement('label');
  whichLabel.append('Map of ', which);
  const saves = [
    ['space-atlas-figure', 'Save map (SVG)'],
    ['space-atlas-figure-png', 'PNG'],
    ['space-atlas-csv', 'Cells (CSV)'],
    ['space-atlas-json', 'JSON'],
  ].map(([id, textContent]) => Object.assign(document.createElement('button'), { type: 'button', id, textContent }));
  showRow.append(whichLabel, hide);
  showRow.hidden = true;
  const saveRow = Object.assign(document.createElement('p'), { className: 'row buttons', hidden: true });
  saveRow.append(...saves);
  const table = document.createElement('table');
  table.className = 'compare';
  table.id = 'space-atlas-table';
  panel.append(intro, form, boxes, buttons, status, showRow, table, saveRow);

  const classes = atlasClasses();
  let last = null;
  // The atlas's own JSON text and the run file it was computed on, for its files.
  let made = null;
  let controller = null;

  // ---- the map on the drawing: numbers under the pointer, a click places the sphere
  const stage = root.querySelector('#stage');
  const tip = root.querySelector('#atlas-tip');
  const labelOf = (m) => methods().find((x) => x.name === m)?.label ?? m;
  const local = (e) => {
    const r = stage.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  const cellAt = ([x, y]) => (last && !showRow.hidden ? demo.atlasCellAt(x, y) : undefined);
  function hover(p) {
    const k = cellAt(p);
    if (!tip) return;
    if (k === undefined) {
      tip.hidden = true;
      return;
    }
    const c = last.cells[k];
    const lines = [`sphere at (${c.centre.map((v) => v.toFixed(3)).join(', ')})`];
    last.methods.forEach((m, i) => {
      const o = c.outcomes[i];
      const cls = classes.find((x) => x.name === o.class)?.label ?? o.class;
      const nums = o.min_clearance == null ? '' : `, smallest clearance ${metres(Math.max(0, o.min_clearance))}${o.min_clearance < 0 ? ' (inside)' : ''}, ${metres(o.final_error)} from the target`;
      lines.push(`${labelOf(m)}: ${cls}${nums}`);
    });
    tip.textContent = lines.join('\n');
    tip.dataset.cell = String(k);
    tip.hidden = false;
    const box = tip.offsetParent?.getBoundingClientRect();
    const [w, h] = [tip.offsetWidth, tip.offsetHeight];
    tip.style.left = `${box && p[0] + 14 + w > box.width ? Math.max(0, p[0] - 14 - w) : p[0] + 14}px`;
    tip.style.top = `${box && p[1] + 14 + h > box.height ? Math.max(0, p[1] - 14 - h) : p[1] + 14}px`;
  }
  let down = null;
  stage?.addEventListener('pointermove', (e) => {
    if (e.buttons === 0 && e.pointerType === 'mouse') hover(local(e));
  });
  stage?.addEventListener('pointerleave', () => tip && (tip.hidden = true));
  // Not on the target or a sphere: those are dragged (space-input.js).
  stage?.addEventListener('pointerdown', (e) => {
    const p = local(e);
    down = demo.hover(p[0], p[1], e.pointerType === 'mouse' ? 4 : 18) ? null : p;
  });
  // A click (or a tap) that did not move places the first sphere on the cell and the run follows.
  stage?.addEventListener('pointerup', (e) => {
    const p = local(e);
    const still = down && Math.hypot(p[0] - down[0], p[1] - down[1]) < (e.pointerType === 'mouse' ? 4 : 12);
    down = null;
    const k = still ? cellAt(p) : undefined;
    if (k === undefined) return;
    try {
      demo.placeSphereAtCell(k);
      changed?.();
      const c = last.cells[k].centre;
      say(`sphere 1 placed on the atlas's cell at (${c.map((v) => v.toFixed(3)).join(', ')}): the run follows`);
    } catch (err) {
      show(describe(err), 'error', true);
    }
  });

  function draw(k) {
    if (!last) return;
    const cls = last.cells.map((c) => classes.findIndex((x) => x.name === c.outcomes[k].class));
    const [axes, at] = planeOf(last);
    demo.setAtlasLayer(axes, at, Float64Array.from(last.grid.region), last.grid.n, Uint8Array.from(cls));
  }
  which.addEventListener('change', () => draw(Number(which.value)));

  // The files: the map of the method shown, the cells and the JSON of every method.
  const stemOf = () => {
    const [axes, at] = planeOf(last);
    // The atlas's arm (a preset's key), else the page's (a robot of your own).
    const arm = String(last.arm ?? demo.state().arm).replace(/[^A-Za-z0-9_-]+/g, '_');
    return `atlas-${arm}-${axes}${Math.round(at * 1000)}mm-${last.grid.n}x${last.grid.n}-${last.methods[Number(which.value)]}`;
  };
  const saving = (button, save) =>
    button.addEventListener('click', async () => {
      if (!made) return;
      button.disabled = true;
      try {
        const { result } = await runWorker({ kind: 'slice-atlas-files', atlas: made.json, run: made.run, methods: [last.methods[Number(which.value)]] });
        await save(result);
      } catch (e) {
        status.textContent = `Could not save: ${describe(e)}`;
      } finally {
        button.disabled = false;
      }
    });
  saving(saves[0], (f) => saveText(`${stemOf()}.svg`, f.figure, 'image/svg+xml'));
  saving(saves[1], async (f) => saveBlob(`${stemOf()}.png`, await svgToPng(f.figure)));
  saving(saves[2], (f) => saveText(`${stemOf()}.csv`, f.csv, 'text/csv'));
  saving(saves[3], (f) => saveText(`${stemOf()}.json`, f.json + '\n', 'application/json'));
  hide.addEventListener('click', () => {
    demo.clearAtlasLayer();
    showRow.hidden = true;
    if (tip) tip.hidden = true;
  });

  function tabulate(a) {
    const head = document.createElement('tr');
    for (const h of ['method', ...classes.map((c) => c.label), 'success where avoidable']) {
      const th = document.createElement('th');
      th.textContent = h;
      head.append(th);
    }
    // Success over the cells where avoidance is possible, as `atlas --arm A` counts it.
    const avoidable = a.cells.filter((cell) => classes.find((c) => c.name === cell.outcomes[0].class)?.avoidable).length;
    const rows = a.methods.map((m, k) => {
      const tr = document.createElement('tr');
      tr.dataset.method = m;
      const counts = classes.map((c) => a.cells.filter((cell) => cell.outcomes[k].class === c.name).length);
      const rate = avoidable ? counts[0] / avoidable : NaN;
      for (const v of [methods().find((x) => x.name === m)?.label ?? m, ...counts.map(String), Number.isFinite(rate) ? pct(rate) : '—']) {
        const td = document.createElement('td');
        td.textContent = v;
        tr.append(td);
      }
      return tr;
    });
    const thead = document.createElement('thead');
    thead.append(head);
    const tbody = document.createElement('tbody');
    tbody.append(...rows);
    table.replaceChildren(thead, tbody);
    which.replaceChildren(...a.methods.map((m, k) => new Option(methods().find((x) => x.name === m)?.label ?? m, String(k))));
  }

  /** Computes the atlas (options: { methods, plane, n }); resolves to its JSON object. */
  async function run(options = {}) {
    const s = demo.state();
    const wanted = options.methods ?? [...boxes.querySelectorAll('input:checked')].map((b) => b.value);
    const learned = methods().filter((m) => wanted.includes(m.name) && (m.networks.phi || m.networks.v));
    // The learned methods with the arm's shipped networks, fetched for the worker (none shipped: left out).
    const set = spaceNetworkSets().find((x) => x.arm === s.arm);
    // Networks of your own (trained here or given): their files travel with the job.
    const own = demo.networkFiles();
    // The hand's pose: Cases 1 and 3 need a Φ for it, which no network has (the core refuses them).
    const pose = s.task === 'pose';
    const noPhi = (name) => !(pose && learned.some((l) => l.name === name && l.networks.phi));
    const chosen = (set || own ? wanted : wanted.filter((m) => !learned.some((l) => l.name === m))).filter(noPhi);
    const left = wanted.filter((m) => !noPhi(m));
    let networks = own ?? undefined;
    if (!own && set && learned.length) {
      const [phi, v] = await Promise.all(set.files.map((f) => fetch(assetUrl(`weights/${f}`)).then((r) => r.text())));
      networks = { phi, v };
    }
    controller?.abort();
    controller = new AbortController();
    go.hidden = true;
    cancel.hidden = false;
    progress.hidden = false;
    progress.value = 0;
    status.textContent = 'Computing…';
    const started = performance.now();
    const runText = demo.runFile();
    try {
      const { atlas: result, json, ms } = await spaceAtlas({
        run: runText,
        methods: chosen,
        plane: options.plane ?? (plane.value.trim() || undefined),
        n: options.n ?? Number(n.value),
        networks,
        signal: controller.signal,
        onProgress: (p) => (progress.value = p.total ? p.done / p.total : 0),
      });
      last = result;
      made = { json, run: runText };
      saveRow.hidden = false;
      revision = s.run_revision;
      delete status.dataset.stale;
      tabulate(last);
      showRow.hidden = false;
      draw(0);
      const took = ms ?? performance.now() - started;
      const [axes, at] = planeOf(last);
      const task = pose ? " of the hand's pose" : '';
      const without = left.length ? ` ${left.map(labelOf).join(' and ')} left out: no network has a Φ for the pose.` : '';
      const text = `Atlas${task} on ${axes}:${Math.round(at * 1000) / 1000}: ${last.cells.length} cells x ${last.methods.length} methods in ${(took / 1000).toFixed(1)} s.${without}`;
      status.textContent = text;
      status.dataset.ms = String(Math.round(took));
      say(text);
      return last;
    } catch (e) {
      status.textContent = e.name === 'AbortError' ? 'Cancelled.' : `The atlas failed: ${describe(e)}`;
      if (e.name !== 'AbortError') show(status.textContent, 'error', true);
      return null;
    } finally {
      go.hidden = false;
      cancel.hidden = true;
      progress.hidden = true;
    }
  }
  go.addEventListener('click', () => run());
  cancel.addEventListener('click', () => controller?.abort());
  let revision = -1;
  return {
    sync(s) {
      // A map drawn for another scene is stale: said once, kept until hidden or recomputed.
      if (last && s.run_revision !== revision && !status.dataset.stale) {
        status.dataset.stale = 'true';
        status.textContent += ' The scene has changed since: compute it again for this one.';
      }
    },
    run,
    result: () => last,
  };
}
