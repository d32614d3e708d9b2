// The lab's controls (issue 25): the joint weighting of eq. (7)
// (`#joint-weighting`, its choices from the module's limits().joint_weightings,
// shown for the methods whose MethodInfo says the weighting reaches them),
// the floor and post as obstacles (`#floor`), in space the links kept apart
// from each other (`#self-collision`), the legend's switches for the
// ellipses at the hand (entries whose `toggle` the module sets) and the note
// of a joint past its limits (`#limit-warning`). Every element is optional.

import { limits, method } from './module.js';

const degrees = (rad) => Math.round((rad * 180) / Math.PI);

/** A joint's range in degrees: `±120°`, or `-90° to 45°`. */
function range([lo, hi]) {
  return lo === -hi ? `±${degrees(hi)}°` : `${degrees(lo)}° to ${degrees(hi)}°`;
}

/** The note of joints past their limits, from the state (empty: none). */
export function limitText(s) {
  if (!s.limit_steps) return '';
  const ranges = s.arm.joint_limits ?? [];
  const now = s.past_limits ?? [];
  const steps = `${s.limit_steps} step${s.limit_steps === 1 ? '' : 's'} of this run`;
  if (!now.length) return `A joint went past its limits: ${steps}. A real arm stops at its limits.`;
  const which = now.map((j) => `Joint ${j} is past its limit (${ranges[j - 1] ? range(ranges[j - 1]) : '?'})`).join('; ');
  return `${which}: ${steps}. A real arm stops at its limits.`;
}

/**
 * Wires the lab's controls under `root` to `demo`; returns `sync(state)`
 * for the animation loop.
 */
export function mountLab(root, demo, { attempt, changed }) {
  const $ = (id) => root.querySelector('#' + id);
  const el = { weighting: $('joint-weighting'), weightingField: $('joint-weighting-field'), floor: $('floor'), self: $('self-collision'), note: $('limit-warning'), legend: $('legend') };
  if (el.weighting && !el.weighting.options.length) {
    for (const [name, label] of limits().joint_weightings) el.weighting.add(new Option(label, name));
  }
  el.weighting?.addEventListener('change', () => {
    if (attempt(() => demo.setWeighting(el.weighting.value), 'error', el.weighting)) changed();
  });
  el.floor?.addEventListener('change', () => {
    demo.setFloor(el.floor.checked);
    changed();
  });
  // In space: the links kept apart from each other (SpaceDemo.setSelfCollision).
  el.self?.addEventListener('change', () => {
    if (attempt(() => demo.setSelfCollision(el.self.checked), 'error', el.self)) changed();
    else el.self.checked = !el.self.checked;
  });
  el.legend?.addEventListener('change', (e) => {
    const key = e.target?.dataset?.toggle;
    if (key) demo.setShown(key, e.target.checked);
  });
  return function sync(s) {
    if (el.weighting && el.weighting.value !== s.weighting) el.weighting.value = s.weighting;
    const field = el.weightingField ?? el.weighting;
    if (field) field.hidden = !method(s.method)?.weighting;
    if (el.floor && el.floor.checked !== s.floor) el.floor.checked = s.floor;
    if (el.self && s.self_collision !== undefined && el.self.checked !== s.self_collision) el.self.checked = s.self_collision;
    // The legend's entries of the pose task's frames and of self-collision, where they are drawn.
    for (const [key, on] of [['frame', s.task === 'pose'], ['self', s.self_collision]]) {
      const entry = el.legend?.querySelector(`[data-key=${key}]`);
      if (entry) entry.hidden = !on;
    }
    if (el.note) {
      const text = limitText(s);
      if (text && el.note.textContent !== text) el.note.textContent = text;
      el.note.hidden = !text;
    }
  };
}
