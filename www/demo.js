// One demo on one root: `mount(root, options)` wires the controls, the
// readouts, the resize and the animation loop to a `Demo` (src/web/), which
// owns the session and draws the canvas, and mounts the rooms around it:
// the stage's pointer and keyboard (stage-input.js), the comparison panel
// (compare.js), the atlas (atlas.js), the playground (playground.js) and
// the "use your own weights" panel (weights-upload.js). No kinematics here,
// and no names, limits or colours of its own: they come from the module
// (module.js).
//
// `mount(root, options)` works on any root that holds the expected ids
// (`#stage` and, all optional, `#plots`, `#mode`, `#legend`, `#play`, `#step`,
// `#reset`, `#task1`, `#task2`, `#lambda`, `#method-params`, `#damping`, `#feedback`, `#speed`,
// `#message`, `#range-warning`, `#handover-note`, `#loading` and
// `[data-readout]` elements): the page's document, or the shadow root of a
// <redundant-ik-demo> element, so several demos on one page stay independent.

import { Demo, loadModule, describe, method, methodGroups, limits, legend, usesNetworks } from './module.js';
import { fixed, metres } from './format.js';
import { mountAtlas } from './atlas.js';
import { mountPlayground } from './playground.js';
import { flatObstacles } from './arm-designer.js';
import { mountCompare } from './compare.js';
import { mountWeightsUpload } from './weights-upload.js';
import { wireStage } from './stage-input.js';
import { followSize, redrawWhenRestored } from './sizing.js';
import { runFrames } from './frame-loop.js';
import { mountMethodParams } from './method-params.js';
import { mountSelfMotion } from './self-motion.js';
import { mountNetworkSet } from './network-set.js';
import { messenger, oneByOne } from './messages.js';
import { mountTakeaway } from './takeaway.js';
import { mountNotes } from './notes.js';
import { mountLab } from './lab.js';
import { mountPath } from './path-input.js';
import { mountTargetFields } from './place-fields.js';
import { mountAnnouncer } from './announce.js';

/**
 * Fills a `<select>` with the methods, grouped ("The paper", "Beyond the
 * paper"): "Case 1: Φ by a network, v exact".
 */
function fillMethods(select) {
  if (!select || select.options.length) return;
  for (const g of methodGroups()) {
    const group = document.createElement('optgroup');
    group.label = g.label;
    group.dataset.group = g.group;
    for (const m of g.methods) group.append(new Option(`${m.label}: ${m.description}`, m.name));
    select.append(group);
  }
}

/**
 * Fills a legend list from the module's legend (the renderer's colours;
 * `entries`, the plane's by default, `legend(true)` the drawing in
 * perspective's); on the plane each entry is shown only while the drawing
 * draws it (`syncLegend`).
 */
export function fillLegend(list, entries = legend()) {
  if (!list || list.children.length) return;
  for (const e of entries) {
    const li = document.createElement('li');
    li.dataset.key = e.key;
    const key = document.createElement('span');
    key.className = `key key-${e.kind}`;
    key.style.setProperty('--swatch', e.swatch);
    li.append(key, e.label);
    // An entry the page may switch (the lab's ellipses): a checkbox, always listed.
    if (e.toggle) {
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.dataset.toggle = e.key;
      label.append(box, ...li.childNodes);
      li.append(label);
      li.dataset.toggle = 'true';
    }
    list.append(li);
  }
}

/** Shows the legend's entries whose bit is set in `mask` (Demo.drawn()). */
function syncLegend(list, mask) {
  if (!list) return;
  [...list.children].forEach((li, i) => {
    const hide = !(mask & (1 << i)) && !li.dataset.toggle;
    if (li.hidden !== hide) li.hidden = hide;
  });
}

const READOUTS = {
  t: (s) => fixed(s.t, 1),
  error: (s) => metres(s.tracking_error),
  // The clearance to the nearest obstacle's edge, as the plots, the
  // comparison, the CSV and the atlas give it (the centre's distance is
  // the state's `distance`).
  clearance: (s) => fixed(s.clearance, 3),
  min_clearance: (s) => fixed(s.min_clearance, 3),
  collision: (s) => (s.collision ? 'now' : s.collided ? 'earlier' : 'none'),
  manipulability: (s) => fixed(s.manipulability, 3),
  sigma: (s) => s.singular_values.map((v) => fixed(v, 3)).join(', '),
  delta: (s) => (s.delta > 0 ? s.delta.toExponential(1) : '0'),
  solver: (s) => fixed(s.solver_ms_per_step, 3),
};

/**
 * Starts a demo on `root`. Options: task (1|2), method (`mode`, the older
 * name, is read too), lambda, target [x, y],
 * obstacle [x, y], obstacles [[x, y, r], ...] or flat [x0, y0, r0, ...]
 * (instead of obstacle), arm { post, links }, damping (bool), feedback
 * (closed-loop gain K, 1/s; default 0, the paper's open loop), networks
 * (a shipped set: 'paper' or 'reach'), params ({ name: value } for the
 * methods' other parameters: refine, influence, ...), speed,
 * autoplay (default true, false where the user prefers reduced motion),
 * projector (bool: data-projector on the page's <html> or the element, for
 * a11y.css), keyboard (element that receives key presses;
 * default none), onChange(state) (after user changes, e.g. to update the
 * URL), onArm(state) (when the arm changes, e.g. to rewrite the page's prose),
 * problems (what the caller could not parse, shown with the settings
 * the core refuses under problemsLabel; default 'Not applied'), start
 * { theta0, tf } (a run's own start pose and final time, from an address),
 * params { name: value } (the methods' parameters), path (the path's
 * text: line, circle:CX,CY[,LAPS], points:X,Y;...), link(state, scene)
 * (the address of the scene, for "Copy link"; default the page's).
 * Returns a controller with state(), worldToClient(x, y), runUntil(t),
 * apply(settings) (the same options, task included, applied to the
 * running demo: what changed; returns what was refused), demo.
 */
export async function mount(root, options = {}) {
  const $ = (id) => root.querySelector('#' + id);
  const stage = $('stage');
  const plots = $('plots');
  const el = {
    method: $('mode'),
    legend: $('legend'),
    play: $('play'),
    step: $('step'),
    reset: $('reset'),
    task1: $('task1'),
    task2: $('task2'),
    damping: $('damping'),
    feedback: $('feedback'),
    speed: $('speed'),
    message: $('message'),
    loading: $('loading'),
  };
  const readouts = [...root.querySelectorAll('[data-readout]')];

  await loadModule();
  fillMethods(el.method);
  fillLegend(el.legend);
  const demo = new Demo(stage, plots ?? undefined, options.task === 2 ? 2 : 1);

  // ---- messages, next to what caused them (messages.js) ---------------
  const messages = messenger(root);
  const show = messages.show;
  const clearMessage = messages.clear;
  const attempt = (fn, kind = 'error', near = undefined) => messages.attempt(fn, kind, near, describe);

  const changed = () => options.onChange && options.onChange(controller.state());

  // ---- the arm, obstacles and training (www/playground.js) --------------
  const playground = mountPlayground(root, demo, { attempt, show, changed: () => changed() });
  const networkSet = mountNetworkSet(root, demo, { show, changed: () => changed() });

  // ---- settings (URL or attributes) -------------------------------------
  // Each is tried on its own: one refused keeps the others. What was
  // refused is returned (and, at the start, shown with what the caller
  // could not parse, options.problems), so no problem hides another.
  // `settings` has mount()'s option names; those undefined are left as
  // they are. The same code applies the element's changed attributes later
  // (controller.apply).
  function apply(settings) {
    const { refused, one: initial } = oneByOne(describe);
    if (settings.task !== undefined && settings.task !== demo.state().task) initial('task', () => demo.loadTask(settings.task === 2 ? 2 : 1));
    if (settings.damping !== undefined && settings.damping !== demo.state().damping) initial('damping', () => demo.setDamping(settings.damping));
    if (settings.feedback !== undefined && settings.feedback !== demo.state().feedback) initial('feedback', () => demo.setFeedback(settings.feedback));
    if (settings.speed) initial('speed', () => demo.setSpeed(settings.speed));
    if (settings.arm) {
      // A preset named in the address brings its limits (and the core its task).
      const { post, links, joint_limits: lim, rate_limits: rat } = settings.arm;
      const own = !settings.limits && !settings.rates && (lim || rat);
      initial('arm', () => (own ? demo.setLimitedArm(post, Float64Array.from(links), lim ? Float64Array.from(lim.flat()) : undefined, rat ? Float64Array.from(rat) : undefined) : demo.setArm(post, Float64Array.from(links))));
    }
    if (settings.limits || settings.rates) initial(settings.limits ? 'limits' : 'rates', () => demo.setArmLimits(settings.limits, settings.rates));
    // The lab's switches (www/lab.js).
    if (settings.weighting && settings.weighting !== demo.state().weighting) initial('weighting', () => demo.setWeighting(settings.weighting));
    if (settings.floor !== undefined && settings.floor !== demo.state().floor) initial('floor', () => demo.setFloor(settings.floor));
    if (settings.obstacles) initial('obstacles', () => demo.setObstacles(flatObstacles(settings.obstacles)));
    // Networks kept in this browser for the arm, before the method that may need them.
    if (settings.arm || settings.restore) playground.restore();
    const wanted = settings.method ?? settings.mode;
    if (wanted && wanted !== demo.state().method) {
      initial('method', () => demo.setMethod(wanted));
    }
    if (settings.lambda !== undefined && settings.lambda !== null) {
      initial('lambda', () => demo.setLambda(settings.lambda));
    }
    if (settings.obstacle && !settings.obstacles) {
      initial('obstacle', () => demo.setObstacle(settings.obstacle[0], settings.obstacle[1]));
    }
    if (settings.target) initial('target', () => demo.setTarget(settings.target[0], settings.target[1], 10));
    if (settings.start) initial('theta0', () => demo.setStart(Float64Array.from(settings.start.theta0), settings.start.tf));
    if (settings.path) initial('path', () => demo.setPath(settings.path));
    for (const [name, value] of Object.entries(settings.params ?? {})) initial(name, () => demo.setParam(name, value));
    // A shipped set other than the one in use is fetched first: it comes in when it arrives.
    // Projector mode: the page's (or the element's) larger text and higher
    // contrast (a11y.css), and the drawing's and the plots' strokes, markers
    // and text larger (the module's setProjector).
    if (settings.projector !== undefined) {
      (root.host ?? root.documentElement)?.toggleAttribute('data-projector', Boolean(settings.projector));
      demo.setProjector(Boolean(settings.projector));
    }
    if (settings.networks && settings.networks !== demo.state().network_set) {
      networkSet.choose(settings.networks).catch((e) => show(`networks: ${describe(e)}`, 'warn', true));
    }
    if (settings.precision && settings.precision !== demo.state().precision) initial('precision', () => demo.setPrecision(settings.precision));
    return refused;
  }
  const problems = [...(options.problems ?? []), ...apply({ ...options, task: undefined, restore: true })];
  if (problems.length) show(`${options.problemsLabel ?? 'Not applied'}: ${problems.join('; ')}`, 'warn', true);
  // Reduced motion asked for: the run waits for Play (unless the caller says autoplay: true).
  const still = typeof matchMedia === 'function' && matchMedia('(prefers-reduced-motion: reduce)').matches;
  if (options.autoplay ?? !still) demo.runTask();
  else demo.setRunning(false);

  // ---- controls -------------------------------------------------------
  function syncControls(s) {
    if (el.method && el.method.value !== s.method) el.method.value = s.method;
    syncParams(s);
    if (el.damping) el.damping.checked = s.damping;
    if (el.feedback) el.feedback.checked = s.feedback > 0;
    syncPath(s);
  }

  el.method?.addEventListener('change', () => {
    const wanted = el.method.value;
    chosenMethod = wanted;
    if (attempt(() => demo.setMethod(wanted), 'error', el.method)) {
      clearMessage();
      changed();
    } else {
      el.method.value = controller.state().method;
    }
  });
  const togglePlay = () => {
    demo.setRunning(!demo.running);
    clearMessage();
  };
  const reset = () => {
    demo.reset();
    clearMessage();
  };
  el.play?.addEventListener('click', togglePlay);
  el.step?.addEventListener('click', () => attempt(() => demo.step(), 'error', el.step));
  el.reset?.addEventListener('click', reset);
  for (const [button, task] of [
    [el.task1, 1],
    [el.task2, 2],
  ]) {
    button?.addEventListener('click', () => {
      if (attempt(() => demo.loadTask(task), 'error', button)) {
        announce.task(task);
        clearMessage();
        changed();
      }
    });
  }
  // λ and the parameters of the method in use (www/method-params.js).
  const syncParams = mountMethodParams(root, demo, { attempt, changed });
  mountSelfMotion(root, demo, { attempt, changed });
  el.damping?.addEventListener('change', () => attempt(() => demo.setDamping(el.damping.checked), 'error', el.damping));
  // "Correct drift": the core's gain K (1/s) of Xdot + K (X_ref - X).
  el.feedback?.addEventListener('change', () => {
    if (attempt(() => demo.setFeedback(el.feedback.checked ? limits().drift_gain : 0), 'error', el.feedback)) changed();
  });
  el.speed?.addEventListener('change', () => attempt(() => demo.setSpeed(Number(el.speed.value)), 'error', el.speed));
  if (el.speed) attempt(() => demo.setSpeed(Number(el.speed.value)));

  // ---- the panels around the stage --------------------------------------
  const compare = mountCompare(root, demo, { attempt });
  const takeaway = mountTakeaway(root, demo, {
    show,
    link: () => (options.link ? options.link(controller.state(), demo.scene()) : location.href),
  });
  const atlas = mountAtlas(root, demo, { changed: () => changed() });
  mountWeightsUpload(root, { attempt, show, install: playground.installNetworks });
  const syncPath = mountPath(root, demo, { attempt, changed, stage });
  wireStage(stage, demo, { attempt, changed, togglePlay, reset, atlas, playground, keyboard: options.keyboard });
  // Fit, over the drawing's top right corner (the page's and the element's
  // button styles, made small): back to the whole reach after a zoom.
  const fitButton = document.createElement('button');
  Object.assign(fitButton, { type: 'button', id: 'fit-view', textContent: 'Fit' });
  fitButton.title = 'Show the whole reach (key 0); zoom with the wheel, two fingers or + and -, pan with the mouse on the empty drawing or two fingers';
  // On a touch screen a tap target of 44 px, as every control there (a11y.css).
  const tap = window.matchMedia?.('(pointer: coarse)').matches ? 44 : 0;
  fitButton.style.cssText = `position: absolute; top: 6px; right: 6px; flex: none; min-height: ${tap}px; min-width: ${tap}px; padding: 1px 8px; font-size: 12px;`;
  fitButton.addEventListener('click', () => demo.fitView());
  stage.after(fitButton);

  // ---- size: sharp on high-DPI screens, follows the layout -------------
  followSize(stage, (w, h, d) => demo.resize(w, h, d), attempt);
  if (plots) followSize(plots, (w, h, d) => demo.resizePlots(w, h, d), attempt);
  redrawWhenRestored([stage, plots], () => demo.draw(), attempt);

  // ---- readouts and the loop -------------------------------------------
  const syncNotes = mountNotes(root);
  const announce = mountAnnouncer(root);
  const syncLab = mountLab(root, demo, { attempt, changed: () => changed() });
  const syncTarget = mountTargetFields(root, demo, { attempt, changed: () => changed() });
  let outOfReachShown = false;
  let chosenMethod = null; // the method the user picked last
  let shownMethod = null;
  let shownArm = null;
  let drawnMask = -1;
  /** Follows the state `s` (the frame's, else asked for now): one state per frame, nothing else asked of the module. */
  function update(s = demo.state()) {
    const mask = s.drawn;
    if (mask !== drawnMask) syncLegend(el.legend, (drawnMask = mask));
    syncNotes(s);
    announce.sync(s);
    syncLab(s);
    syncTarget(s);
    // A switch of method the page made by itself (a new arm without
    // networks for it, networks forgotten) is announced at the menu.
    const [was, now] = [method(shownMethod), method(s.method)];
    if (shownMethod !== null && s.method !== chosenMethod && usesNetworks(was) && !usesNetworks(now)) {
      show(`${was?.label ?? shownMethod} needs networks trained for this arm, which it has not: the page switched to ${now?.label ?? s.method}.`, 'warn', true, el.method);
    }
    shownMethod = s.method;
    chosenMethod = s.method;
    if (s.arm_text !== shownArm) {
      shownArm = s.arm_text;
      if (options.onArm) options.onArm(s);
    }
    for (const r of readouts) {
      const f = READOUTS[r.dataset.readout];
      if (f) {
        const text = f(s);
        if (r.textContent !== text) r.textContent = text;
      }
      if (r.dataset.readout === 'collision') r.dataset.level = s.collision ? 'bad' : s.collided ? 'warn' : 'ok';
    }
    // Said once as the target (or the path) leaves the reach, with the
    // damping on or off.
    if (s.out_of_reach && !outOfReachShown) {
      const what = s.path ? "The path leaves the arm's reach" : 'The target is out of reach';
      show(
        s.auto_damping
          ? `${what}: damping switched on so the joint rates stay finite; the hand stops as close as it can.`
          : `${what}: the hand stops as close as it can.`,
        'warn',
      );
    }
    outOfReachShown = s.out_of_reach;
    syncControls(s);
    atlas.check(s);
    compare?.(s);
    playground.check(s);
    networkSet.sync(s);
    return s;
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
    /** Hides the message beside the drawing. */
    clear: () => clearMessage(),
    attempt,
    /** Applies settings (mount()'s option names; undefined ones stay) to the running demo; returns what was refused, each as `name: why`. */
    apply: (settings) => apply(settings),
    files: () => takeaway.files(),
    atlas: (options) => atlas.run(options),
    useNetworks: (name) => networkSet.choose(name),
    playground,
    atlasResult: () => atlas.result(),
    atlasDescription: () => atlas.describe(),
    stop: () => stop(),
  };

  // First frame now, synchronously (it draws: nothing was drawn yet); then
  // the animation loop. After a failed step the page follows the last good
  // state.
  update(demo.frame(0) ?? demo.state());
  if (el.loading) el.loading.hidden = true;
  const stop = runFrames(
    (elapsed) => demo.frame(elapsed),
    (s) => update(s),
    (e) => {
      show(describe(e), 'error', true);
      update();
    },
  );
  return controller;
}
