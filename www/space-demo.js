// The page with an arm in space (arm=panda, arm=iiwa14): `mountSpace(root,
// options)` puts a SpaceDemo (src/web/space_demo.rs) on the same canvas as
// the plane's demo and wires the controls that apply in space: the method
// menu (every method; the learned ones once the arm's shipped networks
// have loaded), Play, Step, Reset, Task, the speed, λ and the method's
// parameters (method-params.js), Correct drift, the readouts, the legend,
// the comparison, the run's file, the view's reset, the address and the
// live region; the stage's pointer, touch and keys are space-input.js's.
// the path typed or drawn (path-input.js: drawn on the plane through the
// hand's start that faces the camera), the damping switch and the joint
// weighting (lab.js), self-motion (self-motion.js's slider; an elbow
// dragged on the stage). Controls of the plane only (the designer's links,
// training) are hidden by stage.css under html[data-space].

import { SpaceDemo, loadModule, describe, methodGroups, assetUrl, spacePresets, spaceNetworkSets, limits, precisions, legend } from './module.js';
import { fillLegend } from './demo.js';
import { followSize, redrawWhenRestored } from './sizing.js';
import { runFrames } from './frame-loop.js';
import { fixed, metres } from './format.js';
import { simulateWith, flatBalls } from './simulate-options.js';
import { mountMethodParams } from './method-params.js';
import { mountPrecision } from './network-set.js';
import { wireSpaceStage } from './space-input.js';
import { messenger, oneByOne } from './messages.js';
import { writeSpaceAddress } from './space-address.js';
import { mountSpacePanels } from './space-panels.js';
import { mountPath } from './path-input.js';
import { mountLab } from './lab.js';
import { mountSelfMotion } from './self-motion.js';
import { mountWeightsUpload } from './weights-upload.js';
import { mountSpaceTraining } from './space-training.js';
import { mountView, preloadView } from './space-view.js';
import { mountTargetFields } from './place-fields.js';
import { mountPoseFields } from './pose-fields.js';

const READOUTS = {
  t: (s) => fixed(s.t, 1),
  error: (s) => metres(s.tracking_error),
  clearance: (s) => (s.clearance === null ? '—' : fixed(s.clearance, 3)),
  min_clearance: (s) => (s.min_clearance === null ? '—' : fixed(s.min_clearance, 3)),
  collision: (s) => (s.collision ? 'now' : s.collided ? 'earlier' : 'none'),
  manipulability: (s) => fixed(s.manipulability, 4),
  sigma: (s) => s.singular_values.map((v) => fixed(v, 3)).join(', '),
  delta: () => '—',
  solver: () => '—',
};

/** The shipped networks of `arm`, fetched and installed; resolves to null or the reason they are not. */
async function installNetworks(demo, arm) {
  const set = spaceNetworkSets().find((s) => s.arm === arm);
  if (!set) return `no networks are shipped for this arm`;
  try {
    const texts = await Promise.all(
      set.files.map(async (f) => {
        const r = await fetch(assetUrl(`weights/${f}`));
        if (!r.ok) throw new Error(`${f}: HTTP ${r.status}`);
        return r.text();
      }),
    );
    demo.installNetworks(texts[0], texts[1], set.name);
    return null;
  } catch (e) {
    return describe(e);
  }
}

/**
 * Starts the spatial demo on `root` (the page's document). Options: arm
 * (a spatial preset's key), method, task (position or pose), target [x, y, z]
 * (or [x, y, z, roll, pitch, yaw] rad: the full pose, as task=pose),
 * orientation_weight, obstacles (flat x, y, z, r, ...), params { name: value },
 * feedback, weighting, damping, path, floor, self_collision, precision, view [yaw°, pitch°,
 * distance], autoplay, keyboard, problems (shown), onChange
 * (after user changes). Returns a controller with state(), demo,
 * worldToClient(x, y, z), runUntil(t), compare(), runFile().
 */
export async function mountSpace(root, options) {
  const $ = (id) => root.querySelector('#' + id);
  // three.js arrives while the module starts (a failure is said when the view mounts).
  preloadView().catch(() => {});
  await loadModule();
  // A shipped arm, or a robot of the user's (robot-open.js: its chain read from its URDF; its own task).
  const robot = options.robot;
  const preset = robot ? robot.preset : spacePresets().find((p) => p.key === options.arm);
  const stage = $('stage');
  const plots = $('plots');
  const demo = robot ? SpaceDemo.ofChain(stage, plots ?? undefined, preset.key, preset.label, robot.chain, undefined, robot.urdf ?? undefined, robot.base ?? undefined, robot.tip ?? undefined) : new SpaceDemo(stage, plots ?? undefined, preset.key, undefined);
  if (robot) {
    const s = demo.state();
    preset.task = { target: s.target, sphere: null, theta0: s.theta0 };
    preset.joint_limits = s.joint_limits;
  }

  // The page's own <html> (its stylesheet hides the plane's controls); an
  // element (a shadow root) marks only itself.
  (root.host ?? root.documentElement).dataset.space = preset.key;
  const messages = messenger(root);
  const show = messages.show;
  const attempt = (fn, kind = 'error', near = undefined) => messages.attempt(fn, kind, near, describe);
  const announcer = $('announcer');
  const say = (text) => {
    if (announcer) announcer.textContent = text;
  };
  const changed = () => {
    if (options.onChange) options.onChange(demo.state(), preset);
  };
  // The 3-D view under the stage (three.js, fetched now: space-view.js).
  // Its gizmo moves the selected item (the target or a sphere) along an axis or in a plane.
  const view3d = await mountView(stage, demo, { attempt, say, changed }, robot);
  // The frame's state when anything changed (then both drawings are redrawn), else undefined.
  const frame = (elapsed) => {
    const s = demo.frame(elapsed);
    if (s !== undefined) view3d.draw();
    return s;
  };
  // ---- the method menu: every method; the learned ones when networks are in
  const menu = $('mode');
  menu.replaceChildren();
  for (const g of methodGroups()) {
    const group = document.createElement('optgroup');
    group.label = g.label;
    for (const m of g.methods) {
      const o = new Option(`${m.label}: ${m.description}`, m.name);
      o.dataset.networks = String(Boolean(m.networks.phi || m.networks.v));
      group.append(o);
    }
    menu.append(group);
  }
  // The learned methods fetch the arm's shipped networks when first chosen
  // (the Panda's two files are 227 KB gzipped: not on the first load).
  const learned = [...menu.options].filter((o) => o.dataset.networks === 'true');
  const shipped = spaceNetworkSets().find((x) => x.arm === preset.key);
  for (const o of learned) {
    o.disabled = !shipped;
    o.title = shipped ? `Fetches the ${preset.label}'s networks (${shipped.name}) first` : `No networks are shipped for the ${preset.label}`;
  }
  let networks = null;
  const ensureNetworks = () => (networks ??= installNetworks(demo, preset.key));
  // Your own networks (weights-upload.js): two files of redundant-ik train --arm A,
  // checked by the core against this chain; the learned methods use them from then on.
  const upload = $('weights-upload');
  const uploadHint = upload?.querySelector('p');
  if (uploadHint) uploadHint.textContent = `Two weights files written by redundant-ik train --arm ${preset.key} --net phi and --net v: the Φ network and the v network of the ${preset.label}.`;
  const ownNetworks = () => {
    networks = Promise.resolve(null);
    for (const o of learned) {
      o.disabled = false;
      o.title = 'Uses the networks you loaded or trained';
    }
  };
  mountWeightsUpload(root, {
    attempt,
    show,
    install: (phi, v) => {
      demo.installNetworks(phi, v, undefined);
      ownNetworks();
    },
  });
  const choose = async (wanted) => {
    if (learned.some((o) => o.value === wanted) && !demo.state().has_networks) {
      show(`Fetching the ${preset.label}'s networks…`, 'info', false, menu);
      const why = await ensureNetworks();
      if (why) throw new Error(why);
      messages.clear();
    }
    demo.setMethod(wanted);
  };
  menu.addEventListener('change', async () => {
    const wanted = menu.value;
    try {
      await choose(wanted);
      // By the value chosen: the menu follows the state, which switched only now.
      say(`method: ${[...menu.options].find((o) => o.value === wanted)?.textContent ?? wanted}`);
      changed();
    } catch (e) {
      show(describe(e), 'error', true, menu);
      menu.value = demo.state().method;
    }
  });

  // ---- settings from the address, each on its own -------------------------
  const { refused, one: initial } = oneByOne(describe, options.problems ?? []);
  if (options.theta0) initial('theta0', () => demo.setStart(Float64Array.from(options.theta0)));
  if (options.obstacles) initial('obstacles', () => demo.setSpheres(Float64Array.from(options.obstacles)));
  if (options.task || options.target?.length === 6) initial('task', () => demo.setTask(options.task ?? 'pose'));
  if (options.target) initial('target', () => [demo.setTarget(...options.target.slice(0, 3)), options.target.length === 6 && demo.setTargetOrientation(...options.target.slice(3))]);
  if (options.orientation_weight !== undefined) initial('orientation_weight', () => demo.setOrientationWeight(options.orientation_weight));
  for (const [name, value] of Object.entries(options.params ?? {})) initial(name, () => demo.setParam(name, value));
  if (options.feedback !== undefined) initial('feedback', () => demo.setFeedback(options.feedback));
  if (options.weighting) initial('weighting', () => demo.setWeighting(options.weighting));
  if (options.damping !== undefined) initial('damping', () => demo.setDamping(options.damping));
  if (options.path) initial('path', () => demo.setPath(options.path));
  for (const [key, set] of [['floor', (on) => demo.setFloor(on)], ['self_collision', (on) => demo.setSelfCollision(on)]]) if (options[key] !== undefined) initial(key, () => set(options[key]));
  if (options.precision) initial('precision', () => demo.setPrecision(options.precision));
  if (options.view) initial('view', () => demo.setView((options.view[0] * Math.PI) / 180, (options.view[1] * Math.PI) / 180, options.view[2]));
  if (options.projector) (root.host ?? root.documentElement).toggleAttribute('data-projector', true);
  if (options.method) {
    try {
      await choose(options.method);
    } catch (e) {
      refused.push(`method: ${describe(e)}`);
    }
  }
  if (refused.length) show(`${options.problemsLabel ?? 'Not applied'}: ${refused.join('; ')}`, 'warn', true);
  else if (view3d.error) show(view3d.error, 'warn', true);

  // ---- controls ------------------------------------------------------------
  const play = $('play');
  const togglePlay = () => {
    demo.setRunning(!demo.running);
    messages.clear();
  };
  const reset = () => {
    demo.reset();
    messages.clear();
  };
  play?.addEventListener('click', togglePlay);
  $('step')?.addEventListener('click', () => demo.step());
  $('reset')?.addEventListener('click', reset);
  const task = $('task1');
  if (task) {
    task.textContent = 'Task';
    task.title = `The ${preset.label}'s own task: its start pose, line and sphere`;
    // As the plane's task buttons: the task loaded and played from its start.
    task.addEventListener('click', () => {
      if (attempt(() => demo.loadTask(), 'error', task)) {
        demo.setRunning(true);
        say(`the ${preset.label}'s task loaded and playing`);
        changed();
      }
    });
  }
  // The keys of the drawing in space (space-input.js): no elbows, orbit and zoom.
  const hint = $('keys-hint');
  if (hint) {
    hint.innerHTML =
      '<kbd>Space</kbd> play / pause · <kbd>R</kbd> reset · on the drawing: <kbd>n</kbd> selects the target or a sphere, ' +
      '<kbd>←</kbd><kbd>↑</kbd><kbd>→</kbd><kbd>↓</kbd> move it in the plane facing you (<kbd>Shift</kbd>: 5 mm), ' +
      '<kbd>o</kbd> / <kbd>u</kbd> orbit (<kbd>Shift</kbd>: back), <kbd>+</kbd> / <kbd>-</kbd> zoom, <kbd>0</kbd> resets the view; for the full pose <kbd>x</kbd> <kbd>y</kbd> <kbd>z</kbd> turn the target';
  }
  const speed = $('speed');
  speed?.addEventListener('change', () => attempt(() => demo.setSpeed(Number(speed.value)), 'error', speed));
  if (speed) attempt(() => demo.setSpeed(Number(speed.value)));
  const feedback = $('feedback');
  feedback?.addEventListener('change', () => {
    if (attempt(() => demo.setFeedback(feedback.checked ? limits().drift_gain : 0), 'error', feedback)) changed();
  });
  const damping = $('damping');
  damping?.addEventListener('change', () => {
    if (attempt(() => demo.setDamping(damping.checked), 'error', damping)) changed();
  });
  // The path (typed, or drawn on the stage: its stroke is taken before
  // space-input.js's handlers), the joint weighting and the floor.
  const path = $('path');
  if (path) path.placeholder = 'line · circle:CX,CY,CZ,NX,NY,NZ[,LAPS] · points:X,Y,Z;…';
  const drawPath = $('draw-path');
  if (drawPath) drawPath.title = "Press, then draw on the stage: the stroke, on the plane through the hand's start that faces you, becomes a points: path (Escape cancels)";
  const syncPath = mountPath(root, demo, { attempt, changed, stage });
  const syncLab = mountLab(root, demo, { attempt, changed });
  // Self-motion: the slider (an elbow dragged on the stage does the same: space-input.js).
  mountSelfMotion(root, demo, { attempt, changed });
  // The networks' arithmetic: the plane's selector (network-set.js).
  const syncPrecision = mountPrecision(root, (name, near) => {
    if (attempt(() => demo.setPrecision(name), 'error', near)) {
      say(`the networks now compute in ${name}`);
      changed();
    }
  });
  // Spheres: one more beside the line (selected, so the keys move it), or the last one less.
  $('obstacle-add')?.addEventListener('click', () => {
    const s = demo.state();
    const [x, y, z] = s.target;
    if (attempt(() => demo.addSphere(x - 0.1, y - 0.15, z + 0.15, 0.05), 'error', $('obstacle-add'))) {
      say(`sphere ${demo.state().spheres.length} added and selected: the arrow keys move it`);
      changed();
    }
  });
  $('obstacle-remove')?.addEventListener('click', () => {
    const n = demo.state().spheres.length;
    if (n && attempt(() => demo.removeSphere(n - 1), 'error', $('obstacle-remove'))) {
      say(`sphere ${n} removed`);
      changed();
    }
  });
  const syncParams = mountMethodParams(root, demo, { attempt, changed });
  // The target's x, y and z without dragging (WCAG 2.5.7).
  const syncTarget = mountTargetFields(root, demo, { attempt, changed, dims: 3 });
  const syncPose = mountPoseFields(root, demo, { attempt, changed, say, view: view3d });
  wireSpaceStage(stage, demo, { attempt, changed, say, togglePlay, reset, keyboard: options.keyboard, gizmoAxis: view3d.gizmoAxis });
  const view = document.createElement('button');
  Object.assign(view, { type: 'button', id: 'fit-view', textContent: 'Reset view' });
  view.title = 'Back to the first view (key 0); orbit by dragging the empty drawing (or Shift+drag, two fingers, keys o and u), zoom with the wheel, two fingers or + and -';
  const tap = window.matchMedia?.('(pointer: coarse)').matches ? 44 : 0;
  view.style.cssText = `position: absolute; top: 6px; right: 6px; flex: none; min-height: ${tap}px; min-width: ${tap}px; padding: 1px 8px; font-size: 12px;`;
  view.addEventListener('click', () => {
    demo.resetView();
    say('view reset');
  });
  stage.after(view);
  stage.setAttribute(
    'aria-label',
    `The ${preset.label} in 3-D, the spheres and the path. Drag the target or a sphere, or an elbow to move the arm with its hand held still; drag the empty drawing to orbit. With the keyboard: n selects the next item, the arrows move it in the view's plane, o and u orbit, + and - zoom, 0 resets the view; for the hand's full pose x, y and z turn the target.`,
  );

  // The readouts of the velocity ellipsoid: three singular values, m³.
  const readout = (f) => [...root.querySelectorAll('[data-readout]')].find((r) => READOUTS[r.dataset.readout] === f);
  const sigma = readout(READOUTS.sigma)?.closest('div');
  if (sigma?.firstElementChild) {
    const j = document.createElement('i');
    j.textContent = 'J';
    sigma.firstElementChild.replaceChildren('singular values σ₁, σ₂, σ₃ of ', j);
  }
  const volume = readout(READOUTS.manipulability);
  if (volume?.nextSibling) volume.nextSibling.textContent = ' m³';

  // ---- legend --------------------------------------------------------------
  // The module's (the renderer's colours and words), as the plane's; its
  // ellipsoids' switches call demo.setShown (lab.js).
  const legendList = $('legend');
  if (legendList) {
    legendList.replaceChildren();
    fillLegend(legendList, legend(true));
  }

  const panels = mountSpacePanels(root, demo, { attempt, show, say, preset, ensureNetworks, changed, snapshot: () => view3d.snapshot() });
  const training = mountSpaceTraining(root, demo, { preset, show, say, installed: ownNetworks });

  // ---- size ------------------------------------------------------------------
  followSize(
    stage,
    (w, h, d) => {
      demo.resize(w, h, d);
      view3d.resize(w, h, d);
    },
    attempt,
  );
  if (plots) followSize(plots, (w, h, d) => demo.resizePlots(w, h, d), attempt);
  redrawWhenRestored([stage, plots], () => demo.draw(), attempt);
  view3d.three?.renderer.domElement.addEventListener('webglcontextrestored', () => view3d.draw());

  // ---- readouts, the live region and the loop ----------------------------------
  // The networks' trained range, as on the plane.
  const range = $('range-warning');
  if (range) range.textContent = "Outside the networks' trained range: their output is an extrapolation here (the pose on screen, or a sphere for v, lies outside the boxes training saw). Compare with the dashed numerical ghost.";
  const readouts = [...root.querySelectorAll('[data-readout]')];
  const summary = $('stage-summary');
  let seen = { revision: -1, collided: false, ended: true, running: false };
  function update(s) {
    if (menu.value !== s.method) menu.value = s.method;
    if (play) {
      play.textContent = s.running ? 'Pause' : 'Play';
      play.setAttribute('aria-pressed', String(s.running));
    }
    if (feedback) feedback.checked = s.feedback > 0;
    if (damping) damping.checked = s.damping;
    syncPath(s);
    syncLab(s);
    syncPrecision(s, menu.selectedOptions[0]?.dataset.networks === 'true');
    syncParams(s);
    syncTarget(s);
    syncPose(s);
    if (range) range.hidden = s.in_range;
    const ghostKey = legendList?.querySelector('[data-key=ghost]');
    if (ghostKey) ghostKey.hidden = !s.ghost;
    for (const r of readouts) {
      const f = READOUTS[r.dataset.readout];
      if (!f) continue;
      const text = f(s);
      if (r.textContent !== text) r.textContent = text;
      if (r.dataset.readout === 'collision') r.dataset.level = s.collision ? 'bad' : s.collided ? 'warn' : 'ok';
    }
    // Said as it happens: the first collision of a run played, its end.
    if (s.running && s.collided && !seen.collided) say(`collision at t = ${fixed(s.first_collision ?? s.t, 1)} s: a link is inside a sphere`);
    if (s.ended && !seen.ended && seen.running) {
      const m = s.summary;
      const clear = m.min_clearance === null ? '' : `, smallest clearance ${metres(m.min_clearance)}`;
      say(`run ended: final error ${metres(m.final_error)}${clear}${m.collision_steps ? `, a link inside a sphere for ${m.collision_steps} steps` : ', no collision'}${m.limit_steps ? `, ${m.limit_steps} steps past a joint limit` : ''}`);
    }
    if (s.run_revision !== seen.revision && summary) {
      const m = s.summary;
      summary.textContent = `The ${s.arm_label} (${s.dof} joints) in ${menu.selectedOptions[0]?.textContent ?? s.method}; ${s.spheres.length} sphere(s); the run ${m.collision_steps ? `collides for ${m.collision_steps} steps` : 'does not collide'}${m.self_collision_steps ? `, two of its links meet for ${m.self_collision_steps} steps,` : ''} and ends ${metres(m.final_error)} from its target${s.failure ? `; it stopped early: ${s.failure}` : ''}.`;
      if (s.failure) show(`The run stopped at t = ${fixed(s.t, 2)} s: ${s.failure}`, 'warn', true);
    }
    seen = { revision: s.run_revision, collided: s.collided && s.t > 0, ended: s.ended, running: s.running };
    panels.sync(s);
    return s;
  }
  if (options.autoplay ?? !(typeof matchMedia === 'function' && matchMedia('(prefers-reduced-motion: reduce)').matches)) demo.setRunning(true);
  update(frame(0) ?? demo.state());
  const loading = $('loading');
  if (loading) loading.hidden = true;
  const stop = runFrames(frame, update, (e) => show(describe(e), 'error', true));

  return {
    demo,
    preset,
    networks: ensureNetworks,
    state: () => demo.state(),
    worldToClient(x, y, z) {
      const [cx, cy] = demo.worldToCanvas(x, y, z);
      const r = stage.getBoundingClientRect();
      return { x: r.left + cx, y: r.top + cy };
    },
    runUntil(t) {
      demo.runUntil(t);
      return update(frame(0) ?? demo.state());
    },
    compare: () => panels.compare(),
    train: (options) => training.train(options),
    /**
     * A whole run off screen (the plane's window.demo.simulate): options
     * { method, target: [x, y, z], obstacles: [[x, y, z, r], ...], tf,
     * theta0, feedback, refine }, each absent one the scene's (an
     * obstacle's radius 0.05 m); its summary (simulate-options.js).
     */
    simulate: (options) => simulateWith(demo, options, (list) => flatBalls(list, 3, limits().default_radius)),
    runFile: () => demo.runFile(),
    /** The 3-D view with the overlay over it, one 2-D canvas (the PNG saved; the tests' pixels). */
    snapshot: () => view3d.snapshot(),
    /** The 3-D view (space-view.js): its three.js scene is `view3d.three.scene`. */
    view3d,
    atlas: (o) => panels.atlas(o),
    show,
    clear: () => messages.clear(),
    /**
     * Applies changed settings (an element's attributes changed: the keys
     * of readSpaceAddress, each absent one back to its default); returns
     * what was refused, `key: why`. A learned method fetches its networks
     * first, and says there if they cannot be had.
     */
    apply(changed) {
      const { refused, one } = oneByOne(describe);
      const own = preset.task;
      if ('obstacles' in changed) one('obstacles', () => demo.setSpheres(Float64Array.from(changed.obstacles ?? own.sphere ?? [])));
      if ('task' in changed || changed.target?.length === 6) one('task', () => demo.setTask(changed.task ?? (changed.target?.length === 6 ? 'pose' : 'position')));
      if ('target' in changed) one('target', () => [demo.setTarget(...(changed.target ?? own.target).slice(0, 3)), changed.target?.length === 6 && demo.setTargetOrientation(...changed.target.slice(3))]);
      for (const [name, value] of Object.entries(changed.params ?? {})) one(name, () => demo.setParam(name, value));
      if ('feedback' in changed) one('feedback', () => demo.setFeedback(changed.feedback ?? 0));
      if ('weighting' in changed) one('weighting', () => demo.setWeighting(changed.weighting ?? limits().joint_weightings[0][0]));
      for (const [key, set] of [['floor', (v) => demo.setFloor(v ?? false)], ['self_collision', (v) => demo.setSelfCollision(v ?? false)], ['damping', (v) => demo.setDamping(v ?? false)], ['orientation_weight', (v) => v !== undefined && demo.setOrientationWeight(v)]]) if (key in changed) one(key, () => set(changed[key]));
      if ('path' in changed) one('path', () => demo.setPath(changed.path ?? 'line'));
      if ('theta0' in changed) one('theta0', () => demo.setStart(Float64Array.from(changed.theta0 ?? own.theta0)));
      if ('precision' in changed) one('precision', () => demo.setPrecision(changed.precision ?? precisions()[0].name));
      if (changed.view) one('view', () => demo.setView((changed.view[0] * Math.PI) / 180, (changed.view[1] * Math.PI) / 180, changed.view[2]));
      // (A method removed keeps the method in use.)
      if (changed.method) choose(changed.method).catch((e) => show(`Not applied: method: ${describe(e)}`, 'warn', true));
      return refused;
    },
    stop: () => stop(),
  };
}
