// The page's address, and the <redundant-ik-demo> element's attributes (the
// same keys, read by the same readAddress): what `?task=2&method=case3&lambda=4&target=…&obstacle=…
// &obstacles=…&arm=…&limits=…&rates=…&feedback=1&damping=0&weighting=wln&floor=1&theta0=…&tf=…&path=…&influence=…&networks=reach&precision=f32&projector=1` asks
// for, and the state written back into it (what "Copy link" copies). The arm, limits and obstacle syntax is the module's (parseArm, parseObstacles,
// formatArm, parseJointLimits, formatJointLimits, parseRateLimits,
// formatRateLimits: the command line's too). Every parameter that does not parse
// is reported once the page runs (with the core's refusals of those that
// parse but make no sense), never dropped silently; the page then starts
// from its defaults for it.

import { parseArm, parseObstacles, parseJointLimits, formatJointLimits, parseRateLimits, formatRateLimits, limits, methods, params as allParams, defaultMethod, networkSets, precisions, readPrecision } from './module.js';
import { formatObstacles } from './arm-designer.js';
import { coordinate } from './format.js';

/** A number from text: blank is not zero (as `Number('')` is). */
const number = (x) => (x.trim() === '' ? NaN : Number(x));
/** Text a message quotes, cut to 40 characters (an address can be megabytes long). */
const clip = (text) => (String(text).length > 40 ? `${String(text).slice(0, 40)}…` : String(text));

/** A coordinate in millimetres where that is exact up to noise, else in full (a dragged one). */
const exact = coordinate;

/** The parameters the address carries by name (λ has its own). */
const named = () => allParams().filter((p) => p.name !== 'lambda');

/** The keys readAddress reads besides the methods' parameters (the order is mount()'s). */
const KEYS = ['task', 'method', 'mode', 'lambda', 'feedback', 'target', 'obstacle', 'obstacles', 'arm', 'limits', 'rates', 'damping', 'weighting', 'floor', 'theta0', 'tf', 'path', 'networks', 'precision', 'projector'];

/**
 * Every key an address (or the element's attributes) may carry (after
 * loadModule): KEYS and the methods' parameters by name (params()); the
 * notebook widget's traits are named so too.
 */
export function addressKeys() {
  return [...KEYS, ...named().map((p) => p.name)];
}

/**
 * The `mount()` options an address asks for (after loadModule): task,
 * method (the module's defaultMethod() where it names none; `mode=`, the
 * older name, is read where there is no `method=`), lambda,
 * feedback, target, obstacle, obstacles (flat), arm, limits (the arm's
 * joint limits, flat [lo1, hi1, ...]), rates (its rate limits), damping,
 * weighting (a name of limits().joint_weightings), floor (bool), start
 * ({ theta0, tf }: a run's own start pose and final time), path (the
 * path's text, for the module to read), params (the
 * methods' parameters by name), networks (a shipped network set),
 * precision (the networks' arithmetic, a name of precisions()),
 * projector (bool: projector mode, larger text and higher contrast), and
 * `problems`: what did not parse, each as `name: why`.
 */
export function readAddress(search) {
  // A query string, or a URLSearchParams (the element's attributes as pairs).
  const params = new URLSearchParams(search);
  const problems = [];
  const parsed = (name, parse) => {
    const v = params.get(name);
    if (v === null || v === '') return undefined;
    try {
      return parse(v);
    } catch (e) {
      problems.push(`${name}: ${e.message}`);
      return undefined;
    }
  };
  const pair = (name) =>
    parsed(name, (v) => {
      const p = v.split(',').map(number);
      if (p.length !== 2 || !p.every(Number.isFinite)) throw new Error(`expected two numbers x,y, got '${clip(v)}'`);
      return p;
    });
  const num = (name) =>
    parsed(name, (v) => {
      const x = number(v);
      if (!Number.isFinite(x)) throw new Error(`expected a number, got '${clip(v)}'`);
      return x;
    });
  const names = methods().map((m) => m.name);
  const known = (v) => {
    if (!names.includes(v)) throw new Error(`unknown method '${clip(v)}': use ${names.join(', ')}`);
    return v;
  };
  const theta0 = parsed('theta0', (v) => {
    const a = v.split(',').map(number);
    if (!a.length || !a.every(Number.isFinite)) throw new Error(`expected joint angles a,b,c in radians, got '${clip(v)}'`);
    return a;
  });
  const tf = num('tf');
  const start = theta0 && tf !== undefined ? { theta0, tf } : undefined;
  if ((theta0 === undefined) !== (tf === undefined) && !problems.some((p) => /^(theta0|tf):/.test(p))) {
    problems.push('theta0: goes with tf (a run of its own needs both)');
  }
  const values = {};
  for (const p of named()) {
    const x = num(p.name);
    if (x !== undefined) values[p.name] = x;
  }
  return {
    task:
      parsed('task', (v) => {
        if (v !== '1' && v !== '2') throw new Error(`the paper has tasks 1 and 2, got '${clip(v)}'`);
        return Number(v);
      }) ?? 1,
    method: (params.get('method') ? parsed('method', known) : parsed('mode', known)) ?? defaultMethod(),
    lambda: num('lambda'),
    feedback: num('feedback'),
    target: pair('target'),
    obstacle: pair('obstacle'),
    obstacles: parsed('obstacles', parseObstacles),
    // A preset's name (its key in limits().arm_presets) gives the preset, its limits with it.
    arm: parsed('arm', (v) => limits().arm_presets.find((p) => p.key === v) ?? parseArm(v)),
    limits: parsed('limits', parseJointLimits),
    rates: parsed('rates', parseRateLimits),
    damping: parsed('damping', (v) => {
      if (v !== '0' && v !== '1') throw new Error(`expected 0 or 1, got '${clip(v)}'`);
      return v === '1';
    }),
    weighting: parsed('weighting', (v) => {
      const names = limits().joint_weightings.map(([name]) => name);
      if (!names.includes(v)) throw new Error(`unknown joint weighting '${clip(v)}': use ${names.join(' or ')}`);
      return v;
    }),
    floor: parsed('floor', (v) => {
      if (v !== '0' && v !== '1') throw new Error(`expected 0 or 1, got '${clip(v)}'`);
      return v === '1';
    }),
    start,
    // The path's text goes to the module's parser as it is (mount's setPath).
    path: params.get('path') || undefined,
    params: values,
    projector: parsed('projector', (v) => {
      if (v !== '0' && v !== '1') throw new Error(`expected 0 or 1, got '${clip(v)}'`);
      return v === '1';
    }),
    networks: parsed('networks', (v) => {
      const sets = networkSets().map((n) => n.name);
      if (!sets.includes(v)) throw new Error(`unknown network set '${clip(v)}': use ${sets.join(' or ')}`);
      return v;
    }),
    precision: parsed('precision', readPrecision),
    problems,
  };
}

/**
 * Writes the state into the address (history.replaceState): the task, the
 * method, λ, the target; the arm where it is not the page's first (the
 * paper's, the first of the core's presets); its joint and rate limits
 * where it has them (limits=, rates=); the obstacles as a list where
 * there are several or one of another radius than the default, else the one
 * obstacle's centre; the drift gain where it is on; the damping switch
 * where it is off; the joint weighting where it is not the first (none),
 * floor=1 where the floor and post are obstacles; the methods' parameters that differ from their
 * defaults; a shipped network set other than the paper's; the path where
 * it is not the line; and a run's own start pose and final time (a line dropped
 * from where the hand was), in full; embed=1 where the page is embedded
 * (isEmbedded), projector=1 where the page is in projector mode. Returns the address.
 */
export function writeAddress(s) {
  const q = sceneQuery(s);
  // The page in an iframe (embed=1) stays so.
  if (isEmbedded()) q.set('embed', '1');
  // Projector mode is the view's, not the scene's: kept in the address, not in the Embed snippets.
  if (document.documentElement.hasAttribute('data-projector')) q.set('projector', '1');
  history.replaceState(null, '', `${location.pathname}?${q}`);
  return location.href;
}

/**
 * The keys and values of the scene in state `s`, as writeAddress writes
 * them (without embed=): the address's query, and the Embed snippets'
 * attributes (takeaway.js).
 */
export function sceneQuery(s) {
  const q = new URLSearchParams();
  q.set('task', String(s.task));
  q.set('method', s.method);
  q.set('lambda', String(s.lambda));
  q.set('target', s.target.map(exact).join(','));
  const { default_radius: radius } = limits();
  if (!s.paper_arm) q.set('arm', s.arm_text);
  if (s.arm.joint_limits) q.set('limits', formatJointLimits(Float64Array.from(s.arm.joint_limits.flat())));
  if (s.arm.rate_limits) q.set('rates', formatRateLimits(Float64Array.from(s.arm.rate_limits)));
  if (s.obstacles.length !== 1 || s.obstacles[0].radius !== radius) {
    q.set('obstacles', formatObstacles(s.obstacles));
  } else if (s.obstacle) {
    q.set('obstacle', s.obstacle.map(exact).join(','));
  }
  if (s.feedback > 0) q.set('feedback', String(s.feedback));
  if (!s.damping) q.set('damping', '0');
  if (s.weighting !== limits().joint_weightings[0][0]) q.set('weighting', s.weighting);
  if (s.floor) q.set('floor', '1');
  if (s.network_set && s.network_set !== networkSets()[0].name) q.set('networks', s.network_set);
  if (s.precision !== precisions()[0].name) q.set('precision', s.precision);
  for (const p of named()) {
    if (s.params[p.name] !== undefined && s.params[p.name] !== p.default) q.set(p.name, String(s.params[p.name]));
  }
  if (s.path) q.set('path', s.path);
  if (s.own_start) {
    q.set('theta0', s.theta0.map(String).join(','));
    q.set('tf', String(s.tf));
  }
  return q;
}

/** Whether the page's address asks for the embedded view (`embed=1`: the stage and the essential controls, for an iframe). */
export function isEmbedded() {
  return new URLSearchParams(location.search).get('embed') === '1';
}
