#!/usr/bin/env bash
# End-to-end browser test of the demo: serves www/ on a free 127.0.0.1 port,
# drives Debian's Chromium with playwright-core (tests/e2e/e2e.mjs, which runs
# the test files beside it), and exits non-zero on any failure. Assumes
# www/pkg is built (make web).
#
#   scripts/e2e.sh              # all tests
#   CHROMIUM=/path/to/chromium scripts/e2e.sh
#   E2E_SCRIPT=soak.mjs scripts/e2e.sh   # the soak instead (make soak)
#   E2E_JOBS=1 scripts/e2e.sh            # one browser (two shards by default)
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

# The tests in E2E_JOBS shards at once (2 by default; one for E2E_ONLY or
# another script), each its own browser; their reports follow each other.
script="${E2E_SCRIPT:-e2e.mjs}"
jobs="${E2E_JOBS:-2}"
if [[ -n "${E2E_ONLY:-}" || "$script" != e2e.mjs ]]; then jobs=1; fi
if (( jobs <= 1 )); then
  BASE_URL="$url" CHROMIUM="$chromium" node "tests/e2e/$script"
  exit
fi
pids=()
logs=()
for ((k = 0; k < jobs; k++)); do
  logs+=("$(mktemp -t e2e-shard.XXXXXX)")
  E2E_SHARD="$k/$jobs" BASE_URL="$url" CHROMIUM="$chromium" node "tests/e2e/$script" >"${logs[$k]}" 2>&1 &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
cat "${logs[@]}"
awk '/^e2e: [0-9]+ passed, [0-9]+ failed$/ { p += $2; f += $4 } END { printf "e2e: %d passed, %d failed (%d shards)\n", p, f, '"$jobs"' }' "${logs[@]}"
rm -f "${logs[@]}"
exit "$status"
