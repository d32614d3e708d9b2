// "Try this": a tour for class in six steps, each one click ("Show me")
// that sets the scene through the page's own controls, and two sentences;
// the last one opens an arm in space (arm=space: the first preset, the
// Panda) on the same page.
// A card at the top of the controls, never over the drawing: it can be
// skipped or closed at any step, and the page keeps working meanwhile.
// The step's outcome is read from the run itself, not written here.

import { limits, methods, paperMethods } from './module.js';
import { metres } from './format.js';

/** Step 4's obstacle: left of the arm, outside the box the v network saw
 * obstacles in (0.3-0.8 m each way). There, in Task 1, the arm without
 * avoidance collides and the numerical route keeps 0.28 m clear
 * (`redundant-ik simulate --task 1 --damping --obstacle -0.2,0.85`). */
const OUTSIDE = [-0.2, 0.85];

/** The outcome of the run in `s`, once it has ended. */
function outcome(s) {
  if (!s.ended) return 'Running…';
  const hit = s.collided ? 'a link hit the obstacle' : `no collision, smallest distance ${metres(s.min_distance)}`;
  return `This run: ${hit}; the hand ended ${metres(s.final_error)} from the target.${s.in_range ? '' : ' The networks are outside their trained range.'}`;
}

/**
 * Wires `#tour-open` and the tour card (`#tour`, `#tour-title`,
 * `#tour-count`, `#tour-text`, `#tour-result`, `#tour-show`, `#tour-back`,
 * `#tour-next`, `#tour-close`) under `root` to the page's `controller`.
 * Returns `{ open(), step() }`.
 */
export function mountTour(root, controller) {
  const $ = (id) => root.querySelector('#' + id);
  const el = {
    open: $('tour-open'),
    card: $('tour'),
    title: $('tour-title'),
    count: $('tour-count'),
    text: $('tour-text'),
    result: $('tour-result'),
    show: $('tour-show'),
    back: $('tour-back'),
    next: $('tour-next'),
    close: $('tour-close'),
  };
  if (!el.card) return null;
  const demo = controller.demo;

  // Through the page's controls, as a user would.
  const pick = (method) => {
    const select = $('mode');
    select.value = method;
    select.dispatchEvent(new Event('change'));
  };
  const paperArm = () => {
    if (!demo.state().paper_arm) controller.playground.setArm(limits().arm_presets[0]);
  };
  const task1 = (method) => {
    paperArm();
    pick(method);
    $('task1').click();
  };

  // The paper's methods the tour shows, by what they are (the module names
  // them): the one without avoidance, the exact route, both networks.
  const papers = paperMethods().map((name) => methods().find((m) => m.name === name));
  const BARE = papers.find((m) => !m.avoids).name;
  const EXACT = papers.find((m) => m.avoids && !m.networks.phi && !m.networks.v).name;
  const LEARNED = papers.find((m) => m.networks.phi && m.networks.v).name;

  const STEPS = [
    {
      title: 'Without avoidance the arm hits the obstacle',
      text: 'Task 1 of the paper with v = 0: the hand follows the straight line exactly, and the links sweep through the red disc. Watch the collision readout turn red.',
      show: () => task1(BARE),
    },
    {
      title: 'The numerical route goes around it',
      text: 'The null-space vector v bends the elbow away from the obstacle while the hand follows the same line. The links keep clear and the hand still reaches the target.',
      show: () => task1(EXACT),
    },
    {
      title: 'Case 3 matches it inside the trained box',
      text: 'Both networks replace the exact Φ and v; the dashed pink arm is the numerical route, for comparison. The obstacle sits inside the dashed box where the v network saw obstacles in training, and the two arms agree.',
      show: () => task1(LEARNED),
    },
    {
      title: 'Move the obstacle outside the box',
      text: 'The obstacle now sits left of the arm, outside the box the v network was trained on, so the networks extrapolate and the range warning says so. Compare the network arm with the numerical ghost.',
      show: () => {
        task1(LEARNED);
        demo.setObstacle(OUTSIDE[0], OUTSIDE[1]);
        demo.runTask();
      },
    },
    {
      title: 'The atlas shows why',
      text: 'The atlas runs the task with the obstacle on every cell of a grid, for the numerical route and Case 3. Green cells succeed; Case 3 fails mostly outside the dashed box, where its v network never saw an obstacle.',
      show: async () => {
        task1(LEARNED);
        const panel = $('atlas-panel');
        panel.open = true;
        for (const box of panel.querySelectorAll('#atlas-modes input')) box.checked = [EXACT, LEARNED].includes(box.value);
        $('atlas-n').value = '21';
        // The map is drawn under the arm; the tour card stays in view.
        await controller.atlas({});
      },
      result: () => {
        const a = controller.atlasResult();
        const s = a?.summary?.case3;
        if (!s) return '';
        const pct = (r) => (r?.rate === null || r?.rate === undefined ? '–' : `${Math.round(100 * r.rate)}%`);
        return `This atlas (${controller.atlasDescription()}): Case 3 succeeds in ${pct(s.inside_trained_region)} of the cells inside the box and ${pct(s.outside_trained_region)} outside it (the numerical route: ${pct(a.summary.numerical?.avoidable)} overall).`;
      },
    },
    {
      title: 'Beyond the plane: a real arm in space',
      text: "The same question on a seven-joint Franka Panda, whose forearm passes a sphere: in 3-D the paper's criterion at its gain still lets a link hit it. Show me opens it in the numerical route; orbit the view by dragging, then pick the QP with velocity dampers in the menu and watch it stay clear.",
      show: () => {
        location.search = `?arm=space&method=${EXACT}`;
        return new Promise(() => {});
      },
    },
  ];

  let k = 0;
  let shown = false; // whether this step's scene is set
  let timer = 0;

  function render() {
    const step = STEPS[k];
    el.title.textContent = `${k + 1}. ${step.title}`;
    el.count.textContent = `${k + 1} of ${STEPS.length}`;
    el.text.textContent = step.text;
    el.result.textContent = '';
    el.back.disabled = k === 0;
    el.next.textContent = k + 1 === STEPS.length ? 'Done' : 'Next';
    el.card.dataset.step = String(k + 1);
    el.card.dataset.shown = String(shown);
  }

  /** Follows the step's run until it ends, then says how it went. */
  function follow() {
    clearTimeout(timer);
    const step = STEPS[k];
    const tick = () => {
      if (el.card.hidden) return;
      const s = demo.state();
      el.result.textContent = step.result ? step.result() : outcome(s);
      if (!step.result && !s.ended) timer = setTimeout(tick, 250);
    };
    tick();
  }

  el.show.addEventListener('click', async () => {
    el.show.disabled = true;
    el.result.textContent = 'Setting the scene…';
    try {
      await STEPS[k].show();
      shown = true;
      el.card.dataset.shown = 'true';
      follow();
    } catch (e) {
      el.result.textContent = `Could not set the scene: ${e.message ?? e}`;
    } finally {
      el.show.disabled = false;
    }
  });
  const go = (to) => {
    clearTimeout(timer);
    if (to >= STEPS.length) return close();
    k = Math.max(0, to);
    shown = false;
    render();
  };
  el.next.addEventListener('click', () => go(k + 1));
  el.back.addEventListener('click', () => go(k - 1));
  function close() {
    clearTimeout(timer);
    el.card.hidden = true;
    el.card.dataset.done = String(k + 1 === STEPS.length);
  }
  el.close.addEventListener('click', close);
  function open() {
    k = 0;
    shown = false;
    el.card.hidden = false;
    delete el.card.dataset.done;
    render();
    el.card.scrollIntoView({ block: 'nearest' });
  }
  el.open?.addEventListener('click', open);
  return { open, step: () => k + 1 };
}
