// Pointer and keyboard on the stage: drag the target and the obstacles
// (mouse and touch), a long press or a double-click removes an obstacle, a
// click adds one (while the playground asks for it) or picks an atlas cell,
// n selects an item and the arrow keys move it (Shift: fine steps), + - and 0 zoom and
// fit, the wheel (a trackpad's pinch: ctrl+wheel) and two fingers zoom
// about the pointer, a drag on the empty drawing pans, and the page-wide
// keys (page-keys.js: space plays or pauses where no control has the
// focus, r resets; Enter ticks a focused checkbox). The module decides what a point or a
// key grabs and keeps the view (src/web/input.rs, src/view.rs); this file
// only routes the events.

import { wirePageKeys, wireStageFocus } from './page-keys.js';

const LONG_PRESS_MS = 600;

/**
 * Wires `stage` (the canvas) of `demo`. Hooks: `attempt(fn, kind)` runs a
 * call and shows its error; `changed()` after a user change; `togglePlay()`,
 * `reset()`; `atlas` ({ hover, leave, click }) and `playground` ({
 * wantsClick, click, removeObstacle }); `keyboard`, the element that
 * receives the page-wide keys (none: no such keys).
 */
export function wireStage(stage, demo, { attempt, changed, togglePlay, reset, atlas, playground, keyboard }) {
  wirePageKeys(keyboard, { togglePlay, reset });

  // ---- keyboard on the drawing: arrows move the target, Shift+arrows the obstacle, + - 0 the view
  wireStageFocus(stage, demo);
  const zoomKeys = { '+': 1.25, '=': 1.25, '-': 0.8, '_': 0.8 };
  stage.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    // + and - zoom about the middle, 0 fits the view again.
    const factor = zoomKeys[e.key];
    if (factor || e.key === '0') {
      e.preventDefault();
      const [x, y] = [stage.clientWidth / 2, stage.clientHeight / 2];
      if (factor) demo.moveView(x, y, x, y, factor);
      else demo.fitView();
      return;
    }
    let used = false;
    const ok = attempt(() => (used = demo.key(e.key, e.shiftKey)));
    if (!ok || used) e.preventDefault();
    if (ok && used) changed();
  });

  // ---- pointer: drag target and obstacle -------------------------------
  let held = null; // pointerId while dragging
  let longPress = null; // { id, x, y, timer } while a touch holds an obstacle
  const cancelLongPress = () => {
    if (longPress) clearTimeout(longPress.timer);
    longPress = null;
  };
  let press = null; // { id, x, y, at, pan, hold, held } of a press on no handle: a click on an atlas cell, a pan, a finger held on a cell
  const endPress = () => {
    if (press?.hold) clearTimeout(press.hold);
    press = null;
  };
  // A touch the page takes (a grab, a pinch, placing an obstacle) does not
  // scroll the page; one finger on nothing does (issue 27: a swipe that
  // began on the drawing did not scroll the phone's page). The stage's
  // touch-action is pan-y (style.css); pointerdown runs before touchstart,
  // so `claimed` is known when touchstart may cancel the scroll.
  let claimed = false;
  const claim = (e) => {
    if (claimed || e.touches.length > 1) e.preventDefault();
  };
  stage.addEventListener('touchstart', claim, { passive: false });
  stage.addEventListener('touchmove', claim, { passive: false });
  stage.addEventListener('touchend', (e) => {
    if (e.touches.length === 0) claimed = false;
  });
  const local = (e) => {
    const r = stage.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  const slopFor = (e) => (e.pointerType === 'mouse' ? 4 : 18);
  const touches = new Map(); // pointerId -> [x, y]: the fingers on the drawing
  let pinch = null; // { span, mid } of the two fingers while they zoom and pan
  const twoFingers = () => {
    const [a, b] = [...touches.values()];
    return { span: Math.hypot(a[0] - b[0], a[1] - b[1]), mid: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
  };
  stage.addEventListener('pointerdown', (e) => {
    if (e.pointerType === 'touch') {
      touches.set(e.pointerId, local(e));
      if (touches.size > 2) return;
      if (touches.size === 2) {
        // A second finger: the first one's drag or press becomes a pinch.
        if (held !== null) demo.pointerCancel();
        held = null;
        endPress();
        cancelLongPress();
        pinch = twoFingers();
        claimed = true;
        e.preventDefault();
        return;
      }
    }
    if (held !== null || (e.pointerType === 'mouse' && e.button !== 0)) return;
    const [x, y] = local(e);
    if (e.pointerType === 'touch') atlas.leave(); // a cell's details shown by a held finger go with the next touch
    const placing = playground.wantsClick();
    const what = placing ? undefined : demo.pointerDown(x, y, slopFor(e));
    if (!what) {
      endPress();
      press = { id: e.pointerId, x, y, at: [x, y], pan: false, hold: null, held: false };
      if (e.pointerType === 'touch') {
        claimed = placing;
        // A finger held still on the atlas map shows that cell's numbers,
        // as the mouse's hover does; lifting it leaves them until the next touch.
        const mine = press;
        press.hold = setTimeout(() => {
          if (press !== mine) return;
          mine.held = atlas.hover(x, y) !== undefined;
        }, LONG_PRESS_MS);
      }
      return;
    }
    claimed = true;
    if (what === 'obstacle' && e.pointerType !== 'mouse') {
      // A long press on an obstacle removes it.
      const i = demo.state().dragging_obstacle;
      longPress = {
        id: e.pointerId,
        x,
        y,
        timer: setTimeout(() => {
          if (held !== e.pointerId) return;
          held = null;
          demo.pointerCancel();
          attempt(() => playground.removeObstacle(i));
        }, LONG_PRESS_MS),
      };
    }
    held = e.pointerId;
    stage.setPointerCapture(e.pointerId);
    stage.style.cursor = 'grabbing';
    e.preventDefault();
  });
  stage.addEventListener('pointermove', (e) => {
    const [x, y] = local(e);
    if (touches.has(e.pointerId)) touches.set(e.pointerId, [x, y]);
    if (pinch) {
      if (touches.size !== 2) return;
      // What lay between the fingers follows their middle, zoomed as they spread.
      const now = twoFingers();
      demo.moveView(...pinch.mid, ...now.mid, pinch.span > 0 ? now.span / pinch.span : 1);
      pinch = now;
      return;
    }
    if (press && press.id === e.pointerId && e.pointerType === 'touch') {
      // One finger on nothing pans nothing (two fingers do); moving it ends a hold.
      if (press.hold && Math.hypot(x - press.x, y - press.y) >= slopFor(e)) {
        clearTimeout(press.hold);
        press.hold = null;
      }
      return;
    }
    if (press && press.id === e.pointerId && (press.pan || Math.hypot(x - press.x, y - press.y) >= 6)) {
      if (!press.pan) stage.setPointerCapture(e.pointerId);
      press.pan = true;
      demo.moveView(...press.at, x, y, 1);
      press.at = [x, y];
      return;
    }
    if (held === e.pointerId) {
      if (longPress && Math.hypot(x - longPress.x, y - longPress.y) > 8) cancelLongPress();
      attempt(() => demo.pointerMove(x, y), 'warn');
    } else if (held === null && e.pointerType === 'mouse') {
      const handle = demo.hover(x, y, slopFor(e));
      const cell = handle ? atlas.leave() : atlas.hover(x, y);
      stage.style.cursor = handle ? 'grab' : cell !== undefined ? 'pointer' : 'default';
    }
  });
  // A finger leaves the drawing as it lifts: the numbers a held finger showed stay until the next touch.
  stage.addEventListener('pointerleave', (e) => e.pointerType !== 'touch' && atlas.leave());
  const lift = (e) => {
    touches.delete(e.pointerId);
    if (touches.size < 2) pinch = null;
  };
  stage.addEventListener('pointercancel', (e) => {
    lift(e);
    // The browser took the finger to scroll the page.
    if (press?.id === e.pointerId) endPress();
  });
  stage.addEventListener('pointerup', (e) => {
    lift(e);
    if (!press || press.id !== e.pointerId) return;
    const [x, y] = local(e);
    const near = !press.pan && !press.held && Math.hypot(x - press.x, y - press.y) < (e.pointerType === 'touch' ? slopFor(e) : 6);
    endPress();
    if (!near) return;
    if (playground.wantsClick()) attempt(() => playground.click(x, y));
    else attempt(() => atlas.click(x, y), 'warn');
  });
  stage.addEventListener(
    'wheel',
    (e) => {
      e.preventDefault();
      const [x, y] = local(e);
      const px = e.deltaY * (e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1);
      demo.moveView(x, y, x, y, Math.exp(-px * (e.ctrlKey ? 0.01 : 0.002)));
    },
    { passive: false },
  );
  stage.addEventListener('dblclick', (e) => {
    const [x, y] = local(e);
    attempt(() => demo.removeObstacleAt(x, y, 4) !== undefined && changed());
  });
  const release = (e) => {
    cancelLongPress();
    if (held !== e.pointerId) return;
    const [x, y] = local(e);
    held = null;
    stage.style.cursor = 'default';
    if (stage.hasPointerCapture(e.pointerId)) stage.releasePointerCapture(e.pointerId);
    attempt(() => demo.pointerUp(x, y), 'warn');
    changed();
  };
  stage.addEventListener('pointerup', release);
  stage.addEventListener('pointercancel', (e) => {
    if (held !== e.pointerId) return;
    held = null;
    demo.pointerCancel();
  });
}
