// The comparison panel: the scene as it is now, run from t = 0 with every
// method off screen (Demo.compareMethods(), one row per method of
// methods()), tabulated: the smallest link-to-obstacle clearance, hit,
// final error. A hit the obstacle makes unavoidable (on the path the hand
// must follow, or on the arm at the start: the atlas's classes) says so;
// the table greys out when the scene changes after it was computed; its
// rows download as CSV.

import { metres } from './format.js';
import { csv, saveText } from './download.js';

const WHY = {
  path_blocked: 'an obstacle covers the path the hand must follow: no method can follow the line and miss it',
  start_overlap: 'an obstacle touches the arm at t = 0: every method starts inside it',
};

/**
 * Wires `#compare`, `#compare-body`, `#compare-table`, `#compare-status`
 * and `#compare-csv` under `root`, if there. Returns `check(state)` for
 * the animation loop (greys the table out when the scene changed).
 */
export function mountCompare(root, demo, { attempt }) {
  const $ = (id) => root.querySelector('#' + id);
  const button = $('compare');
  const body = $('compare-body');
  const table = $('compare-table');
  const status = $('compare-status');
  const download = $('compare-csv');
  let rows = null;
  let key = null;
  button?.addEventListener('click', () => {
    let result = null;
    if (!attempt(() => (result = demo.compareMethods()), 'error', button)) return;
    rows = result;
    // What the table depends on: everything but the method in use.
    key = demo.state().revision.scene;
    body?.replaceChildren(...rows.map(compareRow));
    if (table) table.dataset.stale = 'false';
    const blocked = rows[0]?.unavoidable;
    if (status) status.textContent = blocked ? `Unavoidable: ${WHY[blocked] ?? blocked}.` : '';
    if (download) download.disabled = false;
  });
  download?.addEventListener('click', () => {
    if (!rows) return;
    const s = demo.state();
    const header = ['method', 'label', 'min_clearance_m', 'collided', 'unavoidable', 'final_error_m', 'reached', 'error', 'limit_steps'];
    const lines = rows.map((r) => {
      const m = r.summary;
      return [r.method, r.label, m?.min_clearance, m?.collided, r.unavoidable ?? '', m?.final_error, m?.reached, r.error ?? '', m?.limit_steps];
    });
    saveText(`compare-task${s.task}.csv`, csv(header, lines), 'text/csv');
  });
  return function check(s) {
    if (!rows || !table) return;
    const stale = s.revision.scene !== key;
    if (String(stale) !== table.dataset.stale) {
      table.dataset.stale = String(stale);
      if (status && stale) status.textContent = 'The scene changed since this comparison: press Compare to run it again.';
    }
  };
}

/** One method's row: `{ method, label, summary, error, unavoidable }`. */
function compareRow(r) {
  const tr = document.createElement('tr');
  tr.dataset.method = r.method;
  const cell = (text, cls) => {
    const td = document.createElement('td');
    td.textContent = text;
    if (cls) td.className = cls;
    tr.append(td);
    return td;
  };
  cell(r.label);
  if (r.summary) {
    const s = r.summary;
    tr.dataset.collided = String(s.collided);
    tr.dataset.minDistance = String(s.min_distance);
    tr.dataset.finalError = String(s.final_error);
    tr.dataset.minClearance = String(s.min_clearance);
    cell(s.min_clearance === null ? '–' : `${s.min_clearance.toFixed(3)} m`, 'num');
    if (s.collided && r.unavoidable) {
      tr.dataset.unavoidable = r.unavoidable;
      cell('unavoidable', 'unavoidable').title = `hit: ${WHY[r.unavoidable] ?? r.unavoidable}`;
    } else {
      cell(s.collided ? 'yes' : 'no', s.collided ? 'bad' : 'ok');
    }
    // Steps past a joint limit, where the method had any (the lab's arms).
    if (s.limit_steps > 0) {
      tr.dataset.limitSteps = String(s.limit_steps);
      const past = document.createElement('span');
      past.className = 'bad';
      past.textContent = `, ${s.limit_steps} step${s.limit_steps === 1 ? '' : 's'} past a joint limit`;
      tr.lastChild.append(past);
    }
    cell(metres(s.final_error), s.reached ? 'num' : 'num warn');
  } else {
    tr.dataset.error = r.error;
    cell(r.error, 'warn').colSpan = 3;
  }
  return tr;
}
