"""paint.json's schema: the report ``pollard-pin paint`` writes beside its film, its sections
typed (:mod:`pollard_pin.outputs.sections`), with the one writer (:func:`dumps`, the file's
exact text) and the one reader (:func:`read_paint_json`, one line for a file that is no paint
report).

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
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..checks import clip, shorten
from ..io.json_text import finite_json
from ..io.table import ResultFileError
from ..model.values import open_regular
from .sections import (
    FilmPly,
    FilmPoints,
    Grid,
    LineSpeeds,
    MotorUse,
    PaintUse,
    Seam,
    Strokes,
    Thickness,
    as_list,
    as_number,
    as_table,
    as_text,
    refuse,
)

# a report is a few kB (a cell of 16 robots: ~60 kB); anything near this is no report
MAX_REPORT_BYTES = 16 << 20


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
            refuse(path, "not a table")
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
            for n, u in as_table(path, key, value).items()}


def _timings(path, key, value) -> dict:
    return {n: as_number(path, f"{key}.{n}", t) for n, t in as_table(path, key, value).items()}


def _robots(path, key, value) -> tuple:
    out = tuple(as_table(path, f"{key}[{i}]", r) for i, r in enumerate(as_list(path, key, value)))
    for i, r in enumerate(out):  # each robot's strategy checked, kept as written
        if "strokes" in r:
            Strokes.from_dict(r["strokes"], f"{key}[{i}].strokes", path)
        if "paint" in r:
            PaintUse.from_dict(r["paint"], f"{key}[{i}].paint", path)
    return out


def _line(path, key, value) -> Mapping:
    """The line table as written, its ``speeds`` (when there) checked."""
    table = as_table(path, key, value)
    if "speeds" in table:
        LineSpeeds.from_dict(table["speeds"], f"{key}.speeds", path)
    return table


def _seams(path, key, value) -> tuple:
    return tuple(Seam.from_dict(s, f"{key}[{i}]", path)
                 for i, s in enumerate(as_list(path, key, value)))


def _section(cls):
    return lambda path, key, value: cls.from_dict(value, key, path)


_READ = {"job": as_table, "kind": as_text, "thickness": _section(Thickness),
         "cycle_time": as_number, "line": _line, "strokes": _section(Strokes),
         "seams": _seams, "robots": _robots,
         "clearance": as_table, "motors": _motors,
         "film_points": _section(FilmPoints), "timings": _timings, "compliance": as_table,
         "film_ply": _section(FilmPly), "paint": _section(PaintUse), "version": as_text}
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
        refuse(path, f"over {MAX_REPORT_BYTES / 2**20:.4g} MiB")
    try:
        report = json.loads(data.decode("utf-8"))
    except (ValueError, RecursionError) as exc:  # not UTF-8, not JSON; deep nesting
        raise ResultFileError(f"{path}: not a paint report ({clip(exc, 100)})") from None
    if not isinstance(report, dict):
        refuse(path, "not a table")
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


__all__ = ["KEYS", "MAX_REPORT_BYTES", "PaintJson", "dumps", "load_paint_json",
           "read_paint_json"]
