#!/usr/bin/env bash
# Serves www/ (and BEFORE_DIR, another built copy of www/, if given) on free
# 127.0.0.1 ports and times the page's training job in headless Chromium
# (scripts/train-web.mjs), alternating between the two: docs/speed.md,
# "Training in the page".
#   PRESETS=quick,thorough RUNS=3 [BEFORE_DIR=/tmp/www-before] scripts/train-web.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
[[ -f www/pkg/redundant_ik_worker_bg.wasm ]] || { echo "train-web: run 'make web' first" >&2; exit 2; }
(cd tests/e2e && [[ -d node_modules/playwright-core ]] || npm ci --no-audit --no-fund --loglevel=error)
servers=()
logs=()
cleanup() {
  for s in "${servers[@]}"; do kill "$s" 2>/dev/null || true; done
  rm -f "${logs[@]}"
}
trap cleanup EXIT INT TERM
serve() {
  local log
  log="$(mktemp -t train-serve.XXXXXX)"
  logs+=("$log")
  python3 scripts/serve.py --port 0 --dir "$1" --quiet >"$log" 2>&1 &
  servers+=($!)
  for _ in $(seq 1 100); do
    url="$(grep -o 'http://127\.0\.0\.1:[0-9]*/' "$log" | head -n1 || true)"
    [[ -n "$url" ]] && return 0
    sleep 0.05
  done
  echo "train-web: the static server for $1 did not start" >&2
  exit 1
}
urls=""
if [[ -n "${BEFORE_DIR:-}" ]]; then
  serve "$BEFORE_DIR"
  urls="$url,"
  echo "before: $BEFORE_DIR at $url"
fi
serve www
urls="$urls$url"
echo "after: www at $url"
BASE_URLS="$urls" PRESETS="${PRESETS:-quick}" RUNS="${RUNS:-3}" node scripts/train-web.mjs
