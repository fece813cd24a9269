"""A part's mesh on a moving line (docs/model.md §23–§24): planned as a panel on the line is,
its film that of the motion seen from the part (the still part's film and report), with the
line table; the lines ``pollard-pin paint`` prints: the line's, then a part's."""
from __future__ import annotations

import time

from ...dynamics.motors import Actuators
from ...version import __version__
from ..film.part import surface_film
from ..line.panel import line_speeds
from ..report import check_report, line_table, surface_report
from ..result import PaintFilm
from ..summary import line_lines, part_summary_lines
from .base import JobKind, Outputs, checked_part, with_speeds
from .line_panel import line_plan


def paint(robot, job, act, options, res):
    """(plan, film, report) of a part on the line."""
    part = checked_part(job, res)
    plan, planning = line_plan(robot, job, act, options, part)
    t0 = time.perf_counter()
    pts, film, painted, efficiency = surface_film(plan.in_part_frame(), res)
    rep = line_part_report(plan, pts, film, painted, efficiency, act)
    rep.update(timings={"plan": planning, "film": time.perf_counter() - t0},
               pollard_pin=__version__)
    rep["line"]["searched"] = options.max_line_speed
    with_speeds(rep, options, lambda: line_speeds(robot, job, act, plan, part,
                                                   policy=options.policy))
    return plan, PaintFilm(pts, film, res, painted=painted, efficiency=efficiency), rep


def line_part_report(plan, points, f, painted, efficiency: float, act: Actuators) -> dict:
    """The numbers of ``paint.json`` for a part on the line (``plan`` a
    :class:`.line.part.LinePartPlan`, ``points``, ``f``, ``painted``, ``efficiency`` its film
    from :func:`.film.part.surface_film` of ``plan.in_part_frame()``): the still part's
    report (§23) of the motion relative to the part, with the cycle and the line table."""
    rep = surface_report(plan.in_part_frame(), points, f, painted, efficiency, act)
    rep["cycle_time"] = plan.times.cycle
    rep["program_time"] = plan.relative.total  # a slow line's waits included
    rep["line"] = line_table(plan)
    rep["strokes"] = plan.strokes.to_dict()
    rep["integration"]["rule"] += ", in the part's frame"
    return check_report(rep, plan.job.source)


def summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a part on the line: the line's, then a part's."""
    return line_lines(rep) + part_summary_lines(rep, names)


# the film and the figure: the part at its t = 0 pose, the path the world's
KIND = JobKind("line part", paint, summary_lines, outputs=Outputs(part_frame=True))

__all__ = ["KIND", "line_part_report", "paint", "summary_lines"]
