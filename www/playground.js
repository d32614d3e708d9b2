// The playground: the arm designer, several obstacles, and networks trained
// for the arm in the page (in a Web Worker, worker.js) with live training
// curves. The module does the work (Demo.setArm, addObstacle, ...; the
// workers' trainNetworks); this file wires the form, draws the curves and
// keeps trained weights in the browser (localStorage, per arm).
//
// `mountPlayground(root, demo, hooks)` wires the elements of `root` that
// exist (`#arm-preset`, `#arm-post`, `#arm-links`, `#link-add`,
// `#link-remove`, `#arm-apply`, `#obstacle-add`, `#obstacle-remove`,
// `#obstacle-list`, `#train-*`, `#train-for-arm`) and returns the
// controller `window.demo` uses: setArm, addObstacle, removeObstacle,
// obstacles, train, exportWeights, plus click/wantsClick for the stage and
// check(state) for the animation loop.

/** The arms the designer offers (post height and link lengths, m). */
export const ARM_PRESETS = {
  paper: { label: "The paper's arm (3 links)", post: 0.5, links: [0.6, 0.85, 0.6] },
  four: { label: '4 links', post: 0.5, links: [0.6, 0.85, 0.6, 0.4] },
  five: { label: '5 links', post: 0.5, links: [0.5, 0.6, 0.5, 0.4, 0.3] },
};

export const MIN_LINKS = 2;
export const MAX_LINKS = 6;
export const MAX_OBSTACLES = 8;

/** `POST:L1,L2,...`, as in the URL (`arm=`) and the CLI's `--arm`. */
export function armKey({ post, links }) {
  return `${+post.toFixed(4)}:${links.map((l) => +l.toFixed(4)).join(',')}`;
}

/** A number from text: blank is not zero (as `Number('')` is). */
export const number = (x) => (x.trim() === '' ? NaN : Number(x));
/** Text a message quotes, cut to 40 characters (an address can be megabytes long). */
export const clip = (text) => (String(text).length > 40 ? `${String(text).slice(0, 40)}…` : String(text));

/** Parses `POST:L1,L2,...`; throws a readable error. */
export function parseArm(text) {
  const m = /^([^:]+):(.+)$/.exec(String(text).trim());
  if (!m) throw new Error(`arm '${clip(text)}': expected POST:L1,L2,... (e.g. 0.5:0.6,0.85,0.6)`);
  const post = number(m[1]);
  const links = m[2].split(',').map(number);
  if (links.length < MIN_LINKS || links.length > MAX_LINKS) {
    throw new Error(`arm '${clip(text)}': ${links.length} links; the page takes ${MIN_LINKS} to ${MAX_LINKS}`);
  }
  if (!Number.isFinite(post) || links.some((l) => !Number.isFinite(l))) {
    throw new Error(`arm '${clip(text)}': every length must be a finite number`);
  }
  return { post, links };
}

/** Parses `x,y,r;x,y,r` (`r` optional); throws a readable error. */
export function parseObstacles(text) {
  const parts = String(text).split(';').filter((p) => p.trim() !== '');
  if (parts.length > MAX_OBSTACLES) throw new Error(`${parts.length} obstacles; at most ${MAX_OBSTACLES}`);
  return parts.map((p) => {
    const v = p.split(',').map(number);
    if (!(v.length === 2 || v.length === 3) || v.some((x) => !Number.isFinite(x))) {
      throw new Error(`obstacle '${clip(p)}': expected x,y or x,y,r (finite numbers)`);
    }
    return v;
  });
}

/** `[[x, y, r?], ...]` flat as the module takes it: `[x0, y0, r0, ...]` (r default 0.05 m). */
export function flatObstacles(list) {
  if (!Array.isArray(list)) throw new Error('obstacles: expected a list of [x, y, r]');
  if (list.length > MAX_OBSTACLES) throw new Error(`${list.length} obstacles; at most ${MAX_OBSTACLES}`);
  return Float64Array.from(
    list.flatMap((o) => {
      const v = Array.isArray(o) ? o : [o?.x, o?.y, o?.r];
      if (v.length < 2 || v.length > 3) throw new Error('an obstacle is [x, y] or [x, y, r]');
      return [Number(v[0]), Number(v[1]), v[2] === undefined ? 0.05 : Number(v[2])];
    }),
  );
}

/** `x,y,r;x,y,r` of the obstacles in the state. */
export function formatObstacles(obstacles) {
  return obstacles.map((o) => [...o.centre, o.radius].map((v) => +v.toFixed(3)).join(',')).join(';');
}

const STORE = 'redundant-ik:weights:';

/** Trained weights kept for an arm: `{ phi, v, report, saved }` or null. */
export function storedWeights(arm) {
  try {
    const raw = localStorage.getItem(STORE + armKey(arm));
    return raw ? JSON.parse(raw) : null;
  } catch (_) {
    forgetWeights(arm); // not JSON: nothing to keep
    return null;
  }
}

function storeWeights(arm, entry) {
  try {
    localStorage.setItem(STORE + armKey(arm), JSON.stringify(entry));
    return true;
  } catch (_) {
    return false; // storage full or switched off: the networks still work until reload
  }
}

function forgetWeights(arm) {
  try {
    localStorage.removeItem(STORE + armKey(arm));
  } catch (_) {
    /* nothing stored */
  }
}

const fmtS = (s) => (s >= 60 ? `${Math.floor(s / 60)} min ${Math.round(s % 60)} s` : `${s.toFixed(1)} s`);
const sci = (v) => (Number.isFinite(v) ? v.toExponential(2) : '–');
const mm = (v) => (Number.isFinite(v) ? (v >= 0.01 ? `${v.toFixed(3)} m` : `${(v * 1000).toFixed(2)} mm`) : '–');

/** Draws MSE curves per epoch on a log scale: `series` is `{ name: [{ epoch, train_mse, val_mse }] }`. */
function drawCurves(canvas, series) {
  if (!canvas) return;
  const dpr = window.devicePixelRatio || 1;
  const r = canvas.getBoundingClientRect();
  if (r.width === 0) return;
  if (canvas.width !== Math.round(r.width * dpr)) {
    canvas.width = Math.round(r.width * dpr);
    canvas.height = Math.round(r.height * dpr);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  const W = r.width;
  const H = r.height;
  ctx.clearRect(0, 0, W, H);
  const css = getComputedStyle(document.documentElement);
  const colour = (name, fallback) => css.getPropertyValue(`--${name}`).trim() || fallback;
  const ink = colour('ink', '#222');
  const muted = colour('muted', '#888');
  const colours = { phi: colour('arm', '#1f5fa8'), v: colour('accent', '#d9822b') };
  const all = Object.values(series).flat();
  const values = all.flatMap((p) => [p.train_mse, p.val_mse]).filter((v) => v > 0 && Number.isFinite(v));
  const pad = { l: 44, r: 8, t: 8, b: 20 };
  ctx.font = '11px system-ui, sans-serif';
  ctx.fillStyle = muted;
  if (!values.length) {
    ctx.fillText('MSE per epoch (log scale) appears here', pad.l, H / 2);
    return;
  }
  let lo = Math.floor(Math.log10(Math.min(...values)));
  let hi = Math.ceil(Math.log10(Math.max(...values)));
  if (hi === lo) hi = lo + 1;
  const maxEpoch = Math.max(10, ...all.map((p) => p.epoch));
  const x = (e) => pad.l + ((W - pad.l - pad.r) * e) / maxEpoch;
  const y = (v) => pad.t + ((H - pad.t - pad.b) * (hi - Math.log10(v))) / (hi - lo);
  ctx.strokeStyle = muted;
  ctx.lineWidth = 0.5;
  for (let d = lo; d <= hi; d++) {
    ctx.beginPath();
    ctx.moveTo(pad.l, y(10 ** d));
    ctx.lineTo(W - pad.r, y(10 ** d));
    ctx.stroke();
    ctx.fillText(`1e${d}`, 4, y(10 ** d) + 4);
  }
  ctx.fillText(`epoch ${maxEpoch}`, W - pad.r - 60, H - 5);
  let legendX = pad.l + 4;
  for (const [name, points] of Object.entries(series)) {
    for (const [key, dashed] of [
      ['train_mse', false],
      ['val_mse', true],
    ]) {
      ctx.strokeStyle = colours[name] ?? ink;
      ctx.lineWidth = 1.5;
      ctx.setLineDash(dashed ? [4, 3] : []);
      ctx.beginPath();
      let started = false;
      for (const p of points) {
        if (!(p[key] > 0)) continue;
        if (started) ctx.lineTo(x(p.epoch), y(p[key]));
        else ctx.moveTo(x(p.epoch), y(p[key]));
        started = true;
      }
      ctx.stroke();
    }
    ctx.setLineDash([]);
    ctx.fillStyle = colours[name] ?? ink;
    ctx.fillText(`${name === 'phi' ? 'Φ' : 'v'}: train —, validation - -`, legendX, H - 5);
    legendX += 150;
  }
}

export function mountPlayground(root, demo, { runWorker, describe, show, changed }) {
  const $ = (id) => root.querySelector('#' + id);
  const el = {
    preset: $('arm-preset'),
    post: $('arm-post'),
    links: $('arm-links'),
    linkAdd: $('link-add'),
    linkRemove: $('link-remove'),
    apply: $('arm-apply'),
    obstacleAdd: $('obstacle-add'),
    obstacleRemove: $('obstacle-remove'),
    obstacleList: $('obstacle-list'),
    trainPanel: $('train-panel'),
    trainPreset: $('train-preset'),
    trainNet: $('train-net'),
    trainRun: $('train-run'),
    trainCancel: $('train-cancel'),
    trainProgress: $('train-progress'),
    trainStatus: $('train-status'),
    trainCurves: $('train-curves'),
    trainReport: $('train-report'),
    trainDownload: $('train-download'),
    trainForget: $('train-forget'),
    trainForArm: $('train-for-arm'),
  };

  // ---- the arm ---------------------------------------------------------
  if (el.preset && !el.preset.options.length) {
    for (const [key, p] of Object.entries(ARM_PRESETS)) el.preset.add(new Option(p.label, key));
    el.preset.add(new Option('Custom', 'custom'));
  }

  function linkInputs(links) {
    if (!el.links) return;
    el.links.replaceChildren(
      ...links.map((l, i) => {
        const label = document.createElement('label');
        const input = document.createElement('input');
        input.type = 'number';
        input.min = '0.05';
        input.max = '3';
        input.step = '0.05';
        input.value = String(l);
        input.dataset.link = String(i);
        input.setAttribute('aria-label', `Length of link ${i + 1} (m)`);
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
    if (el.preset) {
      const key = Object.entries(ARM_PRESETS).find(([, p]) => armKey(p) === armKey(arm))?.[0];
      el.preset.value = key ?? 'custom';
    }
  }

  // The weights files of the networks installed (trained, uploaded or
  // restored), for the workers and the download; the module keeps only
  // their run-time form. Tied to the arm they were installed for.
  let installed = null; // { arm: key, phi, v }
  function installNetworks(phi, v) {
    demo.loadNetworks(phi, v);
    installed = { arm: armKey(demo.state().arm), phi, v };
  }
  function files() {
    if (!installed || installed.arm !== armKey(demo.state().arm)) return null;
    return { phi: installed.phi, v: installed.v };
  }

  /** Networks kept in the browser for this arm, installed if they load. */
  function restoreWeights(arm) {
    const stored = storedWeights(arm);
    if (!stored) return false;
    try {
      installNetworks(stored.phi, stored.v);
      lastReport = stored.report ?? null;
      return true;
    } catch (e) {
      forgetWeights(arm);
      show(`Weights kept for this arm could not be loaded and were dropped: ${describe(e)}`, 'warn');
      return false;
    }
  }

  function setArm(arm) {
    if (!arm || typeof arm !== 'object' || !Array.isArray(arm.links)) {
      throw new Error('setArm expects { post, links: [L1, L2, ...] }');
    }
    if (arm.links.length < MIN_LINKS || arm.links.length > MAX_LINKS) {
      throw new Error(`the page takes ${MIN_LINKS} to ${MAX_LINKS} links (got ${arm.links.length})`);
    }
    demo.setArm(Number(arm.post), Float64Array.from(arm.links, Number));
    restoreWeights(demo.state().arm);
    syncForm(demo.state().arm);
    changed();
    return demo.state().arm;
  }

  const attempt = (fn) => {
    try {
      fn();
      return true;
    } catch (e) {
      show(describe(e), 'error');
      return false;
    }
  };

  el.preset?.addEventListener('change', () => {
    const p = ARM_PRESETS[el.preset.value];
    if (p) attempt(() => setArm(p));
  });
  el.apply?.addEventListener('click', () => attempt(() => setArm(formArm())));
  el.links?.addEventListener('change', () => attempt(() => setArm(formArm())));
  el.post?.addEventListener('change', () => attempt(() => setArm(formArm())));
  el.linkAdd?.addEventListener('click', () => {
    const a = formArm();
    if (a.links.length >= MAX_LINKS) return show(`At most ${MAX_LINKS} links.`, 'warn');
    attempt(() => setArm({ post: a.post, links: [...a.links, a.links[a.links.length - 1] ?? 0.4] }));
  });
  el.linkRemove?.addEventListener('click', () => {
    const a = formArm();
    if (a.links.length <= MIN_LINKS) return show(`At least ${MIN_LINKS} links.`, 'warn');
    attempt(() => setArm({ post: a.post, links: a.links.slice(0, -1) }));
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
  el.obstacleAdd?.addEventListener('click', () => {
    if (demo.state().obstacles.length >= MAX_OBSTACLES) return show(`At most ${MAX_OBSTACLES} obstacles.`, 'warn');
    setAdding(!adding);
  });
  el.obstacleRemove?.addEventListener('click', () => {
    const n = demo.state().obstacles.length;
    if (n === 0) return show('There is no obstacle to remove.', 'warn');
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

  let listKey = '';
  function syncObstacles(s) {
    if (!el.obstacleList) return;
    const key = formatObstacles(s.obstacles) + `|${s.nearest}`;
    if (key === listKey) return;
    listKey = key;
    el.obstacleList.replaceChildren(
      ...s.obstacles.map((o, i) => {
        const li = document.createElement('li');
        li.dataset.index = String(i);
        const text = `#${i + 1} (${o.centre[0].toFixed(2)}, ${o.centre[1].toFixed(2)})`;
        const r = document.createElement('input');
        r.type = 'number';
        r.min = '0.01';
        r.max = '1';
        r.step = '0.01';
        r.value = String(o.radius);
        r.setAttribute('aria-label', `Radius of obstacle ${i + 1} (m)`);
        r.addEventListener('change', () => {
          const all = demo.state().obstacles.map((b) => [...b.centre, b.radius]);
          all[i][2] = Number(r.value);
          if (attempt(() => demo.setObstacles(flatObstacles(all)))) changed();
        });
        const del = document.createElement('button');
        del.type = 'button';
        del.textContent = '×';
        del.title = `Remove obstacle ${i + 1}`;
        del.addEventListener('click', () => attempt(() => removeObstacle(i)));
        li.append(text, ' r ', r, ' ', del);
        if (s.nearest === i) li.classList.add('nearest');
        return li;
      }),
    );
  }

  // ---- training --------------------------------------------------------
  let training = null; // AbortController of the job under way
  let lastReport = null;
  let curves = {};

  function reportText(report, ms) {
    const lines = [];
    if (ms !== undefined) lines.push(`Trained in ${fmtS(ms / 1000)}.`);
    lines.push(
      `Test errors on ${report.phi_error.samples} fresh samples (relative): Φ median ${sci(report.phi_error.median)}, 99th percentile ${sci(report.phi_error.p99)}; v median ${sci(report.v_error.median)}.`,
    );
    if (report.random_tasks_note) lines.push(`No check on random tasks: ${report.random_tasks_note}.`);
    return lines;
  }

  function showReport(report, ms) {
    if (!el.trainReport) return;
    const parts = reportText(report, ms).map((t) => {
      const p = document.createElement('p');
      p.textContent = t;
      return p;
    });
    const table = document.createElement('table');
    table.className = 'compare';
    table.innerHTML = '<thead><tr><th>check</th><th>method</th><th>ok</th><th>hit</th><th>median error</th></tr></thead>';
    const body = document.createElement('tbody');
    for (const t of report.paper_tasks) {
      const tr = document.createElement('tr');
      const ok = !t.error && !t.collided && t.final_error <= 0.005;
      for (const c of [`Task ${t.task}`, t.mode, ok ? 'yes' : 'no', t.collided ? 'yes' : 'no', mm(t.final_error)]) {
        const td = document.createElement('td');
        td.textContent = c;
        tr.append(td);
      }
      body.append(tr);
    }
    for (const c of report.random_tasks) {
      const tr = document.createElement('tr');
      tr.dataset.mode = c.mode;
      tr.dataset.feedback = String(c.feedback);
      tr.dataset.succeeded = String(c.succeeded);
      for (const t of [
        `${c.tasks} random tasks, K = ${c.feedback}`,
        c.mode,
        `${c.succeeded}/${c.tasks}`,
        String(c.collided),
        mm(c.median_final_error),
      ]) {
        const td = document.createElement('td');
        td.textContent = t;
        tr.append(td);
      }
      body.append(tr);
    }
    table.append(body);
    const note = document.createElement('p');
    note.className = 'hint';
    note.textContent =
      'Random tasks: straight lines inside this arm\'s reach with one obstacle that the arm hits without avoidance and that the numerical route avoids; ok = no collision and within 5 mm of the target. K = 1 corrects drift (the "Correct drift" switch).';
    el.trainReport.replaceChildren(...parts, table, note);
    el.trainReport.hidden = false;
  }

  async function train(options = {}) {
    if (training) throw new Error('a training job is already running');
    const allowed = ['net', 'preset', 'samples', 'epochs', 'seed', 'onProgress'];
    for (const k of Object.keys(options)) {
      if (!allowed.includes(k)) throw new Error(`train: unknown option '${k}', expected one of ${allowed.join(', ')}`);
    }
    const s = demo.state();
    const request = {
      arm: s.arm,
      net: options.net ?? el.trainNet?.value ?? 'both',
      preset: options.preset ?? el.trainPreset?.value ?? 'quick',
    };
    for (const k of ['samples', 'epochs', 'seed']) if (options[k] !== undefined) request[k] = options[k];
    const current = files();
    training = new AbortController();
    curves = {};
    const t0 = performance.now();
    let tFirstEpoch = null;
    if (el.trainRun) el.trainRun.disabled = true;
    if (el.trainCancel) el.trainCancel.hidden = false;
    if (el.trainProgress) {
      el.trainProgress.hidden = false;
      el.trainProgress.value = 0;
    }
    const status = (t) => el.trainStatus && (el.trainStatus.textContent = t);
    status('Sampling the numerical route…');
    drawCurves(el.trainCurves, curves);
    try {
      const { result, ms } = await runWorker(
        { kind: 'train', request, phi: current?.phi, v: current?.v },
        {
          signal: training.signal,
          onProgress: (p) => {
            if (el.trainProgress) el.trainProgress.value = p.done / p.total;
            if (!p.epoch) return;
            const e = p.epoch;
            (curves[e.net] ??= []).push({ epoch: e.epoch, train_mse: e.train_mse, val_mse: e.val_mse });
            tFirstEpoch ??= performance.now();
            const elapsed = (performance.now() - t0) / 1000;
            const perEpoch = (performance.now() - tFirstEpoch) / 1000 / Math.max(1, p.done - 1);
            const left = Math.max(0, (p.total - p.done) * perEpoch);
            status(
              `${e.net === 'phi' ? 'Φ' : 'v'} network: epoch ${e.epoch} of at most ${e.max_epochs}, μ ${sci(e.mu)}, train ${sci(e.train_mse)}, validation ${sci(e.val_mse)} · ${fmtS(elapsed)} elapsed, at most ${fmtS(left)} left`,
            );
            if (el.trainStatus) Object.assign(el.trainStatus.dataset, { epoch: String(e.epoch), net: e.net });
            drawCurves(el.trainCurves, curves);
            if (options.onProgress) options.onProgress({ ...e, done: p.done, total: p.total, elapsed_s: elapsed, left_s: left });
          },
        },
      );
      // Swap the networks in; on failure the ones in use stay.
      installNetworks(result.phi, result.v);
      const arm = demo.state().arm;
      const kept = storeWeights(arm, { phi: result.phi, v: result.v, report: result.report, saved: new Date().toISOString() });
      lastReport = result.report;
      const seconds = (performance.now() - t0) / 1000;
      status(`Done in ${fmtS(seconds)}; Cases 1-3 now use these networks${kept ? ', kept in this browser for this arm' : ' (not kept: browser storage unavailable)'}.`);
      showReport(result.report, performance.now() - t0);
      changed();
      return { ...result.report, seconds, worker_ms: ms, stored: kept };
    } catch (e) {
      if (e.name === 'AbortError') {
        status('Cancelled; the networks in use are unchanged.');
      } else {
        status(`Training failed: ${describe(e)}. The networks in use are unchanged.`);
      }
      throw e;
    } finally {
      training = null;
      if (el.trainRun) el.trainRun.disabled = false;
      if (el.trainCancel) el.trainCancel.hidden = true;
      if (el.trainProgress) el.trainProgress.hidden = true;
    }
  }

  // The empty plot says what will appear once the panel is open (a closed panel has no size).
  el.trainPanel?.addEventListener('toggle', () => el.trainPanel.open && drawCurves(el.trainCurves, curves));
  el.trainRun?.addEventListener('click', () => train().catch(() => {}));
  el.trainCancel?.addEventListener('click', () => training && training.abort());
  el.trainForArm?.addEventListener('click', () => {
    if (el.trainPanel) {
      el.trainPanel.open = true;
      el.trainPanel.scrollIntoView({ block: 'nearest' });
    }
    train().catch(() => {});
  });

  function exportWeights() {
    const f = files();
    if (!f) throw new Error('no networks trained or loaded for this arm to export (the built-in ones ship as weights/*.json)');
    return f;
  }

  el.trainDownload?.addEventListener('click', () =>
    attempt(() => {
      const files = exportWeights();
      const tag = armKey(demo.state().arm).replace(/[:,]/g, '_');
      for (const [name, text] of Object.entries(files)) {
        const a = document.createElement('a');
        a.href = URL.createObjectURL(new Blob([text + '\n'], { type: 'application/json' }));
        a.download = `${name}-${tag}.json`;
        document.body.append(a);
        a.click();
        a.remove();
        setTimeout(() => URL.revokeObjectURL(a.href), 1000);
      }
    }),
  );
  el.trainForget?.addEventListener('click', () =>
    attempt(() => {
      const arm = demo.state().arm;
      forgetWeights(arm);
      demo.clearNetworks();
      installed = null;
      lastReport = null;
      if (el.trainReport) el.trainReport.hidden = true;
      show('Trained networks for this arm forgotten.', 'info');
      changed();
    }),
  );

  // ---- the loop --------------------------------------------------------
  let armShown = '';
  let fitShown = null;
  function check(s) {
    const key = armKey(s.arm);
    if (key !== armShown) {
      armShown = key;
      syncForm(s.arm);
    }
    syncObstacles(s);
    const fit = demo.networksFit();
    if (fit !== fitShown) {
      fitShown = fit;
      for (const o of root.querySelectorAll('#mode option')) {
        if (o.value.startsWith('case')) o.disabled = !fit;
      }
      if (el.trainForArm) el.trainForArm.hidden = fit;
    }
  }

  /** A whole run off screen: `{ mode, target?, obstacles?, tf?, theta0? }` -> summary. */
  function simulate(options) {
    const allowed = ['mode', 'target', 'obstacles', 'tf', 'theta0'];
    if (!options || typeof options !== 'object') throw new Error('simulate expects { mode, target?, obstacles?, tf?, theta0? }');
    for (const k of Object.keys(options)) {
      if (!allowed.includes(k)) throw new Error(`simulate: unknown option '${k}', expected one of ${allowed.join(', ')}`);
    }
    const nums = (v, what) => {
      if (v === undefined) return undefined;
      if (!Array.isArray(v)) throw new Error(`simulate: ${what} must be a list of numbers`);
      return Float64Array.from(v, Number);
    };
    return demo.simulate(
      String(options.mode),
      nums(options.target, 'target'),
      options.obstacles === undefined ? undefined : flatObstacles(options.obstacles),
      options.tf === undefined ? undefined : Number(options.tf),
      nums(options.theta0, 'theta0'),
    );
  }

  return {
    simulate,
    setArm,
    addObstacle,
    removeObstacle,
    obstacles: () => demo.state().obstacles.map((o) => ({ x: o.centre[0], y: o.centre[1], r: o.radius })),
    train,
    exportWeights,
    wantsClick: () => adding,
    click(x, y) {
      setAdding(false);
      const [wx, wy] = demo.canvasToWorld(x, y);
      return addObstacle(wx, wy);
    },
    check,
    /** Installs the weights kept for the arm in use, with their report (at start-up). */
    restore() {
      restoreWeights(demo.state().arm);
      if (lastReport) showReport(lastReport);
    },
    installNetworks,
    files,
  };
}
