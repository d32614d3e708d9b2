// Placing the target without dragging (WCAG 2.5.7): number fields for its
// x and y (`#target-x`, `#target-y`; and `#target-z` for an arm in space), kept in step with drags and with
// the keyboard, except while one holds a number typed and not yet applied. A change plans a line
// to the new target, as dropping it there does. The obstacles' fields are
// the playground's list (arm-designer.js).

/** Metres in a field: to the millimetre, as the address writes them. */
const mm = (v) => String(Number(v.toFixed(3)));

/**
 * Wires the target's fields under `root` (none: nothing): x and y, and z
 * where `dims` is 3 (an arm in space: `#target-z`). Hooks: `attempt(fn,
 * kind, near)` runs a call and shows its error beside `near`; `changed()`
 * after a user change. Returns `sync(state)` for the loop.
 */
export function mountTargetFields(root, demo, { attempt, changed, dims = 2 }) {
  const fields = ['x', 'y', 'z'].slice(0, dims).map((a) => root.querySelector(`#target-${a}`));
  if (fields.some((f) => !f)) return () => {};
  const need = `the target needs ${dims === 3 ? 'three numbers, x, y and z' : 'two numbers, x and y'} in metres`;
  const apply = (field) => applyGroup(fields, field, { need, set: (...v) => demo.setTarget(...v), attempt, changed });
  for (const f of fields) f.addEventListener('change', () => apply(f));
  let shown = '';
  return function sync(s) {
    const key = s.target.slice(0, dims).join(',');
    if (key === shown) return;
    shown = key;
    fields.forEach((f, i) => follow(f, s.target[i]));
  };
}

/**
 * Applies a group of number `fields` together (the one the user changed
 * is `field`): where each holds a finite number, `set(...values)`, each
 * times `scale`, through `attempt`, then marks them applied and calls
 * `changed()`; else says `need` beside `field`, changing nothing.
 */
export function applyGroup(fields, field, { scale = 1, need, set, attempt, changed }) {
  const v = fields.map((f) => Number(f.value) * scale);
  if (fields.some((f, i) => f.value.trim() === '' || !Number.isFinite(v[i]))) {
    attempt(() => {
      throw new Error(need);
    }, 'error', field);
    return;
  }
  if (attempt(() => set(...v), 'error', field)) {
    applied(...fields);
    changed();
  }
}

/** The fields' texts are applied: the state follows them now. */
export function applied(...fields) {
  for (const f of fields) f.dataset.written = f.value;
}

/**
 * Writes `metres` (to the millimetre; `format` writes another quantity)
 * into a number `field` unless the user has typed there something not yet
 * applied (a focused field whose text is not the one last written), so a
 * drag never overwrites a half-typed number.
 */
export function follow(field, metres, format = mm) {
  const edited = field.matches(':focus') && field.value !== field.dataset.written;
  if (edited) return;
  field.value = format(metres);
  field.dataset.written = field.value;
}
