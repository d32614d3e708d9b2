// Glue between the page and the WebAssembly module: it wires the controls,
// pointer events and the animation loop to a `Demo` (src/web/), which owns
// the session and draws the canvas. No kinematics here, and no names or
// colours of its own: the methods' names and labels, the palette and the
// legend come from the module.
//
// `mount(root, options)` works on any root that holds the expected ids
// (`#stage` and, all optional, `#plots`, `#mode`, `#legend`, `#play`, `#step`,
// `#reset`, `#task1`, `#task2`, `#lambda`, `#damping`, `#feedback`, `#speed`,
// `#message`, `#range-warning`, `#handover-note`, `#loading` and
// `[data-readout]` elements): the page's document, or the shadow root of a
// <redundant-ik-demo> element, so several demos on one page stay independent.

import init, { Demo, lastPanic, networksError, modes, palette, legend, atlasClasses } from './pkg/redundant_ik.js';
import { mountAtlas } from './atlas.js';
import { mountPlayground, flatObstacles } from './playground.js';

let module = null;
let wasmUrl = null;

/** The .wasm this page runs (see loadModule). */
export function moduleUrl() {
  return wasmUrl;
}

/** The two builds of the module (make web): with wasm SIMD, and without. */
const BUILDS = {
  simd: new URL('./pkg/redundant_ik_simd_bg.wasm', import.meta.url).href,
  baseline: new URL('./pkg/redundant_ik_bg.wasm', import.meta.url).href,
};

/** The same two builds of the workers' module (the atlas, the benchmark). */
const WORKER_BUILDS = {
  simd: new URL('./pkg/redundant_ik_worker_simd_bg.wasm', import.meta.url).href,
  baseline: new URL('./pkg/redundant_ik_worker_bg.wasm', import.meta.url).href,
};

/** Whether this browser validates wasm SIMD (v128, as wasm-feature-detect checks it). */
function simdSupported() {
  try {
    return WebAssembly.validate(
      new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 10, 1, 8, 0, 65, 0, 253, 15, 253, 98, 11]),
    );
  } catch (_) {
    return false;
  }
}

let build = null;
let memory = null;

/** Which build the page runs: 'simd' or 'baseline' (null before loading). */
export function moduleBuild() {
  return build;
}

/** Bytes of the page module's linear memory (it grows, never shrinks; the soak watches it). */
export function moduleMemoryBytes() {
  return memory ? memory.buffer.byteLength : 0;
}

/**
 * Loads and starts the WebAssembly module once per page: the SIMD build
 * where the browser supports SIMD (the networks run about twice as fast),
 * else, or if it fails to start, the baseline build.
 */
export function loadModule() {
  if (!module) {
    const start = async (which) => {
      const exports = await init({ module_or_path: BUILDS[which] });
      memory = exports.memory;
      build = which;
      wasmUrl = BUILDS[which];
      // The drawing's colours, for the stylesheet (var(--arm), ...).
      for (const [name, value] of Object.entries(palette())) {
        document.documentElement.style.setProperty(`--${name}`, value);
      }
    };
    module = (async () => {
      if (simdSupported()) {
        try {
          return await start('simd');
        } catch (e) {
          console.warn(`the SIMD build did not start (${e && e.message ? e.message : e}); using the baseline build`);
        }
      }
      return start('baseline');
    })();
  }
  return module;
}

/** The five methods, `[{ name, label, description }]` (after loadModule). */
export function methods() {
  return modes();
}

/** Fills a `<select>` with the methods: "Case 1: Φ by a network, v exact". */
function fillModes(select) {
  if (!select || select.options.length) return;
  for (const m of modes()) select.add(new Option(`${m.label}: ${m.description}`, m.name));
}

/** Fills a legend list from the module's legend (the renderer's colours). */
function fillLegend(list) {
  if (!list || list.children.length) return;
  for (const e of legend()) {
    const li = document.createElement('li');
    li.dataset.key = e.key;
    const key = document.createElement('span');
    key.className = `key key-${e.kind}`;
    key.style.setProperty('--swatch', e.swatch);
    li.append(key, e.label);
    list.append(li);
  }
}

/** Gain K (1/s) of the "correct drift" switch: Xdot + K (X_ref - X). */
export const FEEDBACK_GAIN = 1;

/**
 * Runs one job in a Web Worker (www/worker.js) on the workers' module of
 * the build the page runs, so the page keeps drawing. `onProgress({ done,
 * total, label })` follows it; `signal` (an AbortSignal) cancels it, which
 * terminates the worker at once. Resolves to `{ result, ms }` (`ms`: the
 * job's time inside the worker).
 */
export async function runWorker(job, { onProgress, signal } = {}) {
  await loadModule();
  return new Promise((resolve, reject) => {
    const abort = () => {
      finish();
      reject(new DOMException('Cancelled.', 'AbortError'));
    };
    if (signal?.aborted) return abort();
    const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
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
    worker.postMessage({ ...job, wasm: WORKER_BUILDS[build] });
  });
}

/**
 * Measures this browser as `redundant-ik bench` measures the machine: one
 * theta_dot and one RK4 step of Task 1 in every mode and the forward passes of
 * both networks (ns); each figure the median of seven batches after a
 * warm-up. Runs in a Web Worker, so the page keeps drawing;
 * `onProgress({ done, total, label })` follows it and `signal` (an
 * AbortSignal) cancels it. Resolves to
 * `{ theta_dot_ns: {mode: ns}, step_ns: {mode: ns}, forward_ns: {phi, v} }`.
 */
export async function bench({ onProgress, signal, batchMs = 20 } = {}) {
  const { result } = await runWorker({ kind: 'bench', batchMs }, { onProgress, signal });
  return result;
}

/** A readable message for an exception thrown by the module. */
export function describe(err) {
  let panic = null;
  try {
    panic = lastPanic();
  } catch (_) {
    /* the module itself failed to load */
  }
  if (panic) return `Internal error in the simulation (please report it): ${panic}`;
  return err && err.message ? err.message : String(err);
}

/** Whether the trained networks are built in; if not, the reason. */
export function networksProblem() {
  return networksError() ?? null;
}

function fmt(v, digits = 3) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '–';
  return v.toFixed(digits);
}

/** A length that may be tiny (tracking error), with its unit. */
function fmtLength(v) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '–';
  if (v >= 0.01) return `${v.toFixed(3)} m`;
  if (v >= 1e-5) return `${(v * 1000).toFixed(2)} mm`;
  return '< 0.01 mm';
}

/** Largest weights file read (the core's `nn::weights::MAX_FILE_BYTES`). */
const MAX_WEIGHTS_BYTES = 8 << 20;

const READOUTS = {
  t: (s) => fmt(s.t, 1),
  error: (s) => fmtLength(s.tracking_error),
  distance: (s) => fmt(s.distance, 3),
  min_distance: (s) => fmt(s.min_distance, 3),
  collision: (s) => (s.collision ? 'now' : s.collided ? 'earlier' : 'none'),
  manipulability: (s) => fmt(s.manipulability, 3),
  delta: (s) => (s.delta > 0 ? s.delta.toExponential(1) : '0'),
  solver: (s) => fmt(s.solver_ms_per_step, 3),
};

/**
 * Starts a demo on `root`. Options: task (1|2), mode, lambda, target [x, y],
 * obstacle [x, y], obstacles [[x, y, r], ...] (instead of obstacle), arm
 * { post, links }, damping (bool), feedback (closed-loop gain K, 1/s; default 0,
 * the paper's open loop), speed, autoplay (default true),
 * keyboard (element that receives key presses; default none),
 * onChange(state) (after user changes, e.g. to update the URL),
 * problems (what the caller could not parse, shown with the settings the
 * core refuses under problemsLabel; default 'Not applied').
 * Returns a controller with state(), worldToClient(x, y), runUntil(t), demo.
 */
export async function mount(root, options = {}) {
  const $ = (id) => root.querySelector('#' + id);
  const stage = $('stage');
  const plots = $('plots');
  const el = {
    mode: $('mode'),
    legend: $('legend'),
    play: $('play'),
    step: $('step'),
    reset: $('reset'),
    task1: $('task1'),
    task2: $('task2'),
    lambda: $('lambda'),
    lambdaValue: $('lambda-value'),
    damping: $('damping'),
    feedback: $('feedback'),
    speed: $('speed'),
    message: $('message'),
    warning: $('range-warning'),
    handover: $('handover-note'),
    loading: $('loading'),
  };
  const readouts = [...root.querySelectorAll('[data-readout]')];

  await loadModule();
  fillModes(el.mode);
  fillLegend(el.legend);
  const demo = new Demo(stage, plots ?? undefined, options.task === 2 ? 2 : 1);

  // ---- messages -------------------------------------------------------
  let messageTimer = 0;
  function show(text, kind = 'error', sticky = false) {
    if (!el.message) return;
    el.message.textContent = text;
    el.message.dataset.kind = kind;
    el.message.hidden = false;
    clearTimeout(messageTimer);
    if (!sticky) messageTimer = setTimeout(() => (el.message.hidden = true), 6000);
  }
  function clearMessage() {
    if (el.message) el.message.hidden = true;
  }
  function attempt(fn, kind = 'error') {
    try {
      fn();
      return true;
    } catch (e) {
      show(describe(e), kind);
      return false;
    }
  }

  const changed = () => options.onChange && options.onChange(controller.state());

  // ---- the arm, obstacles and training (www/playground.js) --------------
  const playground = mountPlayground(root, demo, { runWorker, describe, show, changed: () => changed() });

  // ---- initial settings (URL or attributes) ---------------------------
  // Each is tried on its own: one refused keeps the others. What was
  // refused (with what the caller could not parse, options.problems) is
  // shown together, so no problem hides another.
  const problems = [...(options.problems ?? [])];
  const initial = (name, fn) => {
    try {
      fn();
    } catch (e) {
      problems.push(`${name}: ${describe(e)}`);
    }
  };
  if (options.damping === false) initial('damping', () => demo.setDamping(false));
  if (options.feedback) initial('feedback', () => demo.setFeedback(options.feedback));
  if (options.speed) initial('speed', () => demo.setSpeed(options.speed));
  if (options.arm) initial('arm', () => demo.setArm(options.arm.post, Float64Array.from(options.arm.links)));
  if (options.obstacles) initial('obstacles', () => demo.setObstacles(flatObstacles(options.obstacles)));
  // Networks kept in this browser for the arm, before the mode that may need them.
  playground.restore();
  if (options.mode && options.mode !== 'numerical') {
    initial('mode', () => demo.setMode(options.mode));
  }
  if (options.lambda !== undefined && options.lambda !== null) {
    initial('lambda', () => demo.setLambda(options.lambda));
  }
  if (options.obstacle && !options.obstacles) {
    initial('obstacle', () => demo.setObstacle(options.obstacle[0], options.obstacle[1]));
  }
  if (options.target) initial('target', () => demo.setTarget(options.target[0], options.target[1], 10));
  if (problems.length) show(`${options.problemsLabel ?? 'Not applied'}: ${problems.join('; ')}`, 'warn', true);
  if (options.autoplay !== false) demo.runTask();

  // ---- controls -------------------------------------------------------
  function syncControls(s) {
    if (el.mode && el.mode.value !== s.mode) el.mode.value = s.mode;
    if (el.play) {
      el.play.textContent = s.running ? 'Pause' : 'Play';
      el.play.setAttribute('aria-pressed', String(s.running));
    }
    if (el.lambda && document.activeElement !== el.lambda && Number(el.lambda.value) !== s.lambda) {
      el.lambda.value = String(s.lambda);
    }
    if (el.lambdaValue) el.lambdaValue.textContent = s.lambda.toFixed(1);
    if (el.damping) el.damping.checked = s.damping;
    if (el.feedback) el.feedback.checked = s.feedback > 0;
  }

  if (el.mode) {
    el.mode.addEventListener('change', () => {
      const wanted = el.mode.value;
      if (attempt(() => demo.setMode(wanted))) {
        clearMessage();
        changed();
      } else {
        el.mode.value = controller.state().mode;
      }
    });
  }
  const togglePlay = () => {
    demo.setRunning(!demo.running);
    clearMessage();
  };
  el.play?.addEventListener('click', togglePlay);
  el.step?.addEventListener('click', () => attempt(() => demo.step()));
  el.reset?.addEventListener('click', () => {
    demo.reset();
    clearMessage();
  });
  for (const [button, task] of [
    [el.task1, 1],
    [el.task2, 2],
  ]) {
    button?.addEventListener('click', () => {
      if (attempt(() => demo.loadTask(task))) {
        clearMessage();
        changed();
      }
    });
  }
  el.lambda?.addEventListener('input', () => {
    if (attempt(() => demo.setLambda(Number(el.lambda.value)))) changed();
  });
  el.damping?.addEventListener('change', () => attempt(() => demo.setDamping(el.damping.checked)));
  el.feedback?.addEventListener('change', () => {
    if (attempt(() => demo.setFeedback(el.feedback.checked ? FEEDBACK_GAIN : 0))) changed();
  });
  el.speed?.addEventListener('change', () => attempt(() => demo.setSpeed(Number(el.speed.value))));
  if (el.speed) attempt(() => demo.setSpeed(Number(el.speed.value)));

  // ---- compare the five methods on the current scene -----------------
  const compareButton = $('compare');
  const compareBody = $('compare-body');
  compareButton?.addEventListener('click', () => {
    let rows = null;
    if (!attempt(() => (rows = demo.compareModes()))) return;
    compareBody?.replaceChildren(
      ...rows.map((r) => {
        const tr = document.createElement('tr');
        tr.dataset.mode = r.mode;
        const cell = (text, cls) => {
          const td = document.createElement('td');
          td.textContent = text;
          if (cls) td.className = cls;
          tr.append(td);
          return td;
        };
        cell(r.label);
        if (r.summary) {
          const s = r.summary;
          tr.dataset.collided = String(s.collided);
          tr.dataset.minDistance = String(s.min_distance);
          tr.dataset.finalError = String(s.final_error);
          cell(s.min_distance === null ? '–' : `${s.min_distance.toFixed(3)} m`, 'num');
          cell(s.collided ? 'yes' : 'no', s.collided ? 'bad' : 'ok');
          cell(fmtLength(s.final_error), s.reached ? 'num' : 'num warn');
        } else {
          tr.dataset.error = r.error;
          cell(r.error, 'warn').colSpan = 3;
        }
        return tr;
      }),
    );
  });

  // ---- the atlas (www/atlas.js) ----------------------------------------
  const atlas = mountAtlas(root, demo, {
    runWorker,
    classes: atlasClasses,
    methods: modes,
    weights: () => playground.files(),
    describe,
    changed: () => changed(),
  });


  const weightButton = $('load-weights');
  weightButton?.addEventListener('click', async () => {
    const phi = $('phi-file')?.files?.[0];
    const v = $('v-file')?.files?.[0];
    if (!phi || !v) {
      show('Choose both files: the Φ weights and the v weights.', 'warn');
      return;
    }
    // Too large to be weights: refused before reading (the core says the same of text).
    const tooBig = [phi, v].find((f) => f.size > MAX_WEIGHTS_BYTES);
    if (tooBig) {
      show(`${tooBig.name} has ${(tooBig.size / 1048576).toFixed(1)} MB; weights files are at most ${MAX_WEIGHTS_BYTES / 1048576} MB.`);
      return;
    }
    let phiText;
    let vText;
    try {
      [phiText, vText] = await Promise.all([phi.text(), v.text()]);
    } catch (e) {
      show(`Cannot read the files: ${describe(e)}`);
      return;
    }
    if (attempt(() => playground.installNetworks(phiText, vText))) {
      show(`Loaded ${phi.name} and ${v.name}; Cases 1-3 now use them.`, 'info');
    }
  });

  if (options.keyboard) {
    options.keyboard.addEventListener('keydown', (e) => {
      if (e.ctrlKey || e.metaKey || e.altKey) return;
      const t = e.composedPath()[0];
      const typing = t && t.matches && t.matches('input[type=text], input[type=number], textarea, select');
      if (typing) return;
      if (e.key === ' ' || e.code === 'Space') {
        e.preventDefault();
        togglePlay();
      } else if (e.key === 'r' || e.key === 'R') {
        e.preventDefault();
        demo.reset();
        clearMessage();
      }
    });
  }

  // ---- keyboard on the drawing: arrows move the target, Shift+arrows the
  // obstacle (src/web/input.rs decides)
  if (!stage.hasAttribute('tabindex')) stage.tabIndex = 0;
  stage.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    let used = false;
    const ok = attempt(() => (used = demo.key(e.key, e.shiftKey)));
    if (!ok || used) e.preventDefault();
    if (ok && used) changed();
  });

  // ---- pointer: drag target and obstacle -------------------------------
  let held = null; // pointerId while dragging
  let longPress = null; // { id, x, y, timer } while a touch holds an obstacle
  const LONG_PRESS_MS = 600;
  const cancelLongPress = () => {
    if (longPress) clearTimeout(longPress.timer);
    longPress = null;
  };
  let press = null; // { id, x, y } of a press on no handle: a click on an atlas cell
  const local = (e) => {
    const r = stage.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  const slopFor = (e) => (e.pointerType === 'mouse' ? 4 : 18);
  stage.addEventListener('pointerdown', (e) => {
    if (held !== null || (e.pointerType === 'mouse' && e.button !== 0)) return;
    const [x, y] = local(e);
    const what = playground.wantsClick() ? undefined : demo.pointerDown(x, y, slopFor(e));
    if (!what) {
      press = { id: e.pointerId, x, y };
      return;
    }
    if (what === 'obstacle' && e.pointerType !== 'mouse') {
      // A long press on an obstacle removes it.
      const i = demo.state().dragging_obstacle;
      longPress = { id: e.pointerId, x, y, timer: setTimeout(() => {
        if (held !== e.pointerId) return;
        held = null;
        demo.pointerCancel();
        attempt(() => playground.removeObstacle(i));
      }, LONG_PRESS_MS) };
    }
    held = e.pointerId;
    stage.setPointerCapture(e.pointerId);
    stage.style.cursor = 'grabbing';
    e.preventDefault();
  });
  stage.addEventListener('pointermove', (e) => {
    const [x, y] = local(e);
    if (held === e.pointerId) {
      if (longPress && Math.hypot(x - longPress.x, y - longPress.y) > 8) cancelLongPress();
      attempt(() => demo.pointerMove(x, y), 'warn');
    } else if (held === null && e.pointerType === 'mouse') {
      const handle = demo.hover(x, y, slopFor(e));
      const cell = handle ? atlas.leave() : atlas.hover(x, y);
      stage.style.cursor = handle ? 'grab' : cell !== undefined ? 'pointer' : 'default';
    }
  });
  stage.addEventListener('pointerleave', () => atlas.leave());
  stage.addEventListener('pointerup', (e) => {
    if (!press || press.id !== e.pointerId) return;
    const [x, y] = local(e);
    const near = Math.hypot(x - press.x, y - press.y) < 6;
    press = null;
    if (!near) return;
    if (playground.wantsClick()) attempt(() => playground.click(x, y));
    else attempt(() => atlas.click(x, y), 'warn');
  });
  stage.addEventListener('dblclick', (e) => {
    const [x, y] = local(e);
    const i = demo.obstacleAt(x, y, 4);
    if (i !== undefined) attempt(() => playground.removeObstacle(i));
  });
  const release = (e) => {
    cancelLongPress();
    if (held !== e.pointerId) return;
    const [x, y] = local(e);
    held = null;
    stage.style.cursor = 'default';
    if (stage.hasPointerCapture(e.pointerId)) stage.releasePointerCapture(e.pointerId);
    attempt(() => demo.pointerUp(x, y), 'warn');
    changed();
  };
  stage.addEventListener('pointerup', release);
  stage.addEventListener('pointercancel', (e) => {
    if (held !== e.pointerId) return;
    held = null;
    demo.pointerCancel();
  });

  // ---- size: sharp on high-DPI screens, follows the layout -------------
  const fit = (canvas, resize) => {
    const apply = () => {
      const r = canvas.getBoundingClientRect();
      if (r.width > 0 && r.height > 0) attempt(() => resize(r.width, r.height, window.devicePixelRatio || 1));
    };
    new ResizeObserver(apply).observe(canvas);
    apply();
  };
  fit(stage, (w, h, d) => demo.resize(w, h, d));
  if (plots) fit(plots, (w, h, d) => demo.resizePlots(w, h, d));

  // ---- readouts and the loop -------------------------------------------
  let autoDampingShown = false;
  function update() {
    const s = demo.state();
    for (const r of readouts) {
      const f = READOUTS[r.dataset.readout];
      if (f) {
        const text = f(s);
        if (r.textContent !== text) r.textContent = text;
      }
      if (r.dataset.readout === 'collision') r.dataset.level = s.collision ? 'bad' : s.collided ? 'warn' : 'ok';
    }
    if (el.warning) el.warning.hidden = s.in_range || !s.mode.startsWith('case');
    if (el.handover) {
      const on = s.handover_steps > 0 && (s.mode === 'case1' || s.mode === 'case3');
      if (on) {
        const text = `Near a singular pose the exact damped Φ stood in for the Φ network (${s.handover_steps} step${s.handover_steps === 1 ? '' : 's'} so far${s.phi_handover ? ', now too' : ''}).`;
        if (el.handover.textContent !== text) el.handover.textContent = text;
      }
      el.handover.hidden = !on;
    }
    if (s.auto_damping && !autoDampingShown) {
      show('The target is out of reach: damping switched on so the joint rates stay finite.', 'warn');
    }
    autoDampingShown = s.auto_damping;
    syncControls(s);
    atlas.check(s);
    playground.check(s);
    return s;
  }

  let last = performance.now();
  let stopped = false;
  function tick(now) {
    if (stopped) return;
    const elapsed = now - last;
    last = now;
    try {
      demo.frame(elapsed);
    } catch (e) {
      show(describe(e), 'error', true);
    }
    update();
    requestAnimationFrame(tick);
  }

  const controller = {
    demo,
    state() {
      return demo.state();
    },
    worldToClient(x, y) {
      const [cx, cy] = demo.worldToCanvas(x, y);
      const r = stage.getBoundingClientRect();
      return { x: r.left + cx, y: r.top + cy };
    },
    runUntil(t) {
      demo.runUntil(t);
      demo.draw();
      return update();
    },
    show,
    atlas: (options) => atlas.run(options),
    playground,
    atlasResult: () => atlas.result(),
    stop() {
      stopped = true;
    },
  };

  // First frame now, synchronously; then the animation loop.
  demo.frame(0);
  update();
  if (el.loading) el.loading.hidden = true;
  requestAnimationFrame((now) => {
    last = now;
    requestAnimationFrame(tick);
  });
  return controller;
}
