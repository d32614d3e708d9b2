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

Circles: no two files of `src/` (the command-line tool's `cli/` included)
import each other through a circle of any length. A file's imports are
its `crate::`, `super::` and `self::` paths, each resolved to the deepest
module file it names; a module and the modules inside it (a folder's
`mod.rs` and its files) are one family and may use each other, as Rust's
own tree does. Exits 1 naming the files of each circle.

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
    ["nn", "clearance", "urdf"],
    ["scene"],
    ["model"],
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


PATH = re.compile(r"\b(crate|super|self)((?:::(?:\w+|\{[^;]*?\}))+)")


def module_of(rel):
    """src/<rel> -> (crate, module path): the shells' files (main.rs, the
    tool's cli/, the Python module's python/) count as a crate of their own."""
    parts = list(rel.parts)
    crate = "bin" if parts[0] in ("cli", "python", "main.rs") else "lib"
    if parts[-1] in ("mod.rs", "lib.rs", "main.rs"):
        parts = parts[:-1]
    else:
        parts[-1] = parts[-1][:-3]
    return crate, tuple(parts)


def expand(path):
    """`a::b::{c, d::{e, f}}` -> [[a, b, c], [a, b, d, e], [a, b, d, f]]."""
    m = re.match(r"^([\w:]*?)(?:::)?\{(.*)\}$", path, re.S)
    if not m:
        return [path.split("::")]
    pre = [x for x in m.group(1).split("::") if x]
    items, depth, cur = [], 0, ""
    for ch in m.group(2):
        depth += ch == "{"
        depth -= ch == "}"
        if ch == "," and depth == 0:
            items.append(cur)
            cur = ""
        else:
            cur += ch
    items.append(cur)
    return [pre + [x for x in e if x] for it in items if it.strip() for e in expand(it.strip())]


def circles(root):
    """The circles of imports between the files of src/ (strongly connected
    components of more than one file), each as its sorted file names."""
    files = {module_of(p.relative_to(root)): p.relative_to(root) for p in root.rglob("*.rs")}
    edges = defaultdict(set)
    for (crate, mp), rel in files.items():
        text = "\n".join(code_lines((root / rel).read_text()))
        for m in PATH.finditer(text):
            head, tail = m.group(1), m.group(2)[2:]
            for segs in expand(tail):
                segs = [x.strip() for x in segs if x.strip()]
                base = [] if head == "crate" else list(mp) if head == "self" else list(mp)[:-1]
                while head == "super" and segs and segs[0] == "super":
                    base, segs = base[:-1], segs[1:]
                full = tuple(base + segs)
                target = next(
                    (full[:k] for k in range(len(full), -1, -1) if (crate, full[:k]) in files), None
                )
                if target is None or target[: len(mp)] == mp or mp[: len(target)] == target:
                    continue  # unresolved, or the same family
                edges[(crate, mp)].add((crate, target))
    # Tarjan's strongly connected components, iteratively.
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    for start in files:
        if start in index:
            continue
        work = [(start, iter(sorted(edges[start])))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges[w]))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(str(files[c]) for c in comp))
    return out


def main():
    repo = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    root = repo / "src"
    problems = oversized(repo)
    siblings = defaultdict(set)  # (module, file stem) -> sibling stems it imports
    for path in sorted(root.rglob("*.rs")):
        rel = path.relative_to(root)
        if rel.parts[0] in ("cli", "python", "main.rs", "lib.rs"):
            continue  # the shells (the tool's, the Python module's) and the crate root sit above everything
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
    for circle in circles(root):
        problems.append("src: an import circle: " + " -> ".join(circle))
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
        f"check-house: {len(LAYER)} modules, every import runs down the layers, no import circle; "
        f"no file of src/, www/ or tests/ above {MAX_LINES} lines"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
