"""The pieces of ``paint.json`` that several kinds of job share (each kind's own report: its
module in ``pollard_pin.painting.kinds``): the invariants every report keeps, the gun body's
clearance (docs/model.md §25), a part's report (§23: area-weighted film statistics over the
painted faces, the largest incidence, the transfer efficiency; still or on a line) and the
line table (§24). Computed here; the writers (pollard_pin.outputs.paint_files) only write them."""
from __future__ import annotations

import numpy as np

from ..dynamics.motors import Actuators
from .errors import ReportError
from .film.mesh import MeshFilm
from .film.stats import film_stats
from .plan.part import SurfacePlan

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


__all__ = ["SLACK", "check_report", "clearance_entries", "line_table", "surface_report"]
