// Pointer, touch and keyboard on the 3-D stage (an arm in space,
// SpaceDemo): a drag on the target or a sphere moves it in the plane
// through it that faces the camera (it stays under the pointer); a drag on
// the empty drawing, or any drag with Shift or the right button, orbits;
// the wheel zooms; one finger drags an item (on nothing it scrolls the
// page), two fingers orbit (their midpoint) and zoom (their spread). Keys
// on the drawing: n / Shift+n select the next / previous item, the arrows
// move it in the view's plane (Shift: fine steps), o / Shift+o orbit by 15
// degrees (u / Shift+u up and down), + and - zoom, 0 resets the view; in
// the pose task x, y and z (Shift: backwards) turn the target by 15 degrees
// about the world's axes; the page-wide keys are page-keys.js's. The
// module decides what a point grabs and how it moves (src/session/space);
// this file only routes the events and says what changed (`say`).

import { orientationWords } from './pose-fields.js';
import { wirePageKeys, wireStageFocus } from './page-keys.js';

/**
 * Wires `stage` of the SpaceDemo `demo`. Hooks: `attempt(fn)` runs a call
 * and shows its error; `changed()` after a user change; `say(text)` tells
 * the live region; `togglePlay()`, `reset()`; `keyboard`, the element that
 * receives the page-wide keys (page-keys.js); `gizmoAxis()`, the
 * 3-D view's gizmo part under the pointer (a press there is the gizmo's).
 */
export function wireSpaceStage(stage, demo, { attempt, changed, say, togglePlay, reset, keyboard, gizmoAxis }) {
  wirePageKeys(keyboard, { togglePlay, reset });
  wireStageFocus(stage, demo);
  const where = () => {
    const s = demo.state();
    const [x, y, z] = s.selected === 'target' ? s.target : s.spheres[Number(s.selected.split(' ')[1]) - 1];
    return `${s.selected} at x ${x.toFixed(2)}, y ${y.toFixed(2)}, z ${z.toFixed(2)} m`;
  };
  const view = () => {
    const [yaw, pitch] = demo.state().view;
    return `view from ${Math.round((yaw * 180) / Math.PI)} degrees round, ${Math.round((pitch * 180) / Math.PI)} up`;
  };
  const ARROWS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
  stage.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const k = e.key;
    let said = null;
    if (ARROWS[k]) {
      const [dx, dy] = ARROWS[k];
      if (attempt(() => demo.nudge(dx, dy, e.shiftKey))) {
        changed();
        said = where();
      }
    } else if (k === 'n' || k === 'N') {
      demo.selectNext(!e.shiftKey);
      said = `selected: ${where()}`;
    } else if (k === 'o' || k === 'O') {
      attempt(() => demo.orbitSteps(e.shiftKey ? -1 : 1, 0));
      said = view();
    } else if (k === 'u' || k === 'U') {
      attempt(() => demo.orbitSteps(0, e.shiftKey ? -1 : 1));
      said = view();
    } else if (k === '+' || k === '=' || k === '-' || k === '_') {
      attempt(() => demo.zoom(k === '+' || k === '=' ? 1.25 : 0.8));
      said = `zoom: ${demo.state().view[2].toFixed(1)} m away`;
    } else if (k === '0') {
      demo.resetView();
      said = `view reset: ${view()}`;
    } else if ('xyzXYZ'.includes(k) && demo.state().task === 'pose') {
      // The pose task's target turned by 15 degrees about a world axis.
      const axis = 'xyz'.indexOf(k.toLowerCase());
      if (attempt(() => demo.turnTarget(axis, ((e.shiftKey ? -1 : 1) * Math.PI) / 12))) {
        changed();
        said = `target turned about ${'xyz'[axis]}: ${orientationWords(demo.state().target_rpy)}`;
      }
    } else {
      return;
    }
    e.preventDefault();
    if (said) say(said);
  });

  // ---- pointer and touch --------------------------------------------------
  const local = (e) => {
    const r = stage.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  const slopFor = (e) => (e.pointerType === 'mouse' ? 4 : 18);
  const touches = new Map(); // pointerId -> [x, y]
  let drag = null; // { id, kind: 'item' | 'orbit', last: [x, y] }
  let pinch = null; // { span, mid }
  let claimed = false; // a touch the page takes does not scroll it
  stage.addEventListener('touchstart', (e) => {
    if (claimed || e.touches.length > 1) e.preventDefault();
  }, { passive: false });
  stage.addEventListener('touchmove', (e) => {
    if (claimed || e.touches.length > 1) e.preventDefault();
  }, { passive: false });
  stage.addEventListener('touchend', (e) => {
    if (e.touches.length === 0) claimed = false;
  });
  const two = () => {
    const [a, b] = [...touches.values()];
    return { span: Math.hypot(a[0] - b[0], a[1] - b[1]), mid: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
  };
  stage.addEventListener('contextmenu', (e) => e.preventDefault());
  stage.addEventListener('pointerdown', (e) => {
    const p = local(e);
    if (e.pointerType === 'touch') {
      touches.set(e.pointerId, p);
      if (touches.size === 2) {
        if (drag?.kind === 'item') demo.pointerUp();
        drag = null;
        pinch = two();
        claimed = true;
        return;
      }
      if (touches.size > 2) return;
    }
    // The gizmo's arrows and squares (its listener ran first and found the part under the pointer).
    if (gizmoAxis?.() && !e.shiftKey && e.button !== 2) {
      claimed = true;
      e.preventDefault();
      return;
    }
    const orbitOnly = e.shiftKey || e.button === 2;
    const grabbed = orbitOnly ? undefined : demo.pointerDown(p[0], p[1], slopFor(e));
    if (grabbed) {
      drag = { id: e.pointerId, kind: 'item', last: p, what: grabbed };
      claimed = true;
      stage.setPointerCapture?.(e.pointerId);
      e.preventDefault();
    } else if (e.pointerType !== 'touch') {
      // The mouse or a pen on the empty drawing orbits; one finger there scrolls the page.
      drag = { id: e.pointerId, kind: 'orbit', last: p };
      stage.setPointerCapture?.(e.pointerId);
      e.preventDefault();
    }
  });
  stage.addEventListener('pointermove', (e) => {
    const p = local(e);
    if (e.pointerType === 'touch' && touches.has(e.pointerId)) {
      touches.set(e.pointerId, p);
      if (pinch && touches.size === 2) {
        const now = two();
        attempt(() => demo.orbit(now.mid[0] - pinch.mid[0], now.mid[1] - pinch.mid[1]));
        if (pinch.span > 10 && now.span > 10) attempt(() => demo.zoom(now.span / pinch.span));
        pinch = now;
        return;
      }
    }
    if (!drag || drag.id !== e.pointerId) {
      if (e.pointerType === 'mouse') stage.style.cursor = gizmoAxis?.() || demo.hover(p[0], p[1], 4) ? 'grab' : 'default';
      return;
    }
    if (drag.kind === 'item') attempt(() => demo.pointerMove(p[0], p[1]));
    else attempt(() => demo.orbit(p[0] - drag.last[0], p[1] - drag.last[1]));
    drag.last = p;
  });
  const end = (e) => {
    touches.delete(e.pointerId);
    if (touches.size < 2) pinch = null;
    if (!drag || drag.id !== e.pointerId) return;
    if (drag.kind === 'item') {
      demo.pointerUp();
      changed();
      // An elbow moves the arm in the null space: the hand held, the pose the run's new start.
      say(drag.what.startsWith('elbow') ? `${drag.what} moved, the hand held still: the run starts from this pose` : `moved: ${where()}`);
    } else {
      say(view());
    }
    drag = null;
  };
  stage.addEventListener('pointerup', end);
  stage.addEventListener('pointercancel', end);
  stage.addEventListener(
    'wheel',
    (e) => {
      e.preventDefault();
      attempt(() => demo.zoom(Math.exp(-e.deltaY * 0.0015)));
    },
    { passive: false },
  );
}
