// The training panel: networks trained for the arm in use in a Web Worker
// (the workers' trainNetworks, Levenberg-Marquardt as `redundant-ik
// train`), live training curves, the report, the download of the weights
// and forgetting them. The networks trained are installed and kept through
// the playground's hooks.

import { describe, limits, networkMethodLabels, formatArm, builtinWeightsUrl, builtinWeightsFiles, networkSets, trainingPresets } from './module.js';
import { runWorker, showBusy } from './jobs.js';
import { metres, sci, seconds as fmtS, row } from './format.js';

/** Draws MSE curves per epoch on a log scale: `series` is `{ name: [{ epoch, train_mse, val_mse }] }` (both pages' training panels). */
export function drawCurves(canvas, series) {
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
  const lo = Math.floor(Math.log10(Math.min(...values)));
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
  // The epoch axis; the key of the curves is under the chart (.train-key).
  ctx.textAlign = 'right';
  ctx.fillText(`epoch ${maxEpoch}`, W - pad.r, H - 5);
  ctx.textAlign = 'left';
  ctx.fillText('0', pad.l, H - 5);
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
  }
}

/** The report's table: the paper's tasks, then the random tasks' counts. */
function reportTable(report) {
  const table = document.createElement('table');
  table.className = 'compare';
  table.innerHTML = '<thead><tr><th>check</th><th>method</th><th>ok</th><th>hit</th><th>median error</th></tr></thead>';
  const body = document.createElement('tbody');
  for (const t of report.paper_tasks) {
    const ok = t.success;
    const loop = `${t.feedback_gain ? `, K = ${t.feedback_gain}` : ''}${t.refine ? `, refine ${t.refine}` : ''}`;
    body.append(row([`Task ${t.task}${loop}`, t.method, ok ? 'yes' : 'no', t.collided ? 'yes' : 'no', metres(t.final_error)]));
  }
  for (const c of report.random_tasks) {
    const tr = row([
      `${c.tasks} random tasks, K = ${c.feedback}${c.refine ? `, refine ${c.refine}` : ''}`,
      c.method,
      `${c.succeeded}/${c.tasks}`,
      String(c.collided),
      metres(c.median_final_error),
    ]);
    Object.assign(tr.dataset, { method: c.method, feedback: String(c.feedback), refine: String(c.refine), succeeded: String(c.succeeded) });
    body.append(tr);
  }
  table.append(body);
  return table;
}

/**
 * Wires the training panel's elements under `root` that exist
 * (`#train-panel`, `#train-preset`, `#train-net`, `#train-run`,
 * `#train-cancel`, `#train-progress`, `#train-status`, `#train-curves`,
 * `#train-report`, `#train-download`, `#train-forget`, `#train-for-arm`,
 * and beside the drawing `#verdict-warning`, `#verdict-text`,
 * `#verdict-use`, `#verdict-dismiss`: networks that fail their own check
 * are not swapped in unless the user asks).
 * Hooks: `files()` (the weights files in use, or null), `install(phi, v)`,
 * `keep(arm, entry)` (whether kept), `forget()`, `attempt(fn)`, `show(text,
 * kind)`, `changed()`. Returns `{ train(options), exportWeights(),
 * showReport(report), forgetReport() }`.
 */
export function mountTraining(root, demo, { files, install, keep, forget, attempt, show, changed }) {
  const $ = (id) => root.querySelector('#' + id);
  const el = {
    panel: $('train-panel'),
    preset: $('train-preset'),
    net: $('train-net'),
    run: $('train-run'),
    cancel: $('train-cancel'),
    progress: $('train-progress'),
    status: $('train-status'),
    curves: $('train-curves'),
    report: $('train-report'),
    download: $('train-download'),
    forget: $('train-forget'),
    forArm: $('train-for-arm'),
    verdict: $('verdict-warning'),
    verdictText: $('verdict-text'),
    verdictUse: $('verdict-use'),
    verdictDismiss: $('verdict-dismiss'),
  };
  // The presets and their sizes are the core's; the first is the default.
  const presets = trainingPresets();
  if (el.preset && !el.preset.options.length) {
    for (const p of presets) el.preset.add(new Option(p.label, p.name));
  }
  let pending = null; // trained networks that failed their check: { arm, entry }
  let last = null; // the last training's report

  let training = null; // AbortController of the job under way
  let curves = {};

  function showReport(report, ms) {
    if (!el.report) return;
    const lines = [];
    if (ms !== undefined) lines.push(`Trained in ${fmtS(ms / 1000)}.`);
    lines.push(
      `Test errors on ${report.phi_error.samples} fresh samples (relative): Φ median ${sci(report.phi_error.median)}, 99th percentile ${sci(report.phi_error.p99)}; v median ${sci(report.v_error.median)}.`,
    );
    if (report.random_tasks_note) lines.push(`No check on random tasks: ${report.random_tasks_note}.`);
    const parts = lines.map((t) => {
      const p = document.createElement('p');
      p.textContent = t;
      return p;
    });
    const note = document.createElement('p');
    note.className = 'hint';
    note.textContent =
      "Random tasks: straight lines inside this arm's reach with one obstacle that the arm hits without avoidance and that the numerical route avoids; " +
      `ok = no collision and within ${limits().reach_tolerance * 1000} mm of the target. K = ${limits().drift_gain} corrects drift (the "Correct drift" switch).`;
    el.report.replaceChildren(...parts, reportTable(report), note);
    el.report.hidden = false;
  }

  const status = (t) => el.status && (el.status.textContent = t);

  /** Follows a job's progress: the bar, the curves, the status line. */
  function follower(t0, onProgress) {
    let tFirstEpoch = null;
    return (p) => {
      if (el.progress) el.progress.value = p.done / p.total;
      if (!p.epoch) return;
      const e = p.epoch;
      (curves[e.net] ??= []).push({ epoch: e.epoch, train_mse: e.train_mse, val_mse: e.val_mse });
      tFirstEpoch ??= performance.now();
      const elapsed = (performance.now() - t0) / 1000;
      const perEpoch = (performance.now() - tFirstEpoch) / 1000 / Math.max(1, p.done - 1);
      const left = Math.max(0, (p.total - p.done) * perEpoch);
      status(
        `${e.net === 'phi' ? 'Φ' : 'v'} network: epoch ${e.epoch} of at most ${e.max_epochs}, ${e.optimiser === 'adam' ? 'learning rate η' : 'μ'} ${sci(e.mu)}, train ${sci(e.train_mse)}, validation ${sci(e.val_mse)} · ${fmtS(elapsed)} elapsed, at most ${fmtS(left)} left`,
      );
      if (el.status) Object.assign(el.status.dataset, { epoch: String(e.epoch), net: e.net });
      drawCurves(el.curves, curves);
      if (onProgress) onProgress({ ...e, done: p.done, total: p.total, elapsed_s: elapsed, left_s: left });
    };
  }

  /** Trains networks for the arm in use: `{ net, preset, samples, epochs, seed, onProgress }`, each optional. */
  async function train(options = {}) {
    if (training) throw new Error('a training job is already running');
    const allowed = ['net', 'preset', 'samples', 'epochs', 'seed', 'onProgress'];
    for (const k of Object.keys(options)) {
      if (!allowed.includes(k)) throw new Error(`train: unknown option '${k}', expected one of ${allowed.join(', ')}`);
    }
    const request = {
      arm: demo.state().arm,
      net: options.net ?? el.net?.value ?? 'both',
      preset: options.preset ?? el.preset?.value ?? presets[0].name,
    };
    for (const k of ['samples', 'epochs', 'seed']) if (options[k] !== undefined) request[k] = options[k];
    training = new AbortController();
    curves = {};
    const t0 = performance.now();
    showBusy(el, true);
    status('Sampling the numerical route…');
    drawCurves(el.curves, curves);
    try {
      const follow = follower(t0, options.onProgress);
      const { result, ms } = parallel(request)
        ? await trainBothAtOnce(request, training.signal, follow)
        : await runWorker({ kind: 'train', request, run: demo.run() }, { signal: training.signal, onProgress: follow });
      const seconds = (performance.now() - t0) / 1000;
      const entry = { phi: result.phi, v: result.v, report: result.report, saved: new Date().toISOString() };
      showReport(result.report, performance.now() - t0);
      last = result.report;
      const verdict = result.report.verdict;
      if (!verdict.passed) {
        // Networks that fail their own check stay out unless the user asks.
        pending = { arm: formatArm(request.arm.post, request.arm.links), entry };
        warnVerdict(verdict);
        status(`Done in ${fmtS(seconds)}, but these networks fail their own check: the networks in use are unchanged (see the warning beside the drawing).`);
        return { ...result.report, seconds, worker_ms: ms, stored: false, installed: false };
      }
      // Swap the networks in; on failure the ones in use stay.
      const { kept, restarted } = use(entry);
      status(
        `Done in ${fmtS(seconds)}; ${networkMethodLabels()} now use these networks${kept ? ', kept in this browser for this arm' : ' (not kept: browser storage unavailable)'}${restarted ? '; the run restarted with them' : ''}.`,
      );
      return { ...result.report, seconds, worker_ms: ms, stored: kept, installed: true };
    } catch (e) {
      status(e.name === 'AbortError' ? 'Cancelled; the networks in use are unchanged.' : `Training failed: ${describe(e)}. The networks in use are unchanged.`);
      throw e;
    } finally {
      training = null;
      showBusy(el, false);
    }
  }

  /**
   * Both networks at once where the browser has two cores or more: each in
   * its own worker, then the check in a third (`docs/learning.md`,
   * "Training in the page"). The networks and the report are those of the
   * one-worker job (each network's seed depends on the request alone).
   */
  function parallel(request) {
    return request.net === 'both' && (navigator.hardwareConcurrency ?? 1) >= 2;
  }

  async function trainBothAtOnce(request, signal, follow) {
    // One failure stops the other worker too.
    const both = new AbortController();
    const stop = () => both.abort();
    signal.addEventListener('abort', stop);
    let first = null; // the error that stopped the job, not the abort it caused
    const parts = {};
    const progress = (net) => (p) => {
      parts[net] = p;
      const done = Object.values(parts).reduce((a, q) => a + q.done, 0);
      const total = Object.values(parts).reduce((a, q) => a + q.total, 0);
      follow({ ...p, done: done / Object.keys(parts).length, total: total / Object.keys(parts).length });
    };
    try {
      const jobs = ['phi', 'v'].map((net) =>
        runWorker({ kind: 'train-net', request, net }, { signal: both.signal, onProgress: progress(net) }).catch((e) => {
          first ??= e;
          both.abort();
          throw first;
        }),
      );
      const [phi, v] = await Promise.all(jobs);
      status('Checking the networks on the tasks…');
      const check = await runWorker({ kind: 'conclude', request, phi: phi.result, v: v.result }, { signal: both.signal });
      return { result: check.result, ms: Math.max(phi.ms, v.ms) + check.ms };
    } finally {
      signal.removeEventListener('abort', stop);
    }
  }

  /**
   * Installs and keeps trained networks, and restarts the run on screen
   * where its method uses networks (it would go on with the old ones until
   * replayed); whether they were kept, and the run restarted.
   */
  function use(entry) {
    install(entry.phi, entry.v);
    const kept = keep(demo.state().arm, entry);
    hideVerdict();
    const { uses } = demo.state();
    const restarted = uses.phi || uses.v;
    if (restarted) demo.runTask();
    changed();
    return { kept, restarted };
  }

  function warnVerdict(verdict) {
    if (!el.verdict) return;
    el.verdictText.textContent =
      `The networks just trained for this arm fail their own check (${verdict.checked}): ${verdict.failures.join('; ')}. ` +
      `The networks in use stay; ${networkMethodLabels()} would extrapolate with these.`;
    el.verdict.hidden = false;
  }
  function hideVerdict() {
    pending = null;
    if (el.verdict) el.verdict.hidden = true;
  }
  el.verdictUse?.addEventListener('click', () => {
    if (!pending) return;
    if (pending.arm !== demo.state().arm_text) {
      hideVerdict();
      return show('Those networks were trained for another arm.', 'warn', false, el.verdictUse);
    }
    const entry = pending.entry;
    let restarted = false;
    if (!attempt(() => ({ restarted } = use(entry)), 'error', el.verdictUse)) return;
    status(`${networkMethodLabels()} now use the networks just trained, although they fail their own check${restarted ? '; the run restarted with them' : ''}.`);
    show('In use although they fail their check: compare with the dashed numerical ghost.', 'warn', false, el.verdictUse);
  });
  el.verdictDismiss?.addEventListener('click', () => {
    hideVerdict();
    status('The networks just trained were set aside; the networks in use are unchanged.');
  });

  // The empty plot says what will appear once the panel is open (a closed panel has no size).
  el.panel?.addEventListener('toggle', () => el.panel.open && drawCurves(el.curves, curves));
  el.run?.addEventListener('click', () => train().catch(() => {}));
  el.cancel?.addEventListener('click', () => training && training.abort());
  el.forArm?.addEventListener('click', () => {
    if (el.panel) {
      el.panel.open = true;
      el.panel.scrollIntoView({ block: 'nearest' });
    }
    train().catch(() => {});
  });

  function exportWeights() {
    const f = files();
    if (!f) throw new Error('no networks trained or loaded for this arm to export');
    return f;
  }

  const save = (name, text) => {
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob([text.endsWith('\n') ? text : text + '\n'], { type: 'application/json' }));
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  };
  el.download?.addEventListener('click', async () => {
    const tag = demo.state().arm_text.replace(/[:,]/g, '_');
    const own = files();
    if (own) {
      for (const [name, text] of Object.entries(own)) save(`${name}-${tag}.json`, text);
      return;
    }
    // The built-in networks, where they run: the files served beside the page.
    if (!demo.state().networks) {
      return show('No networks for this arm yet: train them first.', 'warn', false, el.download);
    }
    // The shipped set in use (the paper's where none was chosen).
    const set = demo.run().networks?.set ?? networkSets()[0].name;
    const label = networkSets().find((s) => s.name === set)?.label ?? set;
    try {
      for (const name of builtinWeightsFiles(set)) {
        const r = await fetch(builtinWeightsUrl(name));
        if (!r.ok) throw new Error(`HTTP ${r.status} for weights/${name}`);
        save(name, await r.text());
      }
      show(`The networks in use (${label}), as shipped: the files redundant-ik train writes.`, 'info', false, el.download);
    } catch (e) {
      show(`Could not fetch the built-in networks: ${describe(e)}`, 'error', false, el.download);
    }
  });
  el.forget?.addEventListener('click', () =>
    attempt(() => {
      forget();
      if (el.report) el.report.hidden = true;
      show('Trained networks for this arm forgotten.', 'info');
      changed();
    }),
  );

  /** Shows the button that trains for this arm where the network methods cannot run. */
  function check(s) {
    if (el.forArm) el.forArm.hidden = s.networks;
  }

  return { train, exportWeights, showReport, check, last: () => last };
}
