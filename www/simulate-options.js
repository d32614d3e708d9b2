// window.demo.simulate() for every arm: a script's options checked and
// handed to the binding's simulate (src/web/script.rs), whose core checks
// every value. One definition for the planar page and the page in space.

/** The options simulate takes; `mode` is read too, the older name of `method`. */
export const SIMULATE_OPTIONS = ['method', 'target', 'obstacles', 'tf', 'theta0', 'feedback', 'refine'];

/**
 * A whole run off screen on `demo` (Demo or SpaceDemo): `options` is `{
 * method, target?, obstacles?, tf?, theta0?, feedback?, refine? }`, each
 * absent one the scene's (the method the one in use). `flatObstacles`
 * turns the obstacles into the binding's flat list. Returns the run's
 * summary; throws with a reason on an unknown option or a value that is
 * not a list where one is expected, and with the core's on a bad value.
 */
export function simulateWith(demo, options, flatObstacles) {
  if (!options || typeof options !== 'object') throw new Error(`simulate expects { ${SIMULATE_OPTIONS.join(', ')} }`);
  for (const k of Object.keys(options)) {
    if (!SIMULATE_OPTIONS.includes(k) && k !== 'mode') {
      throw new Error(`simulate: unknown option '${k}', expected one of ${SIMULATE_OPTIONS.join(', ')}`);
    }
  }
  const nums = (v, what) => {
    if (v === undefined) return undefined;
    if (!Array.isArray(v)) throw new Error(`simulate: ${what} must be a list of numbers`);
    return Float64Array.from(v, Number);
  };
  const number = (v) => (v === undefined ? undefined : Number(v));
  return demo.simulate(
    String(options.method ?? options.mode ?? demo.state().method),
    nums(options.target, 'target'),
    options.obstacles === undefined ? undefined : flatObstacles(options.obstacles),
    number(options.tf),
    nums(options.theta0, 'theta0'),
    number(options.feedback),
    number(options.refine),
  );
}

/**
 * The flat list of obstacles a binding takes (the centre's `dims`
 * coordinates and the radius of each) from a script's list: each `[x, y]`
 * or `[x, y, r]` in the plane (`[x, y, z]` or `[x, y, z, r]` in space), or
 * `{ x, y, z, r }`; `radius` where none is given. A typed array or a list
 * of numbers passes as it is, already flat.
 */
export function flatBalls(list, dims, radius) {
  if (ArrayBuffer.isView(list)) return list;
  const names = ['x', 'y', 'z'].slice(0, dims);
  const shape = `[${names.join(', ')}, r]`;
  if (!Array.isArray(list)) throw new Error(`obstacles: expected a list of ${shape}`);
  // Already flat (numbers only): the core checks the count.
  if (list.every((o) => typeof o === 'number')) return Float64Array.from(list);
  return Float64Array.from(
    list.flatMap((o) => {
      const v = Array.isArray(o) ? [...o] : [...names.map((k) => o?.[k]), o?.r];
      if (v.length === dims + 1 && v[dims] === undefined) v.pop();
      if (v.length < dims || v.length > dims + 1) throw new Error(`an obstacle is [${names.join(', ')}] or ${shape}`);
      return [...v.slice(0, dims).map(Number), v[dims] === undefined ? radius : Number(v[dims])];
    }),
  );
}
