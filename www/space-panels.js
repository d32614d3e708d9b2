// The panels around the 3-D stage (an arm in space): the comparison of
// every method on the scene as it is (run whole in the page's module, as
// the stage's run is), Save and share (the run as `simulate --arm A --json`
// writes it, which `simulate --from` replays, and as CSV; the drawing and
// the plots as PNG; the link; the Embed dialog's iframe), and the slice
// atlas (space-atlas.js).

import { fixed, metres } from './format.js';
import { method, describe } from './module.js';
import { runWorker } from './jobs.js';
import { saveText, saveBlob, csv } from './download.js';
import { wireEmbedDialog, snippetsOf } from './takeaway.js';
import { spaceQuery } from './space-address.js';
import { mountSpaceAtlas } from './space-atlas.js';

/** Wires the panels; returns { sync(state), compare(), atlas(options) }. */
export function mountSpacePanels(root, demo, { attempt, show, say, preset, ensureNetworks, changed, snapshot }) {
  const $ = (id) => root.querySelector('#' + id);
  const stem = () => {
    const s = demo.state();
    return `redundant-ik-${s.arm}-${s.method}`;
  };

  // ---- the comparison ---------------------------------------------------------
  const body = $('compare-body');
  const status = $('compare-status');
  const csvButton = $('compare-csv');
  let rows = null;
  // The learned methods need the arm's networks, fetched first where they
  // are shipped; where they cannot be had the table says why they are left out.
  async function compare() {
    let left = '';
    if (!demo.state().has_networks) {
      if (status) status.textContent = `Fetching the ${preset.label}'s networks for Cases 1-3 first…`;
      const why = ensureNetworks ? await ensureNetworks() : 'no networks';
      if (why) left = ` Cases 1-3 are left out: ${why}.`;
    }
    let result = null;
    if (!attempt(() => (result = demo.compareMethods()), 'error', $('compare'))) return null;
    rows = result;
    body?.replaceChildren(
      ...rows.map((r) => {
        const tr = document.createElement('tr');
        tr.dataset.method = r.method;
        const m = r.summary;
        const cells = [
          method(r.method)?.label ?? r.method,
          m.min_clearance === null ? '—' : fixed(m.min_clearance, 3),
          m.collision_steps ? `yes (${m.collision_steps} steps)` : 'no',
          r.failure ? `stopped: ${r.failure}` : metres(m.final_error),
        ];
        for (const c of cells) {
          const td = document.createElement('td');
          td.textContent = c;
          tr.append(td);
        }
        if (m.collision_steps) tr.dataset.level = 'bad';
        return tr;
      }),
    );
    const hits = rows.filter((r) => r.summary.collision_steps > 0).length;
    const text = `${rows.length} methods on the ${preset.label}'s scene: ${hits} collide.${left}`;
    if (status) status.textContent = text;
    if (csvButton) csvButton.disabled = false;
    say(text);
    return rows;
  }
  $('compare')?.addEventListener('click', compare);
  csvButton?.addEventListener('click', () => {
    if (!rows) return;
    const header = ['method', 'min_clearance', 'collision_steps', 'limit_steps', 'relaxed_steps', 'handover_steps', 'max_error', 'final_error', 'failure'];
    const lines = rows.map((r) => {
      const m = r.summary;
      return [r.method, m.min_clearance ?? '', m.collision_steps ?? 0, m.limit_steps ?? 0, m.relaxed_steps ?? 0, m.handover_steps, m.max_tracking_error, m.final_error, r.failure ?? ''];
    });
    saveText(`${stem()}-compare.csv`, csv(header, lines), 'text/csv');
  });

  // ---- Save and share ------------------------------------------------------------
  // The view: the 3-D drawing with the overlay over it (space-view.js's snapshot).
  const canvasPng = (id, suffix) => {
    const canvas = id === 'stage' ? snapshot() : $(id);
    canvas?.toBlob((blob) => blob && saveBlob(`${stem()}-${suffix}.png`, blob), 'image/png');
  };
  $('save-run-json')?.addEventListener('click', () => saveText(`${stem()}.json`, demo.runFile(), 'application/json'));
  $('save-run-csv')?.addEventListener('click', () => saveText(`${stem()}.csv`, demo.runCsv(), 'text/csv'));
  $('save-figure-png')?.addEventListener('click', () => canvasPng('stage', 'view'));
  $('save-plots-png')?.addEventListener('click', () => canvasPng('plots', 'plots'));
  // The figure (the run's two orthographic views, as redundant-ik figure
  // --from FILE draws them) and the plots (figure --from FILE --plots), in a worker.
  const drawn = (kind, suffix, what) => async () => {
    try {
      const { result } = await runWorker({ kind, run: demo.runFile() });
      saveText(`${stem()}${suffix}.svg`, result, 'image/svg+xml');
    } catch (e) {
      show(`The ${what} could not be made: ${describe(e)}`, 'error', true);
    }
  };
  $('save-figure-svg')?.addEventListener('click', drawn('space-figure', '', 'figure'));
  $('save-plots-svg')?.addEventListener('click', drawn('space-plots', '-plots', 'plots'));
  const link = () => `${location.origin}${location.pathname}?${spaceQuery(demo.state(), preset)}`;
  $('copy-link')?.addEventListener('click', async () => {
    const text = link();
    try {
      await navigator.clipboard.writeText(text);
      show('Link copied.', 'info');
    } catch (_) {
      const field = $('link-text');
      if (field) {
        field.hidden = false;
        field.value = text;
        field.select();
      }
    }
  });
  // The iframe and the element, with the address's keys (the view too).
  wireEmbedDialog(root, () => snippetsOf(spaceQuery(demo.state(), preset), location.href, `The ${preset.label} and redundancy resolution`));

  const atlas = mountSpaceAtlas(root, demo, { attempt, show, say, preset, changed });
  return {
    sync(s) {
      atlas.sync(s);
    },
    compare,
    atlas: (o) => atlas.run(o),
  };
}
