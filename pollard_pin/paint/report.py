"""The numbers of ``paint.json`` (docs/model.md §21): the job, the film statistics, timing,
layout and each motor's use. Computed here; the CLI only writes them."""
from __future__ import annotations

import numpy as np

from ..dynamics.motors import Actuators
from .deposition import Film
from .plan import PaintPlan
from .stats import film_stats


def paint_report(plan: PaintPlan, f: Film, act: Actuators) -> dict:
    """The numbers of ``paint.json``: the job, film statistics [m], timing and layout, and
    each motor's peak utilisation (checked at CHECK_REFINE× the path's sampling)."""
    j = plan.job
    tr = plan.trajectory
    swept = 2 * plan.half_length * len(plan.offsets) * plan.spacing * plan.coats
    steps = np.linalg.norm(np.diff(tr.poses[:, :3], axis=0), axis=1)
    return {
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
        "motors": {name: {lim: float(plan.ratios[lim][i]) for lim in plan.ratios}
                   for i, name in enumerate(act.names)},
        "motors_source": act.source,
        "integration": {"rule": "trapezoid over the path samples",
                        "time_step": float(tr.t[1] - tr.t[0]),
                        "largest_step_over_sigma": float(steps.max() / j.sigma),
                        "error_estimate_max": float(np.nanmax(f.error_estimate))},
    }
