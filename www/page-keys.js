// The page-wide keys and the drawing's keyboard focus, one definition for
// every arm (stage-input.js on the planar drawing, space-input.js on the
// 3-D stage): Space plays or pauses where no control has the focus, r
// resets, Enter ticks a focused checkbox as Space does; the item the keys
// move is ringed while the drawing has the keyboard's focus.

/** What a focused control does with Space and Enter itself: the page's keys leave them be. */
const CONTROL = 'button, a[href], summary, [role=button], [role=tab], [role=switch], [tabindex]:not(canvas)';

/**
 * Wires the page-wide keys on `keyboard` (the element that receives them;
 * none: no such keys): `togglePlay()` on Space, `reset()` on r.
 */
export function wirePageKeys(keyboard, { togglePlay, reset }) {
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
    if (t?.matches?.('input, textarea, select, [contenteditable]')) return;
    // Space and Enter do what a focused control does (a button, a link, a
    // panel's heading, a tab, a switch); the page's keys act only on the
    // drawing or on nothing in particular.
    const control = t !== keyboard && t?.matches?.(CONTROL);
    if (e.key === ' ' || e.code === 'Space') {
      if (control) return;
      e.preventDefault();
      togglePlay();
    } else if (e.key === 'r' || e.key === 'R') {
      e.preventDefault();
      reset();
    }
  });
}

/**
 * Makes `stage` (the drawing) reachable by Tab and rings the item its keys
 * move while it has the keyboard's focus (`demo.setKeyboardFocus`).
 */
export function wireStageFocus(stage, demo) {
  if (!stage.hasAttribute('tabindex')) stage.tabIndex = 0;
  stage.addEventListener('focus', () => demo.setKeyboardFocus(stage.matches(':focus-visible')));
  stage.addEventListener('blur', () => demo.setKeyboardFocus(false));
}
