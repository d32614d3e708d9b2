// The comparison panel: the scene as it is now, run from t = 0 with every
// method off screen (Demo.compareModes(), one row per method of
// methods()), tabulated: closest approach, hit, final error.

import { metres } from './format.js';

/** Wires `#compare` and `#compare-body` under `root`, if there. */
export function mountCompare(root, demo, { attempt }) {
  const button = root.querySelector('#compare');
  const body = root.querySelector('#compare-body');
  button?.addEventListener('click', () => {
    let rows = null;
    if (!attempt(() => (rows = demo.compareModes()))) return;
    body?.replaceChildren(...rows.map(compareRow));
  });
}

/** One method's row: `{ mode, label, summary, error }`. */
function compareRow(r) {
  const tr = document.createElement('tr');
  tr.dataset.mode = r.mode;
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
    cell(s.min_distance === null ? '–' : `${s.min_distance.toFixed(3)} m`, 'num');
    cell(s.collided ? 'yes' : 'no', s.collided ? 'bad' : 'ok');
    cell(metres(s.final_error), s.reached ? 'num' : 'num warn');
  } else {
    tr.dataset.error = r.error;
    cell(r.error, 'warn').colSpan = 3;
  }
  return tr;
}
