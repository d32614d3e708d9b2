"""A planning run: what ``simulate`` returns and a run file reads."""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Dict, List, Optional

import numpy as np

from . import _core

Error = _core.Error


class Run:
    """One planning run, step by step, as numpy arrays.

    ``t`` (s, ``steps``), ``theta`` (rad, ``steps x n``), ``hand`` (the
    hand's position, ``steps x 2`` in the plane or ``steps x 3`` in space;
    for the hand's pose task ``pose`` is ``steps x 6``, position then
    rotation vector), ``reference`` (the path's point at each step),
    ``tracking_error`` (m), ``distance`` and ``clearance`` (the smallest
    link-to-obstacle distance and clearance, m; NaN without obstacles),
    ``collision`` (bool per step), ``points`` (the chain's points per
    step). ``summary`` is a dict (``min_clearance``, ``final_error``,
    ``collided``, ``reached``, ...), ``scene`` the scene as the run file
    holds it, ``method`` the method's name.

    ``to_json()`` is the run file, byte for byte what ``redundant-ik
    simulate --json`` writes for the same settings; ``Run.from_json(text)``
    reads one (the command line's, or the page's "Download run");
    ``replay()`` runs its scene again. A run pickles as its file.
    """

    def __init__(self, text: str):
        try:
            data = json.loads(text)
        except ValueError as e:
            raise Error(f"not a run file: {e}") from None
        if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
            raise Error("not a run file: it has no steps (a run file is what simulate --json writes)")
        self._text = text
        self._data = data
        steps: List[Dict[str, Any]] = data["steps"]
        if not steps:
            raise Error("not a run file: its steps are empty")

        def column(key: str, dtype: Any = float) -> np.ndarray:
            return np.array(
                [np.nan if s.get(key) is None else s.get(key) for s in steps], dtype=dtype
            )

        self.t = column("t")
        self.theta = np.array([s["theta"] for s in steps], dtype=float)
        ee = np.array([s["ee"] for s in steps], dtype=float)
        # The pose task's hand is its pose: position, then rotation vector.
        if ee.shape[1] == 6:
            self.pose = ee
            self.hand = ee[:, :3].copy()
        else:
            self.pose = None
            self.hand = ee
        self.reference = np.array([s["reference"] for s in steps], dtype=float)
        self.tracking_error = column("tracking_error")
        self.distance = column("distance")
        self.clearance = column("clearance")
        self.collision = np.array([bool(s.get("collision")) for s in steps])
        self.points = np.array([s["joints"] for s in steps], dtype=float)
        self.summary: Dict[str, Any] = data.get("summary", {})
        self.scene: Dict[str, Any] = data.get("scene", {})
        self.method: str = data.get("method", "")
        self.task: Optional[int] = data.get("task")

    @classmethod
    def from_json(cls, text: str) -> "Run":
        """Reads a run file's text (or a path to one)."""
        if not isinstance(text, str):
            if isinstance(text, os.PathLike):
                text = open(text, encoding="utf-8").read()
            else:
                raise Error(f"Run.from_json: expected the run file's text, got {type(text).__name__}")
        elif not text.lstrip().startswith("{") and os.path.exists(text):
            text = open(text, encoding="utf-8").read()
        return cls(text)

    def to_json(self) -> str:
        """The run file's text: what ``simulate --json`` writes."""
        return self._text

    def replay(self, **kwargs: Any) -> "Run":
        """Runs this run's scene again (``simulate --from`` its file), with
        another ``method`` or network option if given."""
        from . import simulate

        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "run.json")
            with open(path, "w", encoding="utf-8") as f:
                f.write(self._text)
            return simulate(from_=path, **kwargs)

    @property
    def n(self) -> int:
        """Joints."""
        return self.theta.shape[1]

    def __len__(self) -> int:
        return len(self.t)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"Run(method='{self.method}', steps={len(self)}, n={self.n}, "
            f"min_clearance={s.get('min_clearance')}, final_error={s.get('final_error')})"
        )

    def __reduce__(self):
        return (Run, (self._text,))
