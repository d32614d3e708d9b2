// The Panda's slice atlas in the page's worker (window.demo.spaceAtlas, the
// workers' SpaceAtlasJob): the whole default slice, 21 x 21 cells, every
// method with the shipped networks, timed in headless Chromium (the goal:
// at most 8 s), and its JSON checked against the native tool's
// (`redundant-ik atlas --arm panda --methods all --grid 21 --threads 1
// --json`, written to a temporary file at run time): every string, class
// and count equal, every number within 1e-9 (relative above 1). Exits 1 on
// a difference.
//
//   BASE_URL=http://127.0.0.1:8000/ [RUNS=1] [IK=target/release/redundant-ik] node scripts/space-atlas-web.mjs
//
// `make bench-web` serves www/ and calls it after the page's benchmark
// (scripts/bench-web.sh); it needs `make web` and the native tool built
// (`cargo build --release`). Times are measurements on a shared machine.

import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
// playwright-core comes from tests/e2e/node_modules, through the shared launcher.
import { launchChromium } from '../tests/e2e/chromium.mjs';

const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
const RUNS = Number(process.env.RUNS ?? 1);
const IK = process.env.IK ?? 'target/release/redundant-ik';
const TOLERANCE = 1e-9;

// The run whose scene is mapped, and the atlas the native tool computes for it.
const dir = mkdtempSync(join(tmpdir(), 'space-atlas-web-'));
const ik = (args) => execFileSync(IK, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
const runText = ik(['simulate', '--arm', 'panda', '--json']);
writeFileSync(join(dir, 'run.json'), runText);
const t0 = performance.now();
const expectedText = ik(['atlas', '--arm', 'panda', '--methods', 'all', '--grid', '21', '--threads', '1', '--json']);
const nativeS = (performance.now() - t0) / 1000;
writeFileSync(join(dir, 'expected.json'), expectedText);
const expected = JSON.parse(readFileSync(join(dir, 'expected.json'), 'utf8'));

/** Where `a` and `b` differ (numbers beyond the tolerance), as paths; at most `max`. */
function differences(a, b, path = '', out = [], max = 20) {
  if (out.length >= max) return out;
  if (typeof a === 'number' && typeof b === 'number') {
    if (!(Math.abs(a - b) <= TOLERANCE * Math.max(1, Math.abs(a), Math.abs(b)))) out.push(`${path}: ${a} vs ${b}`);
  } else if (Array.isArray(a) && Array.isArray(b)) {
    if (a.length !== b.length) out.push(`${path}: ${a.length} vs ${b.length} entries`);
    else a.forEach((x, i) => differences(x, b[i], `${path}[${i}]`, out, max));
  } else if (a && b && typeof a === 'object' && typeof b === 'object') {
    const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
    for (const k of keys) {
      if (!(k in a) || !(k in b)) out.push(`${path}.${k}: only in the ${k in a ? 'page' : 'native'} atlas`);
      else differences(a[k], b[k], `${path}.${k}`, out, max);
    }
  } else if (a !== b) out.push(`${path}: ${JSON.stringify(a)} vs ${JSON.stringify(b)}`);
  return out;
}

const browser = await launchChromium();
let failed = false;
try {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => console.error(`page exception: ${e.message}`));
  await page.goto(`${BASE}?arm=panda&method=numerical&autoplay=0`);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
  const build = await page.evaluate(() => window.demo.build);
  const times = [];
  for (let i = 0; i < RUNS; i++) {
    const r = await page.evaluate(async (run) => {
      const text = async (f) => (await fetch(`weights/${f}`)).text();
      const networks = { phi: await text('phi-panda-reach.json'), v: await text('v-panda-reach.json') };
      let rows = 0;
      const t = performance.now();
      const out = await window.demo.spaceAtlas({
        run,
        methods: ['all'],
        n: 21,
        networks,
        onProgress: () => rows++,
      });
      return { wall: performance.now() - t, ms: out.ms, json: out.json, rows };
    }, runText);
    times.push(r.wall / 1000);
    const atlas = JSON.parse(r.json);
    const runs = atlas.cells.length * atlas.methods.length;
    console.log(
      `slice atlas of the Panda, ${atlas.grid.n} x ${atlas.grid.n} cells, ${atlas.methods.length} methods ` +
        `(${runs.toLocaleString('en')} runs), in a worker (${build} build): ${(r.wall / 1000).toFixed(2)} s ` +
        `(${(r.ms / 1000).toFixed(2)} s inside the worker; ${r.rows} progress messages)`,
    );
    const diff = differences(atlas, expected);
    const exact = r.json === expectedText.trimEnd();
    if (diff.length) {
      failed = true;
      console.error(`the page's atlas differs from the native tool's:\n  ${diff.join('\n  ')}`);
    } else {
      console.log(`its JSON equals the native tool's (${exact ? 'byte for byte' : `numbers within ${TOLERANCE}`})`);
    }
  }
  const sorted = [...times].sort((a, b) => a - b);
  const median = sorted[(sorted.length - 1) >> 1];
  console.log(
    `median of ${RUNS}: ${median.toFixed(2)} s in the page (goal: at most 8 s); natively ${nativeS.toFixed(2)} s on one core (the whole tool)`,
  );
  await context.close();
} finally {
  await browser.close();
  rmSync(dir, { recursive: true, force: true });
}
if (failed) process.exit(1);
