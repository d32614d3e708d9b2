// The parameters of the method in use, as sliders: `lambda` in its own
// field (`#lambda`, which every page and embed has), the others of the
// method's list (the influence distance of the methods beyond the paper,
// their stop distance, gains, slack weight, rate limit) in `#method-params`.
// Labels, units, bounds and slider spans come from the module (`params()`);
// which ones show, from the method's `params` (`methods()`). The damping
// `delta` has no slider (the page's damping switch schedules it).

import { params, method } from './module.js';

/**
 * Parameters the page gives no slider here: lambda has its own field, the
 * damping switch schedules delta, and the self-collision dampers' own
 * gains act only where self-collision is on, which the page cannot switch
 * on yet (the command line's --self-collision).
 */
const ELSEWHERE = ['lambda', 'delta', 'self_influence', 'self_stop_distance', 'self_damper_gain'];

/** A number as a slider's readout shows it: as many decimals as its step. */
function shown(value, step) {
  const decimals = Math.max(0, Math.min(6, -Math.floor(Math.log10(step))));
  return Number(value).toFixed(decimals);
}

/**
 * Wires `#lambda` and `#method-params` under `root` to `demo`; returns
 * `sync(state)` for the animation loop. `attempt(fn)` shows a refusal;
 * `changed()` after a change the user made.
 */
export function mountMethodParams(root, demo, { attempt, changed }) {
  const $ = (id) => root.querySelector('#' + id);
  const lambda = $('lambda');
  const lambdaValue = $('lambda-value');
  const box = $('method-params');
  const info = Object.fromEntries(params().map((p) => [p.name, p]));
  if (lambda) {
    const [min, max, step] = info.lambda.slider;
    Object.assign(lambda, { min: String(min), max: String(max), step: String(step) });
    lambda.addEventListener('input', () => {
      if (attempt(() => demo.setParam('lambda', Number(lambda.value)), 'error', lambda)) changed();
    });
  }

  let shownFor = null; // the method whose sliders are built
  const sliders = new Map(); // name -> { input, output }

  function build(name) {
    shownFor = name;
    sliders.clear();
    if (!box) return;
    const m = method(name);
    const names = (m?.params ?? []).filter((p) => !ELSEWHERE.includes(p));
    box.replaceChildren(
      ...names.map((p) => {
        const { label, unit, slider, scale } = info[p];
        const log = scale === 'log';
        const [min, max, step] = slider;
        const field = document.createElement('div');
        field.className = 'field';
        field.dataset.param = p;
        const id = `param-${p}`;
        const l = document.createElement('label');
        l.htmlFor = id;
        const output = document.createElement('output');
        output.htmlFor = id;
        l.append(`${label}${unit ? ` (${unit})` : ''} `, output);
        const input = document.createElement('input');
        Object.assign(input, { id, type: 'range', min: String(min), max: String(max), step: String(step) });
        // A weight that spans orders of magnitude moves in powers of ten.
        const toValue = (x) => (log ? 10 ** x : x);
        const toSlider = (v) => (log ? Math.log10(v) : v);
        input.addEventListener('input', () => {
          if (attempt(() => demo.setParam(p, toValue(Number(input.value))), 'error', input)) changed();
        });
        sliders.set(p, { input, output, step: log ? 1 : step, toSlider });
        field.append(l, input);
        return field;
      }),
    );
    box.hidden = names.length === 0;
  }

  /** Per frame: the sliders of the method in use, at the values in force. */
  return function sync(s) {
    if (s.method !== shownFor) build(s.method);
    if (lambda && document.activeElement !== lambda && Number(lambda.value) !== s.lambda) {
      lambda.value = String(s.lambda);
    }
    if (lambdaValue) lambdaValue.textContent = shown(s.lambda, info.lambda.slider[2]);
    if (lambda) lambda.closest('.field')?.toggleAttribute('hidden', !s.reads.includes('lambda'));
    for (const [name, { input, output, step, toSlider }] of sliders) {
      const value = s.params[name];
      if (document.activeElement !== input && Number(input.value) !== toSlider(value)) input.value = String(toSlider(value));
      const text = value >= 1e4 ? value.toExponential(0) : shown(value, step);
      if (output.textContent !== text) output.textContent = text;
    }
  };
}
