"""The numbers of ``paint.json``, one report for every kind of job: a panel (docs/model.md
§21), a part (§23: area-weighted film statistics over the painted faces, the largest
incidence, the transfer efficiency), either on a line (§24: the line table, the cycle).
Each holds the job, the film statistics (:func:`.film.stats.film_stats`), timing, layout
and each motor's use. Computed here; the writers (pollard_pin.io.paint_files) only write
them."""
from __future__ import annotations

import numpy as np

from ..dynamics.motors import Actuators
from .errors import ReportError
from .film.mesh import MeshFilm
from .film.stats import film_stats
from .line.panel import LinePlan
from .plan.panel import PaintPlan
from .plan.part import SurfacePlan
from .spray.deposition import Film

# Relative slack of the invariants: the film's integration error (error_estimate ≲ 1e-3 of
# the target on the examples) on the landed volume; the cycle and the bound are exact sums.
SLACK = 1e-2


def check_report(rep: dict, source: str) -> dict:
    """``rep`` if its lower bound ≤ its cycle and its transfer efficiency ≤ 100 % (within
    SLACK); else a :class:`ReportError` naming both numbers."""
    cycle, bound = rep["cycle_time"], rep["lower_bound"]
    if not bound <= cycle * (1 + 1e-9):
        raise ReportError(f"{source}: internal error: the painting-only lower bound "
                          f"{bound:.6g} s exceeds the cycle {cycle:.6g} s (a bug)")
    eff = rep.get("transfer_efficiency")
    # nan (nothing sprayed) is left to the caller
    if eff is not None and eff == eff and not eff <= 1 + SLACK:
        raise ReportError(f"{source}: internal error: transfer efficiency "
                              f"{100 * eff:.4g} % exceeds 100 % (a bug)")
    return rep


def clearance_entries(plan) -> dict:
    """paint.json's ``min_clearance_m`` (the gun body's least distance from the part [m],
    docs/model.md §25) and ``clearance`` (where, and the bound between samples)."""
    c = plan.clearance
    return {} if c is None else {"min_clearance_m": c.distance, "clearance": c.to_dict()}


def paint_report(plan: PaintPlan, f: Film, act: Actuators) -> dict:
    """The numbers of ``paint.json`` for a still panel: the job, film statistics [m], timing
    and layout, and each motor's peak utilisation (checked at CHECK_REFINE× the path's
    sampling).

    Parameters
    ----------
    plan : PaintPlan
        From :func:`~pollard_pin.painting.plan.plan_paint`.
    f : pollard_pin.painting.spray.deposition.Film
        Its film (:func:`~pollard_pin.painting.film.plan_film`).
    act : Actuators
        The motor ratings.

    Returns
    -------
    dict
        ``job``, ``thickness`` (mean, min, max, std [m], shares within ±5 % and ±10 %),
        ``target`` [m], ``cycle_time`` and ``lower_bound`` [s], passes, spacing, speed, the
        motors' use of their ratings, ...
    """
    j = plan.job
    tr = plan.trajectory
    swept = 2 * plan.half_length * len(plan.offsets) * plan.spacing * plan.coats
    steps = np.linalg.norm(np.diff(tr.poses[:, :3], axis=0), axis=1)
    rep = {
        "job": j.to_dict(),
        "thickness": film_stats(f.thickness, j.thickness),
        "target": j.thickness,
        "cycle_time": plan.cycle_time,
        "lower_bound": plan.lower_bound,
        "swept_lower_bound": swept * j.thickness / j.flow / plan.coats,
        "passes": plan.passes,
        "spacing": plan.spacing,
        "speed": plan.speed,
        "coats": plan.coats,
        "max_pass_speed": plan.max_speed,
        "direction": j.direction,
        "turnarounds": [float(d) for d, k in zip(plan.segments.duration, plan.segments.kind)
                        if k == "turn"],
        "samples": len(tr),
        **clearance_entries(plan),
        "motors": plan.motor_use(act.names),
        "motors_source": act.source,
        "integration": {"rule": "trapezoid over the path samples",
                        "time_step": float(tr.t[1] - tr.t[0]),
                        "largest_step_over_sigma": float(steps.max() / j.sigma),
                        "error_estimate_max": float(np.nanmax(f.error_estimate))},
    }
    return check_report(rep, plan.job.source)


def surface_report(plan: SurfacePlan, points, film: MeshFilm, painted, efficiency: float,
                   act: Actuators) -> dict:
    j, part, lay = plan.job, plan.part, plan.layout
    tr = plan.trajectory
    on = plan.spray > 0
    tip_speed = np.linalg.norm(tr.d_poses[on, :3], axis=1)
    steps = np.linalg.norm(np.diff(tr.poses[:, :3], axis=0), axis=1)
    rep = {
        "job": j.to_dict(),
        "part": {"mesh": part.source, "faces": len(part.faces),
                 "painted_faces": int(part.painted.sum()), "painted_area": part.painted_area},
        "thickness": film_stats(film.thickness[painted], j.thickness, points.areas[painted]),
        "target": j.thickness,
        "largest_incidence_deg": lay.incidence,
        "normal_smoothing": lay.smoothing,
        "transfer_efficiency": efficiency,
        "cycle_time": plan.cycle_time,
        "lower_bound": plan.lower_bound,
        "passes": plan.passes,
        "spacing": lay.spacing,
        "speed": plan.speed,
        "tip_speed_range": [float(tip_speed.min()), float(tip_speed.max())],
        "coats": plan.coats,
        "direction": j.direction,
        "turnarounds": [float(p.duration) for p in plan.program.pieces if p.kind == "turn"],
        "samples": len(tr),
        **clearance_entries(plan),
        "motors": plan.motor_use(act.names),
        "motors_source": act.source,
        "film_points": {"painted": int(np.count_nonzero(painted)), "total": len(points),
                        "resolution": points.resolution},
        "shadows": {"pairs_tested": film.pairs, "shaded": film.shaded,
                    "edges_integrated_apart": film.switches},
        "integration": {"rule": "trapezoid over the path samples; shadow edges by bisection "
                                "and Gauss with the end term (docs/model.md §23)",
                        # the sprayed steps: a line's wait may start with an odd one
                        "time_step": float(np.diff(tr.t)[on[1:] | on[:-1]].max()),
                        "largest_step_over_sigma": float(steps.max() / j.sigma),
                        "error_estimate_max": float(np.nanmax(film.error_estimate))},
    }
    return check_report(rep, plan.job.source)


def line_table(plan) -> dict:
    """The ``line`` table of paint.json (docs/model.md §24) of a panel's or a part's plan on
    the line (its ``length`` along the line and painted ``area``)."""
    j, tr = plan.job, plan.trajectory
    on = plan.spray > 0
    along = tr.poses[on, :3] @ plan.direction
    window = [float(along.min()), float(along.max())]
    cycle = plan.times.cycle  # the wait before is a phase, not the cycle (§24)
    length, area = plan.length, plan.area
    return {"speed": plan.speed, "direction": [float(c) for c in plan.direction],
            "start_delay": plan.times.delay, "program": [plan.times.delay, plan.times.end],
            "window": window, "window_length": window[1] - window[0],
            "travel": plan.speed * cycle, "cycle": cycle, "path_time": float(tr.t[-1]),
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
    rep = {
        "job": j.to_dict(),
        "thickness": th,
        "target": j.thickness,
        "cycle_time": plan.times.cycle,
        "program_time": seg.total,
        "lower_bound": j.width * j.height * j.thickness / j.flow,
        "passes": len(plan.offsets),
        "spacing": plan.spacing,
        "speed": plan.pass_speed,
        "coats": 1,
        "direction": "horizontal" if plan.horizontal else "vertical",
        "turnarounds": [float(d) for d, k in zip(seg.duration, seg.kind) if k == "turn"],
        "samples": len(plan.trajectory),
        **clearance_entries(plan),
        "motors": plan.motor_use(act.names),
        "motors_source": act.source,
        "line": line_table(plan),
        "grid": grid,
        "integration": {"rule": "trapezoid over the sprayed path samples, in the part's "
                                "frame",
                        "error_estimate_max": float(np.nanmax(f.error_estimate))},
    }
    return check_report(rep, plan.job.source)


def line_part_report(plan, points, f, painted, efficiency: float, act: Actuators) -> dict:
    """The numbers of ``paint.json`` for a part on the line (``plan`` a
    :class:`.line.part.LinePartPlan`, ``points``, ``f``, ``painted``, ``efficiency`` its film
    from :func:`.film.part.surface_film` of ``plan.in_part_frame()``): the still part's
    report (§23) of the motion relative to the part, with the cycle and the line table."""
    rep = surface_report(plan.in_part_frame(), points, f, painted, efficiency, act)
    rep["cycle_time"] = plan.times.cycle
    rep["program_time"] = plan.program.total
    rep["line"] = line_table(plan)
    rep["integration"]["rule"] += ", in the part's frame"
    return check_report(rep, plan.job.source)


__all__ = ["SLACK", "check_report", "clearance_entries", "line_part_report", "line_report",
           "line_table", "paint_report", "surface_report"]
