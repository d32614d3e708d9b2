// <redundant-ik-demo task="1" method="case3"> — the demo as a custom element.
//
//   <script type="module" src="https://…/redundant-ik-demo.js"></script>
//   <redundant-ik-demo task="2" method="numerical">
//     If this text stays, the demo's script could not load: …
//   </redundant-ik-demo>
//
// Attributes: exactly the page's address keys (www/address.js, read by the
// same readAddress): task (1 or 2), method (a name of the module's
// methods(); its defaultMethod() where absent; `mode`, its older name, is
// read where there is no method), lambda, feedback (closed-loop gain K in
// 1/s), target and obstacle ("x,y"), obstacles ("x,y,r;..."), arm (a preset
// key of limits().arm_presets, e.g. iiwa-planar, or an arm's text
// "post:l1,l2,..."), limits ("lo:hi,..."), rates ("r,..."), damping ("0"
// switches it off), weighting (a name of limits().joint_weightings), floor
// ("1": the floor and post are obstacles), theta0 and tf (a start pose and
// final time, together), path (line, circle:CX,CY[,LAPS] or
// points:X,Y;X,Y;...), networks (a shipped set, networkSets()), precision
// (the networks' arithmetic, f64 or f32: precisions()), and every
// method parameter by its name in params() (influence=..., refine=...).
// projector ("1": larger text, thicker borders, higher contrast).
// An arm in space (arm="panda" or arm="iiwa14") takes the page in space's
// keys instead (www/space-address.js: method, target="x,y,z",
// obstacles="x,y,z,r;...", path, theta0, lambda and the parameters,
// feedback, weighting, floor, damping="1", precision,
// view="yaw,pitch,distance") and its drawing in perspective (orbit, drag,
// keys). So does a robot's URDF at an address (urdf="URL", with base and
// tip: fetched with its meshes from a host that allows it, as the page's
// urdf= key; where it cannot be, the first shipped arm and the reason).
// The element's own: autoplay ("false" to start paused; unset, it plays
// unless the user prefers reduced motion) and plots (present:
// show the time series). A value that does not parse, or that the core
// refuses, is named in the element's message ("Not applied: ...") and the
// rest runs. Changing an attribute later applies it to the running demo
// (autoplay and plots are read at the start only); removing one sets it
// back to its default (the target, obstacles, arm, limits and start pose
// stay as they are).
//
// Like the page, it has the live region and the drawing's summary
// (announce.js). Each element has its own simulation in its own shadow root (which hides
// the fallback text inside the element: there is no <slot>); the
// WebAssembly module is loaded once per page. This file imports the rest
// when it runs, so a module that cannot be fetched (CORS, 404) is said in
// the element's loading box rather than nothing at all. After its first
// frame an element sets data-ready="true", fires `ready` and exposes
// .controller (state(), worldToClient(), apply(), ...).

const STYLE = `
:host {
  display: block;
  font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif;
  color: var(--ink);
  border: 1px solid #dde3ea;
  border-radius: 10px;
  background: #fff;
  padding: 8px;
  contain: content;
  min-width: 0;
}
:host(:focus-visible) { outline: 2px solid #6ea0dc; outline-offset: 2px; }
.wrap { position: relative; isolation: isolate; }
.view-3d { position: absolute; inset: 0; width: 100%; height: 100%; z-index: -1; pointer-events: none; }
#stage { display: block; width: 100%; aspect-ratio: 14 / 11; touch-action: pan-y; user-select: none; }
#stage:focus { outline: none; }
#stage:focus-visible { outline: 2px solid #6ea0dc; outline-offset: 2px; }
#plots { display: block; width: 100%; height: 300px; margin-top: 6px; }
#loading { position: absolute; inset: 0; display: flex; align-items: center; justify-content: center;
  background: rgba(255,255,255,.92); color: var(--muted); text-align: center; padding: 16px; }
#loading[hidden] { display: none; }
#loading.failed { color: var(--danger); }
.bar { display: flex; flex-wrap: wrap; gap: 6px; align-items: center; margin-top: 6px; }
#mode { flex: 1 1 12em; min-width: 0; max-width: 100%; text-overflow: ellipsis; }
select, button { font: inherit; font-size: 13px; color: var(--ink); border: 1px solid #cdd5de;
  border-radius: 6px; background: #fff; padding: 4px 9px; min-height: 30px; cursor: pointer; }
button:hover, select:hover { background: #f8fafc; border-color: #aab5c2; }
#play { background: var(--arm); border-color: var(--arm); color: #fff; min-width: 64px; }
.read { margin-left: auto; font-size: 12.5px; color: var(--muted); font-variant-numeric: tabular-nums; }
.read b { color: var(--ink); font-weight: 600; }
[data-level="bad"] { color: var(--danger); }
[data-level="warn"] { color: #8a5a00; }
[data-level="ok"] { color: #2a7d4f; }
.notice { margin: 6px 0 0; padding: 6px 9px; border-radius: 6px; font-size: 12.5px;
  background: #fdf0ee; border: 1px solid #f1c4bd; color: #8c2a1e; }
.notice[data-kind="warn"], .notice.warn { background: #fff7e8; border-color: #f3d9a6; color: #7a4d00; }
.notice[hidden] { display: none; }
.visually-hidden { position: absolute; width: 1px; height: 1px; margin: -1px; padding: 0; border: 0;
  overflow: hidden; clip: rect(0 0 0 0); clip-path: inset(50%); white-space: nowrap; }
:host([data-projector]) { font-size: 18px; border: 2px solid #3d4853; --muted: #27313b; }
:host([data-projector]) select, :host([data-projector]) button { font-size: 17px; border: 2px solid #3d4853; min-height: 40px; }
:host([data-projector]) .read, :host([data-projector]) .notice { font-size: 16px; }
@media (pointer: coarse) { select, button { min-height: 44px; } }
`;

const TEMPLATE = `
<style>${STYLE}</style>
<div class="wrap">
  <canvas id="stage" part="stage" aria-label="Redundant arm simulation; drag the target or the obstacle" aria-describedby="stage-summary"></canvas>
  <p id="stage-summary" class="visually-hidden"></p>
  <div id="loading" role="status">Loading the simulation…</div>
</div>
<div class="bar">
  <select id="mode" aria-label="Method"></select>
  <button id="play" type="button">Play</button>
  <button id="reset" type="button">Reset</button>
  <span class="read">t <b data-readout="t">0.0</b> s · clearance <b data-readout="clearance">–</b> m ·
    collision <b data-readout="collision">none</b></span>
</div>
<p id="range-warning" class="notice warn" hidden>Outside the networks' trained range.</p>
<p id="criterion-note" class="notice warn" role="status" hidden></p>
<p id="limits-note" class="notice warn" role="status" hidden></p>
<p id="handover-note" class="notice warn" role="status" hidden></p>
<p id="message" class="notice" role="status" aria-live="polite" hidden></p>
<p id="announcer" class="visually-hidden" role="status" aria-live="polite" aria-atomic="true"></p>
`;

/**
 * Where the rest of the demo lives (the folder of this script): named when
 * it cannot be fetched. A bundle loaded from a blob: URL (the notebook
 * widget) has no folder; its own URL is named then.
 */
function home() {
  try {
    return new URL('./', import.meta.url).href;
  } catch (_) {
    return import.meta.url;
  }
}

/** The demo's modules, imported once when the first element starts (a failure rejects with the reason). */
let modules = null;
const importModules = () =>
  (modules ??= (async () => {
    const [demo, module, address] = await Promise.all([import('./demo.js'), import('./module.js'), import('./address.js')]);
    // The element shows a planar arm: the host page's own address says nothing here.
    await module.loadModule({ space: false });
    return { ...demo, ...module, ...address };
  })());

/** The page in space's scripts, imported once when the first element with an arm in space starts. */
let spaceModules = null;
const importSpace = () =>
  (spaceModules ??= Promise.all([import('./space-demo.js'), import('./space-address.js')]).then(([demo, address]) => ({ ...demo, ...address })));

/** The words for a module that could not be fetched or started: what the host must send. */
function loadFailure(e) {
  const why = e && e.message ? e.message : String(e);
  const from = home();
  const crossOrigin = new URL(from).origin !== location.origin;
  return (
    `The simulation could not load its files from ${from} (${why}). ` +
    'The server that hosts redundant-ik-demo.js must serve the rest of the demo beside it (pkg/, weights/ and the other .js files)' +
    (crossOrigin ? ', and, since this page is on another site, send the header Access-Control-Allow-Origin with every file' : '; for a page on another site it must send the header Access-Control-Allow-Origin with every file') +
    '; .wasm files should be served as application/wasm.'
  );
}

/** An element's attributes as an address's keys. */
const attributes = (el) => new URLSearchParams([...el.attributes].map((a) => [a.name, a.value]));

/** The settings an element's attributes ask for: readAddress over its attributes (readSpaceAddress for an arm in space). */
const readAttributes = (el, m) => (m.readSpaceAddress ?? m.readAddress)(attributes(el));

const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

/** The keys of an arm in space an element watches (space-address.js's, the methods' parameters besides). */
const SPACE_KEYS = ['arm', 'method', 'task', 'theta0', 'target', 'orientation_weight', 'obstacles', 'feedback', 'weighting', 'floor', 'self_collision', 'damping', 'path', 'precision', 'view'];

/** The attributes of an arm in space beyond the plane's address keys: its keys, and a robot's URDF (urdf, base, tip). */
export const SPACE_ATTRIBUTES = [...SPACE_KEYS, 'urdf', 'base', 'tip'];

class RedundantIkDemo extends HTMLElement {
  connectedCallback() {
    if (this.shadowRoot) return;
    const root = this.attachShadow({ mode: 'open' });
    root.innerHTML = TEMPLATE;
    if (this.hasAttribute('plots')) {
      const plots = document.createElement('canvas');
      plots.id = 'plots';
      root.querySelector('.bar').after(plots);
    }
    if (!this.hasAttribute('tabindex')) this.tabIndex = 0;
    this.start(root);
  }

  async start(root) {
    const loading = root.getElementById('loading');
    const fail = (text, e) => {
      loading.hidden = false;
      loading.classList.add('failed');
      loading.textContent = text;
      console.warn(e);
    };
    let m;
    try {
      m = await importModules();
    } catch (e) {
      fail(loadFailure(e), e);
      return;
    }
    try {
      // An arm in space (arm="panda"): the page in space's mount, its own
      // address reader; the attributes are its address keys.
      const arm = this.getAttribute('arm');
      const urdf = this.getAttribute('urdf');
      if (urdf || arm === 'space' || m.spacePresets().some((p) => p.key === arm)) {
        const space = await importSpace();
        m = { ...m, ...space, mount: space.mountSpace };
      }
      this.space = Boolean(m.readSpaceAddress);
      const { problems, ...settings } = readAttributes(this, m);
      let robot = null;
      if (urdf) {
        const { openUrl, openStored } = await import('./robot-open.js');
        const [base, tip] = ['base', 'tip'].map((k) => this.getAttribute(k) ?? undefined);
        try {
          robot = await openStored((await openUrl(new URL(urdf, document.baseURI).href, { base, tip })).hash);
        } catch (e) {
          problems.push(`urdf: ${m.describe(e)}`);
          settings.arm = m.spacePresets()[0].key;
        }
      }
      this.controller = await m.mount(root, {
        ...settings,
        robot,
        problems,
        // Unset: the run plays unless the user prefers reduced motion.
        autoplay: { true: true, false: false }[this.getAttribute('autoplay')],
        keyboard: this,
      });
      this.settings = settings;
      this.watch(m);
      this.dataset.ready = 'true';
      this.dispatchEvent(new CustomEvent('ready', { bubbles: true }));
    } catch (e) {
      fail(`The simulation could not start: ${m.describe(e)}`, e);
    }
  }

  /**
   * Applies changed attributes to the running demo. A MutationObserver
   * rather than observedAttributes: the methods' parameters are attributes
   * too (params()), and their names are the module's, known only once it
   * has loaded, while observedAttributes is read once when the element is
   * defined, before. One observer for every key keeps one path; the
   * changes of one task are applied together (the observer's batch).
   */
  watch(m) {
    const keys = new Set(this.space ? [...SPACE_KEYS, ...m.params().map((p) => p.name)] : m.addressKeys());
    const observer = new MutationObserver((records) => {
      if (!records.some((r) => keys.has(r.attributeName))) return;
      try {
        this.update(m);
      } catch (e) {
        // Nothing a page sets may throw out of the element: said beside the drawing.
        this.controller.show(`Not applied: ${m.describe(e)}`, 'warn', true);
      }
    });
    observer.observe(this, { attributes: true });
    this.observer = observer;
  }

  /** What the attributes ask for now against what was applied: the changes to the controller (apply), the problems shown. */
  update(m) {
    if (this.space) return this.updateSpace(m);
    const { problems, ...now } = readAttributes(this, m);
    const was = this.settings;
    const lambdaDefault = m.params().find((p) => p.name === 'lambda')?.default;
    // An attribute removed goes back to its default; the scene's own parts
    // (target, obstacles, arm, limits, start pose) stay as they are.
    const defaults = {
      lambda: lambdaDefault,
      feedback: 0,
      damping: true,
      weighting: m.limits().joint_weightings[0][0],
      floor: false,
      path: 'line',
      networks: m.networkSets()[0].name,
      precision: m.precisions()[0].name,
      projector: false,
    };
    // A value that does not parse leaves its setting as it is (named, not
    // replaced by the default as at the start): mode= is the method, tf= the start.
    const bad = new Set(problems.map((p) => ({ mode: 'method', theta0: 'start', tf: 'start' })[p.split(':')[0]] ?? p.split(':')[0]));
    for (const key of bad) {
      if (key in now) now[key] = was[key];
      else if (key in was.params) now.params[key] = was.params[key];
    }
    const changed = {};
    // A new task loads the paper's scene: everything asked for is applied again over it.
    const all = now.task !== was.task;
    for (const key of ['task', 'method', 'lambda', 'feedback', 'target', 'obstacle', 'obstacles', 'arm', 'limits', 'rates', 'damping', 'weighting', 'floor', 'start', 'path', 'networks', 'precision', 'projector']) {
      if (all || !same(now[key], was[key])) changed[key] = now[key] ?? defaults[key];
    }
    // The limits go with the arm: a new arm is set with the limits asked for.
    if (changed.arm && now.limits) changed.limits = now.limits;
    if (changed.arm && now.rates) changed.rates = now.rates;
    changed.params = {};
    for (const p of m.params()) {
      if (p.name === 'lambda') continue;
      if (all || now.params[p.name] !== was.params[p.name]) changed.params[p.name] = now.params[p.name] ?? p.default;
    }
    this.settings = now;
    const refused = this.controller.apply(changed);
    const listed = [...problems, ...refused];
    if (listed.length) this.controller.show(`Not applied: ${listed.join('; ')}`, 'warn', true);
    else this.controller.clear();
  }

  /**
   * `update` for an arm in space: each key that changed (an attribute
   * removed: its default, the controller's apply says which); the arm is
   * read at the start only.
   */
  updateSpace(m) {
    const { problems, ...now } = readAttributes(this, m);
    const was = this.settings;
    // A value that does not parse leaves its setting as it is (named).
    for (const key of problems.map((p) => p.split(':')[0])) {
      if (key in was.params) now.params[key] = was.params[key];
      else now[key] = was[key];
    }
    const changed = {};
    for (const key of SPACE_KEYS) {
      if (key !== 'arm' && !same(now[key], was[key])) changed[key] = now[key];
    }
    changed.params = {};
    for (const p of m.params()) {
      if (now.params[p.name] !== was.params[p.name]) changed.params[p.name] = now.params[p.name] ?? p.default;
    }
    this.settings = now;
    const refused = this.controller.apply(changed);
    if (now.arm !== was.arm) refused.push("arm: an element's arm in space is read when it starts");
    const listed = [...problems, ...refused];
    if (listed.length) this.controller.show(`Not applied: ${listed.join('; ')}`, 'warn', true);
    else this.controller.clear();
  }

  disconnectedCallback() {
    this.controller?.stop();
    this.observer?.disconnect();
  }
}

if (!customElements.get('redundant-ik-demo')) {
  customElements.define('redundant-ik-demo', RedundantIkDemo);
}
