"""The tool-pose trajectory type: times and task poses q = (x, y, z, ψ, θ, φ)
(docs/model.md §2) with their first and second time derivatives, SI units and radians, and
the exact curve between the samples when it has one."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..checks import float_array
from ..errors import InputError
from .splines import quintic_hermite

MAX_TIME = 1e6  # s: a time beyond this (11.6 days) is a unit slip, and its squares overflow


class TrajectoryError(InputError):
    """A trajectory (file) is malformed; the message names the row and column (a file) or the
    array and its shape."""


@dataclass(frozen=True)
class Trajectory:
    """A tool-pose trajectory: times, task poses and their first and second time derivatives
    (docs/model.md §2), SI units and radians. Checked when made.

    Parameters
    ----------
    t : ndarray
        Times (N,) [s], strictly increasing.
    poses : ndarray
        Tool poses (N, 6): tip position x, y, z [m] and ZYZ angles ψ, θ, φ [rad], world frame.
    d_poses, dd_poses : ndarray
        Their first (N, 6) [m/s, rad/s] and second (N, 6) [m/s², rad/s²] time derivatives.
    name : str, optional
        A label for messages and output metadata.
    derivatives : str, optional
        Where the derivatives came from (``"analytic"``, ``"quintic spline"``,
        ``"file columns"``).
    curve : Callable or None, optional
        The exact path between the samples, ``curve(times) → (poses, rates,
        accelerations)``; None: the quintic Hermite spline through the samples
        (:func:`~pollard_pin.paths.trajectory_curve`).
    spray : ndarray or None, optional
        The paint gun's trigger per sample (N,), the fraction of its flow in [0, 1]; None: no
        gun.

    Raises
    ------
    TrajectoryError
        An array whose shape does not match ``t``'s, or that is not real numbers (strings,
        complex values, an integer beyond a float); a value that is not finite (NaN, ±inf:
        the first such sample and column named); a spray outside [0, 1].

    Examples
    --------
    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> t = np.linspace(0.0, 2.0, 5)
    >>> poses = np.tile([0.55, 0.0, 0.16, 0.0, 0.0, 0.0], (5, 1))
    >>> still = pp.Trajectory(t, poses, np.zeros((5, 6)), np.zeros((5, 6)), name="still")
    >>> len(still), still.window(1, 3).t.tolist()
    (5, [0.5, 1.0])
    """

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
        for label in ("t", "poses", "d_poses", "dd_poses"):  # real numbers (no copy if so)
            object.__setattr__(self, label, float_array(
                getattr(self, label), f"{self.name}: {label}", error=TrajectoryError))
        if self.t.ndim != 1:
            raise TrajectoryError(f"{self.name}: t has shape {self.t.shape}, expected (N,)")
        n = len(self.t)
        for label, arr in (("poses", self.poses), ("d_poses", self.d_poses),
                           ("dd_poses", self.dd_poses)):
            if np.shape(arr) != (n, 6):
                raise TrajectoryError(f"{self.name}: {label} has shape {np.shape(arr)}, "
                                      f"expected ({n}, 6)")
        for label, arr in (("t", self.t), ("poses", self.poses), ("d_poses", self.d_poses),
                           ("dd_poses", self.dd_poses)):
            if not np.isfinite(arr).all():  # NaN or ±inf: said here, not at the IK's sample
                k, *c = (int(i) for i in np.argwhere(~np.isfinite(arr))[0])
                column = "t" if not c else label.removesuffix("poses") + TASK_NAMES[c[0]]
                raise TrajectoryError(f"{self.name}: sample {k}: {column} = {arr[(k, *c)]} is not "
                                      f"a finite number ({label}[{', '.join(map(str, [k, *c]))}])")
        if self.spray is not None:
            spray = float_array(self.spray, f"{self.name}: spray", error=TrajectoryError)
            if spray.shape != (n,):
                raise TrajectoryError(f"{self.name}: spray has shape {spray.shape}, "
                                      f"expected ({n},)")
            bad = np.flatnonzero(~((spray >= 0) & (spray <= 1)))  # NaN too
            if len(bad):
                k = int(bad[0])
                raise TrajectoryError(f"{self.name}: spray[{k}] = {spray[k]:g} is outside [0, 1] "
                                      "(the fraction of the gun's flow)")
            object.__setattr__(self, "spray", spray)


def trajectory_curve(traj) -> Callable:
    """The path between the samples of ``traj`` (``t``, ``poses``, ``d_poses``,
    ``dd_poses``, optional ``curve``): its own ``curve`` (the thesis curve, the spline a CSV's
    derivatives came from), else the C² quintic Hermite spline through its poses, rates and
    accelerations.

    Parameters
    ----------
    traj : Trajectory
        The samples.

    Returns
    -------
    Callable
        ``curve(times) → (poses, rates, accelerations)``, each (M, 6), at any times [s]
        within ``traj.t``'s span.

    Examples
    --------
    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> from pollard_pin.paths import trajectory_curve
    >>> traj = pp.thesis_trajectory(samples=201)
    >>> poses, rates, acc = trajectory_curve(traj)([10.0])
    >>> bool(np.allclose(poses[0], traj.poses[100]))
    True
    """
    curve = getattr(traj, "curve", None)
    if curve is not None:
        return curve
    return quintic_hermite(traj.t, traj.poses, traj.d_poses, traj.dd_poses)


__all__ = ["Trajectory", "TrajectoryError", "trajectory_curve"]
