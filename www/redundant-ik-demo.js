// <redundant-ik-demo task="1" method="case3"> — the demo as a custom element.
//
//   <script type="module" src="https://…/redundant-ik-demo.js"></script>
//   <redundant-ik-demo task="2" method="numerical"></redundant-ik-demo>
//
// Attributes: task (1 or 2), method (a method's name from methods(): none,
// numerical, case1, ...; the module's defaultMethod() where absent; `mode`,
// its older name, is read too),
// lambda, feedback (closed-loop gain K in 1/s; 0 = the paper's open loop),
// weighting (a joint weighting's name, limits().joint_weightings), floor
// ("1": the floor and post are obstacles),
// path (the path the hand follows: line, circle:CX,CY[,LAPS] or
// points:X,Y;X,Y;..., as the address's path=), autoplay ("false" to start
// paused), plots (present: show the time
// series). Each element has its own simulation in its own shadow root; the
// WebAssembly module is loaded once per page. After its first frame an element
// sets data-ready="true" and exposes .controller (state(), worldToClient()).

import { mount } from './demo.js';
import { describe, loadModule, defaultMethod } from './module.js';

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
.wrap { position: relative; }
#stage { display: block; width: 100%; aspect-ratio: 14 / 11; touch-action: none; user-select: none; }
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
`;

const TEMPLATE = `
<style>${STYLE}</style>
<div class="wrap">
  <canvas id="stage" part="stage" aria-label="Redundant arm simulation; drag the target or the obstacle"></canvas>
  <div id="loading" role="status">Loading the simulation…</div>
</div>
<div class="bar">
  <select id="mode" aria-label="Method"></select>
  <button id="play" type="button">Play</button>
  <button id="reset" type="button">Reset</button>
  <span class="read">t <b data-readout="t">0.0</b> s · distance <b data-readout="distance">–</b> m ·
    collision <b data-readout="collision">none</b></span>
</div>
<p id="range-warning" class="notice warn" hidden>Outside the networks' trained range.</p>
<p id="handover-note" class="notice warn" role="status" hidden></p>
<p id="message" class="notice" role="status" aria-live="polite" hidden></p>
`;

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
    try {
      await loadModule();
      const task = Number(this.getAttribute('task')) === 2 ? 2 : 1;
      const lambda = this.getAttribute('lambda');
      // `mode`, the attribute's older name, is read where `method` is absent.
      const method = this.getAttribute('method') ?? this.getAttribute('mode') ?? defaultMethod();
      this.controller = await mount(root, {
        task,
        method,
        lambda: lambda !== null && Number.isFinite(Number(lambda)) ? Number(lambda) : undefined,
        feedback: Number.isFinite(Number(this.getAttribute('feedback'))) ? Number(this.getAttribute('feedback')) : 0,
        weighting: this.getAttribute('weighting') ?? undefined,
        floor: this.getAttribute('floor') === '1',
        path: this.getAttribute('path') ?? undefined,
        autoplay: this.getAttribute('autoplay') !== 'false',
        keyboard: this,
      });
      this.dataset.ready = 'true';
      this.dispatchEvent(new CustomEvent('ready', { bubbles: true }));
    } catch (e) {
      loading.hidden = false;
      loading.classList.add('failed');
      loading.textContent = `The simulation could not start: ${describe(e)}`;
      console.warn(e);
    }
  }

  disconnectedCallback() {
    this.controller?.stop();
  }
}

if (!customElements.get('redundant-ik-demo')) {
  customElements.define('redundant-ik-demo', RedundantIkDemo);
}
