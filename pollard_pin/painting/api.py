"""Painting from Python: one entry point for every job kind (docs/model.md §20–§24).

    result = pollard_pin.paint(robot, pollard_pin.load_job("examples/paint.toml"))
    result.report.cycle_time, result.report.thickness["within_10pct"]
    result.write("out", "csv")      # what ``pollard-pin paint --out out`` writes

:func:`paint` dispatches on the job's kind (a panel or a part, still or on a line) to the
planner of that kind, integrates the film and computes ``paint.json``'s numbers; the CLI only
parses, calls it, writes and prints.
"""
from __future__ import annotations

import math
import numbers
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..dynamics.motors import Actuators
from ..errors import InputError
from ..version import __version__
from .errors import JobKindError
from .job import KINDS, PartJob, job_kind
from .line.phases import SPEED_RESOLUTION

# The kinds with a compliance report (docs/model.md §27.7): one robot's program, or a cell's
# robots, each one such program in its own base frame (§26.6).
COMPLIANCE_KINDS = ("panel", "part", "line panel", "line part", "cell panel", "cell part")


@dataclass(frozen=True)
class PaintOptions:
    """How :func:`~pollard_pin.painting.api.paint` plans and integrates, validated once.

    Parameters
    ----------
    resolution : float or None, optional
        The film's point spacing [m] (a panel's grid, a part's film points), at most the
        spray spot's σ; None: σ/3.
    max_line_speed : bool, optional
        A job on a line is planned at the fastest line speed that paints it instead of the
        job's speed (docs/model.md §24; default False).
    speed_resolution : float, optional
        That search's relative bracket, in (0, 1) (default 0.01).
    compliance : bool, optional
        Report what the drives' compliance does to the gun and the film (docs/model.md
        §27.7; a second film integration; default True).

    Raises
    ------
    pollard_pin.errors.InputError
        A resolution that is not > 0, a flag that is not a bool, a bracket outside (0, 1).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> pp.PaintOptions(resolution=0.004)
    PaintOptions(resolution=0.004, max_line_speed=False, speed_resolution=0.01, compliance=True)
    """

    resolution: float | None = None
    max_line_speed: bool = False
    speed_resolution: float = SPEED_RESOLUTION
    compliance: bool = True

    def __post_init__(self):
        r = self.resolution
        if r is not None and (isinstance(r, bool) or not isinstance(r, numbers.Real)
                              or not (math.isfinite(r) and r > 0)):
            raise InputError(f"PaintOptions.resolution = {r!r}: expected a spacing > 0 [m] "
                             "(or None for σ/3)")
        if not isinstance(self.max_line_speed, bool):
            raise InputError(f"PaintOptions.max_line_speed = {self.max_line_speed!r}: expected "
                             "True or False")
        s = self.speed_resolution
        if isinstance(s, bool) or not isinstance(s, numbers.Real) or not 0 < s < 1:
            raise InputError(f"PaintOptions.speed_resolution = {s!r}: expected a relative "
                             "bracket in (0, 1)")
        if not isinstance(self.compliance, bool):
            raise InputError(f"PaintOptions.compliance = {self.compliance!r}: expected True or "
                             "False")


@dataclass(frozen=True)
class PaintFilm:
    """The film a plan leaves. A panel: ``points`` (nv, nu, 3) on the grid ``grid`` = (U, V),
    ``film`` a :class:`~pollard_pin.painting.spray.deposition.Film`. A part: ``points`` the
    film points (``paint.film.points.SurfacePoints``: points, normals, areas, faces),
    ``film`` a ``paint.film.mesh.MeshFilm``,
    ``painted`` the mask of points on painted faces, ``efficiency`` the transfer
    efficiency. On a line, the part (or panel) at its t = 0 pose, world coordinates."""

    points: Any
    film: Any
    resolution: float
    grid: tuple | None = None
    painted: np.ndarray | None = None
    efficiency: float | None = None

    @property
    def thickness(self) -> np.ndarray:
        """The film thickness [m] at every point."""
        return self.film.thickness


@dataclass(frozen=True)
class PaintReport:
    """The numbers of ``paint.json`` (docs/model.md §21, §23, §24), its main ones typed.

    Attributes
    ----------
    kind : str
        The job's kind (``"panel"``, ``"part"``, ``"line panel"``, ``"line part"``).
    cycle_time : float
        The program's cycle [s].
    target : float
        The target film thickness [m].
    thickness : Mapping
        The film statistics: ``mean``, ``min``, ``max``, ``std`` [m], ``uniformity``,
        ``within_5pct`` and ``within_10pct`` (shares of the area), ``deviation_min`` and
        ``deviation_max`` (relative to the target).
    motors : Mapping
        Per motor, each limit's use over its rating (``peak_torque``, ``rms_torque``,
        ``speed``).
    line : Mapping or None
        On a line: start delay, window, travel, cycle, pitch, parts per hour, the speed's
        upper bound; None when still.
    timings : Mapping
        Seconds spent planning and integrating the film.
    data : Mapping
        The whole report (``paint.json`` adds film.ply's colour map).
    """

    kind: str
    cycle_time: float
    target: float
    thickness: Mapping
    motors: Mapping
    line: Mapping | None
    timings: Mapping
    data: Mapping

    @classmethod
    def from_dict(cls, kind: str, rep: dict) -> PaintReport:
        return cls(kind, rep["cycle_time"], rep["target"], rep["thickness"], rep["motors"],
                   rep.get("line"), rep["timings"], rep)

    def to_dict(self) -> dict:
        """paint.json's content (a copy at the top level)."""
        return dict(self.data)


@dataclass(frozen=True)
class PaintResult:
    """What :func:`~pollard_pin.painting.api.paint` returns.

    Attributes
    ----------
    job : PaintJob or pollard_pin.painting.job.PartJob
        The job.
    kind : str
        Its kind (``"panel"``, ``"part"``, ``"line panel"``, ``"line part"``).
    plan : object
        The plan of that kind (a :class:`~pollard_pin.painting.plan.PaintPlan` for a still
        panel): its ``trajectory`` (the program, a :class:`~pollard_pin.Trajectory`) and
        ``spray`` (the gun's trigger per sample), passes, speed, cycle time.
    film : pollard_pin.painting.api.PaintFilm
        The film points and the thickness [m] at each.
    report : PaintReport
        The numbers of ``paint.json``.
    actuators : Actuators
        The motor ratings the program was checked against.
    options : PaintOptions
        How it was planned.

    :meth:`write` writes what ``pollard-pin paint`` writes.
    """

    job: Any
    kind: str
    plan: Any
    film: PaintFilm
    report: PaintReport
    actuators: Actuators
    options: PaintOptions

    def write(self, folder: str | Path, format: str = "csv") -> Path:
        """Write path.csv, thickness.csv|parquet, film.ply, paint.json and thickness.png in
        ``folder``, every one or none, as ``pollard-pin paint`` does; the table's path."""
        # the calls up the layers: paint's files are written by io's writers
        if self.kind.startswith("cell"):  # a folder per robot (docs/model.md §26)
            from ..io.paint_cell_files import write_cell

            return write_cell(self, Path(folder), format)
        from ..io.paint_files import write_paint

        return write_paint(self, Path(folder), format)


def default_actuators(job) -> Actuators:
    """The job's ``actuators`` file, else the package's ratings (examples/actuators.toml,
    shipped as models/actuators.toml)."""
    from ..dynamics.motors import load_actuators

    return load_actuators(job.actuators)


def film_spacing_of(job, resolution: float | None = None) -> float:
    """The film point spacing [m] ``paint`` uses for the job (a panel's grid or a part's
    points), refused as a :class:`.errors.ResolutionError`."""
    from .film.grid import film_resolution
    from .film.part import part_resolution

    return (part_resolution if isinstance(job, PartJob) else film_resolution)(job, resolution)


def paint(robot, job, actuators: Actuators | None = None,
          options: PaintOptions | None = None) -> PaintResult:
    """Plan the job (a panel or a part, still or on a line, painted by one robot or by a
    cell of several), integrate its film and compute its report (docs/model.md §20–§24,
    §26): what ``pollard-pin paint`` does. Also callable as
    ``pollard_pin.paint(robot, job, ...)``.

    A job with ``[line]`` and ``[[robot]]`` tables (``job.robots``) is a cell: the part is
    split into zones, one per robot (:func:`~pollard_pin.painting.cell.split.split_cell`),
    each robot's program is planned in its own base frame on the cell's clock
    (:func:`~pollard_pin.painting.cell.plan.plan_cell`), the robots' clearance from each other
    and from the part is checked, and the film is that
    of all robots together; ``result.kind`` is then ``"cell panel"`` or ``"cell part"``. To
    propose the robots' bases: :func:`~pollard_pin.propose_layout`,
    :func:`~pollard_pin.fewest_robots`.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        From :func:`~pollard_pin.load_job`.
    actuators : Actuators or None, optional
        The motor ratings the program must keep (default: the job's ``actuators`` file, else
        the package's, ``examples/actuators.toml``).
    options : PaintOptions or None, optional
        Film resolution, the line speed search.

    Returns
    -------
    PaintResult
        The plan, the film, the report; ``result.write(folder)`` writes the outputs (for a
        cell: ``folder/<robot>/path.csv`` per robot, one film for the whole part).

    Raises
    ------
    PlanError
        No program meets the job: out of reach (naming where, and the largest panel that
        fits), a budget broken (a film too thick for the flow, a panel narrower than the
        spot), the gun's body too close to the part; for a cell, a robot that cannot paint
        its zone, or two robots (or a robot and the part) closer than the clearance.
    JobKindError
        A job of a kind the planner does not handle.
    pollard_pin.errors.InputError
        Options of the wrong type, ``max_line_speed`` without a line.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> job = pp.job_from_dict({
    ...     "panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
    ...               "width": 0.26, "height": 0.12},
    ...     "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
    ...     "job": {"thickness": 25e-6}})
    >>> result = pp.paint(pp.load(), job)
    >>> result.kind, result.report.data["passes"], round(result.report.cycle_time, 1)
    ('panel', 9, 10.0)
    >>> result.report.thickness["within_5pct"]
    1.0
    >>> sorted(p.name for p in result.write("out").parent.iterdir())[:3]
    ['film.ply', 'paint.json', 'path.csv']
    """
    kind = job_kind(job)
    options = PaintOptions() if options is None else options
    if not isinstance(options, PaintOptions):
        raise InputError(f"options: a {type(options).__name__}, expected PaintOptions")
    if options.max_line_speed and job.line is None:
        raise InputError(f"{job.source}: max_line_speed: the {kind} job has no [line] table "
                         "(speed, direction)")
    res = film_spacing_of(job, options.resolution)
    act = default_actuators(job) if actuators is None else actuators
    painter = {"panel": _panel, "part": _part, "line panel": _line_panel,
               "line part": _line_part, "cell panel": _cell, "cell part": _cell}.get(kind)
    if painter is None:
        raise JobKindError(f"{job.source}: a {kind} is not planned yet")
    plan, film, rep = painter(robot, job, act, options, res)
    if options.compliance and kind in COMPLIANCE_KINDS:
        _compliance(robot, plan, film, act, rep)
    return PaintResult(job, kind, plan, film, PaintReport.from_dict(kind, rep), act, options)


def _compliance(robot, plan, film: PaintFilm, act, rep: dict) -> None:
    """paint.json's ``compliance`` entry and its time (docs/model.md §27.7)."""
    from .film.compliance import compliance_entry

    t0 = time.perf_counter()
    if hasattr(plan, "robots"):  # a cell: the worst over its robots, each robot's own
        from .cell.compliance import cell_compliance

        rep["compliance"], per = cell_compliance(robot, plan, film.points, film.thickness,
                                                 act, film.painted)
        for r, c in zip(rep["robots"], per):
            r["compliance"] = c
    else:
        rep["compliance"] = compliance_entry(robot, plan, film.points, film.thickness, act,
                                             film.painted)
    rep["timings"]["compliance"] = time.perf_counter() - t0


def _panel(robot, job, act, options, res):
    from .film.grid import plan_film
    from .plan.panel import plan_paint
    from .report import paint_report

    t0 = time.perf_counter()
    plan = plan_paint(robot, job, act)
    t1 = time.perf_counter()
    U, V, pts, film = plan_film(plan, res)
    t2 = time.perf_counter()
    rep = paint_report(plan, film, act)
    rep.update(timings={"plan": t1 - t0, "film": t2 - t1},
               grid={"nu": len(U), "nv": len(V), "resolution": res}, pollard_pin=__version__)
    return plan, PaintFilm(pts, film, res, grid=(U, V)), rep


def _part(robot, job, act, options, res):
    from .film.part import surface_film
    from .film.points import check_film_points
    from .plan.part import plan_surface
    from .report import surface_report
    from .spray.occlusion import load_painted_part

    part = load_painted_part(job)
    check_film_points(part, res)  # before planning: the budget of the film's points
    t0 = time.perf_counter()
    plan = plan_surface(robot, job, act, part)
    t1 = time.perf_counter()
    pts, film, painted, efficiency = surface_film(plan, res)
    t2 = time.perf_counter()
    rep = surface_report(plan, pts, film, painted, efficiency, act)
    rep.update(timings={"plan": t1 - t0, "film": t2 - t1}, pollard_pin=__version__)
    return plan, PaintFilm(pts, film, res, painted=painted, efficiency=efficiency), rep


def _line_plan(robot, job, act, options, part=None):
    """The plan at the job's line speed or at the fastest, and the planning time [s]."""
    from .line.panel import max_line_speed, plan_line_job

    t0 = time.perf_counter()
    if options.max_line_speed:
        _, plan = max_line_speed(robot, job, act, options.speed_resolution, part)
    else:
        plan = plan_line_job(robot, job, act, part)
    return plan, time.perf_counter() - t0


def _line_panel(robot, job, act, options, res):
    from .film.line import line_film
    from .report import line_report

    plan, planning = _line_plan(robot, job, act, options)
    t0 = time.perf_counter()
    U, V, pts, film = line_film(plan, res)
    rep = line_report(plan, film, act, {"nu": len(U), "nv": len(V), "resolution": res})
    rep.update(timings={"plan": planning, "film": time.perf_counter() - t0},
               pollard_pin=__version__)
    rep["line"]["searched"] = options.max_line_speed
    return plan, PaintFilm(pts, film, res, grid=(U, V)), rep


def _line_part(robot, job, act, options, res):
    from .film.part import surface_film
    from .film.points import check_film_points
    from .report import line_part_report
    from .spray.occlusion import load_painted_part

    part = load_painted_part(job)
    check_film_points(part, res)  # before planning: the budget of the film's points
    plan, planning = _line_plan(robot, job, act, options, part)
    t0 = time.perf_counter()
    pts, film, painted, efficiency = surface_film(plan.in_part_frame(), res)
    rep = line_part_report(plan, pts, film, painted, efficiency, act)
    rep.update(timings={"plan": planning, "film": time.perf_counter() - t0},
               pollard_pin=__version__)
    rep["line"]["searched"] = options.max_line_speed
    return plan, PaintFilm(pts, film, res, painted=painted, efficiency=efficiency), rep


def _cell(robot, job, act, options, res):
    """A cell (docs/model.md §26): every robot's program, the film of all on the part."""
    from .cell.plan import max_cell_speed, plan_cell_job
    from .cell.report import cell_report

    part = None
    if isinstance(job, PartJob):
        from .film.points import check_film_points
        from .spray.occlusion import load_painted_part

        part = load_painted_part(job)
        check_film_points(part, res)
    t0 = time.perf_counter()
    if options.max_line_speed:
        _, plan = max_cell_speed(robot, job, act, options.speed_resolution, part)
    else:
        plan = plan_cell_job(robot, job, act, part)
    t1 = time.perf_counter()
    if part is None:
        from .film.cell import cell_panel_film

        U, V, pts, film = cell_panel_film(plan, res)
        flat = pts.reshape(-1, 3)
        areas = _grid_areas(U, V)
        rep = cell_report(plan, flat, None, film.thickness, areas, act,
                          {"grid": {"nu": len(U), "nv": len(V), "resolution": res}})
        pf = PaintFilm(pts, film, res, grid=(U, V))
    else:
        from .film.cell import cell_part_film

        pts, film, painted, efficiency = cell_part_film(plan, res)
        rep = cell_report(plan, pts.points[painted], pts.normals[painted],
                          film.thickness[painted], pts.areas[painted], act,
                          {"transfer_efficiency": efficiency,
                           "film_points": {"painted": int(np.count_nonzero(painted)),
                                           "total": len(pts), "resolution": res}})
        pf = PaintFilm(pts, film, res, painted=painted, efficiency=efficiency)
    rep.update(timings={"plan": t1 - t0, "film": time.perf_counter() - t1},
               pollard_pin=__version__)
    rep["line"]["searched"] = options.max_line_speed
    return plan, pf, rep


def _grid_areas(U, V) -> np.ndarray:
    """A panel grid point's share of the area (trapezoid weights)."""
    from ..dynamics.averages import trapezoid_weights

    return np.outer(trapezoid_weights(V), trapezoid_weights(U)).ravel()


__all__ = ["KINDS", "PaintFilm", "PaintOptions", "PaintReport", "PaintResult",
           "default_actuators", "film_spacing_of", "job_kind", "paint"]
