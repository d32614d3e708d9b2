"""The robustness atlas: what ``atlas`` returns."""

from __future__ import annotations

import json
from typing import Any, Dict, List

import numpy as np

from . import _core

Error = _core.Error


class Atlas:
    """The scene run with its obstacle on every cell of a grid, in each
    method, as numpy arrays.

    ``methods`` (names), ``centres`` (each cell's obstacle centre, ``cells
    x 2`` in the plane or ``cells x 3`` in space), ``grid`` (points per
    side; cells run row by row, x fastest), ``region``, and per method
    (dicts keyed by the method's name): ``classes`` (``"success"``,
    ``"collision"``, ``"limit"``, ``"missed"``, ``"failed"``,
    ``"path_blocked"``, ``"start_overlap"``, ``"self_collision"``),
    ``clearance`` and ``distance`` (the run's smallest, m; NaN where none),
    ``final_error`` (m); ``avoidance_needed`` (bool per cell).
    ``success_rate(method)`` counts as the tool does, over the cells where
    avoidance is possible. ``to_pandas()`` is one row per cell and method;
    ``to_json()`` the tool's ``atlas --json``.
    """

    def __init__(self, text: str):
        self._text = text
        data = json.loads(text)
        self.data: Dict[str, Any] = data
        self.methods: List[str] = list(data["methods"])
        self.grid: int = data["grid"]["n"]
        self.region = tuple(data["grid"]["region"])
        cells = data["cells"]
        if cells and "centre" in cells[0]:
            self.centres = np.array([c["centre"] for c in cells], dtype=float)
            outcome = lambda c, k, m: c["outcomes"][k]  # noqa: E731
        else:
            self.centres = np.array([[c["x"], c["y"]] for c in cells], dtype=float)
            outcome = lambda c, k, m: c["outcomes"][m]  # noqa: E731
        self.avoidance_needed = np.array([bool(c.get("avoidance_needed")) for c in cells])

        def num(x: Any) -> float:
            return np.nan if x is None else float(x)

        self.classes: Dict[str, np.ndarray] = {}
        self.clearance: Dict[str, np.ndarray] = {}
        self.distance: Dict[str, np.ndarray] = {}
        self.final_error: Dict[str, np.ndarray] = {}
        for k, m in enumerate(self.methods):
            o = [outcome(c, k, m) for c in cells]
            self.classes[m] = np.array([x["class"] for x in o])
            self.clearance[m] = np.array([num(x["min_clearance"]) for x in o])
            self.distance[m] = np.array([num(x["min_distance"]) for x in o])
            self.final_error[m] = np.array([num(x["final_error"]) for x in o])

    def success_rate(self, method: str) -> float:
        """Successes over the cells where avoidance is possible (neither
        ``path_blocked`` nor ``start_overlap``)."""
        if method not in self.classes:
            raise Error(f"the atlas has no method '{method}': it has {', '.join(self.methods)}")
        c = self.classes[method]
        possible = ~np.isin(c, ["path_blocked", "start_overlap"])
        n = int(possible.sum())
        return float((c[possible] == "success").sum() / n) if n else float("nan")

    def to_pandas(self) -> Any:
        """One row per cell and method: the centre, the method, its class,
        clearance, distance and final error, and whether avoidance was
        needed. Needs pandas."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Atlas.to_pandas needs pandas: pip install pandas") from None
        axes = ["x", "y", "z"][: self.centres.shape[1]]
        frames = []
        for m in self.methods:
            d = {a: self.centres[:, i] for i, a in enumerate(axes)}
            d.update(
                method=m,
                cls=self.classes[m],
                clearance=self.clearance[m],
                distance=self.distance[m],
                final_error=self.final_error[m],
                avoidance_needed=self.avoidance_needed,
            )
            frames.append(pd.DataFrame(d))
        return pd.concat(frames, ignore_index=True).rename(columns={"cls": "class"})

    def to_json(self) -> str:
        """The tool's ``atlas --json``."""
        return self._text

    def __len__(self) -> int:
        return len(self.centres)

    def __repr__(self) -> str:
        rates = ", ".join(f"{m} {100 * self.success_rate(m):.1f}%" for m in self.methods)
        return f"Atlas({self.grid} x {self.grid}: {rates})"

    def __reduce__(self):
        return (Atlas, (self._text,))
