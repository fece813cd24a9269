"""The robots of a paint cell: ``[[robot]]`` tables of a line job (docs/model.md §26).

Each robot has a name (its output folder), its base origin in the world [m] and its base's
rotation (rx, ry, rz) [deg] about the world axes, R = Rx·Ry·Rz, the convention of a part's
rotation (:func:`pollard_pin.analytic.taskspace.turn`). A robot's base frame is world ← base:
p_world = R·p_base + base.
"""
from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...analytic.taskspace import turn
from ...model.params import did_you_mean
from ...model.values import fail, number
from ..errors import CellError

ROBOT_KEYS = ("name", "base", "rotation")
MAX_ROBOTS = 16  # a booth holds 4-8 robots a zone; more is a slip
MAX_DISTANCE = 10.0  # m: a base this far from the origin is a unit slip (mm for m)
MAX_TURN = 360.0  # deg
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_-]{0,31}")  # a folder name on every system




@dataclass(frozen=True)
class CellRobot:
    """One robot of a cell: ``name``, ``base`` [m] (world), ``rotation`` [deg] about world
    x, y, z (R = Rx·Ry·Rz)."""

    name: str
    base: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def R(self) -> np.ndarray:
        """The base's rotation, world ← base (3, 3)."""
        return turn(*self.rotation)

    @property
    def origin(self) -> np.ndarray:
        return np.array(self.base, dtype=float)

    def to_world(self, points) -> np.ndarray:
        """Base-frame points (..., 3) → world."""
        return np.asarray(points, float) @ self.R.T + self.origin

    def to_base(self, points) -> np.ndarray:
        """World points (..., 3) → the base frame."""
        return (np.asarray(points, float) - self.origin) @ self.R

    def direction_to_base(self, v) -> np.ndarray:
        """A world direction (..., 3) in the base frame."""
        return np.asarray(v, float) @ self.R

    @property
    def is_origin(self) -> bool:
        """At the world origin, unturned: the single robot of a job without ``[[robot]]``."""
        return not any(self.base) and not any(self.rotation)

    def to_dict(self) -> dict:
        return {"name": self.name, "base": list(self.base), "rotation": list(self.rotation)}


def turn_angle(value: Any, key: str, error: type[Exception], prefix: str = "") -> float:
    """``value`` as an angle [deg] within ±:data:`MAX_TURN` (a robot's or a part's rotation),
    or ``error``: ``{prefix}'{key}' = {value}: must be within ±360 deg``."""
    return number(value, key, error, prefix, limit=MAX_TURN,
                  limit_rule=f"must be within ±{MAX_TURN:g} deg")


def _triple(source: str, key: str, value: Any, limit: float, unit: str) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        fail(CellError, f"{source}: ", key, value, "must be a list of 3 numbers [x, y, z]")
    rule = f"must be within ±{limit:g} {unit}" + (" (SI units: m, not mm)" if unit == "m" else "")
    return tuple(number(v, f"{key}[{i}]", CellError, f"{source}: ", limit=limit, limit_rule=rule)
                 for i, v in enumerate(value))


def robots_from_tables(source: str, tables: Any) -> tuple[CellRobot, ...]:
    """Check the parsed ``[[robot]]`` array of tables: names unique and fit for a folder,
    bases and rotations three finite numbers."""
    if not isinstance(tables, Sequence) or isinstance(tables, (str, bytes)) or not tables:
        fail(CellError, f"{source}: ", "robot", tables,
             "must be an array of tables [[robot]] (name, base, rotation)")
    if len(tables) > MAX_ROBOTS:
        raise CellError(f"{source}: {len(tables)} [[robot]] tables; a cell has at most "
                        f"{MAX_ROBOTS}")
    robots = []
    for i, t in enumerate(tables):
        where = f"robot[{i}]"
        if not isinstance(t, Mapping):
            fail(CellError, f"{source}: ", where, t, "must be a table [[robot]]")
        for k in t:
            if k not in ROBOT_KEYS:
                fail(CellError, f"{source}: ", f"{where}.{k}", t[k],
                     f"unknown key{did_you_mean(k, ROBOT_KEYS)}; [[robot]] takes "
                     f"{', '.join(ROBOT_KEYS)}")
        for k in ("name", "base"):
            if k not in t:
                raise CellError(f"{source}: '{where}.{k}' is missing ([[robot]] needs name "
                                "and base [x, y, z] m; rotation [deg] is optional)")
        name = t["name"]
        if not isinstance(name, str) or not NAME.fullmatch(name):
            fail(CellError, f"{source}: ", f"{where}.name", name,
                 "must be 1-32 letters, digits, '_' or '-' (it names the robot's folder)")
        base = _triple(source, f"{where}.base", t["base"], MAX_DISTANCE, "m")
        rot = _triple(source, f"{where}.rotation", t.get("rotation", [0.0, 0.0, 0.0]),
                      MAX_TURN, "deg")
        robots.append(CellRobot(name, base, rot))
    # compared case-folded: 'low' and 'LOW' are one folder on a case-insensitive file system
    folded = [r.name.casefold() for r in robots]
    for i, n in enumerate(folded):
        if n in folded[:i]:
            j = folded.index(n)
            a, b = robots[j].name, robots[i].name
            said = (f"two robots are named {a!r}" if a == b else
                    f"robots {a!r} and {b!r} differ only in case")
            raise CellError(f"{source}: {said} (robot[{j}] and robot[{i}]); each names its "
                            "own output folder" + ("" if a == b else ", and the two collide "
                                                   "on a case-insensitive file system"))
    return tuple(robots)


def base_footprint(model) -> float:
    """The radius [m] of the robot's base: the farthest base joint from the base origin."""
    return max(float(np.linalg.norm(model.jointPlacements[j].translation))
               for j in range(1, model.njoints) if model.parents[j] == 0)


def check_spacing(robots: Sequence[CellRobot], least: float, source: str = "<python>") -> None:
    """Refuse two bases closer than ``least`` [m] (the robots' own size)."""
    for i, a in enumerate(robots):
        for b in robots[i + 1:]:
            d = float(np.linalg.norm(a.origin - b.origin))
            if d < least:
                raise CellError(f"{source}: robots {a.name!r} and {b.name!r} stand "
                                f"{d * 1e3:.0f} mm apart, closer than a robot's own base "
                                f"({least * 1e3:.0f} mm): move one")




__all__ = ["CellRobot", "MAX_ROBOTS", "ROBOT_KEYS", "base_footprint",
           "check_spacing", "robots_from_tables"]

