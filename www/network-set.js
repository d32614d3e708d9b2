// The network-set selector (`#network-set` in `#network-set-field`): which
// shipped networks Cases 1-3 run, the paper's recipe or the whole-reach
// recipe (docs/learning.md). The module names the sets and their files;
// a set other than the paper's is fetched from beside the page when first
// chosen (module.js, loadNetworkSet), with a plain message if that fails.
// Networks trained or loaded by the user show as their own entry. Beside
// it, the arithmetic selector (`#precision` in `#precision-field`): the
// networks in f64 or f32 (the module's precisions()).

import { describe, loadNetworkSet, networkSets, precisions, method, usesNetworks } from './module.js';

/**
 * Wires the arithmetic selector (`#precision` in `#precision-field`) under
 * `root`, if the page has one (both pages: space-demo.js too): its options
 * from the module's precisions(), and a choice handed to `choose(name,
 * select)`, which applies and reports it. Returns `sync(state, learned)`:
 * the selector shows `state.precision`, and only where `learned` (the
 * method uses networks).
 */
export function mountPrecision(root, choose) {
  const field = root.querySelector('#precision-field');
  const select = root.querySelector('#precision');
  if (!field || !select) return () => {};
  if (!select.options.length) {
    for (const p of precisions()) select.add(new Option(p.label, p.name));
  }
  select.addEventListener('change', () => choose(select.value, select));
  return (s, learned) => {
    field.hidden = !learned;
    if (select.value !== s.precision) select.value = s.precision;
  };
}

/** The select's value for networks that are no shipped set. */
const OWN = 'own';

/**
 * Wires the selector under `root`, if the page has one. `show(text, kind)`
 * reports; `changed()` after a switch of either (the address). Returns
 * `{ choose(name) -> Promise, sync(state) }`.
 */
export function mountNetworkSet(root, demo, { show, changed }) {
  const field = root.querySelector('#network-set-field');
  const select = root.querySelector('#network-set');
  if (select && !select.options.length) {
    for (const s of networkSets()) select.add(new Option(s.label, s.name));
    const own = new Option('trained or loaded here', OWN);
    own.disabled = true;
    select.add(own);
  }
  let pending = null;
  const syncPrecision = mountPrecision(root, (name, near) => {
    try {
      demo.setPrecision(name);
      changed?.();
      show?.(`The networks now compute in ${name}.`, 'info', false, near);
    } catch (e) {
      show?.(describe(e), 'error', true, near);
    }
  });

  /** Installs the shipped set `name`, fetching it first if need be; rejects with a readable reason. */
  async function choose(name) {
    if (!networkSets().some((s) => s.name === name)) {
      throw new Error(`unknown network set '${name}': use ${networkSets().map((s) => s.name).join(' or ')}`);
    }
    pending = name;
    if (select) select.disabled = true;
    try {
      const why = await loadNetworkSet(name);
      if (why) throw new Error(`the '${name}' networks could not be loaded: ${why}`);
      demo.useNetworkSet(name);
      changed?.();
    } finally {
      pending = null;
      if (select) select.disabled = false;
    }
  }

  select?.addEventListener('change', () => {
    const name = select.value;
    if (name === OWN) return;
    show?.(`Loading the '${name}' networks…`, 'info', false, select);
    choose(name).then(
      () => show?.(`Cases 1-3 now run the '${name}' networks.`, 'info', false, select),
      (e) => show?.(describe(e), 'error', true, select),
    );
  });

  return {
    choose,
    /** Shows the set in use, and the selector only where networks run and the shipped sets fit the arm. */
    sync(s) {
      syncPrecision(s, usesNetworks(method(s.method)));
      if (!field || !select) return;
      // The shipped sets run where they were trained for the arm (the core says which).
      const fits = Object.values(s.set_fits).some(Boolean);
      field.hidden = !usesNetworks(method(s.method)) || !fits;
      if (pending) return;
      const value = s.network_set ?? (s.trained_range ? OWN : select.value);
      if (select.value !== value) select.value = value;
    },
  };
}
