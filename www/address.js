// The page's address: what `?task=2&mode=case3&lambda=4&target=…&obstacle=…
// &obstacles=…&arm=…&feedback=1&networks=reach` asks for, and the state written back into
// it. The arm and obstacle syntax is the module's (parseArm, parseObstacles,
// formatArm: the command line's too). Every parameter that does not parse
// is reported once the page runs (with the core's refusals of those that
// parse but make no sense), never dropped silently; the page then starts
// from its defaults for it.

import { parseArm, parseObstacles, formatArm, limits, methods, defaultMethod, networkSets, params as moduleParams } from './module.js';
import { formatObstacles } from './arm-designer.js';

/** A number from text: blank is not zero (as `Number('')` is). */
const number = (x) => (x.trim() === '' ? NaN : Number(x));
/** Text a message quotes, cut to 40 characters (an address can be megabytes long). */
const clip = (text) => (String(text).length > 40 ? `${String(text).slice(0, 40)}…` : String(text));

/**
 * The `mount()` options an address asks for (after loadModule): task,
 * mode (the module's defaultMethod() where it names none), lambda,
 * feedback, target, obstacle, obstacles (flat), arm, and `problems`: what
 * did not parse, each as `name: why`.
 */
export function readAddress(search) {
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
  return {
    task:
      parsed('task', (v) => {
        if (v !== '1' && v !== '2') throw new Error(`the paper has tasks 1 and 2, got '${clip(v)}'`);
        return Number(v);
      }) ?? 1,
    mode:
      parsed('mode', (v) => {
        if (!names.includes(v)) throw new Error(`unknown mode '${clip(v)}': use ${names.join(', ')}`);
        return v;
      }) ?? defaultMethod(),
    lambda: num('lambda'),
    feedback: num('feedback'),
    target: pair('target'),
    obstacle: pair('obstacle'),
    obstacles: parsed('obstacles', parseObstacles),
    arm: parsed('arm', parseArm),
    // The methods' other parameters (refine, influence, ...) by their names.
    params: Object.fromEntries(
      moduleParams()
        .filter((p) => p.name !== 'lambda' && params.has(p.name))
        .map((p) => [p.name, num(p.name)])
        .filter(([, v]) => v !== undefined),
    ),
    networks: parsed('networks', (v) => {
      const sets = networkSets().map((s) => s.name);
      if (!sets.includes(v)) throw new Error(`unknown network set '${clip(v)}': use ${sets.join(' or ')}`);
      return v;
    }),
    problems,
  };
}

/**
 * Writes the state into the address (history.replaceState): the task, the
 * method, λ, the target; the arm where it is not the page's first (the
 * paper's, the first of the core's presets); the obstacles as a list where
 * there are several or one of another radius than the default, else the one
 * obstacle's centre; the drift gain where it is on.
 */
export function writeAddress(s) {
  const q = new URLSearchParams();
  q.set('task', String(s.task));
  q.set('mode', s.mode);
  q.set('lambda', String(s.lambda));
  q.set('target', s.target.map((v) => v.toFixed(3)).join(','));
  const { arm_presets: presets, default_radius: radius } = limits();
  const arm = formatArm(s.arm.post, s.arm.links);
  if (arm !== formatArm(presets[0].post, presets[0].links)) q.set('arm', arm);
  if (s.obstacles.length !== 1 || s.obstacles[0].radius !== radius) {
    q.set('obstacles', formatObstacles(s.obstacles));
  } else if (s.obstacle) {
    q.set('obstacle', s.obstacle.map((v) => v.toFixed(3)).join(','));
  }
  if (s.feedback > 0) q.set('feedback', String(s.feedback));
  if (s.network_set && s.network_set !== 'paper') q.set('networks', s.network_set);
  for (const p of moduleParams()) {
    const v = s.params[p.name];
    if (p.name !== 'lambda' && v !== undefined && v !== p.default) q.set(p.name, String(v));
  }
  history.replaceState(null, '', `${location.pathname}?${q}`);
}
