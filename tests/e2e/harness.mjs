// What every end-to-end test file shares: the browser, the list of tests in
// the order they are registered, and the helpers that open a page and drive
// it. e2e.mjs imports this first, then the test files, then runs the list.

import { launchChromium } from './chromium.mjs';
import { mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import assert from 'node:assert/strict';
import { createRequire } from 'node:module';

export const here = dirname(fileURLToPath(import.meta.url));
export const shots = join(here, 'screenshots');
mkdirSync(shots, { recursive: true });

export const BASE = process.env.BASE_URL ?? 'http://127.0.0.1:8000/';
export const browser = await launchChromium();
export const tests = [];
export const test = (name, fn) => tests.push({ name, fn });

/** A fresh page that records console errors and page exceptions. */
export async function open(path = '', contextOptions = {}) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, ...contextOptions });
  const page = await context.newPage();
  const problems = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') problems.push(`console error: ${msg.text()}`);
  });
  page.on('pageerror', (err) => problems.push(`page exception: ${err.message}`));
  page.problems = problems;
  page.on('close', () => context.close().catch(() => {}));
  await page.goto(BASE + path);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 15000 });
  await listen(page);
  return page;
}

/**
 * Records every text the page's live region (`#announcer`) takes, with
 * when (ms since the page started), in `window.__said`: what a screen
 * reader hears, each text in turn, where the region's text at one moment
 * may already be the next announcement's (a run that ends just after a
 * click says so). `open` listens from the start.
 */
export async function listen(page) {
  await page.evaluate(() => {
    const region = document.getElementById('announcer');
    if (!region || window.__listening) return;
    window.__listening = true;
    window.__said = [];
    new MutationObserver(() => window.__said.push({ text: region.textContent, at: performance.now() })).observe(region, {
      childList: true,
      characterData: true,
      subtree: true,
    });
  });
}

/** How many texts the live region has taken so far: a mark for `heard` (listening from now on if a reload stopped it). */
export async function saidSoFar(page) {
  await listen(page);
  return page.evaluate(() => window.__said?.length ?? 0);
}

/** The texts the live region took from mark `from` on, each part of a joint announcement (`; `) on its own. */
export const said = (page, from = 0) => page.evaluate((k) => (window.__said ?? []).slice(k).flatMap((s) => s.text.split('; ')), from);

/**
 * Waits (up to 15 s) until the live region has said a text matching
 * `pattern` since mark `from` (`saidSoFar` before the action); fails with
 * what it said instead.
 */
export async function heard(page, pattern, from, timeout = 15000) {
  await page
    .waitForFunction(
      ([k, source, flags]) => {
        const re = new RegExp(source, flags);
        return (window.__said ?? []).slice(k).some((s) => s.text.split('; ').some((part) => re.test(part)));
      },
      [from, pattern.source, pattern.flags],
      { timeout },
    )
    .catch(() => {});
  const texts = await said(page, from);
  assert.ok(texts.some((t) => pattern.test(t)), `the live region said ${JSON.stringify(texts)}, nothing matching ${pattern}`);
}

export function clean(page) {
  assert.deepEqual(page.problems, [], 'no console errors or page exceptions');
}

export const state = (page) => page.evaluate(() => window.demo.state());
export const near = (a, b, tol) => Math.hypot(a[0] - b[0], a[1] - b[1]) <= tol;

const AXE = createRequire(import.meta.url).resolve('axe-core/axe.min.js');
/** axe's violations of impact serious or critical on `page` now (details open as they are), each as `[where] rule (impact): where`. */
export async function axe(page, where) {
  if (!(await page.evaluate(() => 'axe' in window))) await page.addScriptTag({ path: AXE });
  const found = await page.evaluate(async () => {
    const r = await window.axe.run(document, { resultTypes: ['violations'] });
    return r.violations
      .filter((v) => v.impact === 'serious' || v.impact === 'critical')
      .map((v) => `${v.id} (${v.impact}): ${v.nodes.slice(0, 4).map((n) => n.target.join(' ')).join(', ')}${v.nodes.length > 4 ? ` and ${v.nodes.length - 4} more` : ''}`);
  });
  return found.map((f) => `[${where}] ${f}`);
}

export async function pause(page) {
  await page.evaluate(() => window.demo.controller.demo.setRunning(false));
}

/** Drags with real mouse events from world point `from` to world point `to`. */
export async function mouseDrag(page, from, to, steps = 12) {
  const a = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), from);
  const b = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), to);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  // One move a frame, as a person's hand gives them: a browser busy with a
  // slow frame merges the moves that arrive within it into one event, and
  // a drag whose moves were merged moves the page's handle less.
  for (let i = 1; i <= steps; i++) {
    await page.mouse.move(a.x + ((b.x - a.x) * i) / steps, a.y + ((b.y - a.y) * i) / steps);
    await nextFrames(page);
  }
  await page.mouse.up();
}

/** A one-finger touch drag through the Chrome DevTools protocol. */
export async function touchDrag(page, from, to, steps = 10) {
  const a = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), from);
  const b = await page.evaluate(([x, y]) => window.demo.worldToClient(x, y), to);
  const cdp = await page.context().newCDPSession(page);
  const point = (x, y) => [{ x, y, id: 1, radiusX: 4, radiusY: 4, force: 1 }];
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: point(a.x, a.y) });
  for (let i = 1; i <= steps; i++) {
    const f = i / steps;
    await cdp.send('Input.dispatchTouchEvent', {
      type: 'touchMove',
      touchPoints: point(a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)),
    });
  }
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await cdp.detach();
}

/** Counts animation frames from now on (window.__frames). */
export async function countFrames(page) {
  await page.evaluate(() => {
    window.__frames = 0;
    const f = () => {
      window.__frames += 1;
      requestAnimationFrame(f);
    };
    requestAnimationFrame(f);
  });
}

export async function selectMethod(page, method) {
  await page.selectOption('#mode', method);
  await nextFrames(page);
}

/**
 * Waits for two animation frames: the page updates its controls and notes
 * from the state in its frame loop, so what a change shows is there after
 * the next frame, not at once (on a loaded machine, late enough to fail a
 * read made at once).
 */
export async function nextFrames(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

/** The page's methods (the module's methods()). */
export const methodsOf = (page) => page.evaluate(() => window.demo.methods());
export const usesNetworks = (m) => m.networks.phi || m.networks.v;

/**
 * Waits until the text of `selector` matches `pattern` (up to 15 s: a
 * status said after a promise or on the next frame comes late on a loaded
 * machine), then returns it; fails with the last text seen.
 */
export async function textMatching(page, selector, pattern, timeout = 15000) {
  try {
    await page.waitForFunction(([s, source, flags]) => new RegExp(source, flags).test(document.querySelector(s)?.textContent ?? ''), [selector, pattern.source, pattern.flags], { timeout });
  } catch (_) {
    // The assertion below says what was there instead.
  }
  const text = await page.textContent(selector);
  if (!pattern.test(text)) throw new Error(`${selector}: ${JSON.stringify(text)} does not match ${pattern}`);
  return text;
}
