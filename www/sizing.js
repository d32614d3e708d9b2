// The drawing's canvases follow their layout, one definition for every
// arm (demo.js on the planar page, space-demo.js on the 3-D stage): each
// backing store the size of its box at the screen's pixel ratio, sharp on
// high-DPI screens, and drawn again when the browser gives a discarded
// context back blank.

/**
 * Calls `resize(width, height, devicePixelRatio)` (through `attempt`,
 * which shows a refusal) now and whenever `canvas`'s box changes size; a
 * hidden canvas (no box) is left as it is.
 */
export function followSize(canvas, resize, attempt) {
  const apply = () => {
    const r = canvas.getBoundingClientRect();
    if (r.width > 0 && r.height > 0) attempt(() => resize(r.width, r.height, window.devicePixelRatio || 1));
  };
  new ResizeObserver(apply).observe(canvas);
  apply();
}

/**
 * The drawing is kept between frames (an idle page draws nothing), so a
 * 2D context the browser discarded and gave back blank is drawn again
 * (`draw`, through `attempt`). Absent canvases are skipped.
 */
export function redrawWhenRestored(canvases, draw, attempt) {
  for (const canvas of canvases) canvas?.addEventListener('contextrestored', () => attempt(draw));
}
