"""What a job kind is (docs/model.md §20–§26): its name, the jobs it recognises, how it paints
them (plan → film → report), the lines ``pollard-pin paint`` prints of its report, whether it
has a compliance report, and what it writes. The kinds themselves: one module each in
``pollard_pin.painting.kinds``, one line each in its table."""
from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..job import PaintJob, PartJob, job_kind


def output_files(out: Path, fmt: str, robots=()) -> tuple[tuple, tuple]:
    """(every file ``paint`` writes in ``out`` with a ``fmt`` table, the other format's table
    files it removes): the path.csv (a cell: one in each of the ``robots``' folders), the
    film table, paint.json, thickness.png and film.ply. Check the first before any work."""
    from ...io.table import FORMATS, table_files

    paths = [out / r / "path.csv" for r in robots] if robots else [out / "path.csv"]
    files = (*(f for p in paths for f in table_files(p)),
             *table_files(out / f"thickness.{fmt}", fmt), out / "paint.json",
             out / "thickness.png", out / "film.ply")
    stale = tuple(f for other in FORMATS if other != fmt  # view --paint never finds two films
                  for f in table_files(out / f"thickness.{other}", other))
    return files, stale


def checked_part(job, resolution: float):
    """The job's part, its mesh read and placed, the budget of its film points checked at
    ``resolution`` before any planning."""
    from ..film.points import check_film_points
    from ..spray.occlusion import load_painted_part

    part = load_painted_part(job)
    check_film_points(part, resolution)  # before planning: the budget of the film's points
    return part


def with_speeds(rep: dict, options, find: Callable) -> None:
    """With ``options.speeds``: ``rep``'s ``line.speeds`` (``find()``, a
    :class:`~pollard_pin.painting.line.speeds.SpeedInterval`) and its time, ``timings.speeds``
    (docs/model.md §24.3); else nothing."""
    if options.speeds:
        t0 = time.perf_counter()
        rep["line"]["speeds"] = find().table()
        rep["timings"]["speeds"] = time.perf_counter() - t0


def robot_compliance(robot, plan, film, act, rep: dict) -> None:
    """``rep``'s ``compliance``: what one robot's drive springs do to the gun and the film
    (docs/model.md §27.7; ``film`` a :class:`~pollard_pin.painting.result.PaintFilm`)."""
    from ..checks.compliance import compliance_entry

    rep["compliance"] = compliance_entry(robot, plan, film.points, film.thickness, act,
                                         film.painted, getattr(film.film, "shade", None))


def world_tips(plan) -> np.ndarray:
    """The gun's tips (N, 3) of a still program: the part does not move."""
    return plan.trajectory.poses[:, :3]


@dataclass(frozen=True)
class Outputs:
    """What a kind's outputs differ in (the writers: pollard_pin.outputs.paint_files, a cell's
    pollard_pin.outputs.paint_cell_files).

    Attributes
    ----------
    per_robot : bool
        Each robot's path.csv in its own folder, one film for the whole part (a cell,
        docs/model.md §26).
    part_frame : bool
        The film table, film.ply and figure give the part at its t = 0 pose, world
        coordinates, the path the world's (a job on a line, docs/model.md §24).
    tips : Callable
        ``tips(plan)``: the gun's tips (N, 3) seen from the part, a panel's figure's tracks.
    """

    per_robot: bool = False
    part_frame: bool = False
    tips: Callable = world_tips

    def files(self, out: Path, fmt: str, robots=()) -> tuple[tuple, tuple]:
        """:func:`output_files` of this kind (``robots``' folders only for a cell's)."""
        return output_files(out, fmt, robots if self.per_robot else ())


@dataclass(frozen=True)
class JobKind:
    """A kind of paint job: one entry of ``pollard_pin.painting.kinds.KINDS``.

    Attributes
    ----------
    name : str
        ``result.kind`` and ``paint.json``'s word for it (``"panel"``, ``"line part"``, ...).
    paint : Callable
        ``paint(robot, job, actuators, options, resolution)`` → (plan, PaintFilm, report
        dict): plan, integrate the film, compute ``paint.json``'s numbers.
    summary_lines : Callable
        ``summary_lines(report, motor_names)`` → the lines ``pollard-pin paint`` prints.
    compliance : Callable or None
        ``compliance(robot, plan, film, actuators, report)`` adds the compliance report to
        the report dict (docs/model.md §27.7); None (or False): the kind has none.
    outputs : Outputs
        What its written files differ in.
    recognise : Callable or None
        ``recognise(job)`` → whether the job is of this kind; None: the paint jobs
        :func:`~pollard_pin.painting.job.job_kind` names ``name``.
    """

    name: str
    paint: Callable
    summary_lines: Callable
    # a factory, not a class attribute: a function there would read as a method
    compliance: Callable | None = field(default_factory=lambda: robot_compliance)
    outputs: Outputs = Outputs()
    recognise: Callable | None = None

    def recognises(self, job) -> bool:
        """Whether ``job`` is of this kind."""
        if self.recognise is not None:
            return bool(self.recognise(job))
        return isinstance(job, PaintJob | PartJob) and job_kind(job) == self.name


__all__ = ["JobKind", "Outputs", "checked_part", "output_files", "robot_compliance",
           "with_speeds", "world_tips"]
