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

log="$(mktemp -t e2e-serve.XXXXXX)"
python3 scripts/serve.py --port 0 --dir www --quiet >"$log" 2>&1 &
server=$!
cleanup() {
  kill "$server" 2>/dev/null || true
  wait "$server" 2>/dev/null || true
  rm -f "$log"
}
trap cleanup EXIT INT TERM

url=""
for _ in $(seq 1 100); do
  url="$(grep -o 'http://127\.0\.0\.1:[0-9]*/' "$log" | head -n1 || true)"
  [[ -n "$url" ]] && break
  if ! kill -0 "$server" 2>/dev/null; then
    echo "e2e: the static server did not start:" >&2
    cat "$log" >&2
    exit 1
  fi
  sleep 0.05
done
if [[ -z "$url" ]]; then
  echo "e2e: the static server printed no URL" >&2
  exit 1
fi
echo "e2e: serving www/ at $url"

BASE_URL="$url" CHROMIUM="$chromium" node "tests/e2e/${E2E_SCRIPT:-e2e.mjs}"
