"""The paint job file's tables (``[panel]`` or ``[part]``, ``[gun]``, ``[job]``; SI units)
checked key by key: which keys each takes, and the rules of their values (:mod:`.job` reads
the file and builds the job from them).

Every rule broken is one :class:`JobError` line naming the job's source, the key, its value
and the rule.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..checks import NUL_IN_PATH
from ..model.params import did_you_mean
from ..model.values import fail, integer, number
from .errors import JobError
from .gun_table import SPOT_KEYS, required_gun_keys, spot_values

# Required and optional keys per table, in file order.
REQUIRED = {"panel": ("center", "normal", "width", "height"),
            "gun": ("standoff", "sigma", "flow"),
            "job": ("thickness",)}
OPTIONAL = {"panel": (),
            "gun": ("clearance", "recoil", *(k for k in SPOT_KEYS if k != "sigma")),
            "job": ("spacing", "speed", "direction", "coats", "actuators")}
# A part's mesh instead of a panel (paint/target/mesh.py reads and places it): [part]
# replaces [panel].
PART_REQUIRED = ("mesh", "position")
PART_OPTIONAL = ("units", "scale", "rotation", "facing", "max_angle")
# The mesh file's length unit [m]: ``units`` names one, or ``scale`` gives it as a number
# (a mesh of unknown unit, sized to a plausible part).
UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "in": 0.0254}
DIRECTIONS = ("horizontal", "vertical")
# A length beyond this is a unit slip (mm for m): the robot reaches ~0.5 m.
MAX_LENGTH = 10.0
# The spray's recoil [N]: a gun kicks back by a few N at most; beyond this a unit slip (the
# drives' linear deflection, docs/model.md §27.7, is long gone anyway).
MAX_RECOIL = 100.0


def unit_values(source: str, part: Mapping) -> dict:
    """``units`` (a name of UNITS) or ``scale`` (the file's unit [m], a number > 0), not
    both: the job reader's one rule for the mesh's length unit."""
    if "units" in part and "scale" in part:
        raise JobError(f"{source}: give part.units or part.scale, not both (scale = the mesh "
                       "file's length unit in m, e.g. 0.001 for mm)")
    if "scale" in part:
        scale = checked_positive(source, "part.scale", part["scale"])
        if not 1e-6 <= scale <= 1e3:
            fail_key(source, "part.scale", part["scale"], "must be within 1e-6..1e3 m per file "
                     "unit (the mesh's length unit in m: 0.001 for mm)")
        return {"scale": scale}
    if "units" in part:
        u = part["units"]
        if not (isinstance(u, str) and u in UNITS):
            fail_key(source, "part.units", u, f"must be {', '.join(repr(k) for k in UNITS)}"
                     f"{did_you_mean(str(u), tuple(UNITS))} (or give part.scale, the unit in m)")
        return {"units": u}
    return {}


def fail_key(source: str, key: str, value: Any, rule: str):
    """One :class:`JobError` line: the job's ``source``, the ``key``, its ``value``, the
    ``rule`` it breaks."""
    fail(JobError, f"{source}: ", key, value, rule)


_LENGTH_RULE = f"must be at most {MAX_LENGTH:g} m in size (SI units: metres, not mm)"


def checked_number(source: str, key: str, value: Any, length: bool = False,
                   positive: bool = False) -> float:
    """``value`` as a finite float (> 0 if ``positive``; a ``length`` at most MAX_LENGTH m)."""
    return number(value, key, JobError, f"{source}: ", positive=positive,
                  limit=MAX_LENGTH if length else None, limit_rule=_LENGTH_RULE)


def checked_positive(source: str, key: str, value: Any, length: bool = False) -> float:
    """``value`` as a float > 0 (:func:`checked_number`)."""
    return checked_number(source, key, value, length, positive=True)


def checked_vector(source: str, key: str, value: Any) -> tuple[float, float, float]:
    """``value`` as 3 lengths [m] (x, y, z)."""
    if not isinstance(value, list) or len(value) != 3:
        fail_key(source, key, value, "must be a list of 3 numbers [x, y, z]")
    return tuple(checked_number(source, f"{key}[{i}]", v, length=True) for i, v in enumerate(value))


def check_table(source: str, d: Mapping, name: str) -> Mapping:
    """The table ``name`` of ``d``: present, a table, no unknown key, every required key
    (the gun's, its spray model's) given."""
    if name not in d:
        raise JobError(f"{source}: missing table [{name}] (a job has [panel] or [part], [gun] "
                       "and [job])")
    table = d[name]
    if not isinstance(table, Mapping):
        fail_key(source, name, table, f"must be a table [{name}]")
    required = PART_REQUIRED if name == "part" else REQUIRED[name]
    allowed = required + (PART_OPTIONAL if name == "part" else OPTIONAL[name])
    if name == "gun":  # the keys its spray model needs (gun_table.py)
        required = required_gun_keys(source, table)
    for k in table:
        if k not in allowed:
            fail_key(source, f"{name}.{k}", table[k],
                     f"unknown key{did_you_mean(k, allowed)}; [{name}] takes "
                     f"{', '.join(allowed)}")
    for k in required:
        if k not in table:
            raise JobError(f"{source}: '{name}.{k}' is missing ([{name}] needs "
                           f"{', '.join(required)})")
    return table


def gun_values(source: str, gun: Mapping) -> dict:
    """The [gun] table's values (standoff, the spot's, flow, clearance, recoil) checked."""
    values = {"standoff": checked_positive(source, "gun.standoff", gun["standoff"], length=True)}
    values.update(spot_values(source, gun, values["standoff"], MAX_LENGTH))
    values["flow"] = checked_positive(source, "gun.flow", gun["flow"])
    if "clearance" in gun:  # the gun body's least distance from the part (§25)
        values["clearance"] = checked_number(source, "gun.clearance", gun["clearance"], length=True)
        if values["clearance"] < 0:
            fail_key(source, "gun.clearance", gun["clearance"], "must be ≥ 0 m")
    if "recoil" in gun:  # along the spray axis, pushing the gun back (§27.7)
        values["recoil"] = number(gun["recoil"], "gun.recoil", JobError, f"{source}: ",
                                  nonnegative=True, limit=MAX_RECOIL,
                                  limit_rule=f"must be at most {MAX_RECOIL:g} N (the force "
                                             "the spray pushes the gun back with)")
    return values


def job_values(source: str, job: Mapping) -> dict:
    """The [job] table's numbers (thickness, spacing, speed, coats), its direction and
    actuators checked."""
    values = {}
    values["thickness"] = checked_positive(source, "job.thickness", job["thickness"], length=True)
    for k in ("spacing", "speed"):
        if k in job:
            values[k] = checked_positive(source, f"job.{k}", job[k], length=k == "spacing")
    if "direction" in job and job["direction"] not in DIRECTIONS:
        fail_key(source, "job.direction", job["direction"],
                 f"must be {' or '.join(repr(x) for x in DIRECTIONS)}"
                 f"{did_you_mean(str(job['direction']), DIRECTIONS)}")
    if "coats" in job:
        values["coats"] = integer(job["coats"], "job.coats", JobError, f"{source}: ")
    a = job.get("actuators")
    if "actuators" in job and not (isinstance(a, str) and a):
        fail_key(source, "job.actuators", a, "must be a file name (a non-empty string)")
    if isinstance(a, str) and "\0" in a:  # the words of every reader's NUL refusal
        fail_key(source, "job.actuators", a, NUL_IN_PATH)
    return values


__all__ = ["DIRECTIONS", "MAX_LENGTH", "MAX_RECOIL", "OPTIONAL", "PART_OPTIONAL",
           "PART_REQUIRED", "REQUIRED", "UNITS", "check_table", "checked_number",
           "checked_positive", "checked_vector", "fail_key", "gun_values", "job_values",
           "unit_values"]
