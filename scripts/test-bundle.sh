#!/usr/bin/env bash
# The tests of the bundled builds in headless Chromium (tests/bundle/):
#
#   scripts/test-bundle.sh offline   # dist/redundant-ik.html from file:// (make test-offline)
#   scripts/test-bundle.sh npm       # the package's tarball installed and served (make test-npm)
#
# Installs playwright-core as scripts/e2e.sh does (tests/e2e/package-lock.json).
# Assumes the build it tests is there (make offline, make npm).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
what="${1:-}"
if [[ ! -f "tests/bundle/$what.mjs" ]]; then
  echo "test-bundle: usage: scripts/test-bundle.sh offline|npm" >&2
  exit 2
fi
chromium="${CHROMIUM:-/usr/bin/chromium}"
if [[ ! -x "$chromium" ]]; then
  echo "test-bundle: no Chromium at $chromium (scripts/setup-wasm.sh installs it)" >&2
  exit 2
fi
command -v node >/dev/null || { echo "test-bundle: node is not installed" >&2; exit 2; }
if [[ ! -d tests/e2e/node_modules/playwright-core ]]; then
  (cd tests/e2e && npm ci --no-audit --no-fund --loglevel=error)
fi
CHROMIUM="$chromium" node "tests/bundle/$what.mjs"
