"""Where a design's robots stand for a line job (docs/model.md §31.3): the part moved for the
design's ``place.back``, the cell's robots proposed as ``paint --robots N`` does and moved back
there; noted in a design's notes under :data:`LAYOUT` (plain data, §31.5), so that the same
design planned again takes them instead of proposing them again.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from ..painting.cell.robots import CellRobot
from ..painting.job import PartJob
from ..painting.layout.cell import propose_layout

LAYOUT = "layout"  # a design's notes: its cell's proposed robots (the rest: its line plans')


def moved_job(job, offset):
    """The job with its part moved by ``offset`` [m] (world): a panel's centre, a part's
    position."""
    o = np.asarray(offset, float)
    if isinstance(job, PartJob):
        return replace(job, position=tuple(float(c) for c in np.add(job.position, o)))
    return replace(job, center=tuple(float(c) for c in np.add(job.center, o)))


def back_offset(ctx, back: float) -> np.ndarray:
    """Where a robot standing ``back`` [m] from the origin sees the part moved: away from it,
    along the part's facing (docs/model.md §31.3)."""
    return -back * np.asarray(ctx.strokes.facing, float)


def placed_job(values: Mapping[str, Any], ctx, robot, n: int,
               notes: dict | None = None):
    """The job a design paints (docs/model.md §31.3): a line job with its ``n`` robots
    proposed as ``paint --robots N`` does, where the robot stands (the part moved for
    ``place.back``), then their bases moved back there; a job without a line as it is.

    Parameters
    ----------
    values : Mapping
        The design's values (its ``place.back``).
    ctx : DesignContext
        From :func:`.evaluation.prepare`.
    robot : Robot
        The design's model (:func:`pollard_pin.load` of its parameters).
    n : int
        The robots in the cell.
    notes : dict or None, optional
        A design's notes (:attr:`Evaluation.notes`): the layout taken from there if it was
        proposed for this robot, count and place, else proposed and noted there.

    Returns
    -------
    PaintJob or pollard_pin.painting.job.PartJob
        The job with its ``robots`` (a cell's ``[[robot]]`` tables).

    Raises
    ------
    pollard_pin.errors.PollardError
        The layout's refusal.
    """
    job = ctx.job
    if job.line is None:
        return job
    back = ctx.space.place_back(values)
    key = repr((robot.params, n, back))  # what the layout reads besides the study's job
    noted = (notes or {}).get(LAYOUT)
    if noted is not None and noted["for"] == key:
        return replace(job, robots=tuple(CellRobot(name, tuple(base), tuple(rotation))
                                         for name, base, rotation in noted["robots"]))
    o = back_offset(ctx, back)
    robots = tuple(replace(r, base=tuple(float(c) for c in np.subtract(r.base, o)))
                   for r in propose_layout(robot, moved_job(job, o), n))
    if notes is not None:
        notes[LAYOUT] = {"for": key, "robots": [[r.name, list(r.base), list(r.rotation)]
                                                for r in robots]}
    return replace(job, robots=robots)


__all__ = ["LAYOUT", "back_offset", "moved_job", "placed_job"]
