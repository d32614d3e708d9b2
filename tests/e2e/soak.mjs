// Browser soak of the demo (make soak; scripts/e2e.sh serves www/ and runs
// this with E2E_SCRIPT=soak.mjs). For SOAK_SECONDS (default 600) it does
// what a restless user does, at random (seeded: SOAK_SEED, default 1):
// drags the target and the obstacles with the mouse, switches methods,
// loads the tasks, toggles damping and drift correction, changes the arm,
// adds and removes obstacles, runs small atlases and short trainings in
// their workers, and resizes the window, with the animation running
// between actions.
//
// It fails on any console error, page exception or panic, and on memory
// growth: every 10 s, after a forced garbage collection, it records the
// page's JS heap (CDP Runtime.getHeapUsage) and the wasm module's linear
// memory; from the end of the first minute (a third of the run, for runs
// shorter than three minutes) to the end, neither may grow more than 10%
// (medians of three samples). Workers are separate heaps that end with
// their job.
//
// Writes the samples as JSON to SOAK_OUT (default target/soak.json) and,
// with SOAK_SVG set, the memory curve as an SVG (docs/img/soak-memory.svg).
// With SOAK_HEAP_DIFF set it also takes a heap snapshot at the baseline and
// at the end and prints the object kinds whose total size grew most (for
// finding what a growing heap holds).

import { launchChromium } from './chromium.mjs';
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname } from 'node:path';
import assert from 'node:assert/strict';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const SECONDS = Number(process.env.SOAK_SECONDS ?? 600);
const OUT = process.env.SOAK_OUT ?? 'target/soak.json';
const SVG = process.env.SOAK_SVG;
const SAMPLE_EVERY = 10;
const BASELINE_AT = Math.min(60, SECONDS / 3);
const LIMIT = 1.1;

// Seeded so that a failure can be replayed (mulberry32).
let seed = Number(process.env.SOAK_SEED ?? 1) >>> 0;
function random() {
  seed = (seed + 0x6d2b79f5) >>> 0;
  let t = seed;
  t = Math.imul(t ^ (t >>> 15), t | 1);
  t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
  return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
}
const pick = (xs) => xs[Math.floor(random() * xs.length)];
const between = (a, b) => a + (b - a) * random();

const ARMS = [
  { post: 0.5, links: [0.6, 0.85, 0.6] },
  { post: 0.5, links: [0.6, 0.85, 0.6] },
  { post: 0.5, links: [0.6, 0.85, 0.6, 0.4] },
  { post: 0.3, links: [0.8, 0.7] },
  { post: 0.4, links: [0.5, 0.5, 0.4, 0.3, 0.3] },
];

const browser = await launchChromium();
const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
const page = await context.newPage();
const problems = [];
page.on('console', (m) => {
  if (m.type() === 'error') problems.push(`console error: ${m.text()}`);
});
page.on('pageerror', (e) => problems.push(`page exception: ${e.message}`));
page.on('crash', () => problems.push('the page crashed'));
// The page's default method (the module's defaultMethod()).
await page.goto(`${BASE}?task=1`);
await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
const cdp = await context.newCDPSession(page);

async function memory() {
  await cdp.send('HeapProfiler.collectGarbage');
  const heap = await cdp.send('Runtime.getHeapUsage');
  const wasm = await page.evaluate(() => window.demo.wasmMemoryBytes());
  return { js: heap.usedSize, wasm };
}

/** Self size and count per object name in a heap snapshot (CDP). */
async function heapCensus() {
  await cdp.send('HeapProfiler.collectGarbage');
  const chunks = [];
  const collect = (e) => chunks.push(e.chunk);
  cdp.on('HeapProfiler.addHeapSnapshotChunk', collect);
  await cdp.send('HeapProfiler.takeHeapSnapshot', { reportProgress: false });
  cdp.off('HeapProfiler.addHeapSnapshotChunk', collect);
  const snap = JSON.parse(chunks.join(''));
  const f = snap.snapshot.meta.node_fields;
  const types = snap.snapshot.meta.node_types[0];
  const [iType, iName, iSize] = ['type', 'name', 'self_size'].map((k) => f.indexOf(k));
  const census = new Map();
  for (let i = 0; i < snap.nodes.length; i += f.length) {
    const type = types[snap.nodes[i + iType]];
    const named = type === 'object' || type === 'closure' || type === 'native';
    const name = named ? `${type === 'native' ? '(native) ' : ''}${snap.strings[snap.nodes[i + iName]]}` : `(${type})`;
    const c = census.get(name) ?? { size: 0, count: 0 };
    c.size += snap.nodes[i + iSize];
    c.count += 1;
    census.set(name, c);
  }
  return census;
}

async function drag(from, to) {
  const a = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), from);
  const b = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), to);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  const steps = 8;
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(a.x + ((b.x - a.x) * i) / steps, a.y + ((b.y - a.y) * i) / steps);
  }
  await page.mouse.up();
}

const state = () => page.evaluate(() => window.demo.state());
// A control's own click (as a keyboard user's), wherever a resize left it.
const press = (id) => page.evaluate((id) => document.getElementById(id).click(), id);
const reach = (s) => s.arm.links.reduce((x, y) => x + y, 0);
const randomPoint = (s) => {
  const r = reach(s) * Math.sqrt(random()) * 0.95;
  const a = between(-Math.PI / 2, Math.PI / 2);
  return [r * Math.sin(a), s.arm.post + r * Math.cos(a)];
};

const counts = {};
const actions = {
  async 'drag target'() {
    const s = await state();
    await drag(s.target, randomPoint(s));
  },
  async 'drag obstacle'() {
    const s = await state();
    if (!s.obstacles.length) return;
    const o = pick(s.obstacles);
    await drag(o.centre, randomPoint(s));
  },
  async 'switch method'() {
    const enabled = await page.$$eval('#mode option', (os) => os.filter((o) => !o.disabled).map((o) => o.value));
    await page.selectOption('#mode', pick(enabled));
  },
  async 'load task'() {
    await press(pick(['task1', 'task2']));
  },
  async 'toggle damping'() {
    await press('damping');
  },
  async 'toggle drift correction'() {
    await press('feedback');
  },
  async 'change arm'() {
    await page.evaluate((arm) => window.demo.setArm(arm), pick(ARMS));
  },
  async 'add obstacle'() {
    const s = await state();
    if (s.obstacles.length >= 8) return;
    const [x, y] = randomPoint(s);
    // Refused on the post: the page says so, and the soak goes on.
    await page.evaluate(([x, y, r]) => {
      try {
        window.demo.addObstacle(x, y, r);
      } catch (_) {
        /* on the post */
      }
    }, [x, y, between(0.03, 0.12)]);
  },
  async 'remove obstacle'() {
    const s = await state();
    if (s.obstacles.length > 1) await page.evaluate((i) => window.demo.removeObstacle(i), Math.floor(random() * s.obstacles.length));
  },
  async 'small atlas'() {
    const names = (await page.evaluate(() => window.demo.methods())).map((m) => m.name);
    const methods = names.filter(() => random() < 0.5);
    if (!methods.length) methods.push(pick(names));
    await page.evaluate(
      async ({ n, methods }) => {
        try {
          await window.demo.atlas({ n, methods });
        } catch (e) {
          // The network methods on an arm without networks are refused: fine.
          if (!/network/i.test(e.message)) throw e;
        }
      },
      { n: 3 + Math.floor(random() * 6), methods },
    );
  },
  async 'short training'() {
    await page.evaluate(() => window.demo.train({ preset: 'quick', samples: 60, epochs: 3 }));
  },
  async 'resize window'() {
    await page.setViewportSize({ width: Math.round(between(360, 1600)), height: Math.round(between(500, 1100)) });
  },
  async 'play or pause'() {
    await press('play');
  },
};
// How often each happens, relative.
const weights = {
  'drag target': 6,
  'drag obstacle': 4,
  'switch method': 3,
  'load task': 2,
  'toggle damping': 1,
  'toggle drift correction': 1,
  'change arm': 1,
  'add obstacle': 1,
  'remove obstacle': 1,
  'small atlas': 1,
  'short training': 0.5,
  'resize window': 1,
  'play or pause': 1,
};
const bag = Object.entries(weights).flatMap(([name, w]) => Array(Math.round(w * 2)).fill(name));

const samples = [];
const t0 = Date.now();
const elapsed = () => (Date.now() - t0) / 1000;
let nextSample = 0;
let failure = null;
let census0 = null;
while (elapsed() < SECONDS && !failure) {
  if (process.env.SOAK_HEAP_DIFF && !census0 && elapsed() >= BASELINE_AT) census0 = await heapCensus();
  if (elapsed() >= nextSample) {
    const m = await memory();
    samples.push({ t: Math.round(elapsed()), ...m });
    console.log(`soak: t = ${Math.round(elapsed())} s, JS heap ${(m.js / 1048576).toFixed(2)} MB, wasm memory ${(m.wasm / 1048576).toFixed(2)} MB`);
    nextSample += SAMPLE_EVERY;
  }
  const name = pick(bag);
  try {
    await actions[name]();
    counts[name] = (counts[name] ?? 0) + 1;
  } catch (e) {
    failure = `${name}: ${e.message}`;
  }
  if (problems.length) failure = problems.join('\n');
  await page.waitForTimeout(between(50, 600));
}
const last = await memory();
samples.push({ t: Math.round(elapsed()), ...last });
if (census0) {
  const census1 = await heapCensus();
  const rows = [...census1].map(([name, c]) => {
    const b = census0.get(name) ?? { size: 0, count: 0 };
    return { name: name.slice(0, 60), bytes: c.size - b.size, count: c.count - b.count };
  });
  rows.sort((a, b) => b.bytes - a.bytes);
  console.log('soak: heap growth since the baseline, by object kind (bytes, count):');
  for (const r of rows.slice(0, 25)) console.log(`  ${String(r.bytes).padStart(9)} ${String(r.count).padStart(7)}  ${r.name}`);
}
await browser.close();

mkdirSync(dirname(OUT), { recursive: true });
writeFileSync(OUT, JSON.stringify({ seconds: SECONDS, baseline_at: BASELINE_AT, counts, samples }, null, 1));
console.log(`soak: actions ${JSON.stringify(counts)}`);

// Each figure is judged by medians of three samples, as a forced GC still
// leaves some noise (the JIT's code comes and goes): the baseline is the
// median of the three samples from BASELINE_AT on, the end the median of
// the last three.
const median3 = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const from = samples.findIndex((s) => s.t >= BASELINE_AT);
const baseSamples = samples.slice(from < 0 ? 0 : from, (from < 0 ? 0 : from) + 3);
const endSamples = samples.slice(-3);
const base = { t: baseSamples[0].t, js: median3(baseSamples.map((s) => s.js)), wasm: median3(baseSamples.map((s) => s.wasm)) };
const end = { js: median3(endSamples.map((s) => s.js)), wasm: median3(endSamples.map((s) => s.wasm)) };
const peak = (k) => Math.max(...samples.filter((s) => s.t >= base.t).map((s) => s[k]));
const growth = { js: end.js / base.js, wasm: end.wasm / base.wasm };
const mb = (v) => (v / 1048576).toFixed(2);
console.log(
  `soak: from ${base.t} s to the end, JS heap ${mb(base.js)} -> ${mb(end.js)} MB (x${growth.js.toFixed(3)}; peak ${mb(peak('js'))} MB), ` +
    `wasm memory ${mb(base.wasm)} -> ${mb(end.wasm)} MB (x${growth.wasm.toFixed(3)}; peak ${mb(peak('wasm'))} MB)`,
);
if (SVG) writeFileSync(SVG, curve(samples, base));

assert.equal(failure, null, `the soak failed: ${failure}`);
assert.ok(growth.js <= LIMIT, `the JS heap grew ${((growth.js - 1) * 100).toFixed(1)}% after ${base.t} s (limit 10%)`);
assert.ok(growth.wasm <= LIMIT, `the wasm memory grew ${((growth.wasm - 1) * 100).toFixed(1)}% after ${base.t} s (limit 10%)`);
console.log(`soak: ${SECONDS} s passed, no errors, memory within 10% after ${base.t} s`);

/** The memory curve: both series in MB over time, the 10% band from the baseline. */
function curve(samples, base) {
  const W = 640;
  const H = 300;
  const L = 56;
  const R = 16;
  const T = 20;
  const B = 40;
  const tMax = Math.max(...samples.map((s) => s.t), 1);
  const mb = (v) => v / 1048576;
  const yMax = Math.max(...samples.map((s) => Math.max(mb(s.js), mb(s.wasm)))) * 1.25;
  const x = (t) => L + ((W - L - R) * t) / tMax;
  const y = (v) => T + (H - T - B) * (1 - v / yMax);
  const line = (k) => samples.map((s) => `${x(s.t).toFixed(1)},${y(mb(s[k])).toFixed(1)}`).join(' ');
  const band = (k, colour) =>
    `<line x1="${x(base.t)}" x2="${x(tMax)}" y1="${y(mb(base[k]) * LIMIT)}" y2="${y(mb(base[k]) * LIMIT)}" stroke="${colour}" stroke-dasharray="4 3" stroke-width="1"/>`;
  const ticks = [];
  for (let v = 0; v <= yMax; v += yMax > 20 ? 10 : yMax > 8 ? 2 : 1) {
    ticks.push(`<text x="${L - 6}" y="${y(v) + 4}" text-anchor="end">${v}</text><line x1="${L}" x2="${W - R}" y1="${y(v)}" y2="${y(v)}" stroke="#eee"/>`);
  }
  for (let t = 0; t <= tMax; t += tMax > 300 ? 120 : 20) {
    ticks.push(`<text x="${x(t)}" y="${H - B + 16}" text-anchor="middle">${t}</text>`);
  }
  return `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" font-family="sans-serif" font-size="11">
<rect width="100%" height="100%" fill="white"/>
${ticks.join('\n')}
<line x1="${L}" x2="${L}" y1="${T}" y2="${H - B}" stroke="#444"/><line x1="${L}" x2="${W - R}" y1="${H - B}" y2="${H - B}" stroke="#444"/>
<text x="${(L + W - R) / 2}" y="${H - 8}" text-anchor="middle">time (s)</text>
<text x="14" y="${(T + H - B) / 2}" text-anchor="middle" transform="rotate(-90 14 ${(T + H - B) / 2})">MB</text>
${band('js', '#1f77b4')}${band('wasm', '#d62728')}
<polyline points="${line('js')}" fill="none" stroke="#1f77b4" stroke-width="2"/>
<polyline points="${line('wasm')}" fill="none" stroke="#d62728" stroke-width="2"/>
<text x="${L + 8}" y="${T + 12}" fill="#1f77b4">JS heap after GC</text>
<text x="${L + 8}" y="${T + 26}" fill="#d62728">wasm linear memory</text>
<text x="${W - R}" y="${T + 12}" text-anchor="end" fill="#666">dashed: +10% over the median from ${base.t} s</text>
</svg>
`;
}
