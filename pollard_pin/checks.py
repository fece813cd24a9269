"""The value rules every layer shares (a real number, finite, within bounds; an argument of
the expected type; a file path), written once. No numpy: the CLI's argument types use them too.
Each caller passes its own error family (a callable taking the one-line message), so a library
error still speaks of values and units and the CLI adds the flag name. The public entry points
check their arguments with these once, where they are called, so a user's mistake in Python is
the same one line the CLI gives, never a traceback from deep inside."""
from __future__ import annotations

import math
import numbers
import os
from pathlib import Path

from .errors import InputError


def problem(x: float, low: float = -math.inf, high: float = math.inf,
            above: bool = False) -> str | None:
    """What is wrong with the number x under the rule low ≤ x ≤ high (low < x with ``above``),
    x finite: "must be a finite number", "must be >= 0", "must be > 0", "must be at most 1";
    None when nothing is."""
    if not math.isfinite(x):
        return "must be a finite number"
    if x < low or (above and x == low):
        return f"must be {'>' if above else '>='} {low:g}"
    if x > high:
        return f"must be at most {high:g}"
    return None


def is_real(value, low: float = -math.inf, high: float = math.inf, *,
            above: bool = False) -> bool:
    """Whether ``value`` is a real number (not a bool or a string) that :func:`problem` passes;
    an integer beyond a float (10**400) is not, where ``math.isfinite`` would raise."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        return problem(float(value), low, high, above) is None
    except OverflowError:
        return False


def real(value, name: str, low: float = -math.inf, high: float = math.inf, *,
         above: bool = False, why: str = "", error=InputError) -> float:
    """``value`` as a float, checked by :func:`problem`; a string, a bool or anything that is
    not a number is refused too. Raises ``error("<name> = <value>: <problem><why>")``."""
    try:
        if isinstance(value, (str, bytes, bool)):
            raise TypeError
        x = float(value)
    except (TypeError, ValueError):
        raise error(f"{name} = {_shown(value)}: is not a number{why}") from None
    except OverflowError:  # an integer beyond a float (10**400)
        raise error(f"{name} = {_shown(value)}: must be a finite number{why}") from None
    wrong = problem(x, low, high, above)
    if wrong is not None:
        raise error(f"{name} = {_shown(value)}: {wrong}{why}")
    return x


def _shown(value) -> str:
    """``value`` short, for a one-line message."""
    try:
        text = repr(value)
    except (ValueError, RecursionError):  # an integer beyond str's digit limit (10**5000)
        return f"<{type(value).__name__}>"
    return text if len(text) <= 60 else text[:57] + "..."


def instance(value, name: str, kinds, expected: str, *, none: bool = False,
             error=InputError):
    """``value`` when it is one of ``kinds`` (or None, with ``none``); else
    ``error("<name> = <value>: expected <expected>, got <type>")``."""
    if (none and value is None) or isinstance(value, kinds):
        return value
    raise error(f"{name} = {_shown(value)}: expected {expected}, got {type(value).__name__}")


def callback(value, name: str, *, error=InputError):
    """``value`` when it is a function (any callable) or None; else
    ``error("<name> = <value>: expected a function or None, got <type>")``, said before any
    work rather than as a TypeError at the first call."""
    if value is None or callable(value):
        return value
    raise error(f"{name} = {_shown(value)}: expected a function or None, got "
                f"{type(value).__name__}")


def file_path(value, name: str, *, error=InputError) -> Path:
    """``value`` (a str or an os.PathLike naming a file, not empty, no NUL) as a Path; else
    ``error("<name> = <value>: ...")``."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise error(f"{name} = {_shown(value)}: expected a file path (str or pathlib.Path), "
                    f"got {type(value).__name__}")
    if not value or "\0" in value:
        raise error(f"{name} = {_shown(value)}: " + ("an empty path" if not value else
                                                      "a path with a NUL character"))
    return Path(value)


def float_array(value, name: str, *, error=InputError):
    """``value`` as an ndarray of floats; anything else (strings, complex or bool values,
    objects, ragged lists, an integer beyond a float) raises ``error("<name>: ...")``, so a
    wrong value is refused with one line before it reaches numpy or Pinocchio. numpy is
    imported here only: the CLI's argument types import this module."""
    import numpy as np

    try:
        arr = np.asarray(value)
        if arr.dtype.kind == "O":  # Python numbers numpy could not type (10**400), or worse
            arr = arr.astype(float)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{name} = {_one_line(value)}: expected an array of real numbers") from None
    if arr.dtype.kind not in "iuf":
        raise error(f"{name} = {_one_line(value)}: expected an array of real numbers, got "
                    f"{arr.dtype} values")
    return arr.astype(float, copy=False)


def _one_line(value) -> str:
    """:func:`_shown` on one line (an array's repr spans lines), made only for a refusal."""
    return " ".join(_shown(value).split())
