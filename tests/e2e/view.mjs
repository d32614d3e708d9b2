// End-to-end tests of the stage's view (src/view.rs): on every screen the
// drawing holds the arm's whole reach and a target above it, its labels lie
// inside the canvas and the stage is tall enough; the wheel, the keys and
// two fingers zoom, Fit restores, and a drag after a zoom stays exact; an
// idle page draws nothing until a change, and draws a restored context again.
// Registered by e2e.mjs, which runs them (scripts/e2e.sh).

import { join } from 'node:path';
import assert from 'node:assert/strict';
import { shots, test, open, clean, state, pause, mouseDrag } from './harness.mjs';

const SCREENS = [
  ['phone', { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true }],
  ['1024', { viewport: { width: 1024, height: 768 } }],
  ['1366', { viewport: { width: 1366, height: 768 } }],
  ['1920', { viewport: { width: 1920, height: 1080 } }],
  ['150%', { viewport: { width: 910, height: 512 }, deviceScaleFactor: 1.5 }],
];

const client = (page, p) => page.evaluate(([x, y]) => window.demo.worldToClient(x, y), p);
const frames = (page, n = 2) =>
  page.evaluate((n) => new Promise((done) => {
    const f = (k) => (k ? requestAnimationFrame(() => f(k - 1)) : done());
    f(n);
  }), n);

/** The stage's rectangle on screen and every text a drawing of it draws, each with its box (CSS px, from measureText); a paused page draws nothing by itself, so the drawing is asked for. */
async function drawnTexts(page) {
  return page.evaluate(async () => {
    const canvas = document.getElementById('stage');
    const ctx = canvas.getContext('2d');
    const texts = [];
    ctx.fillText = function (text, x, y) {
      const m = this.measureText(text);
      texts.push({ text, left: x - m.actualBoundingBoxLeft, right: x + m.actualBoundingBoxRight, top: y - m.actualBoundingBoxAscent, bottom: y + m.actualBoundingBoxDescent });
      return CanvasRenderingContext2D.prototype.fillText.call(this, text, x, y);
    };
    window.demo.controller.demo.draw();
    delete ctx.fillText;
    const r = canvas.getBoundingClientRect();
    return { texts, rect: { left: r.left, top: r.top, width: r.width, height: r.height } };
  });
}

const inside = (p, r, what) =>
  assert.ok(p.x >= r.left && p.x <= r.left + r.width && p.y >= r.top && p.y <= r.top + r.height, `${what} (${p.x.toFixed(1)}, ${p.y.toFixed(1)}) inside the canvas ${JSON.stringify(r)}`);

for (const [name, options] of SCREENS) {
  test(`view on ${name}: the whole reach, a target above it and every label inside the canvas`, async () => {
    const page = await open('?task=1&method=numerical&target=0.6,2.2', options);
    await pause(page);
    const s = await state(page);
    assert.deepEqual(s.target, [0.6, 2.2]);
    const { arm } = await page.evaluate(() => window.demo.controller.demo.scene());
    const reach = arm.links.reduce((a, b) => a + b, 0);
    const { texts, rect } = await drawnTexts(page);
    for (const [what, p] of [
      ['the reach leftmost', [-reach, arm.post]],
      ['the reach rightmost', [reach, arm.post]],
      ['the reach topmost', [0, arm.post + reach]],
      ['the target (0.6, 2.2)', [0.6, 2.2]],
      ['the post foot', [0, 0]],
    ]) {
      inside(await client(page, p), rect, what);
    }
    // Every text (the caption, the tick labels, the axes' names) lies inside.
    assert.ok(texts.length >= 8, `texts drawn: ${texts.map((t) => t.text)}`);
    for (const t of texts) {
      const ok = t.left >= 0 && t.right <= rect.width && t.top >= 0 && t.bottom <= rect.height;
      assert.ok(ok, `'${t.text}' inside the ${rect.width}x${rect.height} canvas: ${JSON.stringify(t)}`);
    }
    assert.ok(texts.some((t) => t.text === '-1.0' || t.text === '-1'), `a negative tick label drawn whole: ${texts.map((t) => t.text)}`);
    // The page never scrolls sideways; beside the controls the stage takes 60% of the screen.
    const { scrollWidth, innerWidth, innerHeight } = await page.evaluate(() => ({ scrollWidth: document.documentElement.scrollWidth, innerWidth, innerHeight }));
    assert.ok(scrollWidth <= innerWidth, `no horizontal scroll (${scrollWidth} > ${innerWidth})`);
    if (innerWidth > 860) assert.ok(rect.height >= 0.59 * innerHeight, `stage ${rect.height} px of ${innerHeight}`);
    console.log(`measure: view on ${name}: canvas ${rect.width.toFixed(0)} x ${rect.height.toFixed(0)} px`);
    await page.screenshot({ path: join(shots, `view-${name.replace('%', 'pct')}.png`) });
    clean(page);
    await page.close();
  });
}

test('view: the wheel and the keys zoom about a point, Fit restores the fitted view', async () => {
  const page = await open('?task=1&method=numerical', { viewport: { width: 1366, height: 768 } });
  await pause(page);
  const fixed = [1.0, 1.0];
  const base = await client(page, [0, 0.5]);
  const at = await client(page, fixed);
  await page.mouse.move(at.x, at.y);
  await page.mouse.wheel(0, -300);
  await frames(page);
  const still = await client(page, fixed);
  // (within the pixel the pointer event rounds its position to)
  assert.ok(Math.hypot(still.x - at.x, still.y - at.y) < 1.5, `the point under the wheel stays (${JSON.stringify([at, still])})`);
  const moved = await client(page, [0, 0.5]);
  assert.ok(Math.hypot(moved.x - base.x, moved.y - base.y) > 50, 'the rest zoomed');
  await page.screenshot({ path: join(shots, 'view-zoomed.png') });
  await page.click('#fit-view');
  const back = await client(page, [0, 0.5]);
  assert.ok(Math.hypot(back.x - base.x, back.y - base.y) < 0.01, 'Fit restores the fitted view');
  // A drag on the empty drawing pans it by the pointer's pixels.
  const empty = await client(page, [-1.6, 2.3]);
  await page.mouse.move(empty.x, empty.y);
  await page.mouse.down();
  await page.mouse.move(empty.x + 80, empty.y + 40, { steps: 8 });
  await page.mouse.up();
  const panned = await client(page, [0, 0.5]);
  assert.ok(Math.hypot(panned.x - base.x - 80, panned.y - base.y - 40) < 0.5, `panned by (80, 40): ${JSON.stringify([base, panned])}`);
  await page.click('#fit-view');
  // The keys on the focused drawing: + zooms in about the middle, 0 fits.
  await page.focus('#stage');
  await page.keyboard.press('+');
  const zoomed = await client(page, [0, 0.5]);
  assert.ok(Math.hypot(zoomed.x - base.x, zoomed.y - base.y) > 5, '+ zoomed');
  await page.keyboard.press('0');
  const fitted = await client(page, [0, 0.5]);
  assert.ok(Math.hypot(fitted.x - base.x, fitted.y - base.y) < 0.01, '0 fits');
  // At most 8 times the fit, however far the wheel turns.
  const z = await page.evaluate(() => window.demo.controller.demo.moveView(100, 100, 100, 100, 1e9));
  assert.equal(z, 8);
  clean(page);
  await page.close();
});

test('view: a drag after a zoom puts the target under the pointer; the zoom stays', async () => {
  const page = await open('?task=1&method=numerical', { viewport: { width: 1366, height: 768 } });
  await pause(page);
  const s = await state(page);
  const at = await client(page, s.target);
  await page.mouse.move(at.x, at.y);
  await page.mouse.wheel(0, -500);
  await frames(page);
  const goal = [s.target[0] + 0.15, s.target[1] + 0.1];
  const drop = await client(page, goal);
  await mouseDrag(page, s.target, goal);
  const after = await state(page);
  const now = await client(page, after.target);
  assert.ok(Math.hypot(now.x - drop.x, now.y - drop.y) <= 2, `target ${JSON.stringify(now)} under the pointer ${JSON.stringify(drop)}`);
  await frames(page);
  const later = await client(page, after.target);
  assert.ok(Math.hypot(later.x - drop.x, later.y - drop.y) <= 2, 'the zoomed view stays after the drop');
  clean(page);
  await page.close();
});

test('view: two fingers zoom on a phone, Fit restores', async () => {
  const page = await open('?task=1&method=numerical', { viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true });
  await pause(page);
  const a = [-1.2, 2.0];
  const b = [-0.6, 2.0];
  const span = async () => {
    const [p, q] = [await client(page, a), await client(page, b)];
    return Math.hypot(p.x - q.x, p.y - q.y);
  };
  const before = await span();
  const base = await client(page, [0, 0.5]);
  const [p, q] = [await client(page, a), await client(page, b)];
  const cdp = await page.context().newCDPSession(page);
  const touch = (type, pts) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: pts.map(([x, y], id) => ({ x, y, id, radiusX: 4, radiusY: 4, force: 1 })) });
  await touch('touchStart', [[p.x, p.y]]);
  await touch('touchStart', [[p.x, p.y], [q.x, q.y]]);
  for (let i = 1; i <= 8; i++) await touch('touchMove', [[p.x - 4 * i, p.y], [q.x + 4 * i, q.y]]);
  await touch('touchEnd', []);
  await cdp.detach();
  const after = await span();
  assert.ok(after > 1.5 * before, `pinched apart: ${before.toFixed(1)} -> ${after.toFixed(1)} px`);
  assert.equal((await state(page)).dragging_obstacle ?? null, null, 'nothing grabbed');
  await page.screenshot({ path: join(shots, 'view-phone-pinched.png') });
  await page.click('#fit-view');
  const back = await client(page, [0, 0.5]);
  assert.ok(Math.hypot(back.x - base.x, back.y - base.y) < 0.01, 'Fit restores');
  clean(page);
  await page.close();
});

// An idle page draws nothing (docs/web.md, "What an idle page costs"): a
// pixel painted over the stage stays through frames, until something
// changes; and a 2D context the browser gives back blank is drawn again.
for (const [name, query] of [['plane', '?task=1&method=numerical'], ['space', '?arm=panda&autoplay=0']]) {
  test(`idle in ${name}: frames draw nothing until a change, and a restored context is drawn again`, async () => {
    const page = await open(query);
    await pause(page);
    await frames(page, 3);
    const mark = () =>
      page.evaluate(() => {
        const g = document.getElementById('stage').getContext('2d');
        g.save();
        g.setTransform(1, 0, 0, 1, 0, 0);
        g.fillStyle = 'rgb(255, 0, 255)';
        g.fillRect(0, 0, 1, 1);
        g.restore();
      });
    const marked = () =>
      page.evaluate(() => {
        const [r, g, b] = document.getElementById('stage').getContext('2d').getImageData(0, 0, 1, 1).data;
        return r === 255 && g === 0 && b === 255;
      });
    await mark();
    await frames(page, 5);
    assert.ok(await marked(), 'five idle frames drew nothing over the mark');
    await page.evaluate(() => document.getElementById('stage').dispatchEvent(new Event('contextrestored')));
    assert.ok(!(await marked()), 'a restored context is drawn again');
    await mark();
    await page.evaluate(() => window.demo.controller.demo.setRunning(true));
    await frames(page, 3);
    assert.ok(!(await marked()), 'a running clock draws');
    clean(page);
    await page.close();
  });
}
