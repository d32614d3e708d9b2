// Placing the target without dragging (WCAG 2.5.7): number fields for its
// x and y (`#target-x`, `#target-y`), kept in step with drags and with
// the keyboard, except while one holds a number typed and not yet applied. A change plans a line
// to the new target, as dropping it there does. The obstacles' fields are
// the playground's list (arm-designer.js).

/** Metres in a field: to the millimetre, as the address writes them. */
const mm = (v) => String(Number(v.toFixed(3)));

/**
 * Wires the target's fields under `root` (none: nothing). Hooks:
 * `attempt(fn, kind, near)` runs a call and shows its error beside `near`;
 * `changed()` after a user change. Returns `sync(state)` for the loop.
 */
export function mountTargetFields(root, demo, { attempt, changed }) {
  const x = root.querySelector('#target-x');
  const y = root.querySelector('#target-y');
  if (!x || !y) return () => {};
  const apply = (field) => {
    const [vx, vy] = [Number(x.value), Number(y.value)];
    if (x.value.trim() === '' || y.value.trim() === '' || !Number.isFinite(vx) || !Number.isFinite(vy)) {
      attempt(() => {
        throw new Error('the target needs two numbers, x and y in metres');
      }, 'error', field);
      return;
    }
    if (attempt(() => demo.setTarget(vx, vy), 'error', field)) {
      applied(x, y);
      changed();
    }
  };
  for (const f of [x, y]) f.addEventListener('change', () => apply(f));
  let shown = '';
  return function sync(s) {
    const key = `${s.target[0]},${s.target[1]}`;
    if (key === shown) return;
    shown = key;
    follow(x, s.target[0]);
    follow(y, s.target[1]);
  };
}

/** The fields' texts are applied: the state follows them now. */
export function applied(...fields) {
  for (const f of fields) f.dataset.written = f.value;
}

/**
 * Writes `metres` (to the millimetre) into a number `field` unless the
 * user has typed there something not yet applied (a focused field whose
 * text is not the one last written), so a drag never overwrites a
 * half-typed number.
 */
export function follow(field, metres) {
  const edited = field.matches(':focus') && field.value !== field.dataset.written;
  if (edited) return;
  field.value = mm(metres);
  field.dataset.written = field.value;
}
