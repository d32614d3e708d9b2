#!/usr/bin/env bash
# Serves www/ on a free 127.0.0.1 port and runs the page's benchmark in
# headless Chromium (scripts/bench-web.mjs): `make bench-web`.
#   RUNS=5 scripts/bench-web.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
[[ -f www/pkg/redundant_ik_bg.wasm ]] || { echo "bench-web: run 'make web' first" >&2; exit 2; }
(cd tests/e2e && [[ -d node_modules/playwright-core ]] || npm ci --no-audit --no-fund --loglevel=error)
log="$(mktemp -t bench-serve.XXXXXX)"
python3 scripts/serve.py --port 0 --dir www --quiet >"$log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -f "$log"' EXIT INT TERM
url=""
for _ in $(seq 1 100); do
  url="$(grep -o 'http://127\.0\.0\.1:[0-9]*/' "$log" | head -n1 || true)"
  [[ -n "$url" ]] && break
  sleep 0.05
done
[[ -n "$url" ]] || { echo "bench-web: the static server did not start" >&2; exit 1; }
BASE_URL="$url" RUNS="${RUNS:-3}" node scripts/bench-web.mjs
# The Panda's slice atlas in a worker against the native tool's (needs it built).
if [[ -x target/release/redundant-ik ]]; then
  BASE_URL="$url" RUNS="${RUNS:-3}" node scripts/space-atlas-web.mjs
else
  echo "bench-web: the slice atlas skipped (cargo build --release first)" >&2
fi
# The frame time while orbiting and dragging the Panda, and while dragging in the plane.
BASE_URL="$url" node scripts/frame-time.mjs
# What an idle page costs the machine (its CPU time, from /proc: Linux only).
if [[ -d /proc/self ]]; then BASE_URL="$url" node scripts/idle-cpu.mjs; fi
