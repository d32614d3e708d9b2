#!/usr/bin/env python3
"""Checks that the page copies no fact of the core.

The methods' names, the shipped network sets' names, the training presets'
names and the arm presets' texts are the core's (`src/planner/methods/`,
`src/networks/builtin.rs`, `src/training/preset.rs`, `src/arm.rs`); the page
reads them from the module (`methods()`, `networkSets()`,
`trainingPresets()`, `limits().arm_presets`, `paperMethods()`). This fails
`make test` on any of those names written as a string literal in www/*.js,
or as an attribute value in www/index.html, and on an arm text such as
`0.5:0.6,0.85,0.6` in code. Comments are skipped; the embed example page
(www/embed.html), whose markup shows a course page how to write the custom
element, is exempt. A literal that is a word of the page's own (a readout
saying 'none') is listed in ALLOWED with its file and why.
"""

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# (file, literal): the page's own words that happen to spell a core name.
ALLOWED = {
    ("www/demo.js", "none"): "the collision readout's word when nothing was hit",
    ("www/space-demo.js", "none"): "the collision readout's word when nothing was hit (the 3-D stage's)",
    ("www/page.js", "paper"): "a data attribute value for the stylesheet (paper's arm or other)",
    ("www/index.html", "distance"): "a readout's key (data-readout), not the method",
    ("www/index.html", "manipulability"): "a readout's key (data-readout), not the method",
    ("www/redundant-ik-demo.js", "distance"): "a readout's key (data-readout), not the method",
}


def core_names():
    names = set()
    for f in (ROOT / "src/planner/methods").rglob("*.rs"):
        names |= set(re.findall(r'info: MethodInfo \{\s*name: "([a-z0-9_]+)"', f.read_text()))
    names |= set(re.findall(r'NetworkSet::\w+ => "(\w+)"', (ROOT / "src/networks/builtin.rs").read_text()))
    names |= set(re.findall(r'Preset::\w+ => "(\w+)"', (ROOT / "src/training/preset.rs").read_text()))
    return names


def code(text):
    """JavaScript without comments (// and /* */), roughly."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return "\n".join(re.sub(r"(^|[^:'\"`])//.*$", r"\1", l) for l in text.splitlines())


def main():
    names = core_names()
    if len(names) < 10:
        print(f"check-page-facts: found only {len(names)} core names; the patterns no longer match the sources")
        return 1
    bad = []
    files = sorted((ROOT / "www").glob("*.js")) + [ROOT / "www/index.html"]
    for path in files:
        rel = str(path.relative_to(ROOT))
        text = path.read_text()
        body = code(text) if path.suffix == ".js" else re.sub(r"<!--.*?-->", "", text, flags=re.S)
        for i, line in enumerate(body.splitlines(), 1):
            for m in re.finditer(r"""(['"`])([a-z0-9_]+)\1""", line):
                word = m.group(2)
                if word in names and (rel, word) not in ALLOWED:
                    bad.append(f"{rel}:{i}: '{word}' is the core's name; read it from the module")
            if re.search(r"\d\.\d+:\d\.\d+,\d", line):
                bad.append(f"{rel}:{i}: an arm written out; read it from limits().arm_presets or the state's arm_text")
    for b in bad:
        print(b)
    if bad:
        return 1
    print(f"check-page-facts: {len(files)} page files write none of the core's {len(names)} names")
    return 0


if __name__ == "__main__":
    sys.exit(main())
