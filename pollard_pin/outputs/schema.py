"""paint.json's schema: the report ``pollard-pin paint`` writes beside its film, as frozen
dataclasses, with the one writer (:func:`dumps`, the file's exact text) and the one reader
(:func:`read_paint_json`, one line for a file that is no paint report).

Every report the package writes has ``job``, ``thickness``, ``target``, ``cycle_time``,
``motors``, ``timings``, ``film_ply`` and ``pollard_pin`` (the version); a panel's has
``grid``, a part's ``film_points``, a line's ``line``, a cell's ``kind``, ``seams`` and
``robots``; ``compliance`` and ``clearance`` are there when computed (docs/model.md §21, §23,
§24, §26, §27.7; docs/formats.md). Only ``target`` is required to read a report (``view``
needs no more); each other section is typed when present. The keys of no typed section (the
plan's numbers: passes, spacing, speed …) are kept as written in :attr:`PaintJson.extra`, and
the order of the keys in :attr:`PaintJson.order`, so that a report read and written back is
the same text."""
from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import MISSING, dataclass, field, fields
from pathlib import Path
from typing import Any

from ..io.json_text import finite_json
from ..io.table import ResultFileError
from ..model.values import clip, open_regular, shorten

# a report is a few kB (a cell of 16 robots: ~60 kB); anything near this is no report
MAX_REPORT_BYTES = 16 << 20


def _refuse(path, why: str):
    raise ResultFileError(f"{path}: not a paint report ({why})")


def _bad(path, key: str, value: Any, rule: str):
    _refuse(path, f"'{key}' = {shorten(value)}: {rule}")


def _number(path, key: str, value: Any):
    """A JSON number (an int or a float; not a bool), kept as written."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        _bad(path, key, value, "must be a number")
    return value


def _count(path, key: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        _bad(path, key, value, "must be a count (an integer >= 0)")
    return value


def _text(path, key: str, value: Any) -> str:
    if not isinstance(value, str):
        _bad(path, key, value, "must be a text")
    return value


def _pair(path, key: str, value: Any) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        _bad(path, key, value, "must be a list of 2 numbers")
    return tuple(_number(path, f"{key}[{i}]", v) for i, v in enumerate(value))


def _table(path, key: str, value: Any) -> Mapping:
    if not isinstance(value, Mapping):
        _bad(path, key, value, "must be a table")
    return value


def _list(path, key: str, value: Any) -> tuple:
    if not isinstance(value, (list, tuple)):
        _bad(path, key, value, "must be a list")
    return tuple(value)


def _text_or_none(path, key: str, value: Any):
    return None if value is None else _text(path, key, value)


# a section field's annotation -> its check (the annotations are strings: __future__)
_CHECKS = {"float": _number, "float | None": _number, "int": _count, "str": _text,
           "str | None": _text_or_none, "tuple[float, float]": _pair}


class Section:
    """A table of paint.json with fixed keys, in the order the package writes them."""

    @classmethod
    def from_dict(cls, table: Any, key: str, path="paint.json"):
        """The section ``key`` of the report ``path`` from its parsed table (one
        :class:`~pollard_pin.io.table.ResultFileError` line for a wrong one)."""
        cls._first(path, table)
        table = _table(path, key, table)
        names = [f.name for f in fields(cls)]
        for k in table:
            if k not in names:
                _bad(path, f"{key}.{k}", table[k], f"unknown key; {key} holds "
                                                     f"{clip(', '.join(names), 100)}")  # paint: 19
        args = {}
        for f in fields(cls):
            if f.name in table:
                args[f.name] = _CHECKS[f.type](path, f"{key}.{f.name}", table[f.name])
            elif f.default is MISSING:
                _refuse(path, f"'{key}.{f.name}' is missing")
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
        _refuse(path, f"grid nu = {shorten(nu)}, nv = {shorten(nv)}: expected point counts "
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


# the typed sections: attribute -> paint.json's key, in the order a panel's report has them
KEYS = {"job": "job", "kind": "kind", "thickness": "thickness", "target": "target",
        "cycle_time": "cycle_time", "line": "line", "strokes": "strokes", "seams": "seams",
        "robots": "robots",
        "clearance": "clearance", "motors": "motors", "grid": "grid",
        "film_points": "film_points", "timings": "timings", "compliance": "compliance",
        "film_ply": "film_ply", "paint": "paint", "version": "pollard_pin"}


@dataclass(frozen=True)
class PaintJson:
    """paint.json: the report of one ``paint`` (every kind: a panel, a part, on a line, a
    cell), its sections typed.

    Attributes
    ----------
    target : float
        The target film thickness [m] (> 0, finite).
    job : Mapping or None
        The job as planned (its ``panel`` or ``part``, ``gun``, ``job``, ``line``,
        ``robot`` tables).
    kind : str or None
        A cell's kind (``"cell panel"``, ``"cell part"``).
    thickness : Thickness or None
        The film's statistics.
    cycle_time : float or None
        The cycle [s].
    line : Mapping or None
        On a line: speed, direction, cycle, pitch, parts per hour … (read by the job's rule,
        ``painting.line.conveyor.line_from_table``, where it moves a film), and with
        ``paint --speeds`` the speeds that paint the job (its ``speeds``, a
        :class:`LineSpeeds`, checked).
    strokes : Strokes or None
        On a line (not a cell, whose robots each have theirs): the strokes' strategy.
    seams : tuple of Seam or None
        A cell's seams.
    robots : tuple of Mapping or None
        A cell's robots: name, base, rotation (read by the job's rule,
        ``painting.cell.robots.robots_from_tables``), zone, start, program, motors ….
    clearance : Mapping or None
        The gun's (a cell: the robots' too) least distance from the part.
    motors : Mapping of str to MotorUse, or None
        Each motor's use of its ratings.
    grid : Grid or None
        A panel's film grid.
    film_points : FilmPoints or None
        A part's film points.
    timings : Mapping of str to float, or None
        Seconds spent planning, integrating the film, on the compliance.
    compliance : Mapping or None
        What the drives' springs do to the gun and the film (docs/model.md §27.7).
    film_ply : FilmPly or None
        What film.ply's colours mean.
    paint : PaintUse or None
        The paint the job uses (docs/model.md §29).
    version : str or None
        The package's version that wrote it (key ``pollard_pin``).
    extra : Mapping
        Every other key, as written (the plan's numbers: passes, spacing, speed …).
    order : tuple of str
        The keys in the file's order (empty: the typed sections' order, then ``extra``'s).
    """

    target: float
    job: Mapping | None = None
    kind: str | None = None
    thickness: Thickness | None = None
    cycle_time: float | None = None
    line: Mapping | None = None
    strokes: Strokes | None = None
    seams: tuple | None = None
    robots: tuple | None = None
    clearance: Mapping | None = None
    motors: Mapping | None = None
    grid: Grid | None = None
    film_points: FilmPoints | None = None
    timings: Mapping | None = None
    compliance: Mapping | None = None
    film_ply: FilmPly | None = None
    paint: PaintUse | None = None
    version: str | None = None
    extra: Mapping = field(default_factory=dict)
    order: tuple = ()

    def __post_init__(self):
        clash = set(self.extra) & set(KEYS.values())
        if clash:
            raise ValueError(f"extra holds typed sections: {sorted(clash)}")

    @property
    def is_cell(self) -> bool:
        """A cell's report (robots listed)."""
        return bool(self.robots)

    @property
    def is_part(self) -> bool:
        """A part's report (its job has a ``part`` table), not a panel's."""
        return isinstance(self.job, Mapping) and "part" in self.job

    @classmethod
    def from_dict(cls, report: Any, path="paint.json") -> PaintJson:
        """The report parsed from ``report`` (paint.json's object, or the report a plan
        computed), every present section checked: one
        :class:`~pollard_pin.io.table.ResultFileError` line naming ``path`` otherwise.

        Parameters
        ----------
        report : Mapping
            paint.json's top-level table.
        path : str or Path
            Where it comes from, for the messages.
        """
        if not isinstance(report, Mapping):
            _refuse(path, "not a table")
        target = report.get("target")
        if isinstance(target, bool) or not isinstance(target, (int, float)) or \
                not 0 < target < math.inf:
            raise ResultFileError(f"{path}: target = {shorten(target)}: expected a film "
                                  "thickness > 0 [m]")
        args, extra = {"target": target}, {}
        if "grid" in report:  # the film's shape: checked first, as view always has
            args["grid"] = Grid.from_dict(report["grid"], "grid", path)
        attr = {k: a for a, k in KEYS.items()}
        for key, value in report.items():
            if key not in attr:
                extra[key] = value
            elif attr[key] not in args:
                args[attr[key]] = _READ[attr[key]](path, key, value)
        return cls(**args, extra=extra, order=tuple(report))

    def to_dict(self) -> dict:
        """paint.json's object: the keys in :attr:`order`, the others after."""
        values = {}
        for a, k in KEYS.items():
            v = getattr(self, a)
            if v is not None:
                values[k] = _WRITE.get(a, _as_is)(v)
        values.update(self.extra)
        out = {k: values[k] for k in self.order if k in values}
        out.update((k, v) for k, v in values.items() if k not in out)
        return out


def _as_is(value):
    return value


def _motors(path, key, value) -> dict:
    return {n: MotorUse.from_dict(u, f"{key}.{n}", path)
            for n, u in _table(path, key, value).items()}


def _timings(path, key, value) -> dict:
    return {n: _number(path, f"{key}.{n}", t) for n, t in _table(path, key, value).items()}


def _robots(path, key, value) -> tuple:
    out = tuple(_table(path, f"{key}[{i}]", r) for i, r in enumerate(_list(path, key, value)))
    for i, r in enumerate(out):  # each robot's strategy checked, kept as written
        if "strokes" in r:
            Strokes.from_dict(r["strokes"], f"{key}[{i}].strokes", path)
        if "paint" in r:
            PaintUse.from_dict(r["paint"], f"{key}[{i}].paint", path)
    return out


def _line(path, key, value) -> Mapping:
    """The line table as written, its ``speeds`` (when there) checked."""
    table = _table(path, key, value)
    if "speeds" in table:
        LineSpeeds.from_dict(table["speeds"], f"{key}.speeds", path)
    return table


def _seams(path, key, value) -> tuple:
    return tuple(Seam.from_dict(s, f"{key}[{i}]", path)
                 for i, s in enumerate(_list(path, key, value)))


def _section(cls):
    return lambda path, key, value: cls.from_dict(value, key, path)


_READ = {"job": _table, "kind": _text, "thickness": _section(Thickness),
         "cycle_time": _number, "line": _line, "strokes": _section(Strokes),
         "seams": _seams, "robots": _robots,
         "clearance": _table, "motors": _motors,
         "film_points": _section(FilmPoints), "timings": _timings, "compliance": _table,
         "film_ply": _section(FilmPly), "paint": _section(PaintUse), "version": _text}
_WRITE = {"thickness": Thickness.to_dict, "strokes": Strokes.to_dict, "grid": Grid.to_dict,
          "film_points": FilmPoints.to_dict, "film_ply": FilmPly.to_dict,
          "paint": PaintUse.to_dict,
          "motors": lambda m: {n: u.to_dict() for n, u in m.items()},
          "seams": lambda s: [x.to_dict() for x in s], "robots": list,
          "timings": dict}


def dumps(report: PaintJson) -> str:
    """paint.json's text: the report's object, indented by 2, a newline at the end (the
    one writer: ``pollard-pin paint`` writes this).

    Parameters
    ----------
    report : PaintJson
        The report.
    """
    return finite_json(report.to_dict(), "paint.json", indent=2) + "\n"


def load_paint_json(path: str | Path) -> dict:
    """paint.json's object as parsed, unchecked but for being a JSON table: a missing,
    special (a FIFO), over-large, non-UTF-8 or malformed file raises one
    :class:`~pollard_pin.io.table.ResultFileError` line.

    Parameters
    ----------
    path : str or Path
        The file.
    """
    try:
        with open_regular(path, "rb") as f:  # never a FIFO: it would block
            data = f.read(MAX_REPORT_BYTES + 1)
    except OSError as exc:
        raise ResultFileError(f"{path}: not a paint report ({clip(exc, 100)})") from None
    if len(data) > MAX_REPORT_BYTES:
        _refuse(path, f"over {MAX_REPORT_BYTES / 2**20:.4g} MiB")
    try:
        report = json.loads(data.decode("utf-8"))
    except (ValueError, RecursionError) as exc:  # not UTF-8, not JSON; deep nesting
        raise ResultFileError(f"{path}: not a paint report ({clip(exc, 100)})") from None
    if not isinstance(report, dict):
        _refuse(path, "not a table")
    return report


def read_paint_json(path: str | Path) -> PaintJson:
    """The paint report in ``path`` (``DIR/paint.json``), every section checked: one
    :class:`~pollard_pin.io.table.ResultFileError` line for a file that is no paint report
    (not JSON, not a table, a section of the wrong type, no film target > 0, a FIFO, a huge
    file).

    Parameters
    ----------
    path : str or Path
        The file.
    """
    return PaintJson.from_dict(load_paint_json(path), path)


__all__ = ["FilmPly", "FilmPoints", "Grid", "KEYS", "LineSpeeds", "MAX_REPORT_BYTES", "MotorUse",
           "PaintJson", "PaintUse", "Seam", "Section", "Strokes", "Thickness", "check_grid",
           "dumps", "load_paint_json", "read_paint_json"]
