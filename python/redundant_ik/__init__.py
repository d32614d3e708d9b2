"""Redundancy resolution with obstacle avoidance, from Rust, in Python.

The core of ``redundant-ik`` (the command-line tool and the browser demo)
as a Python package: numpy in, numpy out, the same arithmetic as the tool.

- ``Robot``: an arm (``Robot.preset("panda")``, ``Robot.planar("0.5:0.6,0.85,0.6")``,
  ``Robot.from_urdf(path_or_text, tip=...)``), its ``forward`` kinematics and
  ``jacobian``;
- ``simulate(...)``: one planning run, a ``Run`` of numpy arrays whose
  ``to_json()`` is the tool's ``simulate --json``;
- ``Controller(robot, method="qp", obstacles=..., **params)``: one rate
  evaluation for a loop of your own (``rates(theta, xdot)``, ``step(theta, t)``);
- ``atlas(...)``: the robustness atlas, an ``Atlas`` of numpy arrays
  (``to_pandas()``);
- ``methods()``, ``train(...)``, ``evaluate(...)``, ``NETWORK_SETS``;
- ``Widget(task=1, method="case3", ...)``: the browser demo in a notebook
  (anywidget).

Keywords are the command line's flags without their dashes, ``_`` for ``-``
(``joint_limits``, ``stop_distance``; ``lambda_`` for ``--lambda``). Every
refusal raises ``Error`` (a ``ValueError``) with the core's message.
See docs/python.md.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Union

from . import _core
from ._core import Error, Robot
from ._flags import flags as _flags
from ._flags import pythonic as _pythonic
from ._flags import run as _run
from .atlas import Atlas
from .run import Run

__version__: str = _core.__version__

__all__ = [
    "Error",
    "Robot",
    "Controller",
    "Run",
    "Atlas",
    "simulate",
    "atlas",
    "methods",
    "train",
    "evaluate",
    "NETWORK_SETS",
    "Widget",
]

#: The shipped network sets: the paper's (near its tasks), the planar
#: arm's whole reach, and the Panda's whole reach in space.
NETWORK_SETS = ("paper", "reach", "panda-reach")


def _scene_flags(command: str, kwargs: Dict[str, Any]) -> List[str]:
    """The flags of a command's scene keywords; ``robot`` (a Robot)
    names the arm by its own flags."""
    kwargs = dict(kwargs)
    robot = kwargs.pop("robot", None)
    out: List[str] = []
    if robot is not None:
        if not isinstance(robot, Robot):
            raise Error(f"robot: expected a redundant_ik.Robot, got {type(robot).__name__}")
        if kwargs.get("arm") is not None:
            raise Error("robot and arm name the arm twice: give one")
        out += robot._flags
    run = kwargs.get("from_")
    if isinstance(run, Run):
        raise Error("from_: give the run file's path, or call run.replay()")
    return out + _flags(command, kwargs)


def simulate(**kwargs: Any) -> Run:
    """One planning run of a scene, as ``redundant-ik simulate --json``.

    Keywords are the tool's ``simulate`` options: ``task`` (1 or 2 for a
    planar arm, ``"position"`` or ``"pose"`` in space), ``arm`` (a preset's
    name or ``"POST:L1,L2,..."``) or ``robot`` (a ``Robot``), ``method``,
    ``theta0``, ``target``, ``obstacles`` (a list of ``(x, y[, r])`` or, in
    space, ``(x, y, z[, r])``), ``radius``, ``path`` (``"circle:CX,CY"``,
    ``"points:X,Y;X,Y"`` or a list of points), ``lambda_``, ``delta`` and
    every method's parameter by name (``influence``, ``stop_distance``,
    ...), ``tf``, ``dt``, ``feedback``, ``damping``, ``joint_limits``,
    ``rate_limits``, ``joint_weighting``, ``floor``, ``self_collision``,
    ``orientation_weight``, ``networks``, ``phi_variant``, ``phi_weights``,
    ``v_weights``, ``refine``, ``precision``, ``from_`` (a run file's path).
    ``redundant_ik.options("simulate")`` lists them all. The GIL is
    released while it runs.
    """
    args = ["simulate", "--json"] + _scene_flags("simulate", kwargs)
    return Run(_run(args))


def atlas(**kwargs: Any) -> Atlas:
    """The robustness atlas, as ``redundant-ik atlas --json``: the scene's
    first obstacle on every cell of a grid, in each method.

    Keywords: the scene's (as ``simulate``'s), ``grid`` (points per side),
    ``region`` (``(x0, x1, y0, y1)``), ``methods`` (``"paper"``, ``"all"``
    or a list of names), ``slice`` (in space: ``"xy:Z0"``, ``"xz:Y0"`` or
    ``"yz:X0"``), ``threads``. The GIL is released while it runs; Ctrl-C
    stops it between rows (KeyboardInterrupt).
    """
    kwargs = dict(kwargs)
    m = kwargs.get("methods")
    if m is not None and not isinstance(m, str):
        kwargs["methods"] = ",".join(m)
    args = ["atlas", "--json"] + _scene_flags("atlas", kwargs)
    return Atlas(_run(args))


def methods() -> List[Dict[str, Any]]:
    """Every method: its ``name``, ``label``, ``description``, ``group``
    (the paper's or beyond), the ``networks`` it needs, whether it runs
    ``in_space``, and its ``params`` (name, flag, bounds, default, unit)."""
    return json.loads(_core.methods_json())


def options(command: str) -> List[str]:
    """The keywords a command takes (``"simulate"``, ``"atlas"``,
    ``"train"``, ``"eval"``): the tool's flags without their dashes."""
    from ._flags import _INTERNAL, keyword
    from ._flags import options as _options

    return sorted(keyword(k) for k in _options(command) if k not in _INTERNAL)


def train(out: Union[str, os.PathLike], **kwargs: Any) -> str:
    """Trains a network and writes its weights file to ``out``, as
    ``redundant-ik train``: ``net`` (``"phi"`` or ``"v"``), ``recipe``,
    ``arm`` or ``robot``, ``seed``, ``samples``, ``epochs``, ... Returns the
    tool's report. The GIL is released; Ctrl-C stops it between epochs.
    Load the networks with ``simulate(phi_weights=..., v_weights=...)``."""
    kwargs = dict(kwargs, out=os.fspath(out))
    kwargs.setdefault("quiet", True)
    return _run(["train"] + _scene_flags("train", kwargs))


def evaluate(**kwargs: Any) -> Dict[str, Any]:
    """The shipped (or given) networks' accuracy and task outcomes, as
    ``redundant-ik eval --json``: ``networks``, ``samples``, ``seed``,
    ``arm`` or ``robot``, ``phi`` and ``v`` (weights files), ..."""
    kwargs = dict(kwargs)
    text = _run(["eval", "--json"] + _scene_flags("eval", kwargs))
    return json.loads(text)


class Controller(_core.Controller):
    """The joint rates of one method, for a loop of your own.

    ``Controller(robot, method="qp", obstacles=None, **params)``: the
    planner ``simulate`` would run with the same keywords (``robot`` a
    ``Robot`` or a preset's name; ``obstacles`` rows ``(x, y, r)`` in the
    plane or ``(x, y, z, r)`` in space; the methods' parameters, ``target``,
    ``path``, ``tf``, ``feedback``, ... by name).

    - ``rates(theta, xdot)``: the joint rates (rad/s) at the angles
      ``theta`` for the hand's velocity ``xdot`` (2 numbers in the plane, 3
      in space, 6 for the pose task);
    - ``step(theta, t)``: the joint rates for the path's velocity at time
      ``t`` (plus the feedback term when ``feedback`` > 0): what each stage
      of ``simulate``'s RK4 step evaluates;
    - ``obstacles`` (get and set) and ``move_obstacle(i, centre)`` move the
      obstacles between calls;
    - ``n``, ``m``, ``method``, ``theta0``, ``dt``, ``tf``, ``reference(t)``.

    Inside, each call is one kinematics pass and one rate evaluation with
    no allocation in the core (a few microseconds); the GIL is held (the
    call is too short to release it).
    """

    def __new__(
        cls,
        robot: Union[Robot, str] = "paper",
        method: str = "numerical",
        obstacles: Optional[Any] = None,
        **params: Any,
    ) -> "Controller":
        if isinstance(robot, str):
            robot = Robot.preset(robot)
        kwargs = dict(params, robot=robot, method=method, obstacles=obstacles)
        flags = _scene_flags("simulate", kwargs)
        try:
            return super().__new__(cls, flags)
        except Error as e:
            raise Error(_pythonic(str(e))) from None

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        pass

    def __reduce__(self):
        raise TypeError("a Controller holds a planner's state; pickle its Robot and keywords instead")


def _restore_robot(kind: str, *args: Any) -> Robot:
    """What a pickled Robot is made from again."""
    return Robot._restore(kind, *args)


def __getattr__(name: str) -> Any:
    # The widget needs anywidget, an optional dependency: imported on use.
    if name == "Widget":
        try:
            from .widget import Widget
        except ImportError as e:
            raise ImportError(f"redundant_ik.Widget needs anywidget: pip install anywidget ({e})") from None
        return Widget
    raise AttributeError(f"module 'redundant_ik' has no attribute '{name}'")
