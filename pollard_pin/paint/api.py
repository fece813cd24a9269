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

from .. import __version__
from ..dynamics.motors import Actuators
from ..errors import InputError
from .errors import JobKindError
from .job import KINDS, PartJob, job_kind
from .line.phases import SPEED_RESOLUTION

# The kinds whose plan is one robot's program (docs/model.md §27.7): a cell's robots are
# each one such program in their own base frame.
COMPLIANCE_KINDS = ("panel", "part", "line panel", "line part")


@dataclass(frozen=True)
class PaintOptions:
    """How :func:`paint` plans and integrates, validated once.

    ``resolution``: the film's point spacing [m] (a panel's grid, a part's film points),
    at most the spray spot's σ; None: σ/3. ``max_line_speed``: a job on a line is planned at
    the fastest line speed that paints it (bisection to ``speed_resolution``, relative)
    instead of the job's speed (docs/model.md §24). ``compliance``: report what the drives'
    compliance does to the gun and the film (docs/model.md §27.7; a second film integration).
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
    ``film`` a :class:`.spray.deposition.Film`. A part: ``points`` the
    :class:`.film.points.SurfacePoints`, ``film`` a :class:`.film.mesh.MeshFilm`,
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
    """The numbers of ``paint.json`` (docs/model.md §21, §23, §24), its main ones typed:
    ``cycle_time`` [s], ``target`` [m], ``thickness`` (the film statistics [m] and shares),
    ``motors`` (per motor, each limit's use over its rating), ``line`` (None when still),
    ``timings`` [s]; ``data`` the whole report (paint.json adds film.ply's colour map:
    :func:`pollard_pin.io.paint_files.report_json`)."""

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
    """What :func:`paint` returns: the job, its kind, the plan (a
    :class:`.plan.panel.PaintPlan`, :class:`.plan.part.SurfacePlan`, :class:`.line.panel.LinePlan`
    or :class:`.line.part.LinePartPlan`), the film, the report and the actuators it was
    checked against."""

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
    from ..model.paths import models_dir

    return load_actuators(job.actuators or models_dir() / "actuators.toml")


def film_spacing_of(job, resolution: float | None = None) -> float:
    """The film point spacing [m] ``paint`` uses for the job (a panel's grid or a part's
    points), refused as a :class:`.errors.ResolutionError`."""
    from .film.grid import film_resolution
    from .film.part import part_resolution

    return (part_resolution if isinstance(job, PartJob) else film_resolution)(job, resolution)


def paint(robot, job, actuators: Actuators | None = None,
          options: PaintOptions | None = None) -> PaintResult:
    """Plan the job (a panel or a part, still or on a line), integrate its film and compute
    its report: one :class:`PaintResult`. ``actuators``: the motor ratings (default: the
    job's, else the package's). A job of another type is a :class:`.errors.JobKindError`."""
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
