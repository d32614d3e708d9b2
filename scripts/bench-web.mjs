// Runs the page's benchmark (window.demo.bench(), a Web Worker) in headless
// Chromium and prints one JSON object per run, then the median of each figure;
// then times the atlas `redundant-ik bench` times natively (Task 1, 41 x 41
// cells, the paper's five methods, in a worker; the page's Atlas panel itself
// ticks every method) as often and prints its median; then the
// time from navigation to data-ready (five loads in fresh contexts) and the
// Case 3 solver time per animation frame and per step (docs/web.md). Each
// round of the benchmark runs the planar page's, the Panda's
// (window.demo.bench({ arm: 'panda' }): the RK4 step of its task per method,
// its networks' forward passes) and, where the native tool is built (NATIVE,
// default target/release/redundant-ik), `redundant-ik bench --json --no-lm
// --no-atlas` and `bench --arm panda --json` right there; it prints the
// page's step times over the native ones, as the ratio of the medians and
// as the median of each round's own ratio. Each benchmark runs in both of
// the networks' precisions (`precision: 'f64'` and `'f32'`, alternated), the
// native f64 figures the reference of every ratio. These are measurements on a
// shared machine: printed, never judged.
//
//   BASE_URL=http://127.0.0.1:8000/ RUNS=3 [BUILD=baseline] [BENCH_ONLY=1] node scripts/bench-web.mjs
//
// BENCH_ONLY=1 stops after the two benchmarks (no atlas, loads or frames).
//
// BUILD=baseline makes the page believe wasm SIMD is missing, so it loads the
// baseline module (as a browser with SIMD switched off would).
//
// `make bench-web` serves www/ and calls it. Needs playwright-core (installed
// under tests/e2e by scripts/e2e.sh) and Debian's Chromium.

// playwright-core comes from tests/e2e/node_modules, through the shared launcher.
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const RUNS = Number(process.env.RUNS ?? 3);
const browser = await launchChromium();

/** A page of a fresh context (with the baseline build if BUILD=baseline), ready. */
async function open(query) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  if (process.env.BUILD === 'baseline') {
    await context.addInitScript(() => {
      const validate = WebAssembly.validate;
      WebAssembly.validate = (bytes) => (new Uint8Array(bytes).includes(0xfd) ? false : validate(bytes));
    });
  }
  const page = await context.newPage();
  page.on('pageerror', (e) => console.error(`page exception: ${e.message}`));
  page.on('close', () => context.close().catch(() => {}));
  await page.goto(`${BASE}${query}`);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  return page;
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
/** The median of each figure under `keys` over `runs`. */
const medians = (runs, keys) => {
  const out = {};
  for (const key of keys) {
    out[key] = {};
    for (const k of Object.keys(runs[0][key] ?? {})) out[key][k] = median(runs.map((r) => r[key][k]));
  }
  return out;
};
// Both precisions of the networks' kernels, and the page and the native
// tool, alternated round by round, so that the machine's drift falls on
// all of them alike; each ratio is also given as the median of the rounds'
// own ratios (each round's page figure over the same round's native one).
// Both pages stay open: an idle page draws nothing (docs/web.md, "What an
// idle page costs").
const PRECISIONS = ['f64', 'f32'];
const page = await open('?task=1&method=numerical');
await page.evaluate(() => window.demo.controller.demo.setRunning(false));
// On the page in space, whose workers' build holds the arms in space.
const spacePage = await open('?arm=panda&method=numerical&autoplay=0');
const NATIVE = process.env.NATIVE ?? 'target/release/redundant-ik';
const hasNative = existsSync(NATIVE);
// The native tool; its f64 kernels (AVX2 + FMA where the CPU has them) are the reference of every ratio.
const native = (args) => JSON.parse(execFileSync(NATIVE, ['bench', '--json', ...args], { encoding: 'utf8' }));
const runs = { f64: [], f32: [] };
const panda = { f64: [], f32: [] };
const nat = { f64: { planar: [], panda: [] }, f32: { planar: [], panda: [] } };
for (let i = 0; i < RUNS; i++) {
  for (const precision of PRECISIONS) {
    const r = await page.evaluate((precision) => window.demo.bench({ precision }), precision);
    runs[precision].push(r);
    console.log(JSON.stringify(r));
  }
  for (const precision of PRECISIONS) {
    const r = await spacePage.evaluate((precision) => window.demo.bench({ arm: 'panda', precision }), precision);
    panda[precision].push(r);
    console.log(JSON.stringify(r));
  }
  if (hasNative) {
    for (const p of PRECISIONS) {
      nat[p].planar.push(native(['--no-lm', '--no-atlas', '--precision', p]));
      const space = native(['--arm', 'panda', '--precision', p]);
      nat[p].panda.push({ step_ns: Object.fromEntries(Object.entries(space.methods).map(([m, f]) => [m, f.step_ns])) });
    }
  }
}
await spacePage.close();
const out = Object.fromEntries(PRECISIONS.map((p) => [p, medians(runs[p], ['theta_dot_ns', 'step_ns', 'forward_ns'])]));
const build = await page.evaluate(() => window.demo.build);
for (const p of PRECISIONS) console.log(`median of ${RUNS} (${build} build, ${p}): ${JSON.stringify(out[p])}`);
const pandaOut = Object.fromEntries(PRECISIONS.map((p) => [p, medians(panda[p], ['step_ns', 'forward_ns'])]));
for (const p of PRECISIONS) console.log(`median of ${RUNS} (${build} build, ${p}), panda: ${JSON.stringify(pandaOut[p])}`);
if (hasNative) {
  const planar = Object.fromEntries(PRECISIONS.map((p) => [p, medians(nat[p].planar, ['step_ns', 'forward_ns'])]));
  const pandaNative = Object.fromEntries(PRECISIONS.map((p) => [p, medians(nat[p].panda, ['step_ns']).step_ns]));
  const kernels = nat.f64.planar[0].kernels;
  // `pageRuns[i][key][m]` over `natRuns[i][key][m]`, round by round: their median.
  const roundRatio = (pageRuns, natRuns, key, m) => median(pageRuns.map((r, i) => r[key][m] / natRuns[i][key][m]));
  const ratios = (page, nat, pageRuns, natRuns) =>
    Object.entries(page)
      .filter(([m]) => nat[m] !== undefined)
      .map(([m, ns]) => `${m} ${(ns / 1000).toFixed(2)} / ${(nat[m] / 1000).toFixed(2)} us = ${(ns / nat[m]).toFixed(2)}x (rounds ${roundRatio(pageRuns, natRuns, 'step_ns', m).toFixed(2)}x)`)
      .join(', ');
  for (const p of PRECISIONS) {
    console.log(`native (${kernels}, ${p}), median of ${RUNS}: planar ${JSON.stringify(planar[p])}`);
    console.log(`native (${kernels}, ${p}), median of ${RUNS}: panda step_ns ${JSON.stringify(pandaNative[p])}`);
  }
  console.log('page / native: the ratio of the medians (rounds: the median of each round\'s own ratio)');
  for (const p of PRECISIONS) {
    const f = out[p].forward_ns;
    const n = planar.f64.forward_ns;
    const fr = (k) => roundRatio(runs[p], nat.f64.planar, 'forward_ns', k).toFixed(2);
    console.log(`page (${build} build, ${p}) / native (f64), Task 1 RK4 step: ${ratios(out[p].step_ns, planar.f64.step_ns, runs[p], nat.f64.planar)}`);
    console.log(`page (${build} build, ${p}) / native (f64), forward: phi ${(f.phi / n.phi).toFixed(2)}x (rounds ${fr('phi')}x), v ${(f.v / n.v).toFixed(2)}x (rounds ${fr('v')}x)`);
    console.log(`page (${build} build, ${p}) / native (f64), Panda RK4 step: ${ratios(pandaOut[p].step_ns, pandaNative.f64, panda[p], nat.f64.panda)}`);
  }
  const learned = ['case1', 'case2', 'case3'];
  const only = (o) => Object.fromEntries(Object.entries(o).filter(([m]) => learned.includes(m)));
  console.log(`page (${build} build, f32) / native (f32), Task 1 RK4 step: ${ratios(only(out.f32.step_ns), planar.f32.step_ns, runs.f32, nat.f32.planar)}`);
  console.log(`page (${build} build, f32) / native (f32), Panda RK4 step: ${ratios(only(pandaOut.f32.step_ns), pandaNative.f32, panda.f32, nat.f32.panda)}`);
} else {
  console.log(`no native tool at ${NATIVE} (cargo build --release): no ratios`);
}
if (process.env.BENCH_ONLY) {
  await browser.close();
  process.exit(0);
}
const atlas = [];
for (let i = 0; i < RUNS; i++) {
  const r = await page.evaluate(async () => {
    const methods = window.demo.methods().filter((m) => m.group === 'paper').map((m) => m.name);
    const a = await window.demo.atlas({ methods });
    const s = Number(document.getElementById('atlas-status').dataset.ms) / 1000;
    return { s, n: a.grid.n, methods: a.methods.length, runs: a.cells.length * a.methods.length };
  });
  const s = r.s;
  atlas.push(s);
  console.log(
    `atlas of Task 1, ${r.n} x ${r.n} cells, the paper's ${r.methods} methods (${r.runs.toLocaleString('en')} runs), in a worker: ${s.toFixed(2)} s`,
  );
}
console.log(`median of ${RUNS} (${build} build): atlas ${median(atlas).toFixed(2)} s`);
await page.close();

// ---- time from navigation to data-ready ------------------------------------
// `window.demo.readyMs` is performance.now() right after the first frame is
// drawn and data-ready set.
const loads = [];
for (let i = 0; i < 5; i++) {
  const p = await open('?task=1&method=numerical');
  loads.push(
    await p.evaluate(() => ({
      ready: window.demo.readyMs,
      dcl: performance.getEntriesByType('navigation')[0].domContentLoadedEventEnd,
    })),
  );
  await p.close();
}
const ready = loads.map((t) => t.ready).sort((a, b) => a - b);
console.log(
  `measure: navigation -> data-ready: median ${median(ready).toFixed(0)} ms, min ${ready[0].toFixed(0)}, max ${ready.at(-1).toFixed(0)} ms ` +
    `(5 loads; DOMContentLoaded median ${median(loads.map((t) => t.dcl)).toFixed(0)} ms)`,
);

// ---- Case 3 solver time per animation frame ----------------------------------
// `state().solver_ms` sums performance.now() around the planner's step calls
// in the last frame that stepped; Task 1 at 8x speed is about 1-2 steps a frame.
const c3 = await open('?task=1&method=case3');
await c3.selectOption('#speed', '8');
await c3.click('#task1');
const frames = await c3.evaluate(
  () =>
    new Promise((resolve) => {
      const out = [];
      let lastSteps = -1;
      const tick = () => {
        const s = window.demo.state();
        if (s.steps !== lastSteps && s.frame_steps > 0) out.push([s.frame_steps, s.solver_ms]);
        lastSteps = s.steps;
        if (s.running) requestAnimationFrame(tick);
        else resolve(out);
      };
      requestAnimationFrame(tick);
    }),
);
const perFrame = frames.map((f) => f[1]).sort((a, b) => a - b);
const stepsPerFrame = frames.reduce((a, f) => a + f[0], 0) / Math.max(frames.length, 1);
// Many steps in a row, timed around the whole batch.
const batch = await c3.evaluate(() => {
  const d = window.demo.controller.demo;
  d.reset();
  d.setRunning(false);
  const t0 = performance.now();
  d.runUntil(100);
  const s = d.state();
  return { method: s.method, steps: s.frame_steps, plannerMs: s.solver_ms, ms: performance.now() - t0 };
});
await c3.close();
console.log(
  `measure: ${batch.method} solver per animation frame (8x speed, ${stepsPerFrame.toFixed(2)} RK4 steps/frame, ${frames.length} frames): ` +
    `median ${median(perFrame).toFixed(3)} ms, max ${perFrame.at(-1)?.toFixed(3)} ms`,
);
console.log(
  `measure: ${batch.method} batch of ${batch.steps} RK4 steps: planner ${((batch.plannerMs / batch.steps) * 1000).toFixed(1)} us/step; ` +
    `with the ghost arm and bookkeeping ${((batch.ms / batch.steps) * 1000).toFixed(1)} us/step`,
);
await browser.close();
