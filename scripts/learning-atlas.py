#!/usr/bin/env python3
"""The atlas table of docs/learning.md: Cases 1-3 against the numerical route
for each shipped network set, refinement and feedback gain, over the whole
reach and over the paper's obstacle box, in Tasks 1 and 2.

Each cell of the table is "a / b = r": of the b cells where the numerical
route succeeds, the method succeeds in a (r = a / b). The atlases are
`redundant-ik atlas --json` runs (41 x 41 cells).

    cargo build --release
    python3 scripts/learning-atlas.py [target/release/redundant-ik] > table.md
"""

import json
import subprocess
import sys

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/redundant-ik"
REGIONS = [("whole reach", []), ("box [0.3, 0.8]²", ["--region", "0.3,0.8,0.3,0.8"])]
SETS = ["paper", "reach"]
LOOPS = [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1), (4, 0), (4, 1)]  # (refine, K)
METHODS = ["case1", "case2", "case3"]


def atlas(task, region, networks, refine, feedback):
    args = [BIN, "atlas", "--task", str(task), "--methods", "numerical," + ",".join(METHODS),
            "--networks", networks, "--refine", str(refine), "--feedback", str(feedback),
            "--json"] + region
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)


def cell(summary):
    a = summary["agreement"]
    both, num = a["both"], a["both"] + a["numerical_only"]
    return f"{both}/{num} = {100 * both / num:.1f}%" if num else "-"


for region_name, region in REGIONS:
    print(f"\n### {region_name}\n")
    print("| networks | refine | K | task | numerical (of avoidable) | " + " | ".join(m.replace("case", "Case ") for m in METHODS) + " |")
    print("|---|---|---|---|---|" + "---|" * len(METHODS))
    for networks in SETS:
        for refine, feedback in LOOPS:
            for task in (1, 2):
                a = atlas(task, region, networks, refine, feedback)
                s = a["summary"]
                n = s["numerical"]["avoidable"]
                row = [networks, str(refine), str(feedback), str(task),
                       f"{n['successes']}/{n['cells']}"] + [cell(s[m]) for m in METHODS]
                print("| " + " | ".join(row) + " |")
                sys.stdout.flush()
