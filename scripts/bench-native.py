#!/usr/bin/env python3
"""Runs `redundant-ik bench --json` several times and writes the median of
each figure (the machine is shared and noisy; one run can be off by 20%).

    python3 scripts/bench-native.py BIN RUNS OUT.json

`make bench-native` writes www/bench-native.json with it: the native figures
the page's "Are the networks faster?" panel shows beside its own, and the
README quotes.
"""

import json
import statistics
import subprocess
import sys


def median_of(runs, key):
    """Median over runs of every number under `key` (nested one level)."""
    first = runs[0][key]
    if isinstance(first, dict):
        return {k: statistics.median(r[key][k] for r in runs) for k in first}
    if first is None:
        return None
    return statistics.median(r[key] for r in runs)


def main() -> int:
    if len(sys.argv) != 4:
        print(__doc__.strip().splitlines()[4].strip(), file=sys.stderr)
        return 2
    binary, runs, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    results = []
    for i in range(runs):
        text = subprocess.run([binary, "bench", "--json"], check=True, capture_output=True, text=True).stdout
        results.append(json.loads(text))
        print(f"bench-native: run {i + 1}/{runs}", file=sys.stderr)
    merged = {"kernels": results[0]["kernels"], "runs": runs}
    for key in ["theta_dot_ns", "step_ns", "forward_ns", "lm_epoch_ms", "allocs_per_step", "atlas_ms"]:
        merged[key] = median_of(results, key)
    with open(out, "w") as f:
        json.dump(merged, f, indent=2)
        f.write("\n")
    print(json.dumps(merged))
    return 0


if __name__ == "__main__":
    sys.exit(main())
