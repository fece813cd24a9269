"""Quintic splines through samples, as curves ``curve(times) -> (poses, rates,
accelerations)``, each (N, 6) (classes, not closures, so that a trajectory holding one
pickles)."""
from __future__ import annotations

import numpy as np


class QuinticHermite:
    """The C² quintic Hermite spline through samples' poses, rates and accelerations, a
    ``curve(times) -> (poses, rates, accelerations)``, each (N, 6): exact at the samples
    (a class, not a closure, so that a trajectory holding it pickles).

    Parameters
    ----------
    t : ndarray
        Sample times (n,) [s], strictly increasing.
    poses, d_poses, dd_poses : ndarray
        Poses (n, 6) and their first and second time derivatives at the samples.

    Examples
    --------
    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> from pollard_pin.paths import QuinticHermite
    >>> traj = pp.thesis_trajectory(samples=401)
    >>> spline = QuinticHermite(traj.t, traj.poses, traj.d_poses, traj.dd_poses)
    >>> t = np.linspace(0.0, 20.0, 3333)                  # mostly between the samples
    >>> bool(np.abs(spline(t)[0] - traj.curve(t)[0]).max() < 1e-7)     # 1.1e-9 m
    True
    """

    def __init__(self, t, poses, d_poses, dd_poses):
        t = np.asarray(t, dtype=float)
        p0, v0, a0 = (np.asarray(x, dtype=float)[:-1] for x in (poses, d_poses, dd_poses))
        p1, v1, a1 = (np.asarray(x, dtype=float)[1:] for x in (poses, d_poses, dd_poses))
        h = np.diff(t)[:, None]
        dp, hv0, hv1, ha0, ha1 = p1 - p0, h * v0, h * v1, h * h * a0, h * h * a1
        # p(τ) = Σ c_k τ^k on each interval, τ = (t − t_i)/h_i ∈ [0, 1]
        self.t, self.h = t, h
        self.coef = np.stack([p0, hv0, ha0 / 2,
                              10 * dp - 6 * hv0 - 4 * hv1 - (3 * ha0 - ha1) / 2,
                              -15 * dp + 8 * hv0 + 7 * hv1 + (3 * ha0 - 2 * ha1) / 2,
                              6 * dp - 3 * (hv0 + hv1) - (ha0 - ha1) / 2])  # (6, n − 1, 6)

    def __call__(self, times):
        times = np.atleast_1d(np.asarray(times, dtype=float))
        t, powers = self.t, np.arange(6)[:, None, None]
        i = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)
        tau = ((times - t[i]) / self.h[i, 0])[None, :, None]
        c, h = self.coef[:, i], self.h[i]
        pos = (c * tau ** powers).sum(0)
        rate = (c[1:] * powers[1:] * tau ** (powers[1:] - 1)).sum(0) / h
        acc = (c[2:] * (powers[2:] * (powers[2:] - 1)) * tau ** (powers[2:] - 2)).sum(0) / h**2
        return pos, rate, acc


quintic_hermite = QuinticHermite


class QuinticSpline:
    """The quintic interpolating spline (not-a-knot ends) as a curve: times -> (poses,
    rates, accelerations); a class, so that a trajectory holding it pickles."""

    def __init__(self, t: np.ndarray, y: np.ndarray):
        from scipy.interpolate import make_interp_spline

        self.spline = make_interp_spline(t, y, k=5, axis=0)

    def __call__(self, times):
        times = np.atleast_1d(np.asarray(times, dtype=float))
        return self.spline(times), self.spline(times, 1), self.spline(times, 2)


__all__ = ["QuinticHermite", "QuinticSpline", "quintic_hermite"]
