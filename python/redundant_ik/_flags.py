"""Keywords to the command-line tool's flags.

Every keyword of ``simulate``, ``atlas``, ``train``, ``evaluate`` and
``Controller`` is one of the tool's options, named as its flag without the
dashes and with ``_`` for ``-`` (``joint_limits`` is ``--joint-limits``,
``lambda_`` is ``--lambda``: ``lambda`` is a word of Python's). The list
of options is the tool's own (``_core.options``), so a keyword the tool
does not know is refused here with the names it does.
"""

from __future__ import annotations

import math
import re
import numbers
import os
from typing import Any, Dict, List, Mapping, Sequence

from . import _core

Error = _core.Error

_OPTIONS: Dict[str, Dict[str, tuple]] = {}

# Options the package sets itself: the output's form.
_INTERNAL = {"json", "csv"}

# Keywords that are not a flag's name: plural lists, Python's words.
_ALIASES = {"lambda_": "lambda", "obstacles": "obstacle", "from_": "from"}


def options(command: str) -> Dict[str, tuple]:
    """The options of a command: id -> (flag, switch, repeated)."""
    if command not in _OPTIONS:
        _OPTIONS[command] = {
            i: (flag, switch, repeated) for i, flag, switch, repeated in _core.options(command)
        }
    return _OPTIONS[command]


def _number(name: str, x: Any) -> str:
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise Error(f"{name}: expected a number, got {x!r}")
    x = float(x)
    if not math.isfinite(x):
        raise Error(f"{name}: {x} is not a finite number")
    # repr of a float is the shortest text that reads back to it.
    return repr(x) if not x.is_integer() or abs(x) >= 1e16 else str(int(x))


def _numbers(name: str, value: Any) -> str:
    if isinstance(value, str):
        return value
    try:
        items = list(value)
    except TypeError:
        return _number(name, value)
    return ",".join(_number(f"{name}[{i}]", x) for i, x in enumerate(items))


def _value(name: str, value: Any) -> str:
    """One value as the tool's text: numbers as their shortest decimal,
    sequences of numbers joined by commas, a path's points by `;`."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, str):
        return value
    if name == "path":
        # A polyline as a list of points.
        try:
            points = [_numbers(f"path[{i}]", p) for i, p in enumerate(value)]
        except TypeError:
            raise Error(f"path: expected a path's text or a list of points, got {value!r}") from None
        return "points:" + ";".join(points)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return _number(name, value)
    return _numbers(name, value)


def flags(command: str, kwargs: Mapping[str, Any]) -> List[str]:
    """The tool's flags for `command` that `kwargs` name; unknown keywords
    and values the tool cannot read raise Error."""
    known = options(command)
    out: List[str] = []
    for key, value in kwargs.items():
        if value is None:
            continue
        name = _ALIASES.get(key, key)
        if name not in known or name in _INTERNAL:
            close = sorted(keyword(k) for k in known if k.startswith(name[:3]) and k not in _INTERNAL)
            hint = f" (did you mean {', '.join(close)}?)" if close else ""
            takes = ", ".join(sorted(keyword(k) for k in known if k not in _INTERNAL))
            raise Error(f"{command}() has no keyword '{key}'{hint}; it takes {takes}")
        flag, switch, repeated = known[name]
        if switch:
            if not isinstance(value, (bool, int)):
                raise Error(f"{key}: expected True or False, got {value!r}")
            if value:
                out.append(flag)
            continue
        if repeated:
            items: Sequence[Any] = value
            if isinstance(value, str) or not _is_sequence(value):
                items = [value]
            elif value and not _is_sequence(value[0]) and not isinstance(value[0], str):
                # One obstacle given as a flat tuple.
                items = [value]
            for v in items:
                out += [flag, _value(name, v)]
            continue
        out += [flag, _value(name, value)]
    return out


def _is_sequence(x: Any) -> bool:
    if isinstance(x, (str, bytes)):
        return False
    try:
        iter(x)
    except TypeError:
        return False
    return True


_KEYWORDS = {v: k for k, v in _ALIASES.items()}


def keyword(flag: str) -> str:
    """The keyword of a flag (``--stop-distance``: ``stop_distance``)."""
    name = flag.lstrip("-").replace("-", "_")
    return _KEYWORDS.get(name, name)


def pythonic(message: str) -> str:
    """The tool's message with its flags named as the keywords where they
    name the value at fault (``invalid value '0.5:' for '--arm <ARM>'``,
    ``--obstacle: ...``)."""
    message = message.replace(" For more information, try '--help'.", "")
    message = re.sub(r"'(--[a-z][a-z0-9-]*) <[A-Z_0-9]+>'", lambda m: f"'{keyword(m.group(1))}'", message)
    return re.sub(r"^(--[a-z][a-z0-9-]*):", lambda m: f"{keyword(m.group(1))}:", message)


def run(args: List[str]) -> str:
    """The tool's command ``args`` in process: what it prints, or Error
    with its message."""
    try:
        return _core.cli(args)
    except Error as e:
        raise Error(pythonic(str(e))) from None
