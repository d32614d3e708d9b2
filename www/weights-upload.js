// The "use your own weights" panel: two weights files written by
// `redundant-ik train` (the Φ network's and the v network's), read from
// the file pickers and installed through the playground (which keeps their
// text for the workers and the download). Files larger than the core reads
// are refused before they are read.

import { describe, limits, networkMethodLabels } from './module.js';

const MB = 1048576;

/** Wires `#load-weights`, `#phi-file` and `#v-file` under `root`, if there. */
export function mountWeightsUpload(root, { attempt, show, install }) {
  const $ = (id) => root.querySelector('#' + id);
  $('load-weights')?.addEventListener('click', async () => {
    const phi = $('phi-file')?.files?.[0];
    const v = $('v-file')?.files?.[0];
    if (!phi || !v) {
      show('Choose both files: the Φ weights and the v weights.', 'warn');
      return;
    }
    // Too large to be weights: refused before reading (the core says the same of text).
    const most = limits().max_weights_bytes;
    const tooBig = [phi, v].find((f) => f.size > most);
    if (tooBig) {
      show(`${tooBig.name} has ${(tooBig.size / MB).toFixed(1)} MB; weights files are at most ${most / MB} MB.`);
      return;
    }
    let phiText;
    let vText;
    try {
      [phiText, vText] = await Promise.all([phi.text(), v.text()]);
    } catch (e) {
      show(`Cannot read the files: ${describe(e)}`);
      return;
    }
    if (attempt(() => install(phiText, vText))) {
      show(`Loaded ${phi.name} and ${v.name}; ${networkMethodLabels()} now use them.`, 'info');
    }
  });
}
