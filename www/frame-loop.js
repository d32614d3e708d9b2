// The page's clock, one definition for every arm (demo.js on the planar
// page, space-demo.js on the 3-D stage): on each animation frame the
// module steps by the time since the last and says whether anything
// changed; the page follows only then (an idle page draws nothing).

/**
 * Starts the loop on the next animation frame: `frame(elapsed)` (ms since
 * the last frame) steps and draws, and returns the state when anything
 * changed (else undefined); `update(state)` follows it; a frame that
 * throws goes to `failed(error)`. Returns `stop()`.
 */
export function runFrames(frame, update, failed) {
  let last = performance.now();
  let stopped = false;
  function tick(now) {
    if (stopped) return;
    const elapsed = now - last;
    last = now;
    let s;
    try {
      s = frame(elapsed);
    } catch (e) {
      failed(e);
    }
    if (s !== undefined) update(s);
    requestAnimationFrame(tick);
  }
  requestAnimationFrame((now) => {
    last = now;
    requestAnimationFrame(tick);
  });
  return () => {
    stopped = true;
  };
}
