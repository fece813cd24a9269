"""A trajectory traversed with a new timing along the same path (docs/model.md §19)."""
from __future__ import annotations

import numpy as np

from ..dynamics.timeopt import TimeOptimal
from ..paths.const_accel import RetimedCurve
from ..paths.trajectory import Trajectory, trajectory_curve


def retimed_trajectory(traj: Trajectory, timing: TimeOptimal, name: str | None = None
                       ) -> Trajectory:
    """``traj``'s path with the timing s(t) of ``timing``: at the grid of ``timing`` on its own
    path (``timing.curve``, :func:`~pollard_pin.dynamics.timeopt.time_optimal_path`: by arc
    length), else at ``traj``'s samples (``timing`` computed on s = (t − t0)/T of ``traj``):
    exact rates p'(s)·ṡ and accelerations p'(s)·s̈ + p''(s)·ṡ². Its ``curve`` is the retimed
    motion between the samples: s̈ constant per interval on that path."""
    sd, sdd = timing.s_dot[:, None], timing.s_ddot[:, None]
    if timing.curve is not None:  # the grid's own path (time_optimal_path: by arc length)
        base, t0, T = timing.curve, timing.t0, timing.span
        poses, rates, accelerations = base(t0 + timing.s * T)
        p_s, p_ss = T * rates, T * T * accelerations
        return Trajectory(timing.t.copy(), poses, p_s * sd, p_s * sdd + p_ss * sd**2,
                          name=name or f"{traj.name}_time_optimal",
                          derivatives=f"{traj.derivatives}, retimed (exact chain rule)",
                          curve=RetimedCurve(base, t0, T, timing))
    t = np.asarray(traj.t, dtype=float)
    if len(timing.s) != len(t):
        raise ValueError(f"timing has {len(timing.s)} samples, the trajectory {len(t)}")
    T = float(t[-1] - t[0])
    p_s, p_ss = T * traj.d_poses, T * T * traj.dd_poses
    return Trajectory(timing.t.copy(), traj.poses.copy(), p_s * sd, p_s * sdd + p_ss * sd**2,
                      name=name or f"{traj.name}_time_optimal",
                      derivatives=f"{traj.derivatives}, retimed (exact chain rule)",
                      curve=RetimedCurve(trajectory_curve(traj), float(t[0]), T, timing))


__all__ = ["retimed_trajectory"]
