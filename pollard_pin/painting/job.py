"""The paint job file (TOML, SI units; ``examples/paint.toml``), read and checked: the job
types and the reader (each table's keys and values: ``job_tables.py``).

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
from ..model.values import read_toml
from .cell.robots import CellRobot, robots_from_tables, turn_angle
from .errors import JobError, JobKindError
from .gun_table import check_spot, gun_table
from .job_tables import (
    DIRECTIONS,
    MAX_LENGTH,
    MAX_RECOIL,
    OPTIONAL,
    PART_OPTIONAL,
    PART_REQUIRED,
    REQUIRED,
    UNITS,
    check_table,
    checked_number,
    checked_positive,
    checked_vector,
    fail_key,
    gun_values,
    job_values,
    unit_values,
)
from .line.conveyor import Line, line_from_table
from .material import Paint, check_paint, paint_from_table
from .spray.spots import Spot

# The smallest panel side, in spray spots σ: below it the film is the spot's own profile and
# "within ±10 %" says nothing about the panel (docs/model.md §21).
MIN_PANEL_SIGMAS = 1.0
# A part's coats: each repeats every pass at 1/coats of the film, and the example gun's
# fastest pass leaves the thinnest coat at ~1/5 of the example target (the panel planner's
# "at most 5 coat(s)"): more only make the program longer and the film thinner per coat.
MAX_PART_COATS = 5


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
    part, gun, job = (check_table(source, d, name) for name in ("part", "gun", "job"))
    mesh = part["mesh"]
    if not (isinstance(mesh, str) and mesh.strip()):
        fail_key(source, "part.mesh", mesh, "must be a mesh file name (STL, OBJ or PLY)")
    values: dict[str, Any] = {"mesh": mesh,
                              "position": checked_vector(source, "part.position", part["position"])}
    values.update(unit_values(source, part))
    if "rotation" in part:
        r = part["rotation"]
        if not isinstance(r, list) or len(r) != 3:
            fail_key(source, "part.rotation", r, "must be a list of 3 angles [rx, ry, rz] in "
                                                 "degrees")
        values["rotation"] = tuple(turn_angle(v, f"part.rotation[{i}]", JobError, f"{source}: ")
                                   for i, v in enumerate(r))
    if "facing" in part:
        values["facing"] = checked_vector(source, "part.facing", part["facing"])
    if "max_angle" in part:
        values["max_angle"] = checked_number(source, "part.max_angle", part["max_angle"])
    values.update(gun_values(source, gun))
    values.update(job_values(source, job))
    if values.get("coats", 1) > MAX_PART_COATS:
        fail_key(source, "job.coats", job["coats"], f"must be at most {MAX_PART_COATS} for a "
                 "part (each coat repeats every pass): a slower gun (job.speed) lays more per coat")
    return PartJob(direction=job.get("direction", "horizontal"), actuators=job.get("actuators"),
                   source=source, **values)


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
    panel, gun, job = (check_table(source, d, name) for name in REQUIRED)
    center = checked_vector(source, "panel.center", panel["center"])
    normal = checked_vector(source, "panel.normal", panel["normal"])
    length = float(np.linalg.norm(normal))
    if not length > 1e-12:
        fail_key(source, "panel.normal", panel["normal"], "has zero length; give the direction "
                                                          "from the panel towards the robot")
    normal = tuple(float(c) / length for c in normal)
    if abs(normal[2]) > 1.0 - 1e-9:
        fail_key(source, "panel.normal", panel["normal"],
                 "is vertical: the panel's height runs along world z projected onto the panel, "
                 "which a horizontal panel does not define")
    values = {k: checked_positive(source, f"panel.{k}", panel[k], length=True)
              for k in ("width", "height")}
    values.update(gun_values(source, gun))
    for k in ("width", "height"):
        if values[k] < MIN_PANEL_SIGMAS * values["sigma"]:
            fail_key(source, f"panel.{k}", panel[k], f"is smaller than the spray spot (σ = "
                     f"{values['sigma']:.4g} m): a panel must be at least "
                     f"{MIN_PANEL_SIGMAS:g} σ wide and high")
    values.update(job_values(source, job))
    return PaintJob(center=center, normal=normal, direction=job.get("direction", "horizontal"),
                    actuators=job.get("actuators"), source=source, **values)


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
