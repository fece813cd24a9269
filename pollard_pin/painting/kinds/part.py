"""A still part's mesh (docs/model.md §23): plan_surface's passes over the surface, the film
on its points; paint.json's numbers are :func:`~pollard_pin.painting.report.surface_report`'s
and the lines ``pollard-pin paint`` prints a part's (both shared with a part on a line)."""
from __future__ import annotations

import time

from ...version import __version__
from ..film.part import surface_film
from ..plan.part import plan_surface
from ..report import surface_report
from ..result import PaintFilm
from ..summary import part_summary_lines
from .base import JobKind, checked_part


def paint(robot, job, act, options, res):
    """(plan, film, report) of a still part."""
    part = checked_part(job, res)
    t0 = time.perf_counter()
    plan = plan_surface(robot, job, act, part, policy=options.policy)
    t1 = time.perf_counter()
    pts, film, painted, efficiency = surface_film(plan, res)
    t2 = time.perf_counter()
    rep = surface_report(plan, pts, film, painted, efficiency, act)
    rep.update(timings={"plan": t1 - t0, "film": t2 - t1}, pollard_pin=__version__)
    return plan, PaintFilm(pts, film, res, painted=painted, efficiency=efficiency), rep


KIND = JobKind("part", paint, part_summary_lines)

__all__ = ["KIND", "paint"]
