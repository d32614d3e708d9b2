"""The browser demo in a notebook: an anywidget whose front end is the
npm package's ``widget.js`` (a ``<redundant-ik-demo>`` element with its
WebAssembly inline), shipped inside the wheel."""

from __future__ import annotations

import pathlib
import re
from typing import Any

import anywidget
import traitlets

from . import _core

Error = _core.Error

#: The front end: the npm package's widget.js, which ``make wheel`` puts
#: beside this file.
ESM = pathlib.Path(__file__).with_name("widget.js")

_NAME = re.compile(r"^[a-z][a-z0-9_]*$")


class Widget(anywidget.AnyWidget):
    """The browser demo in a notebook (Jupyter, VS Code, Colab, marimo).

    ``Widget(task=1, method="case3", lambda_=4, target=(0.6, 0.2),
    obstacles=[(0.6, 0.9, 0.08)], plots=True)``: each keyword is a synced
    trait named as the element's attribute, the page's address keys
    (``task``, ``method``, ``lambda``, ``feedback``, ``target``,
    ``obstacles``, ``arm``, ``floor``, ``path``, ``networks``, the
    methods' parameters by name, ...; in space ``arm="panda"``, ``urdf``,
    ``base``, ``tip``, ``orientation_weight``, ``self_collision``,
    ``view``), and ``autoplay``, ``plots``. Set one later
    (``w.method = "qp"``) and the running demo follows. Lists are written
    as the address writes them (numbers joined by commas).
    """

    _esm = ESM if ESM.exists() else "export default { render({ el }) { el.textContent = 'redundant_ik: this build has no widget front end (make wheel puts it in).'; } };"

    def __init__(self, **traits: Any) -> None:
        if not ESM.exists():
            raise Error(
                "this install of redundant_ik has no widget front end (widget.js): "
                "install the wheel `make wheel` builds, which carries it"
            )
        names = {}
        for key, value in traits.items():
            name = "lambda" if key == "lambda_" else key
            if not _NAME.match(name):
                raise Error(f"Widget: '{key}' is not an attribute's name (lower case, digits, _)")
            names[name] = value
        super().__init__()
        self.add_traits(**{n: traitlets.Any().tag(sync=True) for n in names})
        for n, v in names.items():
            setattr(self, n, _plain(v))


def _plain(value: Any) -> Any:
    """A value as JSON carries it: tuples and numpy arrays as lists."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value
