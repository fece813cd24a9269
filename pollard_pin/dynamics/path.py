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


__all__ = ["PathDynamics", "path_dynamics", "path_dynamics_at"]
