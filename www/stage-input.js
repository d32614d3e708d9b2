// Pointer and keyboard on the stage: drag the target and the obstacles
// (mouse and touch), a long press or a double-click removes an obstacle, a
// click adds one (while the playground asks for it) or picks an atlas cell,
// the arrow keys move the target (Shift: the obstacle), and the page-wide
// keys (space plays or pauses where no control has the focus, r resets;
// Enter ticks a focused checkbox). The module decides what a point
// or a key grabs (src/web/input.rs); this file only routes the events.

const LONG_PRESS_MS = 600;

/**
 * Wires `stage` (the canvas) of `demo`. Hooks: `attempt(fn, kind)` runs a
 * call and shows its error; `changed()` after a user change; `togglePlay()`,
 * `reset()`; `atlas` ({ hover, leave, click }) and `playground` ({
 * wantsClick, click, removeObstacle }); `keyboard`, the element that
 * receives the page-wide keys (none: no such keys).
 */
export function wireStage(stage, demo, { attempt, changed, togglePlay, reset, atlas, playground, keyboard }) {
  keyboard?.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const t = e.composedPath()[0];
    // Enter ticks a checkbox as Space does (Damping, Correct drift, the
    // atlas's methods: issue 27, they could not be changed without a mouse).
    if (e.key === 'Enter' && t?.matches?.('input[type=checkbox]')) {
      e.preventDefault();
      t.click();
      return;
    }
    const typing = t && t.matches && t.matches('input, textarea, select, [contenteditable]');
    if (typing) return;
    // Space and Enter do what a focused control does (a button, a link, a
    // panel's heading); the page's keys act only on the drawing or on
    // nothing in particular.
    const control = t !== keyboard && t?.matches?.('button, a[href], summary, [role=button], [role=tab], [role=switch], [tabindex]:not(canvas)');
    if (e.key === ' ' || e.code === 'Space') {
      if (control) return;
      e.preventDefault();
      togglePlay();
    } else if (e.key === 'r' || e.key === 'R') {
      e.preventDefault();
      reset();
    }
  });

  // ---- keyboard on the drawing: arrows move the target, Shift+arrows the obstacle
  if (!stage.hasAttribute('tabindex')) stage.tabIndex = 0;
  stage.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
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
  let press = null; // { id, x, y } of a press on no handle: a click on an atlas cell
  const local = (e) => {
    const r = stage.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  const slopFor = (e) => (e.pointerType === 'mouse' ? 4 : 18);
  stage.addEventListener('pointerdown', (e) => {
    if (held !== null || (e.pointerType === 'mouse' && e.button !== 0)) return;
    const [x, y] = local(e);
    const what = playground.wantsClick() ? undefined : demo.pointerDown(x, y, slopFor(e));
    if (!what) {
      press = { id: e.pointerId, x, y };
      return;
    }
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
    if (held === e.pointerId) {
      if (longPress && Math.hypot(x - longPress.x, y - longPress.y) > 8) cancelLongPress();
      attempt(() => demo.pointerMove(x, y), 'warn');
    } else if (held === null && e.pointerType === 'mouse') {
      const handle = demo.hover(x, y, slopFor(e));
      const cell = handle ? atlas.leave() : atlas.hover(x, y);
      stage.style.cursor = handle ? 'grab' : cell !== undefined ? 'pointer' : 'default';
    }
  });
  stage.addEventListener('pointerleave', () => atlas.leave());
  stage.addEventListener('pointerup', (e) => {
    if (!press || press.id !== e.pointerId) return;
    const [x, y] = local(e);
    const near = Math.hypot(x - press.x, y - press.y) < 6;
    press = null;
    if (!near) return;
    if (playground.wantsClick()) attempt(() => playground.click(x, y));
    else attempt(() => atlas.click(x, y), 'warn');
  });
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
