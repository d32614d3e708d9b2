#!/usr/bin/env bash
# End-to-end browser test of the demo: serves www/ on a free 127.0.0.1 port,
# drives Debian's Chromium with playwright-core (tests/e2e/e2e.mjs, which runs
# the test files beside it), and exits non-zero on any failure. Assumes
# www/pkg is built (make web).
#
#   scripts/e2e.sh              # all tests
#   CHROMIUM=/path/to/chromium scripts/e2e.sh
#   E2E_SCRIPT=soak.mjs scripts/e2e.sh   # the soak instead (make soak)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

if [[ ! -f www/pkg/redundant_ik_bg.wasm ]]; then
  echo "e2e: www/pkg is not built; run 'make web' first" >&2
  exit 2
fi
chromium="${CHROMIUM:-/usr/bin/chromium}"
if [[ ! -x "$chromium" ]]; then
  echo "e2e: no Chromium at $chromium (scripts/setup-wasm.sh installs it)" >&2
  exit 2
fi
command -v node >/dev/null || { echo "e2e: node is not installed" >&2; exit 2; }

# playwright-core (it never downloads a browser) and axe-core, pinned in package-lock.json.
(
  cd tests/e2e
  if [[ ! -d node_modules/playwright-core || ! -d node_modules/axe-core ]]; then
    if [[ -f package-lock.json ]]; then
      npm ci --no-audit --no-fund --loglevel=error
    else
      npm install --no-audit --no-fund --loglevel=error
    fi
  fi
)

# The command-line tool, for the test that feeds it the page's downloaded weights.
cargo build --quiet --bin redundant-ik
export REDUNDANT_IK="$root/target/debug/redundant-ik"

# shellcheck source=scripts/serve-lib.sh
source scripts/serve-lib.sh
serve_dir e2e www

BASE_URL="$url" CHROMIUM="$chromium" node "tests/e2e/${E2E_SCRIPT:-e2e.mjs}"
