// The 3-D view under the stage of an arm in space: a WebGL canvas behind
// the stage's 2-D canvas (the overlay: the target's handle, the keyboard's
// ring, the axis cross, the caption; it keeps the pointer and the keys),
// drawn by pkg/three-view.js (three.js, bundled by make web from
// www/view/three-view.js), fetched here when an arm in space is first
// shown. Each frame the core changed, it draws SpaceDemo.view().

import { palette } from './module.js';
import { orientationWords } from './pose-fields.js';

let loading = null;
/** pkg/three-view.js, imported once; the page in space starts it with the core's module, so the two arrive together. */
export const preloadView = () => (loading ??= import('./pkg/three-view.js'));
const threeView = preloadView;

/**
 * "Collision volumes" over the drawing, beside "Reset view", where a
 * robot's visuals are drawn: it shows the capsules the planner measures
 * clearance to (hidden under the visuals by default).
 */
function volumesSwitch(stage, view, say) {
  const button = document.createElement('button');
  Object.assign(button, { type: 'button', id: 'show-volumes', textContent: 'Collision volumes' });
  button.setAttribute('aria-pressed', 'false');
  button.title = "Draw the capsules the planner measures clearance to, over the robot's own meshes";
  const tap = window.matchMedia?.('(pointer: coarse)').matches ? 44 : 0;
  button.style.cssText = `position: absolute; top: 6px; right: 100px; flex: none; min-height: ${tap}px; min-width: ${tap}px; padding: 1px 8px; font-size: 12px;`;
  button.addEventListener('click', () => {
    const on = button.getAttribute('aria-pressed') !== 'true';
    view.setVolumes(on);
    button.setAttribute('aria-pressed', String(on));
    say?.(on ? 'collision volumes shown over the meshes' : 'collision volumes hidden');
  });
  stage.after(button);
}

/** The selected item's index among the spheres (`sphere 2` -> 1), or -1 for the target. */
const sphereIndex = (selected) => (selected === 'target' ? -1 : Number(selected.split(' ')[1]) - 1);

/**
 * The gizmo's hooks for `demo`: a drag moves the selected item (the
 * target, or a sphere: the run replans as for any move), its end says
 * where it is; a press on the target or a sphere itself is the core's
 * drag (in the plane facing the camera: space-input.js), not the gizmo's.
 */
function gizmoHooks(stage, demo, { attempt, say, changed }) {
  return {
    moved: (p) => {
      const s = demo.state();
      const k = sphereIndex(s.selected);
      if (k < 0) attempt(() => demo.setTarget(...p));
      else attempt(() => demo.setSpheres(Float64Array.from(s.spheres.flatMap((c, i) => (i === k ? [...p, c[3]] : c)))));
    },
    // The rings, for the pose task's target: its orientation, by rows.
    turned: (rows) => attempt(() => demo.setTargetRotation(Float64Array.from(rows))),
    ended: () => {
      const s = demo.state();
      const k = sphereIndex(s.selected);
      const c = k < 0 ? s.target : s.spheres[k];
      const turned = k < 0 && s.task === 'pose' ? `, turned to ${orientationWords(s.target_rpy)}` : '';
      say(`moved: ${s.selected} at x ${c[0].toFixed(2)}, y ${c[1].toFixed(2)}, z ${c[2].toFixed(2)} m${turned}`);
      changed();
    },
    yields: (e) => {
      const r = stage.getBoundingClientRect();
      const what = demo.hover(e.clientX - r.left, e.clientY - r.top, e.pointerType === 'mouse' ? 4 : 18);
      return Boolean(what) && !what.startsWith('elbow');
    },
  };
}

/**
 * Puts the 3-D view under `stage` (the overlay canvas) for `demo` (a
 * SpaceDemo), with the gizmo on the selected item; the hooks `attempt(fn)`,
 * `say(text)` and `changed()` are the page's. Resolves to { draw(),
 * resize(w, h, dpr), snapshot(), gizmoAxis(), error }, `error` the reason
 * where the browser gives no WebGL (then draw does nothing and the overlay
 * alone is shown).
 */
export async function mountView(stage, demo, hooks, robot = null) {
  const canvas = document.createElement('canvas');
  canvas.className = 'view-3d';
  canvas.setAttribute('aria-hidden', 'true');
  stage.before(canvas);
  let view = null;
  let error = null;
  let drawn = null;
  try {
    const { createView } = await threeView();
    view = createView(canvas, palette());
    view.attachGizmo(stage, gizmoHooks(stage, demo, hooks));
    if (robot) drawn = view.setRobot({ links: robot.read.links, visuals: robot.visuals, meshes: robot.meshes });
    if (drawn?.drawn) volumesSwitch(stage, view, hooks.say);
  } catch (e) {
    error = `this browser draws no 3-D view (${e?.message ?? e}): WebGL is off or missing. The run, its readouts and its plots still work.`;
    canvas.remove();
  }
  let size = null;
  return {
    error,
    resize(width, height, dpr) {
      size = [width, height, dpr];
      view?.resize(width, height, dpr);
    },
    draw() {
      if (view && size) view.draw(demo.view(), () => demo.layerView());
    },
    /** The 3-D view with the overlay over it, one 2-D canvas (or the overlay alone without WebGL). */
    snapshot() {
      if (!view) return stage;
      view.draw(demo.view(), () => demo.layerView());
      return view.snapshot(stage);
    },
    /** A robot's visuals: { drawn, missing } (how many drawn, the mesh files not at hand), or null. */
    robotDrawn: drawn,
    /** The gizmo's part under the pointer, or null (space-input.js leaves a press there to it). */
    gizmoAxis: () => view?.gizmoAxis() ?? null,
    /** Whether the gizmo turns the pose task's target rather than moving it (redrawn now). */
    setTurn(on) {
      view?.setTurn(on);
      this.draw();
    },
    three: view,
  };
}
