#!/usr/bin/env python3
"""Checks that one wasm-bindgen glue file can load two builds of a module
(make web): the planar build (feature page, or worker) and the build with
the arms in space (page,space or worker,space), whose glue the page ships.
The planar module must import nothing the glue does not provide (its
imports a subset of the space build's, by name), and every export the glue
may call and the planar module lacks must be a binding of the arms in space
(SpaceDemo, spacePresets, SpaceAtlasJob, spaceFigure, benchSpaceStep, ...: every name with "space" in it),
which the page and its workers call only on the space build.
Usage: check-glue.py PLANAR.wasm SPACE.wasm
"""
import re
import sys


def leb(b, i):
    r = s = 0
    while True:
        x = b[i]
        i += 1
        r |= (x & 0x7F) << s
        s += 7
        if x < 0x80:
            return r, i


def names(path):
    """The module's import names and export names."""
    d = open(path, "rb").read()
    i, imports, exports = 8, set(), set()
    while i < len(d):
        sid = d[i]
        size, i = leb(d, i + 1)
        b = d[i : i + size]
        if sid == 2:
            n, j = leb(b, 0)
            for _ in range(n):
                length, j = leb(b, j)
                j += length
                length, j = leb(b, j)
                imports.add(b[j : j + length].decode())
                j += length
                kind = b[j]
                j += 1
                if kind == 0:
                    _, j = leb(b, j)
                elif kind in (1, 2):
                    if kind == 1:
                        j += 1
                    flags, j = leb(b, j)
                    _, j = leb(b, j)
                    if flags & 1:
                        _, j = leb(b, j)
                elif kind == 3:
                    j += 2
        elif sid == 7:
            n, j = leb(b, 0)
            for _ in range(n):
                length, j = leb(b, j)
                exports.add(b[j : j + length].decode())
                j += length + 1
                _, j = leb(b, j)
        i += size
    return imports, exports


planar, space = (names(p) for p in sys.argv[1:3])
extra_imports = planar[0] - space[0]
SPACE_ONLY = re.compile(r"space", re.IGNORECASE)
missing = sorted(e for e in space[1] - planar[1] if not SPACE_ONLY.search(e))
if extra_imports or missing:
    print(f"check-glue: the space build's glue cannot load {sys.argv[1]}:")
    for x in sorted(extra_imports):
        print(f"  it imports {x}, which the glue does not provide")
    for x in missing:
        print(f"  it lacks the export {x}, which the glue calls")
    sys.exit(1)
print(f"check-glue: one glue loads both builds ({len(space[1] - planar[1])} exports of the arms in space only)")
