"""The paint job file (TOML, SI units; ``examples/paint.toml``), read and checked.

Every rule broken is one :class:`JobError` line naming the key, its value and the rule.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..checks import file_path, instance
from ..model.params import did_you_mean
from ..model.values import fail, integer, number, read_toml
from .cell.robots import CellRobot, robots_from_tables
from .errors import JobError, JobKindError
from .gun_table import SPOT_KEYS, check_spot, gun_table, required_gun_keys, spot_values
from .line.conveyor import Line, line_from_table
from .material import Paint, check_paint, paint_from_table
from .spray.spots import Spot

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
# The smallest panel side, in spray spots σ: below it the film is the spot's own profile and
# "within ±10 %" says nothing about the panel (docs/model.md §21).
MIN_PANEL_SIGMAS = 1.0
# A part's coats: each repeats every pass at 1/coats of the film, and the example gun's
# fastest pass leaves the thinnest coat at ~1/5 of the example target (the panel planner's
# "at most 5 coat(s)"): more only make the program longer and the film thinner per coat.
MAX_PART_COATS = 5
# The spray's recoil [N]: a gun kicks back by a few N at most; beyond this a unit slip (the
# drives' linear deflection, docs/model.md §27.7, is long gone anyway).
MAX_RECOIL = 100.0


@dataclass(frozen=True, kw_only=True)
class JobBase:
    """What a panel job (:class:`PaintJob`) and a part job (:class:`PartJob`) share, SI units,
    given by keyword: the gun (``standoff``, ``sigma``, ``flow``, ``spot``, ``apex``,
    ``clearance``, ``recoil``), the film (``thickness``, ``spacing``, ``speed``,
    ``direction``, ``coats``, ``paint``), the motors (``actuators``), where it is painted
    (``line``, ``robots``) and the job file (``source``); each as :class:`PaintJob`'s
    attributes say."""

    standoff: float
    sigma: float
    flow: float
    thickness: float
    spacing: float | None = None
    speed: float | None = None
    direction: str = "horizontal"
    coats: int | None = None
    actuators: str | None = None  # a path, relative to the job file's folder
    source: str = "<python>"
    line: Line | None = None  # the conveyor (docs/model.md §24); None: still
    clearance: float | None = None  # gun body to part [m]; None: the default (§25)
    robots: tuple[CellRobot, ...] = ()  # a cell's robots (§26); (): one robot at the origin
    recoil: float | None = None  # the spray's push back on the gun [N] (§27.7); None: none
    paint: Paint | None = None  # the paint's solids, density, transfer efficiency (§29)
    spot: Spot | None = None  # the spray pattern (§20); None: the round Gaussian of sigma
    apex: float | None = None  # the spray cone's apex in front of the nozzle [m]; None: 0

    def __post_init__(self):
        check_spot(self, MAX_LENGTH)  # a spot's sigma is its width (gun_table.py)
        check_paint(self)  # a Paint made in Python meets [paint]'s rules (material.py)

    def to_dict(self) -> dict:
        """The job as the file would say it (None entries left out)."""
        d = {k: v for k, v in asdict(self).items()
             if v is not None and k not in ("source", "robots", "paint")}
        return {**self._target_table(d),
                "gun": gun_table(self, d, REQUIRED["gun"] + OPTIONAL["gun"]),
                "job": {k: d[k] for k in ("thickness",) + OPTIONAL["job"] if k in d},
                **({"line": self.line.to_dict()} if self.line is not None else {}),
                **({"robot": [r.to_dict() for r in self.robots]} if self.robots else {}),
                **({"paint": self.paint.to_dict()} if self.paint is not None else {})}

    def _target_table(self, d: dict) -> dict:
        """What is painted, as the file's table, from the job's entries ``d``."""
        raise NotImplementedError


@dataclass(frozen=True)
class PaintJob(JobBase):
    """A checked panel job, SI units (:func:`~pollard_pin.load_job`). ``normal`` is unit
    length; optional entries are None when the file leaves them to the planner. The entries
    after ``height`` (:class:`~pollard_pin.painting.job.JobBase`'s, a part job's too) are
    given by keyword.

    Attributes
    ----------
    center, normal : tuple of float
        The panel's centre [m] and unit normal (towards the robot), world frame.
    width, height : float
        Its size [m] along u = normal × v and v (world z projected onto the panel).
    standoff, sigma : float
        The gun's distance to the panel and the spray spot's spread [m] (its width,
        :attr:`.spray.spots.Spot.width`, for a spot that is not the round Gaussian; None
        with a spot: set to its width, another value refused).
    flow : float
        Film volume deposited [m³/s].
    thickness : float
        The target film [m].
    spot : pollard_pin.painting.spray.Spot or None
        The spray pattern (``[gun]`` ``model``, docs/model.md §20); None: the round
        Gaussian of ``sigma``.
    apex : float or None
        The spray cone's apex in front of the nozzle [m]; None: 0 (the nozzle).
    spacing, speed : float or None
        Pass spacing [m] and speed [m/s] (None: the planner's).
    direction : str
        ``"horizontal"`` or ``"vertical"`` passes.
    coats : int or None
        Coats (None: the planner's).
    actuators : str or None
        The motor ratings file.
    line : pollard_pin.painting.line.conveyor.Line or None
        The conveyor (docs/model.md §24); None: a still panel.
    clearance : float or None
        The gun body's smallest distance to the part [m] (None: 10 mm).
    source : str
        The job file (for messages).
    robots : tuple of pollard_pin.painting.cell.robots.CellRobot
        A cell's robots; empty: one robot at the origin.
    recoil : float or None
        The spray's push back on the gun along its axis [N] (docs/model.md §27.7); None:
        none.
    paint : pollard_pin.painting.material.Paint or None
        The paint's solids, density and transfer efficiency (``[paint]``, docs/model.md
        §29); None: the report gives the dry film volumes only.
    """

    center: tuple[float, float, float]
    normal: tuple[float, float, float]
    width: float
    height: float

    def _target_table(self, d: dict) -> dict:
        return {"panel": {k: d[k] for k in REQUIRED["panel"]}}


@dataclass(frozen=True)
class PartJob(JobBase):
    """A checked paint job over a part's mesh (``[part]``), SI units: ``mesh`` the file (a
    path, relative to the job file's folder once loaded), its length ``units`` (a name of
    UNITS) or ``scale`` (the file's unit in m; :attr:`unit` is the one rule), ``position``
    [m] and ``rotation`` (rx, ry, rz) [deg]
    (``painting.workpiece.mesh.placement``), the painted faces' ``facing`` direction (None:
    towards the robot) and ``max_angle`` [deg] (None: the default); the gun, film and
    conveyor as :class:`PaintJob`'s (:class:`JobBase`'s, by keyword); ``paint`` the
    ``[paint]`` table (:class:`~pollard_pin.painting.material.Paint`, docs/model.md §29)."""

    mesh: str
    position: tuple[float, float, float]
    units: str = "m"
    scale: float | None = None
    rotation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    facing: tuple[float, float, float] | None = None
    max_angle: float | None = None

    @property
    def unit(self) -> float:
        """The mesh file's length unit [m]: ``scale`` if given, else ``units``'."""
        return self.scale if self.scale is not None else UNITS[self.units]

    def _target_table(self, d: dict) -> dict:
        if self.scale is not None:  # the file names one of units and scale
            del d["units"]
        return {"part": {k: d[k] for k in PART_REQUIRED + PART_OPTIONAL if k in d}}


def part_job_from_dict(d: Mapping, source: str = "<python>") -> PartJob:
    """Validate a parsed job file with a [part] table (the mesh itself is read by
    :func:`.workpiece.mesh.load_part`, which checks the units, facing and max_angle)."""
    part, gun, job = (_check_table(source, d, name) for name in ("part", "gun", "job"))
    mesh = part["mesh"]
    if not (isinstance(mesh, str) and mesh.strip()):
        _fail(source, "part.mesh", mesh, "must be a mesh file name (STL, OBJ or PLY)")
    values: dict[str, Any] = {"mesh": mesh,
                              "position": _vector(source, "part.position", part["position"])}
    values.update(_unit_values(source, part))
    if "rotation" in part:
        r = part["rotation"]
        if not isinstance(r, list) or len(r) != 3:
            _fail(source, "part.rotation", r, "must be a list of 3 angles [rx, ry, rz] in "
                                              "degrees")
        values["rotation"] = tuple(_number(source, f"part.rotation[{i}]", v)
                                   for i, v in enumerate(r))
    if "facing" in part:
        values["facing"] = _vector(source, "part.facing", part["facing"])
    if "max_angle" in part:
        values["max_angle"] = _number(source, "part.max_angle", part["max_angle"])
    values.update(_gun_values(source, gun))
    values.update(_job_values(source, job))
    if values.get("coats", 1) > MAX_PART_COATS:
        _fail(source, "job.coats", job["coats"], f"must be at most {MAX_PART_COATS} for a part "
              "(each coat repeats every pass): a slower gun (job.speed) lays more per coat")
    return PartJob(direction=job.get("direction", "horizontal"), actuators=job.get("actuators"),
                   source=source, **values)


def _unit_values(source: str, part: Mapping) -> dict:
    """``units`` (a name of UNITS) or ``scale`` (the file's unit [m], a number > 0), not
    both: the job reader's one rule for the mesh's length unit."""
    if "units" in part and "scale" in part:
        raise JobError(f"{source}: give part.units or part.scale, not both (scale = the mesh "
                       "file's length unit in m, e.g. 0.001 for mm)")
    if "scale" in part:
        scale = _positive(source, "part.scale", part["scale"])
        if not 1e-6 <= scale <= 1e3:
            _fail(source, "part.scale", part["scale"], "must be within 1e-6..1e3 m per file "
                  "unit (the mesh's length unit in m: 0.001 for mm)")
        return {"scale": scale}
    if "units" in part:
        u = part["units"]
        if not (isinstance(u, str) and u in UNITS):
            _fail(source, "part.units", u, f"must be {', '.join(repr(k) for k in UNITS)}"
                  f"{did_you_mean(str(u), tuple(UNITS))} (or give part.scale, the unit in m)")
        return {"units": u}
    return {}


def _fail(source: str, key: str, value: Any, rule: str):
    fail(JobError, f"{source}: ", key, value, rule)


_LENGTH_RULE = f"must be at most {MAX_LENGTH:g} m in size (SI units: metres, not mm)"


def _number(source: str, key: str, value: Any, length: bool = False,
            positive: bool = False) -> float:
    return number(value, key, JobError, f"{source}: ", positive=positive,
                  limit=MAX_LENGTH if length else None, limit_rule=_LENGTH_RULE)


def _positive(source: str, key: str, value: Any, length: bool = False) -> float:
    return _number(source, key, value, length, positive=True)


def _vector(source: str, key: str, value: Any) -> tuple[float, float, float]:
    if not isinstance(value, list) or len(value) != 3:
        _fail(source, key, value, "must be a list of 3 numbers [x, y, z]")
    return tuple(_number(source, f"{key}[{i}]", v, length=True) for i, v in enumerate(value))


def _check_table(source: str, d: Mapping, name: str) -> Mapping:
    if name not in d:
        raise JobError(f"{source}: missing table [{name}] (a job has [panel] or [part], [gun] "
                       "and [job])")
    table = d[name]
    if not isinstance(table, Mapping):
        _fail(source, name, table, f"must be a table [{name}]")
    required = PART_REQUIRED if name == "part" else REQUIRED[name]
    allowed = required + (PART_OPTIONAL if name == "part" else OPTIONAL[name])
    if name == "gun":  # the keys its spray model needs (gun_table.py)
        required = required_gun_keys(source, table)
    for k in table:
        if k not in allowed:
            _fail(source, f"{name}.{k}", table[k],
                  f"unknown key{did_you_mean(k, allowed)}; [{name}] takes "
                  f"{', '.join(allowed)}")
    for k in required:
        if k not in table:
            raise JobError(f"{source}: '{name}.{k}' is missing ([{name}] needs "
                           f"{', '.join(required)})")
    return table


def job_from_dict(d: Mapping, source: str = "<python>") -> PaintJob | PartJob:
    """Validate a job given as the file's tables (a parsed TOML file, or built in Python).

    Parameters
    ----------
    d : Mapping
        The tables: ``panel`` or ``part``, ``gun``, ``job``, optionally ``line``, ``robot``
        (a list of tables) and ``paint``, keys and units as in a job file (docs/formats.md).
    source : str, optional
        What the messages call the job (a file name).

    Returns
    -------
    PaintJob or pollard_pin.painting.job.PartJob
        The checked job (a relative ``part.mesh`` or ``job.actuators`` is taken as given).

    Raises
    ------
    JobError
        A missing or unknown table or key, a value that breaks its rule (one line).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> job = pp.job_from_dict({
    ...     "panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
    ...               "width": 0.26, "height": 0.12},
    ...     "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
    ...     "job": {"thickness": 25e-6}})
    >>> job.width, job.height, job.line is None
    (0.26, 0.12, True)
    """
    instance(source, "source", str, "a str (what the messages call the job)")
    if not isinstance(d, Mapping):
        raise JobError(f"{source}: d = {d!r:.40}: a {type(d).__name__}, expected the tables "
                       "[panel], [gun] and [job] (a dict)")
    tables = (*REQUIRED, "part", "line", "robot", "paint")
    for name in d:
        if name not in tables:
            raise JobError(f"{source}: [{name}] is not a table of a paint job"
                           f"{did_you_mean(name, tables)}; expected [panel] or [part], [gun], "
                           "[job]")
    if "paint" in d:  # the paint's solids and density (docs/model.md §29)
        from dataclasses import replace

        return replace(job_from_dict({k: v for k, v in d.items() if k != "paint"}, source),
                       paint=paint_from_table(source, d["paint"]))
    if "robot" in d:  # a cell (docs/model.md §26): its robots paint the part as it passes
        from dataclasses import replace

        robots = robots_from_tables(source, d["robot"])
        if "line" not in d:
            raise JobError(f"{source}: [[robot]] needs [line]: a cell's robots paint the part "
                           "as the conveyor carries it past them (add [line] speed, direction)")
        return replace(job_from_dict({k: v for k, v in d.items() if k != "robot"}, source),
                       robots=robots)
    if "line" in d:  # the conveyor (docs/model.md §24), checked in line_job.py
        from dataclasses import replace

        line = line_from_table(source, d["line"], JobError)
        return replace(job_from_dict({k: v for k, v in d.items() if k != "line"}, source),
                       line=line)
    if "part" in d:
        if "panel" in d:
            raise JobError(f"{source}: a job paints a [panel] or a [part], not both")
        return part_job_from_dict(d, source)
    panel, gun, job = (_check_table(source, d, name) for name in REQUIRED)
    center = _vector(source, "panel.center", panel["center"])
    normal = _vector(source, "panel.normal", panel["normal"])
    length = float(np.linalg.norm(normal))
    if not length > 1e-12:
        _fail(source, "panel.normal", panel["normal"], "has zero length; give the direction "
                                                       "from the panel towards the robot")
    normal = tuple(float(c) / length for c in normal)
    if abs(normal[2]) > 1.0 - 1e-9:
        _fail(source, "panel.normal", panel["normal"],
              "is vertical: the panel's height runs along world z projected onto the panel, "
              "which a horizontal panel does not define")
    values = {k: _positive(source, f"panel.{k}", panel[k], length=True)
              for k in ("width", "height")}
    values.update(_gun_values(source, gun))
    for k in ("width", "height"):
        if values[k] < MIN_PANEL_SIGMAS * values["sigma"]:
            _fail(source, f"panel.{k}", panel[k], f"is smaller than the spray spot (σ = "
                  f"{values['sigma']:.4g} m): a panel must be at least "
                  f"{MIN_PANEL_SIGMAS:g} σ wide and high")
    values.update(_job_values(source, job))
    return PaintJob(center=center, normal=normal, direction=job.get("direction", "horizontal"),
                    actuators=job.get("actuators"), source=source, **values)


def _gun_values(source: str, gun: Mapping) -> dict:
    values = {"standoff": _positive(source, "gun.standoff", gun["standoff"], length=True)}
    values.update(spot_values(source, gun, values["standoff"], MAX_LENGTH))
    values["flow"] = _positive(source, "gun.flow", gun["flow"])
    if "clearance" in gun:  # the gun body's least distance from the part (§25)
        values["clearance"] = _number(source, "gun.clearance", gun["clearance"], length=True)
        if values["clearance"] < 0:
            _fail(source, "gun.clearance", gun["clearance"], "must be ≥ 0 m")
    if "recoil" in gun:  # along the spray axis, pushing the gun back (§27.7)
        values["recoil"] = number(gun["recoil"], "gun.recoil", JobError, f"{source}: ",
                                  nonnegative=True, limit=MAX_RECOIL,
                                  limit_rule=f"must be at most {MAX_RECOIL:g} N (the force "
                                             "the spray pushes the gun back with)")
    return values


def _job_values(source: str, job: Mapping) -> dict:
    """The [job] table's numbers (thickness, spacing, speed, coats), its direction and
    actuators checked."""
    values = {}
    values["thickness"] = _positive(source, "job.thickness", job["thickness"], length=True)
    for k in ("spacing", "speed"):
        if k in job:
            values[k] = _positive(source, f"job.{k}", job[k], length=k == "spacing")
    if "direction" in job and job["direction"] not in DIRECTIONS:
        _fail(source, "job.direction", job["direction"],
              f"must be {' or '.join(repr(x) for x in DIRECTIONS)}"
              f"{did_you_mean(str(job['direction']), DIRECTIONS)}")
    if "coats" in job:
        values["coats"] = integer(job["coats"], "job.coats", JobError, f"{source}: ")
    a = job.get("actuators")
    if "actuators" in job and not (isinstance(a, str) and a and "\0" not in a):
        _fail(source, "job.actuators", a, "must be a file name (a string, no NUL)")
    return values


def check_job(job, name: str = "job") -> PaintJob | PartJob:
    """``job`` when it is a paint job (a :class:`PaintJob` or :class:`PartJob`); else one
    :class:`~pollard_pin.errors.InputError` line naming the argument ``name``."""
    return instance(job, name, (PaintJob, PartJob), "a paint job (PaintJob or PartJob, from "
                    "load_job)")


def load_job(path: str | Path) -> PaintJob | PartJob:
    """Read and check a paint job file (format: ``examples/paint.toml``, or
    ``examples/parts/*.toml`` with a [part]). A relative ``job.actuators`` or ``part.mesh`` is
    taken relative to the job file's folder.

    Parameters
    ----------
    path : str or pathlib.Path
        A TOML job: ``[panel]`` (centre, normal, width, height [m]) or ``[part]`` (mesh,
        units, position, rotation, facing, max_angle); ``[gun]`` (standoff, sigma [m], flow
        [m³/s]); ``[job]`` (thickness [m]; optional spacing, speed, direction, coats,
        actuators); optional ``[line]`` (speed [m/s], direction), ``[[robot]]`` and
        ``[paint]`` (solids, density [kg/m³], transfer_efficiency) tables.

    Returns
    -------
    PaintJob or pollard_pin.painting.job.PartJob
        The checked job, SI units.

    Raises
    ------
    JobError
        A missing or malformed file, a missing or unknown key, a value that breaks its rule
        (the message names the file, the key and the rule).

    Examples
    --------
    >>> import os
    >>> import pollard_pin as pp
    >>> lines = ["panel = {center = [0.70, 0.0, 0.16], normal = [-1.0, 0.0, 0.0], "
    ...          "width = 0.26, height = 0.12}",
    ...          "gun = {standoff = 0.15, sigma = 0.010, flow = 1.5e-7}",
    ...          "job = {thickness = 25e-6}"]
    >>> with open("paint.toml", "w") as f:
    ...     _ = f.write(os.linesep.join(lines))
    >>> job = pp.load_job("paint.toml")
    >>> job.width, job.height, job.thickness
    (0.26, 0.12, 2.5e-05)
    """
    from dataclasses import replace

    file_path(path, "path", error=JobError)  # checked; the source is the path as given
    job = job_from_dict(read_toml(path, "paint job file", JobError), str(path))
    if job.actuators is not None and not Path(job.actuators).is_absolute():
        job = replace(job, actuators=str(Path(path).parent / job.actuators))
    if isinstance(job, PartJob) and not Path(job.mesh).is_absolute():
        job = replace(job, mesh=str(Path(path).parent / job.mesh))
    return job


def job_kind(job: Any) -> str:
    """The name of the job's kind: what it paints (``panel``, ``part``) and where (still,
    ``line ...`` with a [line] table, ``cell ...`` with [[robot]] tables; the kinds:
    ``pollard_pin.painting.kinds.KINDS``); :class:`JobKindError` naming the type of anything
    else."""
    if isinstance(job, PaintJob | PartJob):
        what = "panel" if isinstance(job, PaintJob) else "part"
        if job.robots:
            return f"cell {what}"
        return what if job.line is None else f"line {what}"
    raise JobKindError(f"cannot paint a {type(job).__name__}: expected a paint job (a PaintJob "
                       "or PartJob, from load_job)")


__all__ = ["DIRECTIONS", "MAX_RECOIL", "UNITS", "MIN_PANEL_SIGMAS", "JobBase", "PaintJob",
           "PartJob", "job_from_dict", "job_kind", "load_job", "part_job_from_dict"]
