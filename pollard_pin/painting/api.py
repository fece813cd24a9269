"""Painting from Python: one entry point for every job kind (docs/model.md §20–§24).

    result = pollard_pin.paint(robot, pollard_pin.load_job("examples/paint.toml"))
    result.report.cycle_time, result.report.thickness["within_10pct"]
    result.write("out", "csv")      # what ``pollard-pin paint --out out`` writes

:func:`paint` looks the job's kind up in the table of kinds (``pollard_pin.painting.kinds``: a
panel or a part, still, on a line or in a cell), has it plan, integrate the film and compute
``paint.json``'s numbers, and adds the compliance report; the CLI only parses, calls it,
writes and prints (``result.summary_lines()``).
"""
from __future__ import annotations

import time

from ..dynamics.motors import Actuators
from ..errors import InputError
from .job import PartJob
from .kinds import kind_of
from .options import PaintOptions
from .result import PaintFilm, PaintReport, PaintResult


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
    split into zones, one per robot (:func:`~pollard_pin.split_cell`), each robot's program
    is planned in its own base frame on the cell's clock (:func:`~pollard_pin.plan_cell`),
    the robots' clearance from each other and from the part is checked, and the film is that
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
    kind = kind_of(job)
    options = PaintOptions() if options is None else options
    if not isinstance(options, PaintOptions):
        raise InputError(f"options: a {type(options).__name__}, expected PaintOptions")
    if options.max_line_speed and job.line is None:
        raise InputError(f"{job.source}: max_line_speed: the {kind.name} job has no [line] "
                         "table (speed, direction)")
    res = film_spacing_of(job, options.resolution)
    act = default_actuators(job) if actuators is None else actuators
    plan, film, rep = kind.paint(robot, job, act, options, res)
    if options.compliance and kind.compliance:  # docs/model.md §27.7
        _compliance(robot, plan, film, act, rep)
    return PaintResult(job, kind.name, plan, film, PaintReport.from_dict(kind.name, rep), act,
                       options, kind)


def _compliance(robot, plan, film: PaintFilm, act, rep: dict) -> None:
    """paint.json's ``compliance`` entry and its time (docs/model.md §27.7)."""
    from .checks.compliance import compliance_entry

    t0 = time.perf_counter()
    if hasattr(plan, "robots"):  # a cell: the worst over its robots, each robot's own
        from .checks.cell_compliance import cell_compliance

        rep["compliance"], per = cell_compliance(robot, plan, film.points, film.thickness,
                                                 act, film.painted)
        for r, c in zip(rep["robots"], per):
            r["compliance"] = c
    else:
        rep["compliance"] = compliance_entry(robot, plan, film.points, film.thickness, act,
                                             film.painted)
    rep["timings"]["compliance"] = time.perf_counter() - t0


__all__ = ["default_actuators", "film_spacing_of", "paint"]
