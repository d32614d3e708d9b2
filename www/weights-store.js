// Trained weights kept in this browser (localStorage), one entry per arm
// under `redundant-ik:weights:` and the arm's `formatArm` text (the
// address's `arm=` syntax, e.g. `redundant-ik:weights:0.5:0.6,0.85,0.6`):
// `{ phi, v, report, saved }`. Storage may be full or switched off: then
// nothing is kept and the networks still work until the page reloads.

import { formatArm } from './module.js';

const STORE = 'redundant-ik:weights:';
const keyOf = (arm) => STORE + formatArm(arm.post, arm.links);

/** Trained weights kept for an arm: `{ phi, v, report, saved }` or null. */
export function storedWeights(arm) {
  try {
    const raw = localStorage.getItem(keyOf(arm));
    return raw ? JSON.parse(raw) : null;
  } catch (_) {
    forgetWeights(arm); // not JSON: nothing to keep
    return null;
  }
}

/** Keeps weights for an arm; whether they could be kept. */
export function storeWeights(arm, entry) {
  try {
    localStorage.setItem(keyOf(arm), JSON.stringify(entry));
    return true;
  } catch (_) {
    return false; // storage full or switched off: the networks still work until reload
  }
}

/** Drops the weights kept for an arm. */
export function forgetWeights(arm) {
  try {
    localStorage.removeItem(keyOf(arm));
  } catch (_) {
    /* nothing stored */
  }
}
