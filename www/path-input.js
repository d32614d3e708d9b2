// The path the hand follows: the text field `#path` (the core's syntax,
// `line`, `circle:CX,CY[,LAPS]` or `points:X,Y;X,Y;...`, read by the
// module's parser, never here) and the "Draw path" button `#draw-path`:
// while it is pressed, a stroke on the stage (pointerdown to pointerup,
// mouse or finger) becomes a `points:` path, which the module thins to
// points 5 cm apart; Escape or the button again cancels. The stroke's
// events are taken before the stage's own handlers (www/stage-input.js),
// which then see none of them.

/**
 * Wires the path controls under `root` for `demo` on the canvas `stage`.
 * Hooks: `attempt(fn, kind, near)` runs a call and shows its error next to
 * `near`; `changed()` after a change the address should follow. Returns
 * `sync(state)`, which shows the path in use in the field when it changes
 * (empty, showing the syntax, for the line; not while the user types).
 */
export function mountPath(root, demo, { attempt, changed, stage }) {
  const field = root.querySelector('#path');
  const button = root.querySelector('#draw-path');
  let shown = ''; // the path's text the field was last set to ('' for the line)
  const apply = (fn, near) => {
    if (attempt(fn, 'error', near)) changed();
  };
  field?.addEventListener('change', () => apply(() => demo.setPath(field.value), field));

  // ---- drawing on the stage ----------------------------------------------
  let drawing = false;
  let stroke = null; // { id, points: [x0, y0, x1, y1, ...] } while a pointer draws
  const setDrawing = (on) => {
    drawing = on;
    stroke = null;
    if (button) {
      button.setAttribute('aria-pressed', String(on));
      button.classList.toggle('active', on);
    }
    stage.style.cursor = on ? 'crosshair' : 'default';
  };
  const local = (e) => {
    const r = stage.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  const take = (e) => {
    e.stopImmediatePropagation();
    e.preventDefault();
  };
  button?.addEventListener('click', () => setDrawing(!drawing));
  stage.addEventListener(
    'pointerdown',
    (e) => {
      if (!drawing || (e.pointerType === 'mouse' && e.button !== 0)) return;
      take(e);
      stroke = { id: e.pointerId, points: local(e) };
      stage.setPointerCapture(e.pointerId);
    },
    true,
  );
  stage.addEventListener(
    'pointermove',
    (e) => {
      if (!drawing) return;
      take(e);
      if (stroke && stroke.id === e.pointerId) stroke.points.push(...local(e));
    },
    true,
  );
  stage.addEventListener(
    'pointerup',
    (e) => {
      if (!drawing || !stroke || stroke.id !== e.pointerId) return;
      take(e);
      stroke.points.push(...local(e));
      const points = Float64Array.from(stroke.points);
      setDrawing(false);
      apply(() => demo.setPath('', points), button);
    },
    true,
  );
  // A finger drawing the path does not scroll the page (the stage lets one
  // finger on nothing scroll it: stage-input.js).
  stage.addEventListener(
    'touchstart',
    (e) => {
      if (drawing) e.preventDefault();
    },
    { passive: false },
  );
  stage.addEventListener(
    'pointercancel',
    (e) => {
      if (drawing && stroke && stroke.id === e.pointerId) stroke = null;
    },
    true,
  );
  // Escape cancels, wherever the focus is.
  root.addEventListener?.('keydown', (e) => {
    if (drawing && e.key === 'Escape') {
      e.preventDefault();
      setDrawing(false);
    }
  });

  return function sync(s) {
    // Text being typed stays; text refused stays until the path changes.
    const text = s.path ?? '';
    if (!field || text === shown || root.activeElement === field) return;
    field.value = shown = text;
  };
}
