"""Closed-loop forward dynamics and replay (docs/model.md §14).

``pin.constraintDynamics`` (exact, proximal μ = 0) with Baumgarte closure stabilisation and a
fixed-step RK4 integrator; :func:`trajectory_torques` replays a trajectory's own torques. The
caller's model is never changed: rotor inertia and Baumgarte gains go on copies
(:func:`robot_copy`).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..checks import float_array, instance
from ..errors import InputError, SolveError
from ..kinematics.ik import IkOptions, inverse_kinematics
from ..model.build import Robot, check_robot, constraint_residual
from .inverse import JointLosses, inverse_dynamics_sample, reduced_mass_matrix

NEWTON = IkOptions(method="newton")  # sample by sample, warm-started at the last pose


class SimulationError(SolveError):
    """The integration produced a non-finite state."""


@dataclass
class SimulationResult:
    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    closure_residual: np.ndarray  # max |p_A − p_B| component [m]


def robot_copy(robot: Robot, model: pin.Model | None = None,
               baumgarte: tuple[float, float] | None = None) -> Robot:
    """``robot`` with its own ``model`` (default: a copy of ``robot.model``), data and constraint
    models and datas (with Baumgarte gains ``(Kp, Kd)`` if given): changing any of them leaves
    ``robot`` as it was."""
    model = pin.Model(robot.model) if model is None else model
    cms = [pin.RigidConstraintModel(cm) for cm in robot.constraint_models]
    if baumgarte is not None:
        for cm in cms:
            cm.m_baumgarte_parameters.Kp, cm.m_baumgarte_parameters.Kd = (
                float(x) for x in baumgarte)
    return dataclasses.replace(robot, model=model, data=model.createData(),
                               constraint_models=cms,
                               constraint_datas=[cm.createData() for cm in cms])


def forward_dynamics(robot: Robot, q, v, tau_act, settings=None, losses=None) -> np.ndarray:
    """Joint accelerations under actuator torques, with the loops closed (docs/model.md §14).

    ``losses`` subtract friction and add the rotor inertia (armature) to the mass matrix: the
    inverse of the inverse dynamics with the same losses. With rotor inertia the solve runs on
    a copy of the model (``robot.model`` is not changed).

    Parameters
    ----------
    robot : Robot
        The model.
    q, v : ndarray
        Configuration (12,) [rad] on the loops and joint velocities (12,) [rad/s].
    tau_act : ndarray
        Actuator torques (6,) [N·m], :attr:`Robot.actuated` order.
    settings : optional
        Pinocchio's ``ProximalSettings`` for the constrained solve (default: its own).
    losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        Joint friction and rotor inertia (default none).

    Returns
    -------
    ndarray
        Joint accelerations (12,) [rad/s²], :attr:`Robot.joint_names` order.

    Examples
    --------
    The torques of the inverse dynamics give back the accelerations they were computed for:

    >>> import numpy as np
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> traj = pp.thesis_trajectory(duration=20.0, samples=11)
    >>> ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    >>> tau = pp.inverse_dynamics(robot, ik).tau
    >>> a = pp.forward_dynamics(robot, ik.q[5], ik.v[5], tau[5])
    >>> bool(np.allclose(a, ik.a[5], atol=1e-8))
    True
    """
    check_robot(robot)
    n = {"q": robot.model.nq, "v": robot.model.nv, "tau_act": len(robot.actuated_v)}
    q, v, tau_act = (_vector(x, name, n[name]) for x, name in ((q, "q"), (v, "v"),
                                                               (tau_act, "tau_act")))
    instance(settings, "settings", pin.ProximalSettings, "pinocchio.ProximalSettings",
             none=True)
    instance(losses, "losses", JointLosses, "a JointLosses", none=True)
    return _accelerations(robot, q, v, tau_act, settings, losses)


def _vector(value, name: str, n: int) -> np.ndarray:
    """``value`` as n finite floats; else one InputError line (Pinocchio given a vector of the
    wrong size raises from C++, or aborts)."""
    x = float_array(value, name)
    if x.shape != (n,):
        raise InputError(f"{name} has shape {x.shape}, expected ({n},)")
    if not np.isfinite(x).all():
        raise InputError(f"{name}[{int(np.flatnonzero(~np.isfinite(x))[0])}] = "
                         f"{x[~np.isfinite(x)][0]}: must be a finite number")
    return x


def _accelerations(robot: Robot, q, v, tau_act, settings=None, losses=None) -> np.ndarray:
    """:func:`forward_dynamics` on arguments already checked (the integrator's inner loop)."""
    tau = np.zeros(robot.model.nv)
    tau[robot.actuated_v] = tau_act
    if losses is not None:
        tau -= losses.torque(v, np.zeros(robot.model.nv))  # friction; armature·a is on M below
        armature = np.broadcast_to(np.asarray(losses.armature, dtype=float), (robot.model.nv,))
        if np.any(armature):
            # Rotor inertia on the mass-matrix diagonal (Pinocchio's model.armature, also seen
            # by rnea): the convention of inverse_dynamics(..., losses), on a copy.
            robot = robot_copy(robot)
            robot.model.armature = robot.model.armature + armature
            settings = None
    model, data = robot.model, robot.data
    if settings is None:  # a standalone call: constraintDynamics needs its workspace sized
        pin.initConstraintDynamics(model, data, robot.constraint_models, robot.constraint_datas)
        settings = pin.ProximalSettings(1e-14, 0.0, 1)
    return pin.constraintDynamics(model, data, q, v, tau, robot.constraint_models,
                                  robot.constraint_datas, settings).copy()


def replay_open_loop(robot: Robot, torques, q0, v0, duration: float, dt: float = 1e-3,
                     baumgarte: tuple[float, float] = (400.0, 40.0)) -> SimulationResult:
    """Open-loop replay: integrate the loop-closed dynamics under given torques with
    fixed-step RK4 (no controller; closed-loop tracking is
    :func:`~pollard_pin.simulate_tracking`).

    Baumgarte stabilisation (a_c = −Kp·r − Kd·ṙ on the closure) keeps the loops closed; ``Kp``,
    ``Kd`` default to a critically damped 20 rad/s correction. They are set on the run's own
    constraint models and data: ``robot`` is not changed (its model is shared, read only).

    Parameters
    ----------
    robot : Robot
        The model.
    torques : Callable
        ``torques(t, q, v)`` → actuator torques (6,) [N·m] at time ``t`` [s].
    q0, v0 : ndarray
        The start configuration (12,) [rad], on the loops, and velocities (12,) [rad/s].
    duration : float
        Time to integrate [s].
    dt : float, optional
        The RK4 step [s] (default 1 ms).
    baumgarte : tuple of float, optional
        ``(Kp, Kd)`` [1/s², 1/s] of the closure stabilisation.

    Returns
    -------
    pollard_pin.dynamics.forward.SimulationResult
        Times ``t`` (M,) [s], ``q`` and ``v`` (M, 12), and the closure residual (M,) [m].
    """
    return _rk4(robot_copy(robot, robot.model, baumgarte), torques, q0, v0, duration, dt)


def _rk4(robot: Robot, torques, q0, v0, duration: float, dt: float) -> SimulationResult:
    model = robot.model
    pin.initConstraintDynamics(model, robot.data, robot.constraint_models,
                               robot.constraint_datas)
    settings = pin.ProximalSettings(1e-14, 0.0, 1)

    def f(t, q, v):
        return _accelerations(robot, q, v, torques(t, q, v), settings)

    steps = int(round(duration / dt))
    ts = np.arange(steps + 1) * dt
    Q, V = np.empty((steps + 1, model.nq)), np.empty((steps + 1, model.nv))
    res = np.empty(steps + 1)
    q, v = np.array(q0, dtype=float), np.array(v0, dtype=float)
    for k, t in enumerate(ts):
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
            raise SimulationError(f"simulation diverged at step {k} (t = {t:.6g} s): "
                                  "non-finite state; reduce dt or stabilise the motion")
        Q[k], V[k] = q, v
        res[k] = np.abs(constraint_residual(model, robot.data, robot.constraint_models,
                                            robot.constraint_datas, q)).max()
        if k == steps:
            break
        # RK4 on (q, v); revolute joints, so q integrates additively.
        a1 = f(t, q, v)
        q2, v2 = q + 0.5 * dt * v, v + 0.5 * dt * a1
        a2 = f(t + 0.5 * dt, q2, v2)
        q3, v3 = q + 0.5 * dt * v2, v + 0.5 * dt * a2
        a3 = f(t + 0.5 * dt, q3, v3)
        q4, v4 = q + dt * v3, v + dt * a3
        a4 = f(t + dt, q4, v4)
        q = q + dt / 6.0 * (v + 2 * v2 + 2 * v3 + v4)
        v = v + dt / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4)
    return SimulationResult(t=ts, q=Q, v=V, closure_residual=res)


def trajectory_torques(robot: Robot, curve, q_start=None, bandwidth: float | None = None):
    """``(t, q, v) → τ (6,)``: IK + inverse dynamics of ``curve(t) → (pose, rate, acc)``.

    Evaluated exactly at every integrator stage (no interpolation), warm-started from the
    previous call, so :func:`replay_open_loop` can replay a trajectory's own torques. With
    ``bandwidth`` ω [rad/s], a critically damped PD ``M_red (ω² e + 2ω ė)`` on the actuator
    errors is added to this feedforward; ``torques.state["feedback"]`` records its peak
    |torque|. Open loop (``None``) the replay is gravity-unstable over long horizons.
    """
    state = {"q": q_start, "feedback": 0.0}
    ia = robot.actuated_v

    def torques(t: float, q=None, v=None) -> np.ndarray:
        pose, d, dd = curve(np.array([t]))
        ik = inverse_kinematics(robot, pose, d, dd, np.array([t]), state["q"], NEWTON)
        state["q"] = ik.q[0]
        tau = inverse_dynamics_sample(robot, ik.q[0], ik.v[0], ik.a[0])[0]
        if bandwidth is not None and q is not None:
            e, ed = ik.q[0, ia] - q[ia], ik.v[0, ia] - v[ia]
            fb = reduced_mass_matrix(robot, q) @ (bandwidth**2 * e + 2 * bandwidth * ed)
            state["feedback"] = max(state["feedback"], float(np.abs(fb).max()))
            tau = tau + fb
        return tau

    torques.state = state
    return torques
