// Jobs off the page's thread: each runs in its own module Web Worker
// (www/worker.js) on the workers' module of the build the page runs, so
// the page keeps drawing; cancelling terminates the worker at once.

import { assetUrl, loadModule, workerModuleUrl, networkSetsFor } from './module.js';

/** The shipped network sets a job names: its atlas's `networks` option, its run's set. */
const namedSets = (job) => [job.options?.networks, job.run?.networks?.set].filter((s) => typeof s === 'string');

/**
 * The workers' script: worker.js beside the page's module; for an element
 * on another site's page (a worker's script must have the page's origin),
 * a same-origin blob that imports it (its host sends
 * Access-Control-Allow-Origin, as the element needs anyway).
 */
function workerScript() {
  const url = new URL(assetUrl('worker.js'), location.href);
  if (url.origin === location.origin || url.protocol !== 'http:' && url.protocol !== 'https:') return url;
  return URL.createObjectURL(new Blob([`import ${JSON.stringify(url.href)};`], { type: 'text/javascript' }));
}

/**
 * Runs one job in a Web Worker. `onProgress({ done, total, label })`
 * follows it; `signal` (an AbortSignal) cancels it. Resolves to `{ result,
 * ms }` (`ms`: the job's time inside the worker).
 */
export async function runWorker(job, { onProgress, signal } = {}) {
  await loadModule();
  // The workers' module carries no weights: the page hands it the sets the job may use.
  const networks = await networkSetsFor(namedSets(job));
  return new Promise((resolve, reject) => {
    const abort = () => {
      finish();
      reject(new DOMException('Cancelled.', 'AbortError'));
    };
    if (signal?.aborted) return abort();
    const worker = new Worker(workerScript(), { type: 'module' });
    function finish() {
      worker.terminate();
      if (signal) signal.removeEventListener('abort', abort);
    }
    if (signal) signal.addEventListener('abort', abort);
    worker.onmessage = ({ data }) => {
      if (data.type === 'progress') {
        if (onProgress) onProgress(data);
      } else if (data.type === 'done') {
        finish();
        resolve({ result: data.result, ms: data.ms });
      } else {
        finish();
        reject(new Error(data.message));
      }
    };
    worker.onerror = (e) => {
      finish();
      reject(new Error(e.message || 'the worker failed to start'));
    };
    worker.postMessage({ ...job, wasm: workerModuleUrl(), networks });
  });
}

/**
 * Measures this browser as `redundant-ik bench` measures the machine: one
 * theta_dot and one RK4 step of Task 1 in each method the benchmark times
 * (the workers' `benchMethods()`) and the forward passes of both networks
 * (ns); each figure the median of seven batches after a warm-up.
 * `onProgress({ done, total, label })` follows it and `signal` (an
 * AbortSignal) cancels it. Resolves to `{ theta_dot_ns: {method: ns},
 * step_ns: {method: ns}, forward_ns: {phi, v}, verdict: [learned, exact] }`
 * (`verdict`: the two methods whose step times the panel compares).
 *
 * With `arm` an arm in space (`'panda'`, `'iiwa14'`), as `redundant-ik bench
 * --arm KEY`: the RK4 step of its own task in every method that runs there
 * (`methods` to choose; `refine` Newton-Schulz steps on the learned Phi) and
 * the forward passes of its networks, whose weights files the worker fetches
 * from weights/ beside the page; `theta_dot_ns` is empty and `arm` names it.
 * A robot of the user's: `arm` is its run file's text (`SpaceDemo.runFile()`)
 * and `own` its networks' files `{ phi, v }` if it has its own (the learned
 * methods are timed only then); the result's `arm` is `'robot'`.
 *
 * `precision` is the networks' arithmetic, `'f64'` (the default, the page's
 * runs) or `'f32'` (`redundant-ik bench --precision f32`); the result names it.
 */
export async function bench({ onProgress, signal, batchMs = 20, arm, own, methods, refine = 0, precision = 'f64' } = {}) {
  const job = { kind: 'bench', batchMs, precision };
  if (arm !== undefined) Object.assign(job, { arm, own, methods, refine, weights: weightsLocation() });
  const { result } = await runWorker(job, { onProgress, signal });
  return result;
}

/**
 * The slice atlas of an arm in space in a worker (`SpaceAtlasJob`,
 * src/web/space_atlas.rs; `redundant-ik atlas --arm A --json`): `run` is a
 * run file of an arm in space (`simulate --arm A --json`, format
 * `redundant-ik-run/2`), whose scene is mapped; `methods` (names;
 * absent: every method in space, the learned ones only with networks),
 * `plane` ('xz:0.0'; absent: the vertical plane through the line), `n`
 * (points per side; absent: 21), `region` ([u0, u1, v0, v1]; absent: the
 * default square) and `networks` ({ phi, v }: the weights files' text, for
 * Cases 1-3; the Panda's are weights/phi-panda-reach.json and
 * weights/v-panda-reach.json) are the job's options.
 * `onProgress({ done, total, label })` follows it row by row; `signal`
 * (an AbortSignal) cancels it (rejects with an `AbortError`). Resolves to
 * `{ json, atlas, ms }`: the JSON text of `atlas --arm A --json`, that
 * text parsed, and the job's time inside the worker (ms).
 */
export async function spaceAtlas({ run, methods, plane, n, region, networks, onProgress, signal } = {}) {
  const options = { methods, plane, n, region, networks };
  for (const k of Object.keys(options)) if (options[k] === undefined) delete options[k];
  const { result, ms } = await runWorker({ kind: 'space-atlas', run, options }, { onProgress, signal });
  return { json: result, atlas: JSON.parse(result), ms };
}

/**
 * Where a worker finds the weights files: the URL of weights/ beside the
 * page, or, in a single-file build, the map of the files it carries inline.
 */
function weightsLocation() {
  const inline = globalThis.__REDUNDANT_IK_ASSETS__;
  if (!inline) return assetUrl('weights/');
  return Object.fromEntries(Object.entries(inline).filter(([k]) => k.startsWith('weights/')).map(([k, v]) => [k.slice(8), v]));
}

/**
 * A job's controls while it runs (`on`) and after: the button that starts
 * it disabled, its cancel button and its progress bar (from 0) shown.
 */
export function showBusy({ run, cancel, progress }, on) {
  if (run) run.disabled = on;
  if (cancel) cancel.hidden = !on;
  if (progress) {
    progress.hidden = !on;
    if (on) progress.value = 0;
  }
}

let native = null;
/**
 * The native figures quoted beside the page's (`make bench-native` writes
 * www/bench-native.json with `redundant-ik bench --json`), fetched once when
 * first needed: a Promise of the object, or of null where there is none.
 */
export function nativeFigures() {
  native ??= Promise.resolve()
    .then(() => fetch(assetUrl('bench-native.json')))
    .then((r) => (r.ok ? r.json() : null))
    .catch(() => null);
  return native;
}
