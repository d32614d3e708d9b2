// The page's heavy work, off its thread: a module Worker that loads the
// workers' WebAssembly module (src/web/worker.rs; the SIMD or the baseline
// build, as the page chose for itself) and runs one job, posting progress
// as it goes. The page terminates the worker when the job ends or is
// cancelled, so a cancelled job stops at once and leaves nothing behind.
//
// Messages in:
//   { kind: 'bench', wasm, batchMs, precision }
//       the code behind `redundant-ik bench`, one figure per call, over the
//       methods of benchMethods(); the result names benchVerdict()'s pair
//   { kind: 'bench', wasm, batchMs, arm, own, methods, refine, weights, precision }
//       the same for an arm in space (`redundant-ik bench --arm KEY`): the
//       RK4 step of its own task per method and its networks' forward passes;
//       the networks' files (benchSpaceNetworkFiles(arm)) fetched from
//       `weights` (the URL of weights/, or a map of name to URL); a robot
//       of the user's as its run file's text in `arm`, `own` its networks'
//       files { phi, v } if it has its own
//   { kind: 'atlas', wasm, run, options: { methods, n, region, task, feedback, refine, networks } }
//       the atlas of `redundant-ik atlas`, one row of cells per chunk
//   { kind: 'space-atlas', wasm, run, options: { methods, plane, n, region, networks: { phi, v } } }
//       the slice atlas of an arm in space (`redundant-ik atlas --arm A`), one
//       row per chunk; `run` is a spatial run file's JSON text, the result the
//       JSON text of `atlas --arm A --json` (src/web/space_atlas.rs)
//   { kind: 'train', wasm, request: { arm, net, preset, samples, epochs, seed }, run }
//       training of the networks for an arm and their check, a progress
//       message per epoch (with the epoch's numbers in `epoch`)
//   { kind: 'train-net', wasm, request, net }
//       one network of such a request alone ('phi' or 'v'; the page runs
//       both at once in two workers): its weights file as JSON text
//   { kind: 'space-train', wasm, request: { arm | run, name, net, preset, samples, epochs, seed } }
//       one network of an arm in space, of a shipped arm (`arm`, its key) or
//       of the robot of a run file (`run`, its text; `name` in the weights
//       file): its weights file as JSON text (src/web/space_training.rs)
//   { kind: 'conclude', wasm, request, phi, v }
//       the check and report of a request whose networks were trained so
//   { kind: 'robot', wasm, urdf, base, tip, meshes: { name: Uint8Array } }
//       a robot's URDF read into the chain SpaceDemo.ofChain runs, with what
//       the reader made of it (src/web/robot.rs, readRobot)
//   { kind: 'run-files', wasm, run }
//       a run as the JSON of `simulate --json`, CSV, and its figures as SVG
//   { kind: 'atlas-files', wasm, atlas, scene, methods }
//       an atlas's JSON, the CSV of its cells, and its maps (of `methods`) as SVG
// Every message also has `networks`: `{ set: { phi, v } | { error } }`, the
// shipped network sets the job may use (the weights files' text, fetched by
// the page, or why they could not be had), handed to the module before the
// job: the workers' module carries none (docs/web.md, "Bytes on the wire").
// Messages out:
//   { type: 'progress', done, total, label }
//   { type: 'done', result, ms }
//   { type: 'error', message }

import init, {
  AtlasJob,
  SpaceAtlasJob,
  trainNetworks,
  trainNetwork,
  concludeTraining,
  benchThetaDot,
  benchStep,
  benchForward,
  benchMethods,
  benchVerdict,
  benchSpaceMethods,
  benchSpaceNetworkFiles,
  benchSpaceStep,
  benchSpaceForward,
  runFiles,
  readRobot,
  atlasFiles,
  sliceAtlasFiles,
  spaceFigure,
  spacePlots,
  trainSpaceNetwork,
  provideBuiltinNetworks,
  builtinNetworksFailed,
  lastPanic,
} from './pkg/redundant_ik_worker.js';
import { describeError } from './errors.js';

function bench({ batchMs = 20, precision = 'f64' }) {
  // The methods `redundant-ik bench` times, and the two whose step times are the verdict.
  const timed = benchMethods();
  const result = { theta_dot_ns: {}, step_ns: {}, forward_ns: null, verdict: benchVerdict(), precision };
  const jobs = [
    ...timed.map((m) => [`θ̇ ${m}`, () => (result.theta_dot_ns[m] = benchThetaDot(m, batchMs, precision))]),
    ...timed.map((m) => [`step ${m}`, () => (result.step_ns[m] = benchStep(m, batchMs, precision))]),
    ['forward passes', () => (result.forward_ns = benchForward(batchMs, precision))],
  ];
  for (const [i, [label, run]] of jobs.entries()) {
    self.postMessage({ type: 'progress', done: i, total: jobs.length, label });
    run();
  }
  self.postMessage({ type: 'progress', done: jobs.length, total: jobs.length, label: 'done' });
  return result;
}

/** The text of the weights file `name` from `weights` (a base URL or a map of name to URL). */
async function weightsText(weights, name) {
  const url = typeof weights === 'string' ? new URL(name, weights).href : weights?.[name];
  if (!url) throw new Error(`this build does not carry weights/${name}`);
  const r = await fetch(url);
  if (!r.ok) throw new Error(`weights/${name}: HTTP ${r.status}`);
  return r.text();
}

async function benchSpace({ batchMs = 20, arm, own, methods, refine = 0, weights, precision = 'f64' }) {
  const timed = methods ?? benchSpaceMethods(arm, !!own);
  const files = own ? [] : benchSpaceNetworkFiles(arm);
  const [phi, v] = own ? [own.phi, own.v] : files.length ? await Promise.all(files.map((f) => weightsText(weights, f))) : [undefined, undefined];
  // A robot's run file is not a name: the result calls it 'robot'.
  const result = { arm: arm.trimStart().startsWith('{') ? 'robot' : arm, theta_dot_ns: {}, step_ns: {}, forward_ns: null, verdict: benchVerdict(), precision };
  // A warm-up pass first, its figures dropped: each job runs in a fresh
  // worker, whose module V8 compiles lazily and optimises (TurboFan) only
  // once a function is hot, in the background; timed cold, the first
  // methods ran 2-3 times slower than the same code a pass later
  // (docs/web.md, "Numerical route against Case 3 in the browser"). The
  // planar benchmark gets its warm-up from its theta_dot figures.
  const jobs = [
    ...timed.map((m) => [`warm-up ${m}`, () => benchSpaceStep(arm, m, batchMs, refine, phi, v, precision)]),
    ...timed.map((m) => [`step ${m}`, () => (result.step_ns[m] = benchSpaceStep(arm, m, batchMs, refine, phi, v, precision))]),
  ];
  if (phi !== undefined) jobs.push(['forward passes', () => (result.forward_ns = benchSpaceForward(arm, batchMs, phi, v, precision))]);
  for (const [i, [label, run]] of jobs.entries()) {
    self.postMessage({ type: 'progress', done: i, total: jobs.length, label });
    run();
  }
  self.postMessage({ type: 'progress', done: jobs.length, total: jobs.length, label: 'done' });
  return result;
}

/** An atlas job (AtlasJob or SpaceAtlasJob) run a row at a time, posting progress. */
function cells(job) {
  try {
    const total = job.total;
    const chunk = job.row;
    self.postMessage({ type: 'progress', done: 0, total, label: 'cells' });
    while (job.done < total) {
      const done = job.advance(chunk);
      self.postMessage({ type: 'progress', done, total, label: 'cells' });
    }
    return job.finish();
  } finally {
    job.free();
  }
}

const atlas = ({ run, options }) => cells(new AtlasJob(run, options ?? {}));
const spaceAtlas = ({ run, options }) => cells(new SpaceAtlasJob(run, options ?? {}));

function train({ request, run }) {
  // Progress: epochs done over the most epochs of the networks asked for
  // (the second network's most epochs known when it starts).
  const nets = request.net === 'both' ? ['phi', 'v'] : [request.net];
  const offsets = {};
  let before = 0;
  const post = (e) => {
    if (!(e.net in offsets)) {
      offsets[e.net] = before;
      before += e.max_epochs;
    }
    const left = nets.length - Object.keys(offsets).length;
    const total = before + left * e.max_epochs;
    self.postMessage({ type: 'progress', done: offsets[e.net] + e.epoch, total, label: e.net, epoch: e });
  };
  self.postMessage({ type: 'progress', done: 0, total: 1, label: 'sampling' });
  return trainNetworks(request, run, post);
}

/** The progress of one network's training: "sampling" first, then each epoch (both kinds of arm). */
function oneNetwork(train) {
  self.postMessage({ type: 'progress', done: 0, total: 1, label: 'sampling' });
  return train((e) => self.postMessage({ type: 'progress', done: e.epoch, total: e.max_epochs, label: e.net, epoch: e }));
}

const trainNet = ({ request, net }) => oneNetwork((post) => trainNetwork(request, net, post));

/** One network of an arm in space (src/web/space_training.rs), its epochs reported. */
const trainSpace = ({ request }) => oneNetwork((post) => trainSpaceNetwork(request, post));

self.onmessage = async ({ data }) => {
  try {
    await init({ module_or_path: data.wasm });
    for (const [set, files] of Object.entries(data.networks ?? {})) {
      if (files.error) builtinNetworksFailed(files.error, set);
      else {
        try {
          provideBuiltinNetworks(files.phi, files.v, set);
        } catch (_) {
          // Kept by the module as the set's reason: a job that needs it says so.
        }
      }
    }
    const t0 = performance.now();
    let result;
    if (data.kind === 'bench') result = data.arm === undefined ? bench(data) : await benchSpace(data);
    else if (data.kind === 'atlas') result = atlas(data);
    else if (data.kind === 'space-atlas') result = spaceAtlas(data);
    else if (data.kind === 'space-figure') result = spaceFigure(data.run);
    else if (data.kind === 'space-plots') result = spacePlots(data.run);
    else if (data.kind === 'train') result = train(data);
    else if (data.kind === 'train-net') result = trainNet(data);
    else if (data.kind === 'space-train') result = trainSpace(data);
    else if (data.kind === 'conclude') result = concludeTraining(data.request, data.phi, data.v);
    else if (data.kind === 'run-files') result = runFiles(data.run);
    else if (data.kind === 'robot') result = readRobot(data.urdf, data.base ?? undefined, data.tip ?? undefined, data.meshes ?? {});
    else if (data.kind === 'atlas-files') result = atlasFiles(data.atlas, data.scene, data.methods ?? []);
    else if (data.kind === 'slice-atlas-files') result = sliceAtlasFiles(data.atlas, data.run, data.methods ?? []);
    else throw new Error(`unknown job '${data.kind}'`);
    self.postMessage({ type: 'done', result, ms: performance.now() - t0 });
  } catch (e) {
    self.postMessage({ type: 'error', message: describeError(e, lastPanic) });
  }
};
