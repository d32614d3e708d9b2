// What a screen reader hears: one polite live region (`#announcer`) for the
// run's events, from the state every frame (the module's facts: the
// collision flags, the nearest obstacle, the joints, the run's end and its
// errors), and the drawing's text summary (`#stage-summary`, the canvas's
// aria-describedby), rewritten when the run's scene changes. At most one
// announcement every 1.5 s: one that comes sooner waits. Each kind of news
// (a collision, the run's end, the method, what the keys hold, the task)
// keeps its latest text while it waits, and the kinds waiting are said
// together, in the order they came: a burst of selections is one phrase,
// and a run that ends meanwhile does not drown the selection.

import { method } from './module.js';
import { fixed, metres } from './format.js';

/** The fewest milliseconds between two announcements. */
export const ANNOUNCE_GAP_MS = 1500;

const point = (p) => `(${fixed(p[0], 2)}, ${fixed(p[1], 2)}) m`;
const plural = (n, word) => `${n} ${word}${n === 1 ? '' : 's'}`;
const label = (name) => method(name)?.label ?? name;

/** The distance from point `c` to the segment `a`-`b`. */
function toSegment(c, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const len = dx * dx + dy * dy;
  const u = len > 0 ? Math.min(1, Math.max(0, ((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / len)) : 0;
  return Math.hypot(a[0] + u * dx - c[0], a[1] + u * dy - c[1]);
}

/**
 * Which link (1-based) is inside which obstacle (1-based) now: the
 * module says there is a collision and which obstacle is nearest a link;
 * the link is the one nearest that obstacle's centre.
 */
function contact(s) {
  const k = s.nearest;
  const o = k === null || k === undefined ? null : s.obstacles[k];
  if (!s.collision || !o) return null;
  let link = 0;
  let best = Infinity;
  for (let i = 0; i + 1 < s.joints.length; i++) {
    const d = toSegment(o.centre, s.joints[i], s.joints[i + 1]);
    if (d < best) [best, link] = [d, i + 1];
  }
  return { link, obstacle: k + 1 };
}

/** What the collision announcement says. */
function collisionText(s) {
  const c = contact(s);
  const t = `t = ${fixed(s.t, 1)} s`;
  return c ? `collision: link ${c.link} inside obstacle ${c.obstacle} at ${t}` : `collision: a link went inside an obstacle before ${t}`;
}

/** What the end of a run says: its final error, the smallest clearance (to an obstacle's edge, as the readouts), whether a link hit. */
function endText(s) {
  const to = s.path ? "the path's end" : 'the target';
  const hit = s.collided ? 'a link hit an obstacle' : 'no collision';
  const near = s.min_clearance === null || s.min_clearance === undefined ? '' : `, smallest clearance to an obstacle ${fixed(s.min_clearance, 3)} m`;
  return `run ended at t = ${fixed(s.t, 1)} s: the hand is ${metres(s.final_error)} from ${to}${near}, ${hit}`;
}

/** What the keys move (the state's `selected`), in words. */
export function selectedText(s) {
  if (s.selected === 'obstacle') {
    const o = s.obstacles[s.selected_index];
    return `obstacle ${s.selected_index + 1}${o ? ` at ${point(o.centre)}` : ''}`;
  }
  if (s.selected === 'joint') return `elbow ${s.selected_index} (the hand holds still)`;
  return `the target at ${point(s.target)}`;
}

/** The drawing in words: the arm, the path and target, the obstacles, the method. */
export function sceneSummary(s) {
  const links = s.arm.links.map((l) => fixed(l, 2)).join(', ');
  const path = s.path ? `its hand follows the path ${s.path}` : `its hand follows a straight line to the target at ${point(s.target)}`;
  const obstacles = s.obstacles.length
    ? `${plural(s.obstacles.length, 'obstacle')}: ${s.obstacles.map((o, i) => `${i + 1} at ${point(o.centre)}, radius ${fixed(o.radius, 2)} m`).join('; ')}`
    : 'no obstacles';
  const ghost = s.ghost ? '; a dashed ghost arm shows the numerical route' : '';
  return `The drawing: a ${s.arm.links.length}-link arm on a ${fixed(s.arm.post, 2)} m post (links ${links} m); ${path}; ${obstacles}; method: ${label(s.method)}${ghost}.`;
}

/**
 * Wires `#announcer` and `#stage-summary` under `root` (each optional).
 * Returns `{ say(text, kind), sync(state), task(n) }`: `sync` for the
 * animation loop, `task` for a task loaded (the task buttons).
 */
export function mountAnnouncer(root, { gap = ANNOUNCE_GAP_MS } = {}) {
  const region = root.querySelector('#announcer');
  const summary = root.querySelector('#stage-summary');
  let last = -Infinity;
  const pending = new Map(); // kind -> its latest text, in the order the kinds came
  let timer = 0;

  function flush() {
    timer = 0;
    if (pending.size === 0 || !region) return;
    region.textContent = [...pending.values()].join('; ');
    pending.clear();
    last = performance.now();
  }
  /**
   * Says `text` now, or as soon as the gap allows; meanwhile a newer text
   * of the same `kind` replaces it, and one of another kind joins it.
   */
  function say(text, kind = 'note') {
    pending.delete(kind);
    pending.set(kind, text);
    if (timer) return;
    const wait = last + gap - performance.now();
    if (wait <= 0) flush();
    else timer = setTimeout(flush, wait);
  }

  let seen = null; // what the last state said: { collided, ended, method, run }
  function sync(s) {
    if (seen) {
      if (s.collided && !seen.collided) say(collisionText(s), 'collision');
      if (s.ended && !seen.ended) say(endText(s), 'end');
      if (s.method !== seen.method) say(`method: ${label(s.method)}`, 'method');
      if (s.selected !== seen.selected || s.selected_index !== seen.selectedIndex) say(`selected: ${selectedText(s)}`, 'selected');
    }
    if (summary && (!seen || s.revision.run !== seen.run || s.method !== seen.method)) {
      const text = sceneSummary(s);
      if (summary.textContent !== text) summary.textContent = text;
    }
    seen = { collided: s.collided, ended: s.ended, method: s.method, run: s.revision.run, selected: s.selected, selectedIndex: s.selected_index };
  }

  return { say, sync, task: (n) => say(`task ${n}: the paper's scene, from t = 0`, 'task') };
}
