"""A trajectory traversed with a new timing along the same path (docs/model.md §19)."""
from __future__ import annotations

import numpy as np

from ..dynamics.timeopt import TimeOptimal
from ..paths.const_accel import RetimedCurve
from ..paths.trajectory import Trajectory, trajectory_curve


def retimed_trajectory(traj: Trajectory, timing: TimeOptimal, name: str | None = None
                       ) -> Trajectory:
    """``traj``'s path at its own samples with the timing s(t) of ``timing`` (computed on the
    path s = (t − t0)/T of ``traj``): exact rates p'(s)·ṡ and accelerations
    p'(s)·s̈ + p''(s)·ṡ², with p' = T·ṗ and p'' = T²·p̈ of the original timing. Its ``curve``
    is the retimed motion between the samples: s̈ constant per interval on ``traj``'s path."""
    t = np.asarray(traj.t, dtype=float)
    if len(timing.s) != len(t):
        raise ValueError(f"timing has {len(timing.s)} samples, the trajectory {len(t)}")
    T = float(t[-1] - t[0])
    p_s, p_ss = T * traj.d_poses, T * T * traj.dd_poses
    sd, sdd = timing.s_dot[:, None], timing.s_ddot[:, None]
    return Trajectory(timing.t.copy(), traj.poses.copy(), p_s * sd, p_s * sdd + p_ss * sd**2,
                      name=name or f"{traj.name}_time_optimal",
                      derivatives=f"{traj.derivatives}, retimed (exact chain rule)",
                      curve=RetimedCurve(trajectory_curve(traj), float(t[0]), T, timing))


__all__ = ["retimed_trajectory"]
