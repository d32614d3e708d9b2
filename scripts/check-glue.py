#!/usr/bin/env python3
"""Checks that one wasm-bindgen glue file can load a build of a module
(make web). The glue is a build of both parts (the page's: page,space; the
workers': worker,space), and each part is a build of its own: the plane's
(feature page, or worker) and, for the page, the arms in space's
(canvas,space). A part must import nothing the glue does not provide (its
imports a subset of the glue build's, by name), and every export the glue
may call and the part lacks must belong to the other part, which the page
and its workers call only where that part is loaded:
  plane: the bindings of the arms in space (SpaceDemo, spacePresets,
         SpaceAtlasJob, spaceFigure, benchSpaceStep, ...: every name with
         "space" in it);
  space: the planar page's Demo (demo_*) and its shipped network sets'
         loaders (provideBuiltinNetworks, networksError,
         builtinNetworksFailed), which module.js calls only on the plane.
Usage: check-glue.py GLUE.wasm PART.wasm plane|space
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


glue_path, part_path, which = sys.argv[1:4]
OTHER = {
    "plane": re.compile(r"space", re.IGNORECASE),
    "space": re.compile(r"^(demo_|__wbg_demo_free$|provideBuiltinNetworks$|networksError$|builtinNetworksFailed$)"),
}[which]
glue, part = names(glue_path), names(part_path)
extra_imports = part[0] - glue[0]
lacking = glue[1] - part[1]
missing = sorted(e for e in lacking if not OTHER.search(e))
if extra_imports or missing:
    print(f"check-glue: the glue of {glue_path} cannot load {part_path} ({which}):")
    for x in sorted(extra_imports):
        print(f"  it imports {x}, which the glue does not provide")
    for x in missing:
        print(f"  it lacks the export {x}, which the glue calls")
    sys.exit(1)
print(f"check-glue: the glue loads {part_path} ({len(lacking)} exports of the other part absent)")
