#!/usr/bin/env python3
"""Checks that every file the docs cite exists.

Reads README.md and docs/*.md, takes each `code span` that names a file or a
folder (a path with a `/`, or a bare file name such as `paper.rs`), and
fails when no tracked file matches it:

- a path is looked up from the repository's root, from the doc's folder and
  from `src/` (the docs write `planner/methods/` for `src/planner/methods/`),
  and also as the tail of a tracked path (`methods/mod.rs`);
- a bare file name must be the name of some tracked file.

What the build makes (`www/pkg/`, `target/`, ...), the screenshots the
browser tests write, and placeholders (`fuzz/regressions/<target>/`,
`*.rs`) are skipped. Exits 1 and lists each
citation that names nothing.

    python3 scripts/check-docs-paths.py [REPO]
"""

import re
import subprocess
import sys
from pathlib import Path

SPAN = re.compile(r"`([^`\n]+)`")
# A file name: letters, digits, _ . - and a known extension.
FILE = re.compile(r"^[\w.-]+\.(rs|js|mjs|md|py|sh|json|html|css|toml|svg|png)$")
# A path: segments of such characters joined by '/', optionally ending in '/'.
PATH = re.compile(r"^[\w.-]+(/[\w.-]+)*/?$")
# Made by the build or by a run, not tracked.
BUILT = ("www/pkg", "www/weights", "target/", "figures", "tests/e2e/screenshots",
         "fuzz/artifacts", "node_modules", "tests/e2e/node_modules")
# A screenshot's file name as the browser tests write it.
SHOT = re.compile(r"['\"`]([\w-]+\.png)['\"`]")
# Top-level folders a cited path may start with.
ROOTS = ("src", "www", "tests", "docs", "scripts", "fuzz", "weights", "benches", ".ci")


def tracked(repo):
    out = subprocess.run(["git", "-C", str(repo), "ls-files"], check=True,
                         capture_output=True, text=True).stdout
    files = [f for f in out.splitlines() if f]
    folders = {str(Path(f).parent) for f in files}
    for f in list(folders):
        parts = Path(f).parts
        folders.update(str(Path(*parts[:i])) for i in range(1, len(parts)))
    return set(files), folders


def cited(text):
    """The code spans of `text` that look like a file or a folder."""
    for span in SPAN.findall(text):
        span = span.strip()
        if any(c in span for c in "<>*{} ") or "..." in span or span.startswith(("-", "http")):
            continue
        if "/" in span:
            if PATH.match(span) and span.split("/")[0] in ROOTS + ("planner", "nn", "methods"):
                yield span
        elif FILE.match(span):
            yield span


def exists(span, doc, repo, files, folders, shots):
    name = span.rstrip("/")
    if any(name.startswith(b.rstrip("/")) for b in BUILT):
        return True
    if "/" not in name:
        if span.endswith("/"):
            return any(d == name or d.endswith("/" + name) for d in folders)
        return any(Path(f).name == name for f in files) or name in shots
    for base in (Path("."), doc.parent.relative_to(repo), Path("src")):
        candidate = str((base / name))
        candidate = str(Path(candidate))  # normalise ./x
        if candidate in files or candidate in folders:
            return True
        try:
            resolved = str((repo / candidate).resolve().relative_to(repo.resolve()))
        except ValueError:
            continue
        if resolved in files or resolved in folders:
            return True
    return any(f.endswith("/" + name) for f in files | folders)


def main():
    repo = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    files, folders = tracked(repo)
    # Screenshots the browser tests write (tests/e2e/screenshots/, not tracked).
    shots = set()
    for test in sorted((repo / "tests" / "e2e").glob("*.mjs")):
        shots.update(SHOT.findall(test.read_text()))
    docs = [repo / "README.md"] + sorted((repo / "docs").glob("*.md"))
    missing = []
    count = 0
    for doc in docs:
        for n, line in enumerate(doc.read_text().splitlines(), 1):
            for span in cited(line):
                count += 1
                if not exists(span, doc, repo, files, folders, shots):
                    missing.append(f"{doc.relative_to(repo)}:{n}: `{span}` names no tracked file")
    if missing:
        print("check-docs-paths: the docs cite files that are not there:")
        for m in missing:
            print("  " + m)
        return 1
    print(f"check-docs-paths: {count} file citations in {len(docs)} docs, each names a tracked file")
    return 0


if __name__ == "__main__":
    sys.exit(main())
