#!/usr/bin/env python3
"""A/B benchmark: runs `bench --json` of two builds of redundant-ik in
alternation, RUNS times each, and prints the median of every figure side by
side (a shared machine drifts; alternating keeps the comparison fair).

    python3 scripts/bench-ab.py RUNS BIN_A BIN_B [extra bench arguments...]

For example, against the commit before the speed work:

    git worktree add /tmp/before bfe8027 && (cd /tmp/before && cargo build --release)
    cargo build --release
    python3 scripts/bench-ab.py 5 /tmp/before/target/release/redundant-ik target/release/redundant-ik

A or B may carry bench arguments of its own, quoted: 'BIN --baseline-kernels'.
Figures missing from one build (older builds report fewer) print as '-'.
"""

import json
import statistics
import subprocess
import sys


def flatten(report, prefix=""):
    """`{"step_ns.case3": 1215.0, ...}` from one bench report, at any depth
    (`--arm`'s report nests its figures: `methods.case3.step_ns`)."""
    out = {}
    for key, value in report.items():
        if isinstance(value, dict):
            out.update(flatten(value, f"{prefix}{key}."))
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out[f"{prefix}{key}"] = value
    return out


def main() -> int:
    if len(sys.argv) < 4:
        print(__doc__.strip().splitlines()[4].strip(), file=sys.stderr)
        return 2
    runs, a, b, extra = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4:]
    results = {a: [], b: []}
    for i in range(runs):
        for binary in (a, b):
            path, *own = binary.split()
            text = subprocess.run(
                [path, "bench", "--json", *own, *extra], check=True, capture_output=True, text=True
            ).stdout
            results[binary].append(flatten(json.loads(text)))
        print(f"bench-ab: round {i + 1}/{runs}", file=sys.stderr)
    keys = list(dict.fromkeys(k for r in results[a] + results[b] for k in r))
    print(f"{'figure':<36} {'A':>12} {'B':>12} {'B/A':>7}")
    for k in keys:
        med = []
        for binary in (a, b):
            xs = [r[k] for r in results[binary] if k in r]
            med.append(statistics.median(xs) if xs else None)
        ratio = f"{med[1] / med[0]:.2f}" if med[0] and med[1] is not None else "-"
        cells = ["-" if m is None else f"{m:.1f}" for m in med]
        print(f"{k:<36} {cells[0]:>12} {cells[1]:>12} {ratio:>7}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
