// The in-browser benchmark, off the page's thread: a module Worker that loads
// the same WebAssembly build as the page and times one figure per call
// (src/wasm.rs: benchThetaDot, benchStep, benchForward, the code behind
// `redundant-ik bench`), posting progress after each. The Levenberg-Marquardt
// epoch is measured natively only: the trainer is not in the page's build.
//
// Message in:  { wasm: URL of the .wasm the page loaded, batchMs }
// Messages out: { type: 'progress', done, total, label }
//               { type: 'done', result: { theta_dot_ns, step_ns, forward_ns } }
//               { type: 'error', message }

import init, { benchThetaDot, benchStep, benchForward, modes } from './pkg/redundant_ik.js';

self.onmessage = async ({ data }) => {
  try {
    await init({ module_or_path: data.wasm });
    const batchMs = data.batchMs ?? 20;
    const MODES = modes().map((m) => m.name);
    const result = { theta_dot_ns: {}, step_ns: {}, forward_ns: null };
    const jobs = [
      ...MODES.map((m) => [`θ̇ ${m}`, () => (result.theta_dot_ns[m] = benchThetaDot(m, batchMs))]),
      ...MODES.map((m) => [`step ${m}`, () => (result.step_ns[m] = benchStep(m, batchMs))]),
      ['forward passes', () => (result.forward_ns = benchForward(batchMs))],
    ];
    for (const [i, [label, run]] of jobs.entries()) {
      self.postMessage({ type: 'progress', done: i, total: jobs.length, label });
      run();
    }
    self.postMessage({ type: 'progress', done: jobs.length, total: jobs.length, label: 'done' });
    self.postMessage({ type: 'done', result });
  } catch (e) {
    self.postMessage({ type: 'error', message: e && e.message ? e.message : String(e) });
  }
};
