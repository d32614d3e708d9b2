// End-to-end test of the demo in headless Chromium (Debian's), driven by
// playwright-core. Run by scripts/e2e.sh, which serves www/ and passes its URL:
//
//   BASE_URL=http://127.0.0.1:8000/ node tests/e2e/e2e.mjs
//
// E2E_ONLY=<part of a test's name> runs only the matching tests.
//
// Every test fails on any console error or page exception. Screenshots go to
// tests/e2e/screenshots/ (ignored by git). Some tests print what they
// measured on the way as lines starting with "measure:"; the timings that
// are only measurements (time to data-ready, the Case 3 solver time per
// frame) are `make bench-web`'s (scripts/bench-web.mjs), not tests.
//
// The tests live in one file per part of the page, registered in this order:
// stage.mjs, methods.mjs, page.mjs, atlas.mjs, module.mjs, playground.mjs,
// hostile.mjs, reach.mjs, runs.mjs, self-motion.mjs, paths.mjs, embed.mjs (embedding from the page), a11y.mjs (accessibility: axe-core, the live region, phone, projector), view.mjs (the view holds the reach; zoom, pan, Fit), the page in space (space.mjs, space-controls.mjs, embed-space.mjs) its 3-D view (view3d.mjs) and a robot of the user's (robot.mjs), then the page for a class (class.mjs)
// and the arm's joint limits (limits.mjs) and the lab's page (lab.mjs); harness.mjs
// holds the browser and the helpers they share.

import { browser, tests, test, open, clean, state, shots, mouseDrag, touchDrag, selectMethod, methodsOf, usesNetworks, BASE, near, pause, countFrames } from './harness.mjs';
import './stage.mjs';
import './methods.mjs';
import './page.mjs';
import './atlas.mjs';
import './module.mjs';
import './playground.mjs';
import './hostile.mjs';
import './reach.mjs';
import './runs.mjs';
import './self-motion.mjs';
import './paths.mjs';
import './embed.mjs';
import './a11y.mjs';
import './view.mjs';
import './space.mjs';
import './space-controls.mjs';
import './embed-space.mjs';
import './view3d.mjs';
import './robot.mjs';
import './pose.mjs';
import { classTests } from './class.mjs';
import { limitsTests } from './limits.mjs';
import { labTests } from './lab.mjs';

classTests({ test, open, clean, state, shots, mouseDrag, touchDrag, selectMethod, methodsOf, usesNetworks, browser, BASE, near, pause, countFrames });
limitsTests({ test, open, clean, state, shots });
labTests({ test, open, clean, state, shots });

// E2E_ONLY=text runs only the tests whose name contains it (for development).
// E2E_SHARD=k/n runs every nth test from the kth (scripts/e2e.sh runs shards
// at once: each test has its own browser context, and a test mostly waits
// on its page, so two shards take about half the time on two cores).
const only = process.env.E2E_ONLY;
const [shard, shards] = (process.env.E2E_SHARD ?? '0/1').split('/').map(Number);
if (!(Number.isInteger(shard) && Number.isInteger(shards) && shard >= 0 && shard < shards)) throw new Error(`E2E_SHARD=${process.env.E2E_SHARD}: expected k/n with 0 <= k < n`);
let passed = 0;
let failed = 0;
for (const { name, fn } of tests.filter((t) => !only || t.name.includes(only)).filter((_, i) => i % shards === shard)) {
  const t0 = Date.now();
  try {
    await fn();
    passed++;
    console.log(`ok   ${name} (${Date.now() - t0} ms)`);
  } catch (e) {
    failed++;
    console.log(`FAIL ${name}\n     ${String(e && e.stack ? e.stack : e).split('\n').slice(0, 6).join('\n     ')}`);
  }
}
await browser.close();
console.log(`e2e: ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
