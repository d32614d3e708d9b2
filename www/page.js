// The full page (index.html): loads the module, fills the prose the module
// knows (the methods explained, the limits quoted, the arm described as it
// is now), mounts the demo on the document with the settings of the
// address (address.js), wires the benchmark panel (bench-panel.js) and the
// tour (tour.js), the introduction's "More" and the projector-mode switch, keeps the stage column's top for the layout (stage.css)
// and exposes `window.demo` for scripts and tests. With embed=1 in the
// address it marks the document (data-embed) for stage.css, which shows the
// stage and the essential controls only (for an iframe). If the module cannot
// start, the page says so and disables its controls instead of showing a
// blank stage.

import { loadModule, describe, methods, methodGroups, fillLimits, moduleBuild, moduleMemoryBytes, limits, networkMethodLabels, spacePresets, formatJointLimits, formatRateLimits } from './module.js';
import { mountTour } from './tour.js';
import { bench, spaceAtlas } from './jobs.js';
import { mount } from './demo.js';
import { readAddress, writeAddress, isEmbedded } from './address.js';
import { mountBenchPanel } from './bench-panel.js';
import { spaceArmOf, readSpaceAddress, writeSpaceAddress } from './space-address.js';

/** The methods, each with what it computes: the "The methods" list of the page. */
function explainMethods(list) {
  if (!list) return;
  for (const g of methodGroups()) {
    const head = document.createElement('dt');
    head.className = 'group';
    head.textContent = g.label;
    list.append(head);
    for (const m of g.methods) {
      const dt = document.createElement('dt');
      dt.textContent = m.label;
      const dd = document.createElement('dd');
      dd.textContent = m.description;
      list.append(dt, dd);
    }
  }
}

const WORDS = ['no', 'one', 'two', 'three', 'four', 'five', 'six', 'seven', 'eight'];
const word = (n) => WORDS[n] ?? String(n);
const cap = (s) => s[0].toUpperCase() + s.slice(1);

/** The prose that describes the arm, rewritten for the arm in `s`. */
function describeArm(s) {
  const n = s.arm.links.length;
  const spare = n - 2;
  const links = s.arm.links.map(String);
  const list = links.length > 1 ? `${links.slice(0, -1).join(', ')} and ${links.at(-1)}` : links[0];
  for (const el of document.querySelectorAll('[data-arm="links"]')) el.textContent = word(n);
  // The clause with its verb, which agrees with it: "its two spare degrees of freedom bend".
  const clause = spare === 0 ? 'it has no spare degree of freedom to bend' : spare === 1 ? 'its spare degree of freedom bends' : `its ${word(spare)} spare degrees of freedom bend`;
  for (const el of document.querySelectorAll('[data-arm="spare"]')) el.textContent = clause;
  const see = document.getElementById('what-you-see');
  if (see) {
    const use =
      spare > 0
        ? `${cap(word(n))} joints for a two-dimensional task leave ${spare === 1 ? 'one degree of freedom' : `${word(spare)} degrees of freedom`} spare: the planner spends ${spare === 1 ? 'it' : 'them'} on the null-space vector <i>v</i>, which grows the triangles between each link and the obstacle centre, pushing the links away from it.`
        : `${cap(word(n))} joints for a two-dimensional task leave none spare: there is no null space, so the arm cannot bend away from an obstacle while its hand follows the line.`;
    see.innerHTML = `The arm stands on a ${s.arm.post} m post and has links of ${list} m. Its end effector follows the dashed straight line at constant speed (the grey dot is where it should be now). ${use}`;
  }
  const note = document.getElementById('network-note');
  const isPaper = s.paper_arm;
  if (note) {
    note.dataset.arm = isPaper ? 'paper' : 'other';
    if (!isPaper) {
      note.textContent =
        `The networks shipped with the page were trained for the paper's arm, not this one: ${networkMethodLabels()} need networks trained for this arm ` +
        '("Train the networks for this arm"). The training report, and a warning beside the drawing when they fail their own check, say how well they do.';
    } else if (note.dataset.original) {
      note.innerHTML = note.dataset.original;
    }
  }
}

/** Keeps --stage-top and --stage-top0 (where the sticky stage column starts on screen, now and unscrolled) for stage.css. */
function followLayout() {
  const demo = document.querySelector('.demo');
  if (!demo) return;
  let queued = false;
  const apply = () => {
    queued = false;
    const top = demo.getBoundingClientRect().top;
    const style = document.documentElement.style;
    // Where the column starts now (it grows as the header scrolls away:
    // the plots take the room), and where it starts unscrolled (the
    // drawing's height depends on that only, so it never rescales while
    // the page scrolls or a note appears).
    style.setProperty('--stage-top', `${Math.round(Math.max(8, top))}px`);
    style.setProperty('--stage-top0', `${Math.round(top + scrollY)}px`);
  };
  const queue = () => {
    if (!queued) requestAnimationFrame(apply);
    queued = true;
  };
  addEventListener('scroll', queue, { passive: true });
  addEventListener('resize', queue);
  apply();
}

/** The introduction's "More" on small and short screens (a11y.css shows the one-line lede there). */
function wireLede() {
  const lede = document.getElementById('lede');
  const more = document.getElementById('lede-more');
  more?.addEventListener('click', () => {
    const open = lede.dataset.more !== 'true';
    lede.dataset.more = String(open);
    more.setAttribute('aria-expanded', String(open));
    more.textContent = open ? 'Less' : 'More';
  });
}

/** The header's projector-mode switch: through the controller (projector=1 in the address). */
function wireProjector(controller) {
  const button = document.getElementById('projector');
  if (!button) return;
  const sync = () => button.setAttribute('aria-pressed', String(document.documentElement.hasAttribute('data-projector')));
  button.addEventListener('click', () => {
    controller.apply({ projector: !document.documentElement.hasAttribute('data-projector') });
    sync();
    writeAddress(controller.state());
  });
  sync();
}

async function start() {
  const loading = document.getElementById('loading');
  try {
    await loadModule();
    explainMethods(document.getElementById('modes-explained'));
    fillLimits(document);
    const note = document.getElementById('network-note');
    if (note) note.dataset.original = note.innerHTML;
    followLayout();
    if (spaceArmOf(location.search) || /[?&](robot|urdf)=/.test(location.search)) {
      await startSpace();
      return;
    }
    const { problems, ...settings } = readAddress(location.search);
    const controller = await mount(document, {
      ...settings,
      problems,
      problemsLabel: 'Ignored in the address',
      keyboard: document,
      onChange: writeAddress,
      onArm: describeArm,
      link: (s) => writeAddress(s),
    });
    const tour = mountTour(document, controller);
    wireProjector(controller);
    window.demo = {
      state: () => controller.state(),
      worldToClient: (x, y) => controller.worldToClient(x, y),
      runUntil: (t) => controller.runUntil(t),
      bench: (options) => bench(options),
      atlas: (options) => controller.atlas(options),
      useNetworks: (name) => controller.useNetworks(name),
      atlasResult: () => controller.atlasResult(),
      setArm: (arm) => controller.playground.setArm(arm),
      addObstacle: (x, y, r) => controller.playground.addObstacle(x, y, r),
      removeObstacle: (i) => controller.playground.removeObstacle(i),
      obstacles: () => controller.playground.obstacles(),
      train: (options) => controller.playground.train(options),
      lastTraining: () => controller.playground.lastTraining(),
      exportWeights: () => controller.playground.exportWeights(),
      simulate: (options) => controller.playground.simulate(options),
      methods: () => structuredClone(methods()),
      build: moduleBuild(),
      wasmMemoryBytes: () => moduleMemoryBytes(),
      controller,
      tour,
      files: () => controller.files(),
      readyMs: performance.now(),
    };
    document.body.dataset.ready = 'true';
  } catch (e) {
    loading.hidden = false;
    loading.classList.add('failed');
    for (const c of document.querySelectorAll('aside button, aside input, aside select')) c.disabled = true;
    document.getElementById('loading-text').textContent =
      `The simulation could not start: ${describe(e)}. ` + 'It needs a current browser with WebAssembly, served over http (make demo).';
    console.warn(e);
  }
}

/** The prose that describes the arm, for an arm in space (`n` joints). */
function describeSpaceArm(preset, n) {
  const lede = document.getElementById('lede-text');
  if (lede) lede.textContent = `The ${preset.label} moves its hand along a straight line past spheres: the hand's position takes three of its ${word(n)} joints' freedoms, and the planner spends the ${word(n - 3)} spare ones keeping its links clear. Orbit the view, drag the target or a sphere, switch methods.`;
  const see = document.getElementById('what-you-see');
  if (see) see.textContent = `The ${preset.label} (${preset.source}) drawn in 3-D: its links as capsules of the radius the clearance is measured to, the spheres, their shadows on the floor's 0.1 m grid. The hand follows the dashed line to the target at constant speed over the run; its orientation is left free.`;
  for (const el of document.querySelectorAll('[data-arm="links"]')) el.textContent = word(n);
}

/** The page with an arm in space (arm=panda, arm=iiwa14): space-demo.js on the same stage. */
async function startSpace() {
  const { problems, ...settings } = readSpaceAddress(location.search);
  // Fetched only here: the planar page never loads the drawing in space
  // and its panels (about 13 KB gzipped; docs/web.md, "Bytes on the wire").
  const { mountSpace } = await import('./space-demo.js');
  // A robot of the user's (robot=HASH): read from this browser's storage by
  // the workers' module; where it cannot be, the first shipped arm, and why.
  // A robot at an address (urdf=URL, with base and tip) is fetched, kept and opened the same way.
  let robot = null;
  const q = new URLSearchParams(location.search);
  const key = q.has('urdf') ? 'urdf' : 'robot';
  if (q.has(key)) {
    const { openStored, openUrl } = await import('./robot-open.js');
    try {
      const hash = key === 'urdf' ? (await openUrl(q.get('urdf'), { base: q.get('base') ?? undefined, tip: q.get('tip') ?? undefined })).hash : q.get('robot');
      robot = await openStored(hash);
    } catch (e) {
      problems.push(`${key}: ${describe(e)}`);
      settings.arm = spacePresets()[0].key;
    }
  }
  const controller = await mountSpace(document, {
    ...settings,
    robot,
    problems,
    problemsLabel: 'Ignored in the address',
    keyboard: document,
    onChange: (s, preset) => writeSpaceAddress(s, preset),
  });
  const preset = controller.preset;
  describeSpaceArm(preset, controller.state().dof);
  const arms = document.getElementById('arm-preset');
  if (arms) {
    // The designer offers every preset; another arm opens its own page.
    arms.replaceChildren();
    const plane = document.createElement('optgroup');
    plane.label = 'In the plane';
    for (const p of limits().arm_presets) plane.append(new Option(p.label, p.key));
    const space = document.createElement('optgroup');
    space.label = 'In space';
    for (const p of spacePresets()) space.append(new Option(p.label, p.key));
    arms.append(plane, space);
    if (robot) arms.append(new Option(`${preset.label} (your URDF)`, preset.key));
    arms.value = preset.key;
    arms.addEventListener('change', () => (location.search = `?arm=${arms.value}`));
    const lim = document.getElementById('arm-limits');
    const rates = document.getElementById('arm-rates');
    if (lim) Object.assign(lim, { value: formatJointLimits(Float64Array.from(preset.joint_limits.flat())), readOnly: true });
    if (rates) Object.assign(rates, { value: preset.rate_limits ? formatRateLimits(Float64Array.from(preset.rate_limits)) : '', readOnly: true });
    const source = document.createElement('p');
    source.className = 'hint';
    source.id = 'space-arm-source';
    source.textContent = `${preset.label}: ${preset.source}`;
    arms.closest('.row, p, div')?.after(source);
    if (robot) {
      // What the reader made of the robot: its chain, joints and limits, volumes, warnings.
      const { describeRobot } = await import('./robot-open.js');
      const made = document.createElement('ul');
      made.id = 'robot-read';
      made.className = 'hint';
      const drawn = controller.view3d.robotDrawn;
      const shown = !drawn ? [] : [`Drawn: ${drawn.drawn} visual${drawn.drawn === 1 ? '' : 's'} from the URDF${drawn.missing.length ? `; mesh files not chosen, so not drawn: ${drawn.missing.join(', ')}` : ''}${drawn.drawn ? ' ("Collision volumes" shows the capsules)' : ': the collision capsules are drawn'}.`];
      for (const line of [...describeRobot(robot.read), ...shown]) made.append(Object.assign(document.createElement('li'), { textContent: line }));
      source.after(made);
    }
  }
  writeSpaceAddress(controller.state(), preset);
  window.demo = {
    state: () => controller.state(),
    worldToClient: (x, y, z) => controller.worldToClient(x, y, z),
    runUntil: (t) => controller.runUntil(t),
    bench: (options) => bench(options),
    compare: () => controller.compare(),
    simulate: (options) => controller.simulate(options),
    train: (options) => controller.train(options),
    runFile: () => controller.runFile(),
    snapshot: () => controller.snapshot(),
    atlas: (options) => controller.atlas(options),
    spaceAtlas: (options) => spaceAtlas(options),
    networks: () => controller.networks(),
    methods: () => structuredClone(methods()),
    build: moduleBuild(),
    wasmMemoryBytes: () => moduleMemoryBytes(),
    controller,
    readyMs: performance.now(),
  };
  document.body.dataset.ready = 'true';
}

/** "Open robot…" and "Open folder…" (robot-open.js, imported when first used): a .urdf with its meshes, a folder or a .zip opens the page in space on it. */
function wireOpenRobot() {
  for (const [buttonId, inputId] of [['open-robot', 'robot-files'], ['open-robot-folder', 'robot-folder']]) {
    const button = document.getElementById(buttonId);
    const input = document.getElementById(inputId);
    if (!button || !input) continue;
    button.addEventListener('click', () => input.click());
    input.addEventListener('change', async () => {
      if (!input.files?.length) return;
      const { openFiles } = await import('./robot-open.js');
      const { messenger } = await import('./messages.js');
      const { show } = messenger(document);
      button.disabled = true;
      show('Reading the robot…', 'info', false, button);
      try {
        const link = (id) => document.getElementById(id)?.value.trim() || undefined;
        const { hash } = await openFiles(input.files, { base: link('robot-base'), tip: link('robot-tip') });
        location.search = `?robot=${hash}`;
      } catch (e) {
        show(`The robot could not be opened: ${describe(e)}`, 'error', true, button);
      } finally {
        button.disabled = false;
        input.value = '';
      }
    });
  }
}

if (isEmbedded()) document.documentElement.dataset.embed = 'true';
wireOpenRobot();
wireLede();
start();
mountBenchPanel(document);
