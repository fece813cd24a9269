"""The numbers of ``paint.json`` for a part (docs/model.md §23): the job, the area-weighted
film statistics over the painted faces, the largest incidence, the transfer efficiency,
timing, layout and each motor's use. Computed here; the CLI only writes them."""
from __future__ import annotations

import numpy as np

from ..dynamics.motors import Actuators
from .mesh_film import MeshFilm
from .stats import film_stats
from .surface_plan import SurfacePlan


def surface_report(plan: SurfacePlan, points, film: MeshFilm, painted, efficiency: float,
                   act: Actuators) -> dict:
    j, part, lay = plan.job, plan.part, plan.layout
    tr = plan.trajectory
    on = plan.spray > 0
    tip_speed = np.linalg.norm(tr.d_poses[on, :3], axis=1)
    steps = np.linalg.norm(np.diff(tr.poses[:, :3], axis=0), axis=1)
    return {
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
        "motors": {name: {lim: float(plan.ratios[lim][i]) for lim in plan.ratios}
                   for i, name in enumerate(act.names)},
        "motors_source": act.source,
        "film_points": {"painted": int(np.count_nonzero(painted)), "total": len(points),
                        "resolution": points.resolution},
        "shadows": {"pairs_tested": film.pairs, "shaded": film.shaded,
                    "edges_integrated_apart": film.switches},
        "integration": {"rule": "trapezoid over the path samples; shadow edges by bisection "
                                "and Gauss with the end term (docs/model.md §23)",
                        "time_step": float(tr.t[1] - tr.t[0]),
                        "largest_step_over_sigma": float(steps.max() / j.sigma),
                        "error_estimate_max": float(np.nanmax(film.error_estimate))},
    }


__all__ = ["surface_report"]
