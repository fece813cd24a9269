"""The value rules every layer shares (a real number, finite, within bounds), written once. No
numpy: the CLI's argument types use them too. Each caller passes its own error family (a
callable taking the one-line message), so a library error still speaks of values and units
and the CLI adds the flag name."""
from __future__ import annotations

import math

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


def real(value, name: str, low: float = -math.inf, high: float = math.inf, *,
         above: bool = False, why: str = "", error=InputError) -> float:
    """``value`` as a float, checked by :func:`problem`; a string, a bool or anything that is
    not a number is refused too. Raises ``error("<name> = <value>: <problem><why>")``."""
    try:
        if isinstance(value, (str, bytes, bool)):
            raise TypeError
        x = float(value)
    except (TypeError, ValueError):
        raise error(f"{name} = {value!r}: is not a number{why}") from None
    wrong = problem(x, low, high, above)
    if wrong is not None:
        raise error(f"{name} = {value!r}: {wrong}{why}")
    return x
