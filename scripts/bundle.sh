#!/usr/bin/env bash
# The builds bundled by esbuild (tools/bundle.mjs): `scripts/bundle.sh
# offline` writes dist/redundant-ik.html, `scripts/bundle.sh npm` the
# package folder target/npm/redundant-ik/ and its tarball (npm pack),
# `scripts/bundle.sh view` the 3-D view www/pkg/three-view.js and the
# unzip www/pkg/unzip.js (make web). Installs esbuild, three and fflate,
# pinned in tools/package-lock.json, where they are missing. Assumes www/ is built (make web).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
command -v node >/dev/null || { echo "bundle: node is not installed" >&2; exit 2; }
if [[ "${1:-}" != view && ! -f www/pkg/redundant_ik_simd_bg.wasm ]]; then
  echo "bundle: www/pkg is not built; run 'make web' first" >&2
  exit 2
fi
if [[ ! -d tools/node_modules/esbuild || ! -d tools/node_modules/three || ! -d tools/node_modules/fflate ]]; then
  (cd tools && npm ci --no-audit --no-fund --loglevel=error)
fi
node tools/bundle.mjs "$@"
if [[ "${1:-}" == npm ]]; then
  (cd target/npm && npm pack ./redundant-ik --pack-destination . --loglevel=error >/dev/null)
  for f in target/npm/redundant-ik-*.tgz; do echo "bundle: $f: $(stat -c %s "$f") B"; done
fi
