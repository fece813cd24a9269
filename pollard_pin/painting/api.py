"""One computation for every job kind (docs/model.md §20–§26): :func:`paint_job` looks the
job's kind up in the table of kinds (``pollard_pin.painting.kinds``: a panel or a part, still,
on a line or in a cell), has it plan, integrate the film and compute ``paint.json``'s numbers,
and adds the compliance report. It writes nothing: :func:`pollard_pin.paint` (on the outputs
floor, ``pollard_pin.outputs.result``) returns the same as a result that writes itself.
"""
from __future__ import annotations

import time
from pathlib import Path

from ..dynamics.motors import Actuators, as_actuators
from ..errors import InputError
from ..model.build import check_robot
from .accounting import with_material
from .job import PartJob
from .kinds import kind_of
from .options import PaintOptions
from .progress import showing
from .result import PaintedJob, PaintReport


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


def paint_job(robot, job, actuators: Actuators | str | Path | None = None,
              options: PaintOptions | None = None) -> PaintedJob:
    """Plan the job, integrate its film and compute its report, writing nothing: the
    computation of :func:`pollard_pin.paint` (which returns it as a
    :class:`~pollard_pin.PaintResult` that also writes itself; its docstring says what each
    kind does and what is raised).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        From :func:`~pollard_pin.load_job`.
    actuators : Actuators or str or Path or None, optional
        The motor ratings, or an actuator file's path (read by
        :func:`~pollard_pin.load_actuators`) (default: the job's ``actuators`` file, else the
        package's).
    options : PaintOptions or None, optional
        Film resolution, the line speed search, the planners' policy.

    Returns
    -------
    PaintedJob
        The plan, the film and the report.

    Raises
    ------
    pollard_pin.errors.InputError
        An argument of the wrong type (one line naming it), or a cell's knob of the policy
        (``seam_run``, ``smoothing``, ``seams``) for a job of one robot, before anything is
        planned.
    """
    check_robot(robot)
    kind = kind_of(job)
    actuators = as_actuators(actuators)
    options = PaintOptions() if options is None else options
    if not isinstance(options, PaintOptions):
        raise InputError(f"options: a {type(options).__name__}, expected PaintOptions")
    for flag in ("max_line_speed", "speeds"):
        if getattr(options, flag) and job.line is None:
            raise InputError(f"{job.source}: {flag}: the {kind.name} job has no [line] "
                             "table (speed, direction)")
    knobs = options.policy.cell_knobs()
    if knobs and not job.robots:  # not read by one robot's planner: not silently dropped
        raise InputError(f"{job.source}: PlannerPolicy.{', '.join(knobs)}: a cell's (a job "
                         f"with [[robot]] tables, or --robots); the {kind.name} job has one "
                         "robot")
    res = film_spacing_of(job, options.resolution)
    act = default_actuators(job) if actuators is None else actuators
    with showing(options.progress):
        plan, film, rep = kind.paint(robot, job, act, options, res)
        rep = with_material(_with_film_check(rep), job, film)  # docs/model.md §29
        if options.compliance and kind.compliance:  # docs/model.md §27.7
            t0 = time.perf_counter()
            kind.compliance(robot, plan, film, act, rep)
            rep["timings"]["compliance"] = time.perf_counter() - t0
    return PaintedJob(job, kind.name, plan, film, PaintReport.from_dict(kind.name, rep), act,
                       options, kind)


def _with_film_check(rep: dict) -> dict:
    """``rep`` with its ``film_check`` (the film against the acceptance) after its
    ``target``."""
    from .film.stats import film_check

    out = {}
    for k, v in rep.items():
        out[k] = v
        if k == "target":
            out["film_check"] = film_check(rep["thickness"], rep["target"])
    return out


__all__ = ["default_actuators", "film_spacing_of", "paint_job"]
