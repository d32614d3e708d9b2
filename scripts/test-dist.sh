#!/usr/bin/env bash
# The page as `make dist` builds it, tested as a host would serve it: checks
# that dist/'s files use relative URLs only, serves dist/ under a sub-path
# (/courses/robotics/arm/) on a free 127.0.0.1 port, and runs the page's
# smoke test there in headless Chromium (tests/e2e/dist.mjs): the page and
# the embed page load, a Task 1 run, an atlas in a worker, the weights
# fetched, no console errors, no request that fails or leaves the sub-path.
#
#   make test-dist            # builds dist/ first
#   bash scripts/test-dist.sh # dist/ already built
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
prefix=/courses/robotics/arm/

[[ -f dist/index.html ]] || { echo "test-dist: dist/ is not built; run 'make dist' first" >&2; exit 2; }
[[ -f dist/redundant-ik.html ]] || { echo "test-dist: dist/ has no redundant-ik.html, the page in one file (make offline)" >&2; exit 1; }
chromium="${CHROMIUM:-/usr/bin/chromium}"
[[ -x "$chromium" ]] || { echo "test-dist: no Chromium at $chromium (scripts/setup-wasm.sh installs it)" >&2; exit 2; }

# Relative URLs only: no src/href, url(), fetch, import or Worker of a path from the host's root.
absolute='(src|href)="/|url\(["'"'"']?/|(fetch|import|URL|Worker)\(["'"'"'`]/|from ["'"'"']/'
if grep -nE "$absolute" dist/*.html dist/*.js dist/*.css dist/pkg/*.js; then
  echo "test-dist: the lines above name a URL from the host's root; dist/ must work from any sub-path" >&2
  exit 1
fi

(
  cd tests/e2e
  [[ -d node_modules/playwright-core ]] || npm ci --no-audit --no-fund --loglevel=error
)

# shellcheck source=scripts/serve-lib.sh
source scripts/serve-lib.sh
serve_dir test-dist dist --prefix "$prefix"

BASE_URL="$url" CHROMIUM="$chromium" node tests/e2e/dist.mjs
