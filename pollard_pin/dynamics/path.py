"""A path and its exact closed-loop dynamics, at its samples and anywhere between them
(docs/model.md §19).

A trajectory p(t), t ∈ [t0, t0 + T], is the path p(s), s = (t − t0)/T ∈ [0, 1]. Along any
timing s(t) the actuator torques are exactly τ = a(s)·s̈ + b(s)·ṡ² + c(s)
(:func:`path_dynamics`). Between the samples the path is a ``curve(t) -> (poses, rates,
accelerations)``: the analytic curve when there is one, else the quintic Hermite spline
through the samples' poses, rates and accelerations (:mod:`pollard_pin.paths.splines`;
:func:`path_dynamics_at` evaluates it anywhere).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..kinematics.ik import inverse_kinematics
from .inverse import inverse_dynamics


@dataclass(frozen=True)
class PathDynamics:
    """Closed-loop actuator torques along a path s ∈ [0, 1] (docs/model.md §19):
    τ = a(s)·s̈ + b(s)·ṡ² + c(s), and q̇ = q_s·ṡ, q̈ = q_s·s̈ + q_ss·ṡ² for the actuated
    joints. Arrays (n, 6) at the points ``s`` (n,)."""

    s: np.ndarray
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    q_s: np.ndarray
    q_ss: np.ndarray
    duration: float  # of the trajectory the path came from, s = (t − t0) / duration

    def take(self, index) -> PathDynamics:
        """The points ``index`` (an index array or slice) as a path of their own."""
        return replace(self, **{k: getattr(self, k)[index]
                                for k in ("s", "a", "b", "c", "q_s", "q_ss")})


def path_dynamics(robot, ik, t0: float | None = None,
                  duration: float | None = None) -> PathDynamics:
    """The path of an IK result, s = (t − t0)/T ∈ [0, 1] (by default t0 and T of ``ik.t``
    itself), with its exact torque coefficients.

    The IK is exact in the task rates, so q_s = T·q̇ and q_ss = T²·q̈ at every sample for any
    trajectory. RNEA plus the closure split is linear in the tree torque at fixed q, so
    c = τ(q, 0, 0) (gravity), a = τ(q, 0, q_s) − c and b = τ(q, q_s, q_ss) − c.
    """
    t = np.asarray(ik.t, dtype=float)
    t0 = float(t[0]) if t0 is None else float(t0)
    duration = float(t[-1] - t[0]) if duration is None else float(duration)
    v_s, a_s = duration * ik.v, duration * duration * ik.a
    zero = np.zeros_like(v_s)

    def tau(v, a):
        return inverse_dynamics(robot, replace(ik, v=v, a=a), energies=False).tau

    c = tau(zero, zero)
    ia = robot.actuated_v
    return PathDynamics(s=(t - t0) / duration, a=tau(zero, v_s) - c, b=tau(v_s, a_s) - c,
                        c=c, q_s=v_s[:, ia], q_ss=a_s[:, ia], duration=duration)


def path_dynamics_at(robot, curve, t0: float, duration: float, s) -> PathDynamics:
    """:func:`path_dynamics` at any points ``s`` ∈ [0, 1] of the path ``curve`` (times
    t0 + s·T): IK of the curve there, then the three RNEA passes."""
    s = np.asarray(s, dtype=float)
    t = t0 + s * duration
    poses, rates, accelerations = curve(t)
    ik = inverse_kinematics(robot, poses, rates, accelerations, t)
    return replace(path_dynamics(robot, ik, t0, duration), s=s)


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


__all__ = ["ArcLengthPath", "PathDynamics", "arc_length_path", "path_dynamics",
           "path_dynamics_at"]
