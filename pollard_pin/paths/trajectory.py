"""The tool-pose trajectory type: times and task poses q = (x, y, z, ψ, θ, φ)
(docs/model.md §2) with their first and second time derivatives, SI units and radians, and
the exact curve between the samples when it has one."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .splines import quintic_hermite


class TrajectoryError(InputError):
    """A trajectory (file) is malformed; the message names the row and column."""


@dataclass(frozen=True)
class Trajectory:
    t: np.ndarray  # (N,) s, strictly increasing
    poses: np.ndarray  # (N, 6)
    d_poses: np.ndarray  # (N, 6)
    dd_poses: np.ndarray  # (N, 6)
    name: str = "trajectory"
    derivatives: str = "analytic"  # or "quintic spline", ...
    # the exact path between the samples, times -> (poses, rates, accelerations); None: the
    # quintic Hermite spline through the samples (see :func:`trajectory_curve`)
    curve: Callable | None = None
    # the paint gun's trigger per sample, the fraction of its flow in [0, 1] (a paint
    # program's ``spray`` column); None: no gun
    spray: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.t)

    def window(self, start: int, stop: int) -> Trajectory:
        """Samples ``start:stop`` as a trajectory of their own (views, no copy)."""
        spray = None if self.spray is None else self.spray[start:stop]
        return Trajectory(self.t[start:stop], self.poses[start:stop],
                          self.d_poses[start:stop], self.dd_poses[start:stop], self.name,
                          self.derivatives, self.curve, spray)

    def windows(self, size: int):
        """``(start, window)`` pairs of at most ``size`` samples, in order (streaming)."""
        for start in range(0, len(self), size):
            yield start, self.window(start, start + size)

    def __post_init__(self):
        n = len(self.t)
        for label, arr in (("poses", self.poses), ("d_poses", self.d_poses),
                           ("dd_poses", self.dd_poses)):
            if np.shape(arr) != (n, 6):
                raise TrajectoryError(f"{self.name}: {label} has shape {np.shape(arr)}, "
                                      f"expected ({n}, 6)")
        if self.spray is not None and np.shape(self.spray) != (n,):
            raise TrajectoryError(f"{self.name}: spray has shape {np.shape(self.spray)}, "
                                  f"expected ({n},)")


def trajectory_curve(traj) -> Callable:
    """The path between the samples of ``traj`` (``t``, ``poses``, ``d_poses``,
    ``dd_poses``, optional ``curve``): its own ``curve`` (the thesis curve, the spline a CSV's
    derivatives came from), else the C² quintic Hermite spline through its poses, rates and
    accelerations."""
    curve = getattr(traj, "curve", None)
    if curve is not None:
        return curve
    return quintic_hermite(traj.t, traj.poses, traj.d_poses, traj.dd_poses)


__all__ = ["Trajectory", "TrajectoryError", "trajectory_curve"]
