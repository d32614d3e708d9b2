// The self-motion slider: the arm moves in the null space of its Jacobian
// through joint 2 (the hand holds still; the new pose becomes the run's
// start), for a keyboard what dragging an elbow on the stage does. The
// slider is relative: each change moves the arm by the step it made, then
// it comes back to the middle, so the arrow keys move it step by step.

/** Wires `#self-motion` of `root`, if it exists. */
export function mountSelfMotion(root, demo, { attempt, changed }) {
  const slider = root.querySelector('#self-motion');
  if (!slider) return;
  let last = 0;
  slider.addEventListener('input', () => {
    const value = Number(slider.value);
    const moved = attempt(() => demo.selfMotion(1, value - last), 'warn', slider);
    last = value;
    if (moved) changed();
  });
  slider.addEventListener('change', () => {
    slider.value = '0';
    last = 0;
  });
}
