// Writes www/pkg/space-arms.js (make web, after the builds): the keys of
// the arms in space (`arm=panda`, `arm=iiwa14`), as the space build of the
// page's module names them (spacePresets). module.js reads it to choose a
// build before any is loaded: the space build for those keys (and
// `arm=space`), the plane's for every other address, a planar preset's key
// (`arm=iiwa-planar`) included. The space build has no planar demo, so the
// choice must be exact; the keys live in the core (src/space/preset.rs).
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const www = join(dirname(fileURLToPath(import.meta.url)), '..', 'www');
const glue = await import(pathToFileURL(join(www, 'pkg/redundant_ik.js')).href);
glue.initSync({ module: readFileSync(join(www, 'pkg/redundant_ik_space_bg.wasm')) });
const keys = glue.spacePresets().map((p) => p.key);
if (!keys.length || keys.some((k) => typeof k !== 'string')) throw new Error(`space-arms: unexpected presets ${JSON.stringify(keys)}`);
writeFileSync(
  join(www, 'pkg/space-arms.js'),
  `// Written by scripts/space-arms.mjs (make web) from the module's spacePresets(): do not edit.\nexport const SPACE_ARMS = ${JSON.stringify(keys)};\n`,
);
console.log(`space-arms: ${keys.join(', ')}`);
