"""The film of a panel on the line (docs/model.md §24); a part's is the still part's film
of the plan seen from the part (:meth:`.line.part.LinePartPlan.in_part_frame`).

The film is integrated in the part's frame: the gun's world positions minus the line's
displacement, over each run of samples where the gun sprays; the grid (a part: its film points) is
the part at its t = 0 pose, in world coordinates.
"""
from __future__ import annotations

import numpy as np

from ...analytic.taskspace import rotation
from ..errors import PlanError
from ..line.panel import LinePlan
from ..spray.deposition import gun_of
from .cell import weighted_film
from .grid import MAX_FILM_PAIRS, film_grid


def part_frame_positions(plan: LinePlan) -> np.ndarray:
    """The gun's tips (N, 3) in the part's frame (the part at its t = 0 pose)."""
    tr = plan.trajectory
    return tr.poses[:, :3] - plan.speed * tr.t[:, None] * plan.direction[None, :]


def line_film(plan: LinePlan, resolution: float | None = None):
    """(U, V, points (nv, nu, 3) at t = 0, Film) of the line's program."""
    U, V, pts = film_grid(plan.frame, plan.job, resolution)
    tr = plan.trajectory
    on = plan.spray > 0
    pairs = float(pts.shape[0] * pts.shape[1]) * int(on.sum())
    if pairs > MAX_FILM_PAIRS:
        raise PlanError(f"the film map needs {pairs:.3g} point × sample pairs, budget "
                        f"{MAX_FILM_PAIRS:.3g}: a coarser film grid")
    # each run of open trigger integrated apart: a wait with the trigger shut sprays nothing
    # (the rule over the sprayed samples alone would spray through it); the spot turns with
    # the gun (docs/model.md §20)
    f = weighted_film(gun_of(plan.job), tr.t, part_frame_positions(plan), rotation(tr.poses),
                      plan.spray, pts.reshape(-1, 3), plan.frame.n, plan.frame.c)
    return U, V, pts, f


__all__ = ["line_film", "part_frame_positions"]
