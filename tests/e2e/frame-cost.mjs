// What a frame costs the page while the user drags an obstacle: calls into
// the module (the page module's exported functions and Demo methods, counted
// by V8's precise coverage through the DevTools protocol) and the JS heap
// allocated (V8's sampling heap profiler, objects collected meanwhile
// included), per animation frame. Used by the e2e test (at most two calls
// per frame) and by scripts/frame-cost.mjs (the figures in docs/web.md).

/**
 * Drags the obstacle at world point `from` round a circle of radius `r` (m)
 * for `seconds`, one pointer move per 16 ms; returns `{ frames,
 * callsPerFrame, calls: { name: count }, heapBytesPerFrame }`.
 */
export async function dragCost(page, { from, r = 0.1, seconds = 5, interval = 4096 }) {
  const exported = await page.evaluate(async () => {
    const m = await import('./pkg/redundant_ik.js');
    const names = Object.keys(m).filter((k) => typeof m[k] === 'function' && k !== 'default' && k !== 'initSync');
    const demo = Object.getOwnPropertyNames(m.Demo.prototype).filter((k) => k !== 'constructor');
    return [...new Set([...names, ...demo])];
  });
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('HeapProfiler.enable');
  await cdp.send('Profiler.startPreciseCoverage', { callCount: true, detailed: false });
  const centre = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), from);
  await page.mouse.move(centre.x, centre.y);
  await page.mouse.down();
  const scale = await page.evaluate(([x, y, r]) => {
    const a = window.demo.worldToClient(x, y);
    const b = window.demo.worldToClient(x + r, y);
    return b.x - a.x;
  }, [...from, r]);
  // Counters from here: coverage reset, frames counted, heap sampled.
  await cdp.send('Profiler.takePreciseCoverage');
  await page.evaluate(() => {
    window.__frames = 0;
    const count = () => {
      window.__frames += 1;
      window.__frameCounter = requestAnimationFrame(count);
    };
    window.__frameCounter = requestAnimationFrame(count);
  });
  await cdp.send('HeapProfiler.startSampling', {
    samplingInterval: interval,
    includeObjectsCollectedByMajorGC: true,
    includeObjectsCollectedByMinorGC: true,
  });
  const t0 = Date.now();
  for (let k = 1; Date.now() - t0 < seconds * 1000; k++) {
    const a = (k / 60) * 2 * Math.PI;
    await page.mouse.move(centre.x + scale * (Math.cos(a) - 1), centre.y + scale * Math.sin(a));
    await page.waitForTimeout(16);
  }
  const { profile } = await cdp.send('HeapProfiler.stopSampling');
  const frames = await page.evaluate(() => {
    cancelAnimationFrame(window.__frameCounter);
    return window.__frames;
  });
  const { result } = await cdp.send('Profiler.takePreciseCoverage');
  await page.mouse.up();
  await cdp.send('Profiler.stopPreciseCoverage');
  await cdp.detach();
  const calls = {};
  for (const script of result) {
    if (!/\/pkg\/redundant_ik\.js/.test(script.url)) continue;
    for (const f of script.functions) {
      const count = f.ranges[0]?.count ?? 0;
      if (count && exported.includes(f.functionName)) calls[f.functionName] = (calls[f.functionName] ?? 0) + count;
    }
  }
  const total = Object.values(calls).reduce((a, b) => a + b, 0);
  return {
    frames,
    callsPerFrame: total / Math.max(frames, 1),
    calls,
    heapBytesPerFrame: (profile.samples.length * interval) / Math.max(frames, 1),
  };
}
