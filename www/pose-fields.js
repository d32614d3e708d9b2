// The hand's full pose as the task, on the page in space (SpaceDemo's
// setTask): the Hand menu (position, or the full pose with the paper's Z),
// the target's roll, pitch and yaw in degrees (number fields: the WCAG
// 2.5.7 alternative to the gizmo's rings), Z's orientation weight, and the
// button that turns the gizmo from moving the target to turning it. The
// keys x, y and z on the drawing turn the target about the world's axes
// (space-input.js).

import { applied, applyGroup, follow } from './place-fields.js';

const DEG = Math.PI / 180;

/** The target's orientation as words, degrees rounded. */
export function orientationWords(rpy) {
  const [r, p, y] = rpy.map((a) => Math.round(a / DEG));
  return `roll ${r}, pitch ${p}, yaw ${y} degrees`;
}

/**
 * Wires the pose controls under `root` (none: nothing). Hooks: `attempt(fn,
 * kind, near)`, `changed()`, `say(text)`, and `view` (space-view.js's,
 * whose setTurn(on) makes the gizmo turn the target). Returns `sync(state)`
 * for the loop.
 */
export function mountPoseFields(root, demo, { attempt, changed, say, view }) {
  const $ = (id) => root.querySelector(`#${id}`);
  const group = $('pose-fields');
  const task = $('hand-task');
  const angles = ['roll', 'pitch', 'yaw'].map((a) => $(`target-${a}`));
  const weight = $('orientation-weight');
  const turn = $('gizmo-turn');
  if (!group || !task || angles.some((f) => !f) || !weight || !turn) return () => {};
  const posed = group.querySelectorAll('[data-pose]');
  const setTurn = (on) => {
    turn.setAttribute('aria-pressed', String(on));
    view.setTurn(on);
  };
  task.addEventListener('change', () => {
    if (attempt(() => demo.setTask(task.value), 'error', task)) {
      const s = demo.state();
      say(s.task === 'pose' ? `task: the hand's full pose, the target turned as the hand is: ${orientationWords(s.target_rpy)}` : "task: the hand's position, its orientation free");
      if (s.task !== 'pose') setTurn(false);
      changed();
    } else task.value = demo.state().task;
  });
  const need = 'the target orientation needs three angles, roll, pitch and yaw, in degrees';
  const apply = (field) => applyGroup(angles, field, { scale: DEG, need, set: (...v) => demo.setTargetOrientation(...v), attempt, changed });
  for (const f of angles) f.addEventListener('change', () => apply(f));
  weight.addEventListener('change', () => {
    if (attempt(() => demo.setOrientationWeight(Number(weight.value)), 'error', weight)) {
      applied(weight);
      changed();
    }
  });
  turn.addEventListener('click', () => {
    const on = turn.getAttribute('aria-pressed') !== 'true';
    setTurn(on);
    say(on ? "the gizmo turns the target: drag its rings (or keys x, y and z on the drawing)" : 'the gizmo moves the target: drag its arrows');
  });
  let shown = '';
  return function sync(s) {
    const key = `${s.dof}|${s.task}|${s.target_rpy}|${s.orientation_weight}`;
    if (key === shown) return;
    shown = key;
    group.hidden = s.dof < 6;
    task.value = s.task;
    for (const el of posed) el.hidden = s.task !== 'pose';
    if (s.task !== 'pose') return;
    angles.forEach((f, i) => follow(f, s.target_rpy[i] / DEG));
    // The weight spans 1e-6 to 1e6: six significant digits, not millimetres.
    follow(weight, s.orientation_weight, (z) => String(Number(z.toPrecision(6))));
  };
}
