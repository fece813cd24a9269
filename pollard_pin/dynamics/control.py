"""Controllers in actuator space and their reference (docs/model.md §18).

* :func:`desired_trajectory` — the reference at the control ticks: joint motion by the batched
  constrained IK and the nominal closed-loop inverse dynamics (feedforward), once, up front.
* Controllers: any callable ``controller(t, q, v) → τ (6,)`` (:class:`Controller`), given the
  state the robot measures (actuator angles and rates, passive joints by forward kinematics,
  :mod:`.tracking`). Built in: :class:`ComputedTorque` (the classical law at the measured
  state), :class:`FeedforwardPD` (reference feedforward plus an inertia-scaled PD) and
  :class:`PDGravity`.
"""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import pinocchio as pin

from ..errors import InputError
from ..kinematics.errors import JointLimitError
from ..kinematics.ik import IkOptions, inverse_kinematics
from ..kinematics.limits import check_joint_limits
from ..model.build import Robot
from ..paths.trajectory import trajectory_curve
from .inverse import (
    JointLosses,
    inverse_dynamics,
    inverse_dynamics_sample,
    reduced_inverse_dynamics,
    reduced_mass_matrix,
)
from .plant import ModelMismatch, perturbed_robot

CONTROL_PERIOD = 1e-3  # s, zero-order hold
WN, ZETA = 60.0, 1.0  # rad/s, 1: default error dynamics (≈ 10 Hz at a 1 kHz control rate)
MAX_WN = 1e6  # rad/s: a time constant under 1 µs is a unit slip
CONTROLLERS = ("computed-torque", "feedforward-pd", "pd")


class ControlError(InputError):
    """A simulation input the controller or integrator cannot use (one line)."""


class Controller(Protocol):
    """``controller(t, q, v) → τ``: actuator torques (6,) [N·m], docs/model.md §6 order, from the
    time [s] and the measured tree state q, v (12,): the actuator angles and rates as sensed
    (with their noise), the passive joints by forward kinematics from them. (The built-in ones
    also take the constraint Jacobian ``Jc``, velocity map ``N`` and the loops' a₀ at q, v
    that sensing built, so as not to build them again.)"""

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray: ...


@dataclass(frozen=True)
class Gains:
    """The gains of the built-in controllers: actuator-space error dynamics
    ë + 2ζω ė + ω² e = 0 (docs/model.md §18).

    Parameters
    ----------
    wn : float, optional
        Natural frequency ω [rad/s] (default 60), at most 1e6.
    zeta : float, optional
        Damping ratio ζ (default 1, critical).

    Raises
    ------
    pollard_pin.dynamics.control.ControlError
        A gain that is negative, not finite, or ω above 1e6 rad/s.

    Examples
    --------
    >>> from pollard_pin.dynamics import Gains
    >>> Gains(wn=120.0)
    Gains(wn=120.0, zeta=1.0)
    """

    wn: float = WN
    zeta: float = ZETA

    def __post_init__(self):
        for name, value in (("natural frequency ω [rad/s]", self.wn),
                            ("damping ratio ζ", self.zeta)):
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise ControlError(f"{name} must be a finite number >= 0, got {value}")
        if self.wn > MAX_WN:  # ω² overflowed float64 at 1e300 (a traceback)
            raise ControlError(f"natural frequency ω must be at most {MAX_WN:g} rad/s (a "
                               f"time constant of 1 µs), got {self.wn}")

    @property
    def kp(self) -> float:
        return self.wn ** 2

    @property
    def kd(self) -> float:
        return 2.0 * self.zeta * self.wn


@dataclass
class DesiredTrajectory:
    """The reference at the control ticks ``t`` (K,): tree joint motion ``q``, ``v``, ``a``
    (K, 12) and the feedforward ``tau`` (K, 6) of the nominal model, held on [t_k, t_k+1): the
    mean of the inverse dynamics at both ends (the torque's time average to O(T²))."""

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    tau: np.ndarray
    tau_exact: np.ndarray  # (K, 6) inverse dynamics at the ticks themselves

    def index(self, t: float) -> int:
        """The last tick at or before ``t``."""
        ticks = self.__dict__.get("_ticks")
        if ticks is None:  # the ticks as Python floats, once: bisect on them is ≈ 5× faster
            ticks = self.__dict__["_ticks"] = self.t.tolist()
        k = bisect.bisect_right(ticks, t + 1e-9 * (ticks[1] - ticks[0])) - 1
        return min(max(k, 0), len(ticks) - 1)


def control_ticks(t0: float, t1: float, period: float) -> np.ndarray:
    """t0, t0 + T, … strictly before t1, then t1."""
    n = int(math.floor((t1 - t0) / period + 1e-9))
    ticks = t0 + period * np.arange(n + 1)
    if t1 - ticks[-1] > 1e-9 * period:
        ticks = np.append(ticks, t1)
    ticks[-1] = t1
    return ticks


def desired_trajectory(robot: Robot, trajectory, period: float = CONTROL_PERIOD, curve=None,
                       losses: JointLosses | None = None, joint_limits: bool = True,
                       ik: IkOptions | None = None) -> DesiredTrajectory:
    """The reference of ``trajectory`` (times, poses and their rates and accelerations) at the
    control ticks, by the batched IK and inverse dynamics of ``robot`` (the nominal model),
    with the joint ``losses`` the controller knows (rotor inertia, friction; default none).

    Parameters
    ----------
    robot : Robot
        The nominal model (the controller's).
    trajectory : Trajectory
        The tool path to follow (``t``, ``poses``, ``d_poses``, ``dd_poses``).
    period : float, optional
        The control period [s] (default 1 ms): the ticks run from the first sample's time to
        the last's.
    curve : Callable or None, optional
        ``curve(t) → (poses, rates, accelerations)``, the tool path between samples (default:
        the trajectory's own ``curve``, else the quintic Hermite spline through its samples,
        :func:`~pollard_pin.paths.trajectory_curve`).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        The joint losses the controller knows (default none).
    joint_limits : bool, optional
        Refuse a tick with a joint outside its limits (default True, the rule of every
        command).
    ik : IkOptions or None, optional
        How the IK solves.

    Returns
    -------
    pollard_pin.dynamics.control.DesiredTrajectory
        At the ticks ``t`` (K,): ``q``, ``v``, ``a`` (K, 12) and the feedforward torque
        ``tau`` (K, 6) [N·m], held over each period.

    Raises
    ------
    pollard_pin.dynamics.control.ControlError
        A control period that is not > 0, a trajectory of fewer than 2 samples.
    KinematicsError
        A tick the kinematics cannot solve (unreachable, singular, out of the joint limits).
    """
    if not (math.isfinite(period) and period > 0):
        raise ControlError(f"control period must be > 0 s, got {period}")
    t = np.asarray(trajectory.t, dtype=float)
    if len(t) < 2:
        raise ControlError("the trajectory needs at least 2 samples to be simulated")
    span = float(t[-1] - t[0])
    if period > span:  # one tick only: the controller would act once, at the start
        raise ControlError(f"control period {period:g} s is longer than the trajectory "
                           f"({span:.6g} s): give a period <= the trajectory's duration")
    ticks = control_ticks(float(t[0]), float(t[-1]), period)
    poses, d, dd = (curve or trajectory_curve(trajectory))(ticks)
    ik = inverse_kinematics(robot, poses, d, dd, ticks, options=ik)
    if joint_limits:
        try:
            check_joint_limits(robot, ik.q, ticks)
        except JointLimitError as exc:  # a tick is no sample of the file: say the time
            raise JointLimitError(f"the reference at t = {exc.time:.6g} s (control tick "
                                  f"{exc.sample}): {exc.detail}", chain=exc.chain,
                                  amount=exc.amount) from None
    tau = inverse_dynamics(robot, ik, losses, energies=False).tau
    held = tau.copy()
    held[:-1] = 0.5 * (tau[:-1] + tau[1:])
    return DesiredTrajectory(t=ticks, q=ik.q, v=ik.v, a=ik.a, tau=held, tau_exact=tau)


class ComputedTorque:
    """The classical computed-torque law at the measured state (docs/model.md §18):

        τ = M_red(q)·(θ̈_d + ω² e + 2ζω ė) + h_red(q, q̇),   e = θ_d − θ, ė = θ̇_d − θ̇,

    M_red, h_red the nominal closed-loop dynamics in actuator coordinates
    (:func:`~pollard_pin.dynamics.inverse.reduced_dynamics`) with the joint ``losses`` the
    controller knows. With an exact model the actuator errors obey ë + 2ζω ė + ω² e = 0
    wherever the robot is, on the reference or not. θ̈_d is held over each control period as
    the mean of its ends (as the feedforward, :class:`DesiredTrajectory`).

    Called as ``controller(t, q, v)`` with the measured state, it returns the six actuator
    torques [N·m]; :func:`~pollard_pin.simulate_tracking` builds it from its name.

    Parameters
    ----------
    robot : Robot
        The nominal model (the controller's).
    desired : pollard_pin.dynamics.control.DesiredTrajectory
        The reference at the control ticks (:func:`~pollard_pin.dynamics.desired_trajectory`).
    gains : Gains, optional
        ω [rad/s] and ζ of the error dynamics (default ω = 60, ζ = 1).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        The joint losses the controller knows (default none).
    """

    def __init__(self, robot: Robot, desired: DesiredTrajectory, gains: Gains = Gains(),
                 losses: JointLosses | None = None):
        # reduced_dynamics takes the losses whole (rotor inertia too): no model copy needed
        self.robot, self.desired, self.gains, self.losses = robot, desired, gains, losses
        self._ia = robot.actuated_v
        acc = desired.a[:, self._ia]
        self._acc = acc.copy()
        self._acc[:-1] = 0.5 * (acc[:-1] + acc[1:])
        # the gains as arrays: numpy multiplies two arrays faster than a Python float and an
        # array (same bits; this runs every control tick)
        self._kp, self._kd = np.full(len(self._ia), gains.kp), np.full(len(self._ia), gains.kd)
        self._q, self._v = desired.q[:, self._ia], desired.v[:, self._ia]

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray, Jc=None, N=None,
                 a0=None) -> np.ndarray:
        ia = self._ia
        k = self.desired.index(t)
        u = self._acc[k] + self._kp * (self._q[k] - q[ia]) + self._kd * (self._v[k] - v[ia])
        # M_red·u + h_red by one RNEA at θ̈ = u (reduced_inverse_dynamics)
        return reduced_inverse_dynamics(self.robot, q, v, u, self.losses, Jc, N, a0)


class FeedforwardPD:
    """τ = τ_ff(t) + M_red(q)·(ω² e + 2ζω ė): the nominal closed-loop inverse dynamics along the
    reference (computed once, :class:`DesiredTrajectory`) plus a PD on the actuator errors
    scaled by the nominal closed-loop inertia at the measured configuration (docs/model.md
    §18). Off the reference it does not cancel the dynamics at the measured state.
    ``losses``: the rotor inertia the controller knows (in M_red; the feedforward's losses
    are ``desired``'s).

    Called as ``controller(t, q, v)`` with the measured state, it returns the six actuator
    torques [N·m]; :func:`~pollard_pin.simulate_tracking` builds it from its name.

    Parameters
    ----------
    robot : Robot
        The nominal model (the controller's).
    desired : pollard_pin.dynamics.control.DesiredTrajectory
        The reference at the control ticks (:func:`~pollard_pin.dynamics.desired_trajectory`).
    gains : Gains, optional
        ω [rad/s] and ζ of the error dynamics (default ω = 60, ζ = 1).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        The joint losses the controller knows (default none).
    """

    def __init__(self, robot: Robot, desired: DesiredTrajectory, gains: Gains = Gains(),
                 losses: JointLosses | None = None):
        self.robot, self.desired, self.gains = _known(robot, losses), desired, gains
        self._ia = robot.actuated_v

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray, Jc=None, N=None,
                 a0=None) -> np.ndarray:
        d, g, ia = self.desired, self.gains, self._ia
        k = d.index(t)
        e, ed = d.q[k, ia] - q[ia], d.v[k, ia] - v[ia]
        return d.tau[k] + reduced_mass_matrix(self.robot, q, N) @ (g.kp * e + g.kd * ed)


class PDGravity:
    """τ = g_red(q) + K_p e + K_d ė: the baseline. g_red is the nominal closed-loop gravity
    torque at the measured configuration; K_p = ω² M₀, K_d = 2ζω M₀ with M₀ the nominal
    closed-loop inertia at the reference's start (constant gains; rotor inertia of ``losses``
    included).

    Called as ``controller(t, q, v)`` with the measured state, it returns the six actuator
    torques [N·m]; :func:`~pollard_pin.simulate_tracking` builds it from its name.

    Parameters
    ----------
    robot : Robot
        The nominal model (the controller's).
    desired : pollard_pin.dynamics.control.DesiredTrajectory
        The reference at the control ticks (:func:`~pollard_pin.dynamics.desired_trajectory`).
    gains : Gains, optional
        ω [rad/s] and ζ of the error dynamics (default ω = 60, ζ = 1).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        The joint losses the controller knows (default none).
    """

    def __init__(self, robot: Robot, desired: DesiredTrajectory, gains: Gains = Gains(),
                 losses: JointLosses | None = None):
        self.robot, self.desired, self.gains = robot, desired, gains
        self._ia = robot.actuated_v
        m0 = reduced_mass_matrix(_known(robot, losses), desired.q[0])
        self.kp, self.kd = gains.kp * m0, gains.kd * m0
        self._zero = np.zeros(robot.model.nv)

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray, Jc=None, N=None,
                 a0=None) -> np.ndarray:
        d, ia = self.desired, self._ia
        k = d.index(t)
        if N is None:
            gravity = inverse_dynamics_sample(self.robot, q, self._zero, self._zero, Jc=Jc)[0]
        else:  # sensed on the loops: τ = Nᵀ g_tree (Jc·N = 0 drops the closures, §13)
            model, data = self.robot.model, self.robot.data
            gravity = N.T @ pin.computeGeneralizedGravity(model, data, q)
        return gravity + self.kp @ (d.q[k, ia] - q[ia]) + self.kd @ (d.v[k, ia] - v[ia])


def _known(robot: Robot, losses: JointLosses | None) -> Robot:
    """``robot`` with the rotor inertia of ``losses`` in its ``model.armature`` (a copy)."""
    if losses is None or not np.any(losses.armature):
        return robot
    return perturbed_robot(robot, ModelMismatch(losses=losses))


def make_controller(name: str, robot: Robot, desired: DesiredTrajectory,
                    gains: Gains = Gains(), losses: JointLosses | None = None) -> Controller:
    """A built-in controller by name (:data:`CONTROLLERS`); ``losses``: the joint losses it
    knows (build ``desired`` with the same)."""
    kinds = {"computed-torque": ComputedTorque, "feedforward-pd": FeedforwardPD,
             "pd": PDGravity}
    if name not in kinds:
        raise ControlError(f"unknown controller {name!r} (expected one of: "
                           f"{', '.join(CONTROLLERS)})")
    return kinds[name](robot, desired, gains, losses)
