// A .zip of a robot's files (its URDF and meshes) unpacked in the page:
// fflate (MIT; pinned in tools/package.json), bundled by make web into
// pkg/unzip.js (tools/bundle.mjs view), which robot-open.js imports only
// when a .zip is chosen.

import { unzipSync } from 'fflate';

/**
 * The files of `bytes` (a .zip) that a robot can use, `{ path: Uint8Array }`
 * (.urdf, .xml, .stl, .dae, .obj; folders and the rest left out), at most
 * `limit` bytes unpacked in all: a larger archive is refused before it is
 * inflated past that (a zip bomb's promise is read from its directory).
 */
export function unzipRobot(bytes, limit) {
  let total = 0;
  return unzipSync(bytes, {
    filter: (file) => {
      if (!/\.(urdf|xml|stl|dae|obj)$/i.test(file.name)) return false;
      total += file.originalSize;
      if (total > limit) throw new Error(`the archive unpacks to more than the ${limit} bytes the page takes`);
      return true;
    },
  });
}
