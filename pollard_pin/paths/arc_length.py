"""A timed path re-parameterised by its arc length in task space: the parameter TOPP-RA runs
on, so that the time-optimal cycle does not depend on how the samples were timed
(docs/model.md §19). A curve, so it lives with the other curves."""
from __future__ import annotations

import numpy as np

from .splines import QuinticHermite

ARC_POINTS = 2  # knots per sample interval of the arc-length path at least, and
# at least this many in all: u(σ)'s second derivative within 5e-5 of the thesis curve's
# (4e-3 with 6400, 4e-4 with 12,800: docs/model.md §19)
ARC_KNOTS = 25600
STOP = 1e-6  # an interior point this slow (relative to the fastest) is a stop on the path
# an end this slow (relative to the fastest) stands: u(σ) ~ √σ there, no polynomial, so the
# path is the chord spline (ChordArcLengthPath)
END_STOP = 1e-3
MIN_CHORD = 0.1  # of the median chord: the chord spline's closest knots


def _speed(rates, accelerations, scale):
    """g = |dp/du| scaled and dg/du; at a rest end (g = 0) its one-sided limit ±|d²p/du²|,
    the speed rising from the start and falling to the end."""
    g = np.sqrt(((rates / scale) ** 2).sum(axis=1))
    dot = ((rates / scale) * (accelerations / scale)).sum(axis=1)
    side = np.where(np.arange(len(g)) < len(g) / 2, 1.0, -1.0)
    limit = side * np.sqrt(((accelerations / scale) ** 2).sum(axis=1))
    with np.errstate(divide="ignore", invalid="ignore"):
        return g, np.where(g > 0, dot / g, limit)


def _arc(u, rates, accelerations, scale) -> np.ndarray:
    """σ at the points ``u`` by the end-corrected trapezoid rule (O(h⁵) per interval)."""
    g, g1 = _speed(rates, accelerations, scale)
    h = np.diff(u)
    return np.concatenate([[0.0], np.cumsum(h * (g[1:] + g[:-1]) / 2
                                            + h * h * (g1[:-1] - g1[1:]) / 12)])


class _Grid:
    """The grid in ∫√(1 + κ) dσ shared by both arc-length paths (knots σ, ``length``)."""

    def _measure(self, sigma: np.ndarray) -> None:
        kappa = np.sqrt(((self(sigma)[2] / self.scale) ** 2).sum(axis=1))
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


class ArcLengthPath(_Grid):
    """The tool path of ``curve`` between times ``t[0]`` and ``t[-1]`` parameterised by its
    arc length σ [0, ``length``] in task space, lengths and angles each divided by ``scale``
    (their largest range along the path): a ``curve(σ) -> (poses, dp/dσ, d²p/dσ²)``, the same
    whatever the timing of the samples (docs/model.md §19). The poses are ``curve`` itself at
    its time u(σ), so the geometry is exact; u(σ) is the quintic Hermite spline through the
    knots' (σ, u, 1/g, −g'/g³), g = |dp/du| scaled, σ by the end-corrected trapezoid rule
    (error O(h⁵) per knot interval)."""

    def __init__(self, curve, u: np.ndarray, rates: np.ndarray, accelerations: np.ndarray,
                 scale: np.ndarray):
        g, g1 = _speed(rates, accelerations, scale)
        sigma = _arc(u, rates, accelerations, scale)
        self.curve, self.scale, self.knots = curve, scale, sigma
        self.times = (float(u[0]), float(u[-1]))  # of ``curve``: where the path starts, ends
        self.length = float(sigma[-1])
        self.time = QuinticHermite(sigma, u[:, None], (1 / g)[:, None], (-g1 / g**3)[:, None])
        self._measure(sigma)

    def __call__(self, sigma):
        sigma = np.atleast_1d(np.asarray(sigma, dtype=float))
        u, u1, u2 = (x[:, 0] for x in self.time(sigma))
        poses, rates, accelerations = self.curve(u)
        return (poses, rates * u1[:, None],
                accelerations * (u1 * u1)[:, None] + rates * u2[:, None])


class ChordArcLengthPath(_Grid):
    """:class:`ArcLengthPath` of a path that stands at an end (σ from its chords, the poses a
    quintic interpolating spline in σ): smooth where the timed path comes to rest, its
    geometry within the spline's error of ``curve``'s."""

    def __init__(self, sigma: np.ndarray, poses: np.ndarray, scale: np.ndarray, times):
        from scipy.interpolate import make_interp_spline

        self.length, self.knots, self.scale = float(sigma[-1]), sigma, scale
        self.times = times
        self.spline = make_interp_spline(sigma, poses, k=5, axis=0)
        self._measure(sigma)

    def __call__(self, sigma):
        sigma = np.atleast_1d(np.asarray(sigma, dtype=float))
        return self.spline(sigma), self.spline(sigma, 1), self.spline(sigma, 2)


def _stops_inside(speed: np.ndarray) -> bool:
    """Whether the path stops (speed ≤ STOP of the fastest) at an interior point other than
    while it speeds up from a rest start or slows down to a rest end (densely sampled, the
    knots next to a rest end are that slow)."""
    slow = np.flatnonzero(speed[1:-1] <= STOP * speed.max()) + 1
    if not len(slow):
        return False
    step = np.diff(speed)
    rising = int(np.argmax(step < 0)) if np.any(step < 0) else len(speed)  # speed[:rising+1] ↑
    falling = len(speed) - 1 - (int(np.argmax(step[::-1] > 0)) if np.any(step > 0) else
                                len(speed))  # speed[falling:] ↓
    return bool(np.any((slow > rising) & (slow < falling)))


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
    if not speed.max() > 0 or _stops_inside(speed):
        return None
    if min(speed[0], speed[-1]) > END_STOP * speed.max():
        return ArcLengthPath(curve, dense, rates, accelerations, scale)
    chord = np.sqrt(((np.diff(poses, axis=0) / scale) ** 2).sum(axis=1))
    if np.any(chord <= 0):
        return None
    sigma = _arc(dense, rates, accelerations, scale)
    # near a rest end the chords shrink as the time step squared (1e-13 at 2 ms steps): the
    # spline through them blows up; knots closer than MIN_CHORD of the median are dropped
    keep = _spaced(sigma, MIN_CHORD * float(np.median(chord)))
    return ChordArcLengthPath(sigma[keep], poses[keep], scale, (float(t[0]), float(t[-1])))


def _spaced(sigma: np.ndarray, gap: float) -> np.ndarray:
    """Indices of the knots ``sigma`` (increasing) at least ``gap`` apart, first and last
    kept (greedy from the start; the last replaces a kept knot within ``gap`` of it)."""
    if np.diff(sigma).min() >= gap:
        return np.arange(len(sigma))
    keep, last = [0], sigma[0]
    for k in range(1, len(sigma) - 1):
        if sigma[k] - last >= gap:
            keep.append(k)
            last = sigma[k]
    if sigma[-1] - last < gap and len(keep) > 1:
        keep.pop()
    return np.array(keep + [len(sigma) - 1])


__all__ = ["ARC_KNOTS", "ARC_POINTS", "END_STOP", "STOP", "ArcLengthPath", "ChordArcLengthPath",
           "arc_length_path"]
