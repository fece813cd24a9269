"""The film of a panel or a part on the line and the numbers of its ``paint.json``
(docs/model.md §24).

The film is integrated in the part's frame: the gun's world positions minus the line's
displacement, over the samples where the gun sprays; the grid (a part: its film points) is
the part at its t = 0 pose, in world coordinates.
"""
from __future__ import annotations

import numpy as np

from ..analytic.taskspace import rotation
from ..dynamics.motors import Actuators
from .deposition import Film, film, gun_of
from .errors import PlanError
from .film import MAX_FILM_PAIRS, film_grid
from .line import LinePlan
from .stats import film_stats


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
    axes = rotation(tr.poses[on])[:, :, 0]
    f = film(gun_of(plan.job), tr.t[on], part_frame_positions(plan)[on], axes,
             pts.reshape(-1, 3), plan.frame.n, origin=plan.frame.c)
    return U, V, pts, f


def line_table(plan) -> dict:
    """The ``line`` table of paint.json (docs/model.md §24) of a panel's or a part's plan on
    the line (its ``length`` along the line and painted ``area``)."""
    j, tr = plan.job, plan.trajectory
    on = plan.spray > 0
    along = tr.poses[on, :3] @ plan.direction
    window = [float(along.min()), float(along.max())]
    cycle = float(tr.t[-1])
    length, area = plan.length, plan.area
    return {"speed": plan.speed, "direction": [float(c) for c in plan.direction],
            "start_delay": plan.times.delay, "program": [plan.times.delay, plan.times.end],
            "window": window, "window_length": window[1] - window[0],
            "travel": plan.speed * cycle, "cycle": cycle,
            "min_pitch": plan.speed * cycle, "parts_per_hour": 3600.0 / cycle,
            "part_length": length,
            "upper_bound": (length + window[1] - window[0]) / (area * j.thickness / j.flow),
            "frames": "thickness table, grid and film.ply: the part at its t = 0 pose, "
                      "world coordinates; path.csv: the world path"}


def line_report(plan: LinePlan, f: Film, act: Actuators, grid: dict) -> dict:
    """The numbers of ``paint.json`` for a panel on the line."""
    j = plan.job
    th = film_stats(f.thickness, j.thickness)
    seg = plan.segments
    return {
        "job": j.to_dict(),
        "thickness": th,
        "target": j.thickness,
        "cycle_time": float(plan.trajectory.t[-1]),
        "program_time": seg.total,
        "lower_bound": j.width * j.height * j.thickness / j.flow,
        "passes": len(plan.offsets),
        "spacing": plan.spacing,
        "speed": plan.pass_speed,
        "coats": 1,
        "direction": "horizontal" if plan.horizontal else "vertical",
        "turnarounds": [float(d) for d, k in zip(seg.duration, seg.kind) if k == "turn"],
        "samples": len(plan.trajectory),
        "motors": {name: {lim: float(plan.ratios[lim][i]) for lim in plan.ratios}
                   for i, name in enumerate(act.names)},
        "motors_source": act.source,
        "line": line_table(plan),
        "grid": grid,
        "integration": {"rule": "trapezoid over the sprayed path samples, in the part's "
                                "frame",
                        "error_estimate_max": float(np.nanmax(f.error_estimate))},
    }


def line_part_report(plan, points, f, painted, efficiency: float, act: Actuators) -> dict:
    """The numbers of ``paint.json`` for a part on the line (``plan`` a
    :class:`.line_part.LinePartPlan`, ``points``, ``f``, ``painted``, ``efficiency`` its film
    from :func:`.surface_plan.surface_film` of ``plan.in_part_frame()``): the still part's
    report (§23) of the motion relative to the part, with the cycle and the line table."""
    from .surface_report import surface_report

    rep = surface_report(plan.in_part_frame(), points, f, painted, efficiency, act)
    rep["cycle_time"] = float(plan.trajectory.t[-1])
    rep["program_time"] = plan.program.total
    rep["line"] = line_table(plan)
    rep["integration"]["rule"] += ", in the part's frame"
    return rep


__all__ = ["line_film", "line_part_report", "line_report", "line_table",
           "part_frame_positions"]
