// The notes beside the drawing, from the state every frame: where the run
// is (ended and holding still, paused, ready), a link below the floor, a
// network's input outside its trained range, the exact Φ standing in near
// a singular pose, the paper's criterion with several obstacles; and the
// play button's word (Play, Pause, Replay). Each element is optional
// (`#run-note`, `#floor-warning`, `#range-warning`, `#handover-note`,
// `#criterion-note`, `#limits-note`, `#play`), so the custom element shows what it has.

import { metres } from './format.js';
import { method, paperMethods } from './module.js';

let paper = null; // the paper's methods, asked of the module once (this runs every frame)
/**
 * Whether method `name` avoids obstacles by the paper's criterion (the
 * triangle areas of eq. 14: the paper's methods that avoid).
 */
const areaCriterion = (name) => Boolean(method(name)?.avoids && (paper ??= new Set(paperMethods())).has(name));

/** Why the paper's criterion may hit the near obstacle of several (issue 27: read as a bug). */
const CRITERION_TEXT =
  "Several obstacles: the paper's criterion grows the triangle areas between the links and each obstacle's centre (eq. 14), " +
  'and an area grows with the distance, so a far obstacle pulls harder than a near one and a link may still hit the near one. ' +
  'The distance gradient, task priority and the QP push away from the nearest.';

const plural = (n, word) => `${n} ${word}${n === 1 ? '' : 's'}`;

/** What the run note says, or '' to hide it. */
function runText(s) {
  if (s.running) return '';
  const t = s.t.toFixed(1);
  if (s.ended) {
    const hit = s.collided ? ' A link hit an obstacle during the run.' : '';
    // A path other than the line (s.path) ends at its own end, not the target.
    if (s.path) {
      return (
        `The run ended at t = ${t} s, where its path ends: the hand is ${metres(s.final_error)} from the path's end and holds still.${hit} ` +
        'Type or draw another path, move an obstacle to replay the run with it there, or press Replay.'
      );
    }
    return (
      `The run ended at t = ${t} s, where its line ends: the hand is ${metres(s.final_error)} from the target and holds still.${hit} ` +
      'Drag the target for a new line, move an obstacle to replay the run with it there, or press Replay.'
    );
  }
  if (s.t === 0) return `Ready at the start of a ${s.tf.toFixed(1)} s run: press Play.`;
  return `Paused at t = ${t} s of ${s.tf.toFixed(1)} s.`;
}

/** Wires the notes under `root`; returns `sync(state)` for the animation loop. */
export function mountNotes(root) {
  const $ = (id) => root.querySelector('#' + id);
  const el = { run: $('run-note'), floor: $('floor-warning'), range: $('range-warning'), handover: $('handover-note'), criterion: $('criterion-note'), limits: $('limits-note'), play: $('play') };
  // The methods' text, where the page has it (the custom element has none).
  const explained = $('modes-explained');
  const set = (node, text) => {
    if (!node) return;
    if (text && node.textContent !== text) node.textContent = text;
    node.hidden = !text;
  };
  return function sync(s) {
    if (el.play) {
      const word = s.running ? 'Pause' : s.ended ? 'Replay' : 'Play';
      if (el.play.textContent !== word) el.play.textContent = word;
      el.play.setAttribute('aria-pressed', String(s.running));
    }
    if (el.run) {
      set(el.run, runText(s));
      el.run.dataset.state = s.running ? 'running' : s.ended ? 'ended' : 'paused';
    }
    // The core says whether the networks in use see inputs inside their
    // trained range (always, for a method without networks).
    if (el.range) el.range.hidden = s.in_range;
    set(
      el.floor,
      s.below_floor_steps > 0
        ? `A link ${s.below_floor ? 'is' : 'went'} below the floor (y < 0), drawn in red: ${plural(s.below_floor_steps, 'step')} of this run. A real arm would hit the ground there.`
        : '',
    );
    if (el.criterion) {
      const on = s.obstacles.length > 1 && areaCriterion(s.method);
      if (on && !el.criterion.childNodes.length) {
        el.criterion.append(CRITERION_TEXT);
        if (explained) {
          const a = document.createElement('a');
          a.href = '#modes-explained';
          a.textContent = 'The methods';
          el.criterion.append(' ', a, '.');
        }
      }
      el.criterion.hidden = !on;
    }
    // A method that keeps to the joints' ranges, on an arm that has none (the core says why).
    set(el.limits, s.without_limits ? `${s.without_limits}.` : '');
    set(
      el.handover,
      s.handover_steps > 0 && s.uses.phi
        ? `Near a singular pose the exact damped Φ stood in for the Φ network (${plural(s.handover_steps, 'step')} so far${s.phi_handover ? ', now too' : ''}).`
        : '',
    );
  };
}
