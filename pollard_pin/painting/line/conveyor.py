"""The ``[line]`` table of a paint job: the conveyor the part rides (docs/model.md §24)."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ...errors import InputError
from ...model.values import fail, number

# A conveyor faster than this is a unit slip (mm/s for m/s): paint lines run at cm/s.
MAX_LINE_SPEED = 2.0  # m/s
LINE_KEYS = ("speed", "direction")


@dataclass(frozen=True)
class Line:
    """The conveyor: ``speed`` [m/s] > 0 along the unit world ``direction``."""

    speed: float
    direction: tuple[float, float, float]

    def to_dict(self) -> dict:
        return {"speed": self.speed, "direction": list(self.direction)}


def line_from_table(source: str, table: Any, error=InputError) -> Line:
    """Check a parsed [line] table (one ``error`` line per broken rule, the values shown
    short: model.values.fail)."""
    prefix = f"{source}: "
    if not isinstance(table, Mapping):
        fail(error, prefix, "line", table, "must be a table [line]")
    for k in table:
        if k not in LINE_KEYS:
            fail(error, prefix, f"line.{k}", table[k],
                 f"unknown key; [line] takes {', '.join(LINE_KEYS)}")
    for k in LINE_KEYS:
        if k not in table:
            raise error(f"{source}: 'line.{k}' is missing ([line] needs speed [m/s] and "
                        "direction [x, y, z])")
    try:
        s = number(table["speed"], "line.speed", error, prefix, positive=True,
                   limit=MAX_LINE_SPEED,
                   limit_rule=f"must be at most {MAX_LINE_SPEED:g} m/s (SI units: m/s, not mm/s)")
    except error as exc:  # the interval said whatever the rule broken (0, NaN, −, too fast)
        raise error(f"{exc}; a line speed is 0 < s ≤ {MAX_LINE_SPEED:g} m/s") from None
    d = table["direction"]
    if not isinstance(d, list) or len(d) != 3:
        fail(error, prefix, "line.direction", d, "must be a list of 3 numbers [x, y, z]")
    d = [number(c, f"line.direction[{i}]", error, prefix) for i, c in enumerate(d)]
    norm = math.hypot(*d)  # no overflow at 1e300
    if not norm > 1e-12:
        fail(error, prefix, "line.direction", d,
             "has zero length; give the part's direction of travel")
    return Line(float(s), tuple(float(c) / norm for c in d))


__all__ = ["LINE_KEYS", "Line", "MAX_LINE_SPEED", "line_from_table"]
