#!/usr/bin/env bash
# The peer benchmark (python/bench/peers.py): makes target/bench-venv,
# installs python/bench/requirements.txt and the redundant_ik package, and
# runs it; the results go to target/bench/peers.json. Arguments go to
# peers.py (--quick, --rounds N, --json PATH, --peer-rates arm, ...).
# Not a test, and not part of `make test`.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=target/bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q --disable-pip-version-check --only-binary=:all: -r python/bench/requirements.txt
wheel=$(ls -t target/wheels/redundant_ik-*.whl 2>/dev/null | head -n 1 || true)
if [ -z "$wheel" ]; then
    # The product's numbers are the release wheel's (a development build
    # is several times slower).
    echo "redundant_ik: no wheel in target/wheels: make wheel first (make bench-python does)" >&2
    exit 2
fi
echo "redundant_ik: $wheel"
"$venv/bin/pip" install -q --disable-pip-version-check --force-reinstall --no-deps "$wheel"
exec nice "$venv/bin/python" python/bench/peers.py --json target/bench/peers.json "$@"
