// "Are the networks faster? Measure it": the in-browser benchmark (jobs.js,
// in a Web Worker) tabulated beside the native figures, and the verdict:
// the step-time ratio of the two methods the workers' module names
// (benchVerdict(): the learned route and the exact one it imitates), the
// networks in the arithmetic the page's Arithmetic selector shows.

import { describe, method, moduleBuild } from './module.js';
import { bench, nativeFigures, showBusy } from './jobs.js';
import { nanoseconds, row } from './format.js';
import { csv, saveText } from './download.js';

const verdictText = (x) => (x >= 1 ? `${x.toFixed(1)}× slower` : `${(1 / x).toFixed(1)}× faster`);

/**
 * Wires `#bench`, `#bench-cancel`, `#bench-progress`, `#bench-table`,
 * `#bench-body`, `#bench-result` and `#bench-csv` (the figures as CSV)
 * under `root`.
 */
export function mountBenchPanel(root) {
  const $ = (id) => root.querySelector('#' + id);
  const button = $('bench');
  const cancel = $('bench-cancel');
  const progress = $('bench-progress');
  const table = $('bench-table');
  const body = $('bench-body');
  const result = $('bench-result');
  const download = $('bench-csv');
  if (!button || !result) return;
  // On the page in space the benchmark times the arm's own task: the intro says so when the panel opens.
  const panel = $('bench-panel');
  const intro = panel?.querySelector('p');
  panel?.addEventListener('toggle', () => {
    const key = document.documentElement.dataset.space;
    if (!panel.open || !key || !intro) return;
    const label = window.demo?.state?.().arm_label ?? key;
    const flag = key === 'robot' ? '--urdf FILE' : `--arm ${key}`;
    intro.textContent = `Times one Runge–Kutta step of the ${label}'s own task with each method in this browser, as redundant-ik bench ${flag} does natively: a warm-up, then the median of seven batches. It runs in the background; the drawing goes on.`;
  });
  let last = null; // { r, nat, build }
  download?.addEventListener('click', () => {
    if (!last) return;
    const { r, nat, build } = last;
    const rows = Object.keys(r.step_ns).map((m) => [m, build, r.theta_dot_ns[m], r.step_ns[m], nat?.step_ns?.[m]]);
    if (r.forward_ns) rows.push(['forward phi', build, '', r.forward_ns.phi, ''], ['forward v', build, '', r.forward_ns.v, '']);
    saveText('benchmark.csv', csv(['method', 'build', 'theta_dot_ns', 'step_ns', 'native_step_ns'], rows), 'text/csv');
  });
  const controls = { run: button, cancel, progress };
  let abort = null;
  cancel?.addEventListener('click', () => abort && abort.abort());
  button.addEventListener('click', async () => {
    showBusy(controls, true);
    result.textContent = 'Measuring…';
    abort = new AbortController();
    try {
      // On the page in space (html[data-space]), its arm's task (the workers' build with the arms in space);
      // a robot of the user's goes as its run file, with its networks' files where it has its own.
      const key = document.documentElement.dataset.space || undefined;
      const robot = key === 'robot' ? window.demo?.controller?.demo : null;
      const arm = robot ? robot.runFile() : key;
      const own = robot?.networkFiles() ?? undefined;
      // In the arithmetic the page's networks run in (its Arithmetic selector).
      const precision = $('precision')?.value || undefined;
      const r = await bench({
        arm,
        own,
        precision,
        signal: abort.signal,
        onProgress: ({ done, total, label }) => {
          if (progress) progress.value = done / total;
          result.textContent = `Measuring… ${label}`;
        },
      });
      // The native figures shipped beside the page are the plane's (make bench-native).
      const nat = arm ? null : await nativeFigures();
      // One row per method timed, in the worker's order.
      body?.replaceChildren(
        ...Object.keys(r.step_ns).map((m) =>
          row([method(m)?.label ?? m, nanoseconds(r.theta_dot_ns?.[m]), nanoseconds(r.step_ns[m]), nanoseconds(nat?.step_ns?.[m])]),
        ),
      );
      if (table) table.hidden = false;
      last = { r, nat, build: moduleBuild() };
      if (download) download.hidden = false;
      const [learned, exact] = r.verdict;
      const [L, E] = [method(learned), method(exact)];
      if (r.step_ns[learned] === undefined) {
        // No networks for this arm: the exact methods only.
        result.textContent = `Per RK4 step, ${E.label} takes ${nanoseconds(r.step_ns[exact])} here; ${L.label} is not timed: this arm has no networks yet (train them in the page, or give your own).`;
        Object.assign(result.dataset, { learned: '', exact, learnedNs: '', exactNs: String(r.step_ns[exact]), precision: r.precision });
        return;
      }
      const ratio = r.step_ns[learned] / r.step_ns[exact];
      const buildName = moduleBuild() === 'simd' ? 'wasm SIMD build' : 'baseline wasm build, no SIMD';
      let text = `Per RK4 step, ${L.label} (${L.description}) is ${verdictText(ratio)} than ${E.label} (${E.description}) here (${buildName}, networks in ${r.precision})`;
      if (nat?.step_ns?.[learned] && nat.step_ns[exact]) text += ` (${verdictText(nat.step_ns[learned] / nat.step_ns[exact])} natively)`;
      result.textContent = `${text}. Forward passes: Φ ${nanoseconds(r.forward_ns.phi)}, v ${nanoseconds(r.forward_ns.v)}.`;
      Object.assign(result.dataset, {
        learned,
        exact,
        learnedNs: String(r.step_ns[learned]),
        exactNs: String(r.step_ns[exact]),
        thetaDotLearnedNs: String(r.theta_dot_ns[learned]),
        thetaDotExactNs: String(r.theta_dot_ns[exact]),
        precision: r.precision,
      });
    } catch (e) {
      result.textContent = e.name === 'AbortError' ? 'Cancelled.' : `The benchmark failed: ${describe(e)}`;
    } finally {
      showBusy(controls, false);
      abort = null;
    }
  });
}
