// The playground: the arm designer and the obstacles (arm-designer.js),
// networks trained for the arm in the page (training.js), weights kept in
// the browser per arm (weights-store.js), and whole runs off screen. This
// file holds what they share: the arm change that restores the networks
// kept for the new arm. The networks in use are the module's (its run
// names them: a shipped set, or the weights files' text); no copy is kept
// here.
//
// `mountPlayground(root, demo, hooks)` wires the elements of `root` that
// exist and returns the controller `window.demo` uses: setArm, addObstacle,
// removeObstacle, obstacles, train, exportWeights, simulate, plus
// click/wantsClick for the stage, check(state) for the animation loop,
// restore() at start-up, installNetworks() and files().

import { describe, methods, usesNetworks } from './module.js';
import { storedWeights, storeWeights, forgetWeights } from './weights-store.js';
import { mountArmDesigner, flatObstacles } from './arm-designer.js';
import { simulateWith } from './simulate-options.js';
import { mountTraining } from './training.js';

export function mountPlayground(root, demo, { attempt, show, changed }) {
  function installNetworks(phi, v) {
    demo.loadNetworks(phi, v);
  }
  /** The user's weights files in use (trained, uploaded or restored), from the module's run: `{ phi, v }` or null. */
  function files() {
    const n = demo.run().networks;
    return n?.phi ? { phi: n.phi, v: n.v } : null;
  }

  /** Networks kept in the browser for this arm, installed if they load: the kept entry, or null. */
  function restoreWeights(arm) {
    const stored = storedWeights(arm);
    if (!stored) return null;
    try {
      if (typeof stored.phi !== 'string' || typeof stored.v !== 'string') {
        throw new Error('the entry is not a pair of weights files');
      }
      installNetworks(stored.phi, stored.v);
      return stored;
    } catch (e) {
      forgetWeights(arm);
      show(`Weights kept for this arm could not be loaded and were dropped: ${describe(e)}`, 'warn');
      return null;
    }
  }

  /**
   * A new arm `{ post, links, joint_limits?, rate_limits? }` (as the state
   * and the presets write it; the core checks it), with the networks kept
   * for it.
   */
  function setArm(arm) {
    if (!arm || typeof arm !== 'object' || !Array.isArray(arm.links)) {
      throw new Error('setArm expects { post, links: [L1, L2, ...] }');
    }
    const flat = (list) => (Array.isArray(list) ? Float64Array.from(list.flat(), Number) : undefined);
    demo.setLimitedArm(Number(arm.post), Float64Array.from(arm.links, Number), flat(arm.joint_limits), flat(arm.rate_limits));
    restoreWeights(demo.state().arm);
    designer.syncForm(demo.state().arm);
    changed();
    return demo.state().arm;
  }

  const designer = mountArmDesigner(root, demo, { setArm, attempt, show, changed });
  const training = mountTraining(root, demo, {
    files,
    install: installNetworks,
    keep: storeWeights,
    forget() {
      forgetWeights(demo.state().arm);
      demo.clearNetworks();
    },
    attempt,
    show,
    changed,
  });

  // The method menu: the methods that run networks are offered only where they can run.
  let fitShown = null;
  function check(s) {
    designer.check(s);
    training.check(s);
    if (s.networks !== fitShown) {
      fitShown = s.networks;
      for (const o of root.querySelectorAll('#mode option')) {
        o.disabled = !s.networks && usesNetworks(methods().find((m) => m.name === o.value));
      }
    }
  }

  /**
   * A whole run off screen: `{ method?, target?, obstacles?, tf?, theta0?, feedback?, refine? }` -> summary
   * (the method in use where none is given; `mode`, the older name of `method`, is read too).
   */
  function simulate(options) {
    return simulateWith(demo, options, flatObstacles);
  }

  return {
    simulate,
    setArm,
    addObstacle: designer.addObstacle,
    removeObstacle: designer.removeObstacle,
    obstacles: () => demo.state().obstacles.map((o) => ({ x: o.centre[0], y: o.centre[1], r: o.radius })),
    train: training.train,
    lastTraining: training.last,
    exportWeights: training.exportWeights,
    wantsClick: designer.wantsClick,
    click: designer.click,
    check,
    /** Installs the weights kept for the arm in use, with their report (at start-up). */
    restore() {
      const stored = restoreWeights(demo.state().arm);
      if (stored?.report) training.showReport(stored.report);
    },
    installNetworks,
    files,
  };
}
