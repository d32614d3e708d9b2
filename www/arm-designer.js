// The arm designer and the obstacle list: the "Arm and obstacles" panel.
// Presets and bounds come from the module's limits(); the core checks every
// arm, its joint and rate limits (their syntax too: parseJointLimits,
// parseRateLimits, Demo.setArmLimits) and obstacle (Demo.setArm,
// addObstacle, setObstacles) and this file shows its refusals.

import { applied, follow } from './place-fields.js';
import { coordinate } from './format.js';
import { flatBalls } from './simulate-options.js';
import { limits, formatArm, parseJointLimits, formatJointLimits, parseRateLimits, formatRateLimits } from './module.js';

/**
 * `[[x, y, r?], ...]` (or `{ x, y, r }` each) flat as the module takes it:
 * `[x0, y0, r0, ...]`, each missing radius the core's default. A typed
 * array is taken as already flat (parseObstacles() returns one).
 */
export function flatObstacles(list) {
  return flatBalls(list, 2, limits().default_radius);
}

/** `x,y,r;x,y,r` of the obstacles in the state (what parseObstacles reads). */
export function formatObstacles(obstacles) {
  const exact = (v) => String(Number(coordinate(v)));
  return obstacles.map((o) => [...o.centre, o.radius].map(exact).join(',')).join(';');
}

const armText = (arm) => formatArm(arm.post, arm.links);
/** The arm's joint limits as `LO:HI,...`, '' when it has none. */
const limitsText = (arm) => (arm.joint_limits ? formatJointLimits(Float64Array.from(arm.joint_limits.flat())) : '');
/** The arm's rate limits as `R,...`, '' when it has none. */
const ratesText = (arm) => (arm.rate_limits ? formatRateLimits(Float64Array.from(arm.rate_limits)) : '');

/** A number field: `min`, `max`, `step` and `value`, named for screen readers by `label`. */
function numberInput(min, max, step, value, label) {
  const input = document.createElement('input');
  input.type = 'number';
  Object.assign(input, { min: String(min), max: String(max), step: String(step), value: String(value) });
  input.setAttribute('aria-label', label);
  return input;
}

/**
 * Wires the elements of `root` that exist (`#arm-preset`, `#arm-post`,
 * `#arm-links`, `#arm-limits`, `#arm-rates`, `#link-add`, `#link-remove`, `#arm-apply`,
 * `#obstacle-add`, `#obstacle-remove`, `#obstacle-list`). Hooks:
 * `setArm(arm)` (the playground's, which also restores kept networks),
 * `attempt(fn)`, `show(text, kind)`, `changed()`. Returns `{ addObstacle,
 * removeObstacle, wantsClick, click, check }`.
 */
export function mountArmDesigner(root, demo, { setArm, attempt, show, changed }) {
  const $ = (id) => root.querySelector('#' + id);
  const el = {
    preset: $('arm-preset'),
    post: $('arm-post'),
    links: $('arm-links'),
    limits: $('arm-limits'),
    rates: $('arm-rates'),
    linkAdd: $('link-add'),
    linkRemove: $('link-remove'),
    apply: $('arm-apply'),
    obstacleAdd: $('obstacle-add'),
    obstacleRemove: $('obstacle-remove'),
    obstacleList: $('obstacle-list'),
  };
  const { arm_presets: presets, min_links: fewest, max_links: most, max_obstacles: mostObstacles } = limits();

  // ---- the arm ---------------------------------------------------------
  if (el.preset && !el.preset.options.length) {
    for (const p of presets) el.preset.add(new Option(p.label, p.key));
    el.preset.add(new Option('Custom', 'custom'));
    // The arms in space open the page's 3-D stage: arm=space (the first of
    // them) loads the build that holds them, which lists them all.
    const space = document.createElement('optgroup');
    space.label = 'In space';
    space.append(new Option('Arms in space (3-D)…', 'space'));
    el.preset.append(space);
  }

  function linkInputs(links) {
    if (!el.links) return;
    el.links.replaceChildren(
      ...links.map((l, i) => {
        const label = document.createElement('label');
        const input = numberInput(0.05, 3, 0.05, l, `Length of link ${i + 1} (m)`);
        input.dataset.link = String(i);
        label.append(`L${i + 1} `, input);
        return label;
      }),
    );
  }

  function formArm() {
    const post = Number(el.post?.value);
    const links = [...(el.links?.querySelectorAll('input') ?? [])].map((i) => Number(i.value));
    return { post, links };
  }

  function syncForm(arm) {
    if (el.post && document.activeElement !== el.post) el.post.value = String(arm.post);
    const shown = formArm().links;
    if (shown.length !== arm.links.length || shown.some((l, i) => l !== arm.links[i])) linkInputs(arm.links);
    if (el.preset) el.preset.value = presets.find((p) => armText(p) === armText(arm))?.key ?? 'custom';
    if (el.limits && document.activeElement !== el.limits) el.limits.value = limitsText(arm);
    if (el.rates && document.activeElement !== el.rates) el.rates.value = ratesText(arm);
  }

  // The limits' fields, in the core's syntax (blank: unlimited), applied
  // together to the arm as it is; a refusal shows next to the field.
  const parsedField = (field, parse) => (field && field.value.trim() !== '' ? parse(field.value) : undefined);
  const applyLimits = (field) => {
    const ok = attempt(() => demo.setArmLimits(parsedField(el.limits, parseJointLimits), parsedField(el.rates, parseRateLimits)), 'error', field);
    if (ok) changed();
  };
  el.limits?.addEventListener('change', () => applyLimits(el.limits));
  el.rates?.addEventListener('change', () => applyLimits(el.rates));

  el.preset?.addEventListener('change', () => {
    if (el.preset.value === 'space') {
      location.search = '?arm=space';
      return;
    }
    const p = presets.find((p) => p.key === el.preset.value);
    if (p) attempt(() => setArm(p), 'error', el.preset);
  });
  // Other lengths keep the arm's limits (the same joints).
  const applyForm = () => {
    const { joint_limits, rate_limits } = demo.state().arm;
    attempt(() => setArm({ ...formArm(), joint_limits, rate_limits }), 'error', el.apply);
  };
  el.apply?.addEventListener('click', applyForm);
  el.links?.addEventListener('change', applyForm);
  el.post?.addEventListener('change', applyForm);
  el.linkAdd?.addEventListener('click', () => {
    const a = formArm();
    if (a.links.length >= most) return show(`At most ${most} links.`, 'warn', false, el.linkAdd);
    attempt(() => setArm({ post: a.post, links: [...a.links, a.links[a.links.length - 1] ?? 0.4] }), 'error', el.linkAdd);
  });
  el.linkRemove?.addEventListener('click', () => {
    const a = formArm();
    if (a.links.length <= fewest) return show(`At least ${fewest} links.`, 'warn', false, el.linkRemove);
    attempt(() => setArm({ post: a.post, links: a.links.slice(0, -1) }), 'error', el.linkRemove);
  });

  // ---- obstacles -------------------------------------------------------
  let adding = false;
  function setAdding(on) {
    adding = on;
    if (el.obstacleAdd) {
      el.obstacleAdd.setAttribute('aria-pressed', String(on));
      el.obstacleAdd.textContent = on ? 'Click on the drawing…' : 'Add obstacle';
    }
  }
  el.obstacleAdd?.addEventListener('click', (e) => {
    if (demo.state().obstacles.length >= mostObstacles) return show(`At most ${mostObstacles} obstacles.`, 'warn', false, el.obstacleAdd);
    // From the keyboard (Enter or Space: a click of detail 0) there is no
    // pointer to place it with: at the middle of the view, selected for the
    // arrows, as the drawing's `a` key does (issue 27).
    if (e.detail === 0 && !adding) {
      if (attempt(() => demo.key('a', false), 'error', el.obstacleAdd)) changed();
      return;
    }
    setAdding(!adding);
  });
  // Escape leaves the placing mode.
  root.addEventListener?.('keydown', (e) => {
    if (adding && e.key === 'Escape') {
      e.preventDefault();
      setAdding(false);
    }
  });
  el.obstacleRemove?.addEventListener('click', () => {
    const n = demo.state().obstacles.length;
    if (n === 0) return show('There is no obstacle to remove.', 'warn', false, el.obstacleRemove);
    attempt(() => removeObstacle(n - 1));
  });

  function addObstacle(x, y, r) {
    const i = demo.addObstacle(Number(x), Number(y), r === undefined ? undefined : Number(r));
    changed();
    return i;
  }
  function removeObstacle(i) {
    demo.removeObstacle(Number(i));
    changed();
  }

  /**
   * Obstacle `i`'s entry: its centre's x and y and its radius as number
   * fields (placement without dragging, WCAG 2.5.7; kept in step with
   * drags by `syncObstacles` except while edited), a remove button.
   */
  function obstacleItem(i) {
    const li = document.createElement('li');
    li.dataset.index = String(i);
    const name = document.createElement('span');
    name.textContent = `#${i + 1}`;
    const x = numberInput(-10, 10, 0.01, 0, `Centre x of obstacle ${i + 1} (m)`);
    const y = numberInput(-10, 10, 0.01, 0, `Centre y of obstacle ${i + 1} (m)`);
    const place = (field) => {
      const [vx, vy] = [Number(x.value), Number(y.value)];
      if (x.value.trim() === '' || y.value.trim() === '') return show(`Obstacle ${i + 1} needs a centre x and y in metres.`, 'error', false, field);
      if (attempt(() => demo.moveObstacle(i, vx, vy), 'error', field)) {
        applied(x, y);
        changed();
      }
    };
    x.addEventListener('change', () => place(x));
    y.addEventListener('change', () => place(y));
    const r = numberInput(0.01, 1, 0.01, 0.05, `Radius of obstacle ${i + 1} (m)`);
    r.addEventListener('change', () => {
      if (attempt(() => demo.setObstacleRadius(i, Number(r.value)), 'error', r)) changed();
    });
    const del = document.createElement('button');
    del.type = 'button';
    del.textContent = '×';
    del.title = `Remove obstacle ${i + 1}`;
    del.setAttribute('aria-label', `Remove obstacle ${i + 1}`);
    del.addEventListener('click', () => attempt(() => removeObstacle(i)));
    li.append(name, ' x ', x, ' y ', y, ' r ', r, ' ', del);
    return { li, x, y, r, centre: '', radius: NaN };
  }

  // The entries, rebuilt only when the obstacles come or go; their text
  // and radius follow the state in place (a drag changes no element).
  let items = [];
  let nearestShown = null;
  function syncObstacles(s) {
    if (!el.obstacleList) return;
    if (items.length !== s.obstacles.length) {
      items = s.obstacles.map((_, i) => obstacleItem(i));
      el.obstacleList.replaceChildren(...items.map((it) => it.li));
      nearestShown = null;
    }
    s.obstacles.forEach((o, i) => {
      const it = items[i];
      const centre = `${o.centre[0]},${o.centre[1]}`;
      if (it.centre !== centre) {
        it.centre = centre;
        follow(it.x, o.centre[0]);
        follow(it.y, o.centre[1]);
      }
      if (it.radius !== o.radius && document.activeElement !== it.r) it.r.value = String((it.radius = o.radius));
    });
    if (s.nearest !== nearestShown) {
      items.forEach((it, i) => it.li.classList.toggle('nearest', s.nearest === i));
      nearestShown = s.nearest;
    }
  }

  // ---- the loop --------------------------------------------------------
  let armShown = '';
  /** Follows the state (per frame, cheap): the form and the list. */
  function check(s) {
    const { joint_limits: jl, rate_limits: rl } = s.arm;
    const key = jl || rl ? `${s.arm_text}|${jl ?? ''}|${rl ?? ''}` : s.arm_text;
    if (key !== armShown) {
      armShown = key;
      syncForm(s.arm);
    }
    syncObstacles(s);
  }

  return {
    addObstacle,
    removeObstacle,
    syncForm,
    check,
    wantsClick: () => adding,
    /** A click on the drawing while adding: an obstacle there. */
    click(x, y) {
      setAdding(false);
      const i = demo.addObstacleAt(x, y);
      changed();
      return i;
    },
  };
}
