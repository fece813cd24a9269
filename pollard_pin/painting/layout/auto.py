"""``--robots auto`` and ``--robots N``: a proposed cell planned, each count plain first, then
with the cell's levers (docs/model.md §26.5).

:func:`fewest_robots` tries n from the fewest whose bands hold the zones
(:func:`.cell.fewest_for`), at most :data:`AUTO_MORE` more. Each count's proposal
(:func:`.cell.propose_layout`) is planned as the user gave it; refused, it is planned again
with the levers left at their defaults set by rule (:mod:`.levers`) before the next count:
a count the levers make paint is fewer robots than any larger plain cell. A count refused
at a line speed over :data:`SPEED_PAST` times the fastest its plan paints (or under the
slowest by as much) is not tried with the levers: they move ramps by millimetres and ease
the turns; they do not bring a part twice too fast within reach of the line.
"""
from __future__ import annotations

from dataclasses import replace

from ...checks import instance, integer
from ...dynamics.motors import as_actuators
from ...errors import say_less
from ...model.build import check_robot
from ..causes import cause_of, search_refusal
from ..cell.bands import job_strokes
from ..cell.robots import MAX_ROBOTS
from ..errors import BudgetError, CellError, LayoutSearchError, PlanError, kept, made_again
from ..job import PartJob, check_job
from ..progress import bar, showing
from .cell import (
    LayoutOptions,
    check_layout_job,
    fewest_for,
    narrow_refusal,
    propose_layout,
    reference_band,
)
from .levers import levers_for, with_levers
from .seat import paint_seated

AUTO_MORE = 3  # robots tried beyond the fewest whose bands hold the zones (0.47 m door: +3)
SPEED_PAST = 2.0  # a line this many times past the speeds a count paints: no levered try


def fewest_robots(robot, job, actuators=None, options=None, layout: LayoutOptions | None = None,
                  count: int | None = None):
    """The fewest robots whose :func:`~.cell.propose_layout` paints the job at its line speed
    (or at the fastest, with ``options.max_line_speed``), and their plan (docs/model.md
    §26.5).

    The first n tried is the fewest whose bands hold the zones; a plan refused (reach,
    motors, the line's speed) is planned again with the levers (module docstring), then
    n + 1 is tried, at most ``AUTO_MORE`` times: more robots shorten every zone, which cures
    a motor or reach refusal at once or not at all (a line too slow for the programs' drift
    gets worse). Each count's failure is sorted by
    :func:`pollard_pin.painting.causes.cause_of` (the constraint that binds, its figure). A
    plan found with the levers says them in its report (``levers``: each set, and the plain
    refusal of the counts tried).

    Parameters
    ----------
    robot : Robot
        The model every robot shares (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        A job with ``[line]`` and no ``[[robot]]`` tables.
    actuators : Actuators or str or Path or None, optional
        The motor ratings or an actuator file's path (default: the job's file, else the
        package's).
    options : PaintOptions or None, optional
        As for :func:`pollard_pin.painting.api.paint_job`.
    layout : LayoutOptions or None, optional
        The spacing, the names, the room at the free edges and the top robot's pitch.
    count : int or None, optional
        Plan this many robots only, plain then with the levers (``--robots N``; default
        None: the fewest, as above).

    Returns
    -------
    robots : tuple of CellRobot
        The proposed robots.
    result : pollard_pin.painting.result.PaintedJob
        The cell's plan, film and report with them (``pollard_pin.PaintResult.of(result)``
        writes itself).

    Raises
    ------
    pollard_pin.painting.errors.LayoutSearchError
        No layout of up to ``AUTO_MORE`` more robots paints the part: one line naming the
        counts tried (from 1) and each one's cause, the levers' where they bind otherwise,
        said with less until it fits ("3 bottom band 40 mm short of the run-on; 4
        turnarounds out of reach (levers: motor 104 %); 5 motor 126 % at any speed"); its
        ``causes`` holds each count's plain :class:`~pollard_pin.painting.causes.Cause`,
        ``levered`` the levers' by count.
    pollard_pin.painting.errors.PlanError
        With ``count``: that count's refusal (the levers' cause added where tried).
    pollard_pin.painting.errors.CellError
        The job has robots or no line, or no count up to MAX_ROBOTS has bands wide enough
        (with ``count``: that count's bands are too narrow).
    """
    from ..options import PaintOptions
    from ..spray.occlusion import load_painted_part

    check_robot(robot)
    check_job(job)
    check_layout_job(job)
    actuators = as_actuators(actuators)
    options = instance(options, "options", PaintOptions, "PaintOptions or None",
                       none=True) or PaintOptions()
    layout = instance(layout, "layout", LayoutOptions, "LayoutOptions or None",
                      none=True) or LayoutOptions()
    if count is not None:
        count = integer(count, "count", 1, MAX_ROBOTS, error=CellError)
    part = load_painted_part(job) if isinstance(job, PartJob) else None
    strokes = job_strokes(job, part)
    reference = (strokes, reference_band(robot, strokes))
    if count is None:
        first = fewest_for(strokes, reference[1].width)
        if first is None:
            raise CellError(f"{job.source}: more than {MAX_ROBOTS} robots' bands would be "
                            "needed to stack zones over the part")
        # the counts whose bands are too narrow: why each cannot
        causes = {n: cause_of(narrow_refusal(strokes, reference[1], n))
                  for n in range(1, first)}
        counts = range(first, min(MAX_ROBOTS, first + AUTO_MORE) + 1)
    else:
        first, causes, counts = count, {}, (count,)
    levers = levers_for(job, strokes, options.policy, layout)
    speed = None if options.max_line_speed else job.line.speed
    levered, plain = {}, None

    def planned(n, options, layout):
        robots = propose_layout(robot, job, n, layout, part, options.policy, reference)
        return paint_seated(robot, job, robots, actuators, options, part)

    with showing(options.progress):  # a bar on a terminal, if asked
        for n in bar(counts, "layout search", unit="layout"):
            try:
                return planned(n, options, layout)
            except BudgetError:
                raise
            except (CellError, PlanError) as exc:
                plain = kept(exc)  # its words: not the frames (and plans) it was raised in
                causes[n] = cause_of(str(exc).removeprefix(f"{job.source}: "))
            if (levers is None or narrow_refusal(strokes, reference[1], n)
                    or speed is not None and causes[n].past_speeds(speed, SPEED_PAST)):
                continue  # no levers, or none that could answer it
            try:
                robots, painted = planned(n, *with_levers(options, layout, levers))
            except BudgetError:
                raise
            except (CellError, PlanError) as exc:
                levered[n] = cause_of(str(exc).removeprefix(f"{job.source}: "))
                continue
            said = (str(made_again(plain)) if count is not None else  # the plain refusal
                    search_refusal(job.source, causes, first, speed))
            said = {**levers.as_dict(), "plain": said.removeprefix(f"{job.source}: ")}
            return robots, replace(painted, report=replace(painted.report, data={
                **painted.report.data, "levers": said}))
    if count is None:
        raise LayoutSearchError(search_refusal(job.source, causes, first, speed, levered),
                                causes, speed, levered)
    plain = made_again(plain)
    if count not in levered:
        raise plain
    lever = levered[count]
    raise PlanError(say_less(f"{plain}; with its levers ({levers.flags()}): {lever.said}",
                             f"{plain}; with its levers: {lever.short}", str(plain)))


__all__ = ["AUTO_MORE", "SPEED_PAST", "fewest_robots"]
