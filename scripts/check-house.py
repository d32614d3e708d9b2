#!/usr/bin/env python3
"""Checks the house: the crate's layers, and the size of its rooms.

Layers: which module may import which.

Every top-level module of `src/` has a layer; a module may import only
modules of lower layers (or itself). Inside a module, sibling files must
not import each other both ways (a cycle such as `nn/mlp.rs` <->
`nn/kernel`). An import is any `crate::<module>` path in code (comments
and doc comments are skipped), and for files under `src/<module>/`, a
`super::<sibling>` path. Exits 1 and lists each arrow that runs against
the layers; `make test` runs it (docs/architecture.md draws the layers).

Rooms: no file of `src/` or `www/` (Rust, JavaScript, HTML, CSS) or of
`tests/` (Rust, JavaScript modules) is longer than 500 lines; a longer one
holds more than one concern and is split (a Rust test into a folder,
`tests/<name>/main.rs` and its modules, still one test binary).
"""

import re
import sys
from collections import defaultdict
from pathlib import Path

# Lowest first. A module may import any module of a lower layer. The
# math core (error .. obstacle) knows nothing of scenes, planners or
# training; `nn` knows nothing of the planner or the paper's networks;
# training and evaluation do not import each other both ways (the
# training job sits above both).
LAYERS = [
    ["error", "palette", "json"],
    ["geometry", "qp"],
    ["arm"],
    ["kinematics"],
    ["ik", "obstacle", "space"],
    ["nn", "clearance"],
    ["scene"],
    ["planner"],
    ["networks", "twin"],
    ["run"],
    ["training", "atlas"],
    ["evaluation", "session", "export", "figure"],
    ["training_job", "bench", "view"],
    ["web"],
]
LAYER = {m: i for i, names in enumerate(LAYERS) for m in names}

CRATE_PATH = re.compile(r"\bcrate::(\{[^}]*\}|\w+)")
INNER_PATH = re.compile(r"\bcrate::(\w+)::(\{[^}]*\}|\w+)")
SUPER_PATH = re.compile(r"\bsuper::(\{[^}]*\}|\w+)")


def code_lines(text):
    """The lines of a Rust file without comments (// and /* */)."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    for line in text.splitlines():
        yield line.split("//", 1)[0]


def names(group):
    """`a` or `{a, b::c, d}` -> the first path segments."""
    if group.startswith("{"):
        return [p.strip().split("::")[0] for p in group[1:-1].split(",") if p.strip()]
    return [group]


MAX_LINES = 500


# The folders whose files are rooms, and the kinds of file counted in each.
ROOMS = {
    "src": (".rs", ".js", ".mjs", ".html", ".css"),
    "www": (".rs", ".js", ".mjs", ".html", ".css"),
    "tests": (".rs", ".mjs"),
}


def oversized(repo):
    """Files of src/, www/ and tests/ above MAX_LINES lines (built output and
    installed packages skipped)."""
    out = []
    for folder, kinds in ROOMS.items():
        for path in sorted((repo / folder).rglob("*")):
            if path.suffix not in kinds or not path.is_file():
                continue
            if "pkg" in path.parts or "node_modules" in path.parts:
                continue
            n = len(path.read_text().splitlines())
            if n > MAX_LINES:
                out.append(f"{path.relative_to(repo)}: {n} lines (at most {MAX_LINES})")
    return out


def main():
    repo = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    root = repo / "src"
    problems = oversized(repo)
    siblings = defaultdict(set)  # (module, file stem) -> sibling stems it imports
    for path in sorted(root.rglob("*.rs")):
        rel = path.relative_to(root)
        if rel.parts[0] in ("cli", "main.rs", "lib.rs"):
            continue  # the binary's shell and the crate root sit above everything
        module = rel.parts[0].removesuffix(".rs")
        if module not in LAYER:
            problems.append(f"{rel}: module '{module}' has no layer in scripts/check-house.py")
            continue
        text = path.read_text()
        for n, line in enumerate(code_lines(text), 1):
            for group in CRATE_PATH.findall(line):
                for target in names(group):
                    if target in ("self", "Error", "Result") or target == module:
                        continue
                    if target not in LAYER:
                        continue  # a re-export at the crate root, e.g. crate::Arm
                    if LAYER[target] >= LAYER[module]:
                        problems.append(
                            f"{rel}:{n}: {module} (layer {LAYER[module]}) imports "
                            f"{target} (layer {LAYER[target]})"
                        )
            # Units of one module (src/<module>/<unit>.rs or <unit>/...):
            # crate::<module>::<unit> anywhere below it, super::<unit> from
            # a file directly in src/<module>/. The module's mod.rs declares
            # and re-exports its units, so it is not a unit itself.
            if len(rel.parts) >= 2 and rel.parts[1] != "mod.rs":
                unit = Path(rel.parts[1]).stem
                targets = [t for m, g in INNER_PATH.findall(line) if m == module for t in names(g)]
                if len(rel.parts) == 2:
                    targets += [t for g in SUPER_PATH.findall(line) for t in names(g)]
                for target in targets:
                    if target != unit:
                        siblings[(module, unit)].add(target)
    for (module, a), targets in siblings.items():
        for b in targets:
            if a in siblings.get((module, b), ()):
                if a < b:
                    problems.append(f"src/{module}: {a}.rs and {b}.rs import each other")
    if problems:
        print("check-house: imports against the layers, or rooms too large:")
        for p in problems:
            print("  " + p)
        return 1
    print(
        f"check-house: {len(LAYER)} modules, every import runs down the layers; "
        f"no file of src/, www/ or tests/ above {MAX_LINES} lines"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
