// The one wording of an error for people, in the page and in its workers:
// a panic inside the module (a bug) says so; any other error is its message.

/** A readable message for `err`, thrown by a module whose `lastPanic()` is given. */
export function describeError(err, lastPanic) {
  let panic = null;
  try {
    panic = lastPanic();
  } catch (_) {
    /* the module itself failed to load */
  }
  if (panic) return `Internal error in the simulation (please report it): ${panic}`;
  return err && err.message ? err.message : String(err);
}
