"""A timed path re-parameterised by its arc length in task space: the parameter TOPP-RA runs
on, so that the time-optimal cycle does not depend on how the samples were timed
(docs/model.md §19). A curve, so it lives with the other curves."""
from __future__ import annotations

import numpy as np

ARC_POINTS = 8  # points per sample interval from which the arc-length path is built, and
ARC_KNOTS = 6400  # at least this many in all (201 samples × 8 cut the thesis curve's bends)
STOP = 1e-6  # an interior point this slow (relative to the fastest) is a stop on the path


class ArcLengthPath:
    """The tool path of ``curve`` between times ``t[0]`` and ``t[-1]`` parameterised by its
    arc length σ [0, ``length``] in task space, lengths and angles each scaled by their largest
    range along the path: a ``curve(σ) -> (poses, dp/dσ, d²p/dσ²)``, the same whatever the
    timing of the samples (docs/model.md §19). A quintic interpolating spline through
    ARC_POINTS chords per sample interval, so it is smooth where the timed path comes to rest
    (where p(t) is not: dp/ds = 0 there)."""

    def __init__(self, sigma: np.ndarray, poses: np.ndarray, scale: np.ndarray):
        from scipy.interpolate import make_interp_spline

        self.length = float(sigma[-1])
        self.knots, self.scale = sigma, scale
        self.spline = make_interp_spline(sigma, poses, k=5, axis=0)
        kappa = np.sqrt(((self.spline(sigma, 2) / scale) ** 2).sum(axis=1))
        w = np.sqrt(1.0 + kappa)
        self._tau = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(sigma))])
        self.extent = float(self._tau[-1])  # ∫√(1 + κ) dσ: the grid's measure of the path

    def grid(self, n: int) -> np.ndarray:
        """``n`` points σ/length ∈ [0, 1], evenly spaced in ∫√(1 + κ) dσ, κ = |d²p/dσ²| the
        curvature (lengths normalised): a bend of radius r is crossed at most at √(a·r), so
        it gets √(1/r) more of the grid than a straight stretch of the same length."""
        tau = self._tau
        grid = np.interp(np.linspace(0.0, tau[-1], n), tau, self.knots) / self.length
        grid[0], grid[-1] = 0.0, 1.0
        return grid

    def __call__(self, sigma):
        sigma = np.atleast_1d(np.asarray(sigma, dtype=float))
        return self.spline(sigma), self.spline(sigma, 1), self.spline(sigma, 2)


def arc_length_path(curve, t) -> ArcLengthPath | None:
    """:class:`ArcLengthPath` of ``curve`` over the times ``t`` (n,), or None where arc length
    is no parameter: the path stands still, or stops inside (a cusp: it may turn back)."""
    t = np.asarray(t, dtype=float)
    per = max(ARC_POINTS, -(-ARC_KNOTS // max(len(t) - 1, 1)))
    theta = np.arange(per) / per
    dense = np.append((t[:-1, None] + theta * np.diff(t)[:, None]).ravel(), t[-1])
    poses, rates, accelerations = curve(dense)
    scale = np.ones(6)
    for g in (slice(0, 3), slice(3, 6)):
        scale[g] = max(float(np.ptp(poses[:, g], axis=0).max()), 1e-300)
    speed = np.sqrt(((rates / scale) ** 2).sum(axis=1))
    if not speed.max() > 0 or np.any(speed[1:-1] <= STOP * speed.max()):
        return None
    chord = np.sqrt(((np.diff(poses, axis=0) / scale) ** 2).sum(axis=1))
    if np.any(chord <= 0):
        return None
    return ArcLengthPath(np.concatenate([[0.0], np.cumsum(chord)]), poses, scale)


__all__ = ["ARC_KNOTS", "ARC_POINTS", "ArcLengthPath", "STOP", "arc_length_path"]
