// Loading the page's WebAssembly module (src/web/), once per page, and the
// facts it exports that the page reads instead of writing them down
// itself: the methods, the limits, the default method, the arm and
// obstacle syntax. Everything else in www/ imports them from here, after
// loadModule() has resolved.

import init, {
  lastPanic,
  methods as moduleMethods,
  params as moduleParams,
  limits as moduleLimits,
  defaultMethod as moduleDefaultMethod,
  builtinWeightsFiles,
  provideBuiltinNetworks,
  builtinNetworksFailed,
  networksError,
  networkSets as moduleNetworkSets,
  networkSetLabels,
  palette,
  methodGroupLabels as moduleGroupLabels,
} from './pkg/redundant_ik.js';

// The arm, limits and obstacle syntax (`parseArm(text)`, `formatArm(post,
// links)`, `parseJointLimits(text)` and `formatJointLimits(flat)` for
// `LO:HI,...`, `parseRateLimits(text)` and `formatRateLimits(rates)` for
// `R,...`, `parseObstacles(text)`), the legend, the atlas classes and the
// Demo, as the module exports them.
import { describeError } from './errors.js';

export {
  parseArm,
  formatArm,
  parseJointLimits,
  formatJointLimits,
  parseRateLimits,
  formatRateLimits,
  parseObstacles,
  legend,
  atlasClasses,
  trainingPresets,
  paperMethods,
  Demo,
  SpaceDemo,
  spaceNetworkSets,
  spaceTrainingRecipes,
  palette,
  moduleVersion,
} from './pkg/redundant_ik.js';
import { spacePresets } from './pkg/redundant_ik.js';
export { spacePresets };
import { precisions as modulePrecisions } from './pkg/redundant_ik.js';
/** The built-in networks' weights files, `[phi, v]` (served in weights/). */
export { builtinWeightsFiles };

/**
 * The address of a file the page or its workers load, `path` relative to
 * www/ ('pkg/redundant_ik_simd_bg.wasm', 'weights/v-plain.json',
 * 'worker.js', 'bench-native.json'): every URL the page and its workers
 * resolve comes from here. Normally the file beside this module; in a
 * build that carries its files inline (the offline file, the package's
 * compat entry: tools/bundle.mjs) the data: URL of its copy, from the map
 * `globalThis.__REDUNDANT_IK_ASSETS__` that the build's first lines fill.
 */
export function assetUrl(path) {
  const inline = globalThis.__REDUNDANT_IK_ASSETS__;
  if (!inline) return new URL(path, import.meta.url).href;
  if (!Object.hasOwn(inline, path)) throw new Error(`this single-file build does not carry ${path} (it carries ${Object.keys(inline).join(', ')})`);
  return inline[path];
}

/** The two builds of the module (make web), each with every arm: with wasm SIMD, and without. */
const BUILDS = {
  simd: 'pkg/redundant_ik_simd_bg.wasm',
  baseline: 'pkg/redundant_ik_bg.wasm',
};

/**
 * Whether an address asks for an arm in space (after loadModule): it names
 * one by its preset's key (`arm=panda`), or `arm=space` (the first), or a
 * robot of the user's (`robot=HASH`, `urdf=URL`: robot-open.js). Every
 * other address (a planar preset's key such as `arm=iiwa-planar`, an arm
 * written out, `0.5:1,1,1`) is the plane's.
 */
export function asksForSpace(search = globalThis.location?.search ?? '') {
  const q = new URLSearchParams(search);
  const arm = q.get('arm') ?? '';
  return arm === 'space' || spacePresets().some((p) => p.key === arm) || q.has('robot') || q.has('urdf');
}

/** The same two builds of the workers' module (the atlas, the benchmark, the trainer, the figures). */
const WORKER_BUILDS = {
  simd: 'pkg/redundant_ik_worker_simd_bg.wasm',
  baseline: 'pkg/redundant_ik_worker_bg.wasm',
};

/** Whether this browser validates wasm SIMD (v128, as wasm-feature-detect checks it). */
function simdSupported() {
  try {
    return WebAssembly.validate(
      new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 10, 1, 8, 0, 65, 0, 253, 15, 253, 98, 11]),
    );
  } catch (_) {
    return false;
  }
}

let module = null;
let build = null;
let memory = null;
/** Whether the page shows an arm in space (its workers then need no planar networks). */
let inSpace = false;

/** Which build the page runs: 'simd' or 'baseline' (null before loading). */
export function moduleBuild() {
  return build;
}

/** The workers' .wasm of the build the page runs (null before loading). */
export function workerModuleUrl() {
  return build && assetUrl(WORKER_BUILDS[build]);
}

/** Bytes of the page module's linear memory (it grows, never shrinks; the soak watches it). */
export function moduleMemoryBytes() {
  return memory ? memory.buffer.byteLength : 0;
}

/** The fetches of shipped network sets under way or done, by name. */
const fetchedSets = new Map();
/** The weights files' text of each shipped set fetched, by name: `[phi, v]` (for the workers). */
const setTexts = new Map();
/** Why a shipped set could not be fetched, by name (for the workers). */
const setFailures = new Map();

/**
 * Fetches a shipped network set's weights files (the module names them)
 * and hands them to the module, or tells it why they could not be had: the
 * page's module does not carry them (15 KB of its gzipped size for the
 * paper's set). The paper's set is fetched at start-up, the others when
 * first chosen. Resolves to null when the set is ready, else to the
 * reason; a failure leaves the page running, and the methods that need
 * networks then say why.
 */
export function loadNetworkSet(set = moduleNetworkSets()[0]) {
  // The page in space runs no planar networks (nor loads them).
  if (inSpace) return Promise.resolve('the page in space runs no planar networks');
  if (!fetchedSets.has(set)) {
    fetchedSets.set(
      set,
      (async () => {
        try {
          const files = builtinWeightsFiles(set);
          const texts = await Promise.all(
            files.map(async (name) => {
              const r = await fetch(builtinWeightsUrl(name));
              if (!r.ok) throw new Error(`could not fetch weights/${name} (HTTP ${r.status})`);
              return r.text();
            }),
          );
          setTexts.set(set, texts);
          provideBuiltinNetworks(texts[0], texts[1], set);
        } catch (e) {
          const why = e && e.message ? e.message : String(e);
          if (!setTexts.has(set)) setFailures.set(set, why);
          // The first set (the paper's) is what the network methods start
          // with: its failure is kept as their reason. Another set may be
          // tried again.
          if (set === moduleNetworkSets()[0]) builtinNetworksFailed(why, set);
          else {
            fetchedSets.delete(set);
            return why;
          }
        }
        return networksError(set) ?? null;
      })(),
    );
  }
  return fetchedSets.get(set);
}

/**
 * The shipped sets a worker's job needs, for the workers' module, which
 * carries none (make web; docs/web.md, "Bytes on the wire"): the paper's
 * and the sets named in `names` (unknown names left to the module's
 * message), fetched first if need be (once per page; the worker fetches
 * nothing). Resolves to `{ name: { phi, v } }` with the weights files'
 * text, or `{ name: { error } }` with why they could not be fetched.
 */
export async function networkSetsFor(names = []) {
  // The jobs of the page in space read the spatial networks' files themselves.
  if (inSpace) return {};
  const known = moduleNetworkSets();
  const out = {};
  for (const name of new Set([known[0], ...names])) {
    if (!known.includes(name)) continue;
    const why = await loadNetworkSet(name);
    const texts = setTexts.get(name);
    // Fetched files go as they are (a corrupt one is refused by the workers' module as here).
    out[name] = texts ? { phi: texts[0], v: texts[1] } : { error: setFailures.get(name) ?? why ?? 'not fetched' };
  }
  return out;
}

let cachedSets = null;

/** The shipped network sets (after loadModule): `[{ name, label }]`. */
export function networkSets() {
  if (!cachedSets) {
    const labels = networkSetLabels();
    cachedSets = moduleNetworkSets().map((name, i) => ({ name, label: labels[i] }));
  }
  return cachedSets;
}

let cachedPrecisions = null;

/** The networks' arithmetics (after loadModule), the default first: `[{ name, label }]`. */
export function precisions() {
  cachedPrecisions ??= modulePrecisions().map(([name, label]) => ({ name, label }));
  return cachedPrecisions;
}

/** The arithmetic an address names (`precision=`): one of precisions(), else throws naming them. */
export function readPrecision(text) {
  const names = precisions().map((p) => p.name);
  if (names.includes(text)) return text;
  const shown = text.length > 40 ? `${text.slice(0, 40)}…` : text;
  throw new Error(`unknown arithmetic '${shown}': use ${names.join(' or ')}`);
}

/**
 * The URL of the built-in networks' weights file `name`, which `make web`
 * puts in weights/ beside the page (fetched at start-up, for downloads).
 */
export function builtinWeightsUrl(name) {
  return assetUrl(`weights/${name}`);
}

/**
 * Loads and starts the WebAssembly module once per page: the SIMD build
 * where the browser supports SIMD (the networks run about twice as fast),
 * else, or if it fails to start, the baseline build; then the built-in
 * networks of the plane, unless the first call says the page shows an arm
 * in space (`space`; default: the address asks for one, asksForSpace).
 */
export function loadModule({ space } = {}) {
  if (!module) {
    const start = async (which) => {
      const exports = await init({ module_or_path: assetUrl(BUILDS[which]) });
      memory = exports.memory;
      build = which;
      // The drawing's colours, for the stylesheet (var(--arm), ...).
      for (const [name, value] of Object.entries(palette())) {
        document.documentElement.style.setProperty(`--${name}`, value);
      }
    };
    module = (async () => {
      let started = false;
      if (simdSupported()) {
        try {
          await start('simd');
          started = true;
        } catch (e) {
          console.warn(`the SIMD build did not start (${e && e.message ? e.message : e}); using the baseline build`);
        }
      }
      if (!started) await start('baseline');
      inSpace = space ?? asksForSpace();
      if (!inSpace) await loadNetworkSet();
    })();
  }
  return module;
}

let cachedMethods = null;
let cachedParams = null;
let cachedLimits = null;

/**
 * Every parameter of the methods (after loadModule): `[{ name, flag, label,
 * unit, bounds, slider: [min, max, step], default }]`.
 */
export function params() {
  cachedParams ??= moduleParams();
  return cachedParams;
}

/** The groups of methods in menu order: `[{ group, label, methods }]`. */
export function methodGroups() {
  const labels = Object.fromEntries(moduleGroupLabels());
  const groups = [];
  for (const m of methods()) {
    let g = groups.find((x) => x.group === m.group);
    if (!g) groups.push((g = { group: m.group, label: labels[m.group] ?? m.group, methods: [] }));
    g.methods.push(m);
  }
  return groups;
}

/**
 * Every method, in the order of the menus (after loadModule): `[{ name,
 * label, description, group, paper_figures, networks: { phi, v }, avoids,
 * colour, params }]`. Read once; the same array every call.
 */
export function methods() {
  cachedMethods ??= moduleMethods();
  return cachedMethods;
}

/** The method called `name`, or undefined. */
export function method(name) {
  return methods().find((m) => m.name === name);
}

/** Whether method `m` (an entry of methods()) runs networks. */
export const usesNetworks = (m) => Boolean(m && (m.networks.phi || m.networks.v));

/** The labels of the methods that run networks, for messages: "Case 1, Case 2, Case 3". */
export function networkMethodLabels() {
  return methods()
    .filter(usesNetworks)
    .map((m) => m.label)
    .join(', ');
}

/**
 * The core's limits and defaults (after loadModule): `{ min_links,
 * max_links, max_obstacles, default_radius, max_weights_bytes,
 * reach_tolerance, default_grid, max_grid, drift_gain, max_lambda,
 * arm_presets: [{ key, label, post, links }] }`.
 */
export function limits() {
  cachedLimits ??= moduleLimits();
  return cachedLimits;
}

/** The method a page starts with where its address or attributes name none. */
export function defaultMethod() {
  return moduleDefaultMethod();
}

/** A readable message for an exception thrown by the module. */
export const describe = (err) => describeError(err, lastPanic);

/**
 * Fills every `[data-limit]` element under `root` with that limit (e.g.
 * `<span data-limit="max_obstacles">`), times `data-scale` if given (1000
 * for a tolerance in mm), so the page's prose quotes the core's numbers.
 */
export function fillLimits(root) {
  for (const el of root.querySelectorAll('[data-limit]')) {
    const value = limits()[el.dataset.limit];
    if (typeof value === 'number') el.textContent = String(+(value * Number(el.dataset.scale ?? 1)).toPrecision(6));
  }
}
