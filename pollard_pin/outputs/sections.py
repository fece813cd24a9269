"""paint.json's typed sections (docs/formats.md): each a frozen dataclass with fixed keys,
read from its parsed table with every value checked (its type, finite, within its range) in
one :class:`~pollard_pin.io.table.ResultFileError` line, and written back as it was read.
:mod:`pollard_pin.outputs.schema` assembles them into the report."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import MISSING, dataclass, fields
from typing import Any

from ..checks import clip, shorten
from ..io.table import ResultFileError

# no figure of a report comes near this (the largest: film point counts, ~10⁶); a larger
# one is a corrupt or hand-made file, not a paint report
MAX_FIGURE = 1e15


def refuse(path, why: str):
    raise ResultFileError(f"{path}: not a paint report ({why})")


def bad(path, key: str, value: Any, rule: str):
    refuse(path, f"'{key}' = {shorten(value)}: {rule}")


def as_number(path, key: str, value: Any):
    """A JSON number (an int or a float; not a bool), finite and at most MAX_FIGURE in size
    (Python's JSON reader takes NaN, Infinity and integers of any length), kept as written."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        bad(path, key, value, "must be a number")
    if not (isinstance(value, int) or math.isfinite(value)) or abs(value) > MAX_FIGURE:
        bad(path, key, value, f"must be a finite number of size at most {MAX_FIGURE:.0e}")
    return value


def as_count(path, key: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        bad(path, key, value, "must be a count (an integer >= 0)")
    if value > MAX_FIGURE:
        bad(path, key, value, f"must be a count of at most {MAX_FIGURE:.0e}")
    return value


def as_text(path, key: str, value: Any) -> str:
    if not isinstance(value, str):
        bad(path, key, value, "must be a text")
    return value


def as_pair(path, key: str, value: Any) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        bad(path, key, value, "must be a list of 2 numbers")
    return tuple(as_number(path, f"{key}[{i}]", v) for i, v in enumerate(value))


def as_table(path, key: str, value: Any) -> Mapping:
    if not isinstance(value, Mapping):
        bad(path, key, value, "must be a table")
    return value


def as_list(path, key: str, value: Any) -> tuple:
    if not isinstance(value, (list, tuple)):
        bad(path, key, value, "must be a list")
    return tuple(value)


def in_range(path, key: str, value, low: float, high: float = math.inf) -> None:
    """``value`` within [low, high], else one line naming the key and the interval."""
    if not low <= value <= high:
        bad(path, key, value, f"must be in [{low:g}, {high:g}]")


def as_text_or_none(path, key: str, value: Any):
    return None if value is None else as_text(path, key, value)


# a section field's annotation -> its check (the annotations are strings: __future__)
_CHECKS = {"float": as_number, "float | None": as_number, "int": as_count, "str": as_text,
           "str | None": as_text_or_none, "tuple[float, float]": as_pair}


class Section:
    """A table of paint.json with fixed keys, in the order the package writes them; ``RANGES``
    maps a numeric key to the closed interval its value must lie in."""

    RANGES: dict = {}

    @classmethod
    def from_dict(cls, table: Any, key: str, path="paint.json"):
        """The section ``key`` of the report ``path`` from its parsed table (one
        :class:`~pollard_pin.io.table.ResultFileError` line for a wrong one)."""
        cls._first(path, table)
        table = as_table(path, key, table)
        names = [f.name for f in fields(cls)]
        for k in table:
            if k not in names:
                bad(path, f"{key}.{k}", table[k], f"unknown key; {key} holds "
                                                     f"{clip(', '.join(names), 100)}")  # paint: 19
        args = {}
        for f in fields(cls):
            if f.name in table:
                args[f.name] = _CHECKS[f.type](path, f"{key}.{f.name}", table[f.name])
                if f.name in cls.RANGES and args[f.name] is not None:
                    in_range(path, f"{key}.{f.name}", args[f.name], *cls.RANGES[f.name])
            elif f.default is MISSING:
                refuse(path, f"'{key}.{f.name}' is missing")
        return cls(**args)

    @classmethod
    def _first(cls, path, table) -> None:
        """What a section checks before its keys (nothing but for the grid)."""

    def to_dict(self) -> dict:
        """The section as paint.json holds it (its optional keys left out when None)."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None and f.default is None:
                continue
            out[f.name] = list(value) if isinstance(value, tuple) else value
        return out


@dataclass(frozen=True)
class Thickness(Section):
    """paint.json's ``thickness``: the film's statistics (docs/model.md §21, §23;
    painting.film.stats).

    Attributes
    ----------
    mean, min, max, std : float
        Over the film points (area-weighted on a part) [m].
    uniformity : float
        min / max.
    within_5pct, within_10pct : float
        The share of the area within ±5 % and ±10 % of the target.
    deviation_min, deviation_max : float
        min / target − 1 and max / target − 1.
    """

    RANGES = {**dict.fromkeys(("mean", "min", "max", "std"), (0.0, math.inf)),
              **dict.fromkeys(("uniformity", "within_5pct", "within_10pct"), (0.0, 1.0)),
              **dict.fromkeys(("deviation_min", "deviation_max"), (-1.0, math.inf))}

    mean: float
    min: float
    max: float
    std: float
    uniformity: float
    within_5pct: float
    within_10pct: float
    deviation_min: float
    deviation_max: float


@dataclass(frozen=True)
class MotorUse(Section):
    """One motor's entry of paint.json's ``motors``: each limit's use over its rating.

    Attributes
    ----------
    peak_torque, rms_torque, speed : float
        The peak torque, RMS (continuous) torque and speed over their ratings.
    """

    RANGES = dict.fromkeys(("peak_torque", "rms_torque", "speed"), (0.0, math.inf))

    peak_torque: float
    rms_torque: float
    speed: float


@dataclass(frozen=True)
class Grid(Section):
    """paint.json's ``grid`` (a panel's film): ``nv`` rows of ``nu`` points.

    Attributes
    ----------
    nu, nv : int
        Points along the panel's width and height.
    resolution : float or None
        The spacing [m].
    """

    RANGES = {"resolution": (0.0, math.inf)}

    nu: int
    nv: int
    resolution: float | None = None

    @classmethod
    def _first(cls, path, table) -> None:
        # point counts >= 1 (view reshapes the film table by them), said as view always has
        nu, nv = (table.get("nu"), table.get("nv")) if isinstance(table, Mapping) else \
            (None, None)
        check_grid(path, nu, nv)


def check_grid(path, nu, nv) -> None:
    """``nu`` and ``nv`` point counts >= 1, else the one line ``view`` has always said."""
    if not all(type(n) is int and n >= 1 for n in (nu, nv)):
        refuse(path, f"grid nu = {shorten(nu)}, nv = {shorten(nv)}: expected point counts "
                      ">= 1")


@dataclass(frozen=True)
class FilmPoints(Section):
    """paint.json's ``film_points`` (a part's film, docs/model.md §23).

    Attributes
    ----------
    painted, total : int
        The film points on painted faces, and all of them.
    resolution : float
        Their spacing [m].
    """

    RANGES = {"resolution": (0.0, math.inf)}

    painted: int
    total: int
    resolution: float


@dataclass(frozen=True)
class FilmPly(Section):
    """paint.json's ``film_ply``: what film.ply's vertex colours mean
    (``pollard_pin.film_scale.ply_colours``).

    Attributes
    ----------
    colour_map : str
        Matplotlib's name of the colour map.
    range : tuple of float
        The thickness [m] at its two ends.
    """

    colour_map: str
    range: tuple[float, float]


@dataclass(frozen=True)
class Seam(Section):
    """One entry of a cell's ``seams`` (docs/model.md §26): the film where two robots' zones
    meet.

    Attributes
    ----------
    at : float
        The seam's place along the split axis [m].
    band_m : float
        The half width of the band about it [m].
    min, max, mean : float
        The film in the band over the target.
    """

    RANGES = dict.fromkeys(("band_m", "min", "max", "mean"), (0.0, math.inf))

    at: float
    band_m: float
    min: float
    max: float
    mean: float


@dataclass(frozen=True)
class LineSpeeds(Section):
    """A line's ``line.speeds`` (``paint --speeds``): the line speeds that paint the job
    (docs/model.md §24.3; painting.line.speeds.SpeedInterval).

    Attributes
    ----------
    min, max : float
        The slowest and the fastest speed found to paint [m/s], both planned in full.
    resolution : float
        The relative bracket each end was bisected to.
    min_bound, max_bound : str
        What stops the run beyond each end: ``"budget floor"`` (the path's sample budget),
        ``"too slow: <why>"``, ``"too fast: <why>"`` or ``"searched no further"``.
    """

    RANGES = dict.fromkeys(("min", "max", "resolution"), (0.0, math.inf))

    min: float
    max: float
    resolution: float
    min_bound: str
    max_bound: str


@dataclass(frozen=True)
class Strokes(Section):
    """paint.json's ``strokes`` (a cell: each robot's): the strategy planned on a line
    (docs/model.md §24.2).

    Attributes
    ----------
    direction : str
        ``"across"`` or ``"along"`` the travel.
    step_from : str or None
        The end the strokes step from (``"leading"``, ``"trailing"``); None along the travel.
    dwell_s : float
        The waits at the turnarounds in all [s] (a line slower than the strokes' pace).
    why : str or None
        Why this strategy: ``"forced"``, a cell's rule, or ``auto``'s comparison of the
        strategies' cycles and refusals.
    """

    RANGES = {"dwell_s": (0.0, math.inf)}

    direction: str
    step_from: str | None = None
    dwell_s: float = 0.0
    why: str | None = None


@dataclass(frozen=True)
class PaintUse(Section):
    """paint.json's ``paint``, and a cell robot's (its volumes and overspray only): the paint
    the job uses (docs/model.md §29; painting.accounting). Volumes of dry film [L]; with the
    job's ``[paint]`` table, liquid paint [L] and [kg] too.

    Attributes
    ----------
    covered_share : float or None
        The share of the target the painted area's film reaches.
    painted_area_m2, target_area_m2 : float or None
        The area of the target faces with film ≥ covered_share × target, and theirs [m²].
    dry_sprayed_l, dry_on_part_l : float or None
        The dry film volume sprayed (flow × spray-on time) and on the part (∫ film dA) [L].
    overspray : float or None
        1 − dry_on_part_l / dry_sprayed_l: the geometric overspray (None: nothing sprayed).
    parts_per_hour : float or None
        3600 s over the cycle.
    solids, density, transfer_efficiency : float or None
        The paint's volume solids, density [kg/m³] and the transfer efficiency used.
    sprayed_l, sprayed_kg, on_part_l, on_part_kg : float or None
        Liquid paint per part: sprayed (dry / (solids · transfer efficiency)) and on the part
        (dry / solids).
    sprayed_l_per_h, sprayed_kg_per_h, on_part_l_per_h, on_part_kg_per_h : float or None
        The same per hour.
    holds : str or None
        Where the figures hold.
    """

    # shares and efficiencies within [0, 1]; the overspray 1 − on/sprayed may round below 0
    RANGES = {**dict.fromkeys(("covered_share", "solids", "transfer_efficiency"), (0.0, 1.0)),
              "overspray": (-1.0, 1.0),
              **dict.fromkeys(("painted_area_m2", "target_area_m2", "dry_sprayed_l",
                               "dry_on_part_l", "parts_per_hour", "density", "sprayed_l",
                               "sprayed_kg", "on_part_l", "on_part_kg", "sprayed_l_per_h",
                               "sprayed_kg_per_h", "on_part_l_per_h", "on_part_kg_per_h"),
                              (0.0, math.inf))}

    covered_share: float | None = None
    painted_area_m2: float | None = None
    target_area_m2: float | None = None
    dry_sprayed_l: float | None = None
    dry_on_part_l: float | None = None
    overspray: float | None = None
    parts_per_hour: float | None = None
    solids: float | None = None
    density: float | None = None
    transfer_efficiency: float | None = None
    sprayed_l: float | None = None
    sprayed_kg: float | None = None
    on_part_l: float | None = None
    on_part_kg: float | None = None
    sprayed_l_per_h: float | None = None
    sprayed_kg_per_h: float | None = None
    on_part_l_per_h: float | None = None
    on_part_kg_per_h: float | None = None
    holds: str | None = None


__all__ = ["FilmPly", "FilmPoints", "Grid", "LineSpeeds", "MAX_FIGURE", "MotorUse", "PaintUse",
           "Seam", "Section", "Strokes", "Thickness", "as_count", "as_list", "as_number",
           "as_pair", "as_table", "as_text", "as_text_or_none", "bad", "check_grid", "in_range",
           "refuse"]
