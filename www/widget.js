// The demo as a notebook widget: an anywidget front-end module
// (https://anywidget.dev/en/afm/) whose view is a <redundant-ik-demo>.
// The scene is the model's traits, named as the element's attributes,
// which are the page's address keys (address.js's addressKeys(): task,
// method, lambda, target "x,y", obstacles, arm, ..., the methods'
// parameters by name), those of an arm in space (arm="panda", urdf, base,
// tip, orientation_weight, self_collision, view, ...) and autoplay, plots:
// each trait the model has is set as that attribute, and a change of it
// (`change:NAME`) sets it again; a change that moves the demo between the
// plane and space (arm, urdf) makes a new element, whose kind is read
// when it starts. The
// package's widget.js is this module bundled with the compat element
// (tools/bundle.mjs), so a notebook loads it as its one module text.

import { SPACE_ATTRIBUTES } from './redundant-ik-demo.js';
import { loadModule } from './module.js';
import { addressKeys } from './address.js';

/**
 * Trait `name`'s value as its attribute's text (null: no attribute). A
 * boolean is the address's 1 or 0 (floor, damping), autoplay's "false" to
 * start paused, plots' presence.
 */
function attribute(name, value) {
  if (value === undefined || value === null || value === '') return null;
  if (name === 'plots') return value ? '' : null;
  if (typeof value === 'boolean') return name === 'autoplay' ? String(value) : value ? '1' : '0';
  return Array.isArray(value) ? value.join(',') : String(value);
}

export default {
  async render({ model, el, signal }) {
    await loadModule({ space: false });
    const names = [...new Set([...addressKeys(), ...SPACE_ATTRIBUTES, 'autoplay', 'plots'])];
    const make = () => {
      const demo = document.createElement('redundant-ik-demo');
      for (const name of names) apply(demo, name);
      return demo;
    };
    const apply = (demo, name) => {
      const text = attribute(name, model.get(name));
      if (text === null) demo.removeAttribute(name);
      else demo.setAttribute(name, text);
    };
    let demo = make();
    const handlers = names.map((name) => [
      `change:${name}`,
      () => {
        // The element reads whether it shows the plane or space when it starts.
        if (name === 'arm' || name === 'urdf') {
          const next = make();
          demo.replaceWith(next);
          demo = next;
        } else apply(demo, name);
      },
    ]);
    for (const [event, handler] of handlers) model.on(event, handler);
    el.append(demo);
    const cleanup = () => {
      for (const [event, handler] of handlers) model.off(event, handler);
      demo.remove();
    };
    signal?.addEventListener('abort', cleanup, { once: true });
    return cleanup;
  },
};
