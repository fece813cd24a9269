"""Closed-loop simulation of a tool trajectory: controllers in actuator space against a plant
(docs/model.md §18).

* :func:`desired_trajectory` — the reference at the control ticks: joint motion by the batched
  constrained IK and the nominal closed-loop inverse dynamics (feedforward), once, up front.
* Controllers: any callable ``controller(t, q, v) → τ (6,)`` (:class:`Controller`), given the
  measured tree state; :class:`ComputedTorque` and :class:`PDGravity` are built in.
* :func:`simulate_tracking` — the plant (:class:`~pollard_pin.dynamics.plant.Plant`) integrated
  by fixed-step RK4 under the controller's torque, held over each control period (zero-order
  hold), saturated per actuator, with optional measurement noise. One row per sample time of the
  input trajectory.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np
import pinocchio as pin

from ..kinematics.closure import tool_pose
from ..kinematics.ik import inverse_kinematics
from ..analytic.taskspace import rotation
from ..model.build import Robot
from .forward import SimulationError
from .inverse import (JointLosses, inverse_dynamics, inverse_dynamics_sample,
                      reduced_mass_matrix)
from .plant import BAUMGARTE, Plant, PlantErrors, perturbed_robot

DT = 1e-3  # s, RK4 step
CONTROL_PERIOD = 1e-3  # s, zero-order hold
WN, ZETA = 60.0, 1.0  # rad/s, 1: default error dynamics (≈ 10 Hz at a 1 kHz control rate)
START_TOL = 1e-6  # m and rad: a start configuration this close to the first pose is on the path
CONTROLLERS = ("computed-torque", "pd")


class ControlError(ValueError):
    """A simulation input the controller or integrator cannot use (one line)."""


class Controller(Protocol):
    """``controller(t, q, v) → τ``: actuator torques (6,) [N·m], docs/model.md §6 order, from the
    time [s] and the measured tree state q, v (12,) (noise, if any, on the actuated entries)."""

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray: ...


@dataclass(frozen=True)
class Gains:
    """Actuator-space error dynamics ë + 2ζω ė + ω² e = 0: natural frequency ω [rad/s] and
    damping ratio ζ."""

    wn: float = WN
    zeta: float = ZETA

    def __post_init__(self):
        for name, value in (("natural frequency --wn", self.wn), ("damping --zeta", self.zeta)):
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise ControlError(f"{name} must be a finite number >= 0, got {value}")

    @property
    def kp(self) -> float:
        return self.wn ** 2

    @property
    def kd(self) -> float:
        return 2.0 * self.zeta * self.wn


@dataclass(frozen=True)
class MeasurementNoise:
    """Gaussian noise on the measured actuator angles [rad] and rates [rad/s], seeded."""

    position: float = 0.0
    velocity: float = 0.0
    seed: int | None = 0

    def __post_init__(self):
        for name, value in (("position noise", self.position),
                            ("velocity noise", self.velocity)):
            if not (math.isfinite(value) and value >= 0):
                raise ControlError(f"{name} standard deviation must be >= 0, got {value}")


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
        k = int(np.searchsorted(self.t, t + 1e-9 * (self.t[1] - self.t[0]), side="right")) - 1
        return min(max(k, 0), len(self.t) - 1)


def _hermite(trajectory):
    """``curve(t) → (poses, rates, accelerations)``: the quintic Hermite interpolant of the
    trajectory's samples (positions, rates and accelerations matched at every sample)."""
    from scipy.interpolate import BPoly

    y = np.stack([trajectory.poses, trajectory.d_poses, trajectory.dd_poses], axis=1)
    spline = BPoly.from_derivatives(trajectory.t, y)
    d1, d2 = spline.derivative(1), spline.derivative(2)
    return lambda t: (spline(t), d1(t), d2(t))


def control_ticks(t0: float, t1: float, period: float) -> np.ndarray:
    """t0, t0 + T, … strictly before t1, then t1."""
    n = int(math.floor((t1 - t0) / period + 1e-9))
    ticks = t0 + period * np.arange(n + 1)
    if t1 - ticks[-1] > 1e-9 * period:
        ticks = np.append(ticks, t1)
    ticks[-1] = t1
    return ticks


def desired_trajectory(robot: Robot, trajectory, period: float = CONTROL_PERIOD, curve=None,
                       losses: JointLosses | None = None, **ik_options) -> DesiredTrajectory:
    """The reference of ``trajectory`` (times, poses and their rates and accelerations) at the
    control ticks, by the batched IK and inverse dynamics of ``robot`` (the nominal model),
    with the joint ``losses`` the controller knows (rotor inertia, friction; default none).

    ``curve(t) → (poses, rates, accelerations)`` evaluates the tool path between samples
    (default: the quintic Hermite interpolant of the samples).
    """
    if not (math.isfinite(period) and period > 0):
        raise ControlError(f"control period must be > 0 s, got {period}")
    t = np.asarray(trajectory.t, dtype=float)
    if len(t) < 2:
        raise ControlError("the trajectory needs at least 2 samples to be simulated")
    ticks = control_ticks(float(t[0]), float(t[-1]), period)
    poses, d, dd = (curve or _hermite(trajectory))(ticks)
    ik = inverse_kinematics(robot, poses, d, dd, ticks, **ik_options)
    tau = inverse_dynamics(robot, ik, losses, energies=False).tau
    held = tau.copy()
    held[:-1] = 0.5 * (tau[:-1] + tau[1:])
    return DesiredTrajectory(t=ticks, q=ik.q, v=ik.v, a=ik.a, tau=held, tau_exact=tau)


class ComputedTorque:
    """τ = τ_ff(t) + M_red(q) (ω² e + 2ζω ė): the nominal closed-loop inverse dynamics along the
    reference plus a PD on the actuator errors e = θ_d − θ scaled by the nominal closed-loop
    inertia at the measured configuration (docs/model.md §18). ``losses``: the rotor inertia
    the controller knows (in M_red; the feedforward's losses are ``desired``'s)."""

    def __init__(self, robot: Robot, desired: DesiredTrajectory, gains: Gains = Gains(),
                 losses: JointLosses | None = None):
        self.robot, self.desired, self.gains = _known(robot, losses), desired, gains
        self._ia = robot.actuated_v

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        d, g, ia = self.desired, self.gains, self._ia
        k = d.index(t)
        e, ed = d.q[k, ia] - q[ia], d.v[k, ia] - v[ia]
        return d.tau[k] + reduced_mass_matrix(self.robot, q) @ (g.kp * e + g.kd * ed)


class PDGravity:
    """τ = g_red(q) + K_p e + K_d ė: the baseline. g_red is the nominal closed-loop gravity
    torque at the measured configuration; K_p = ω² M₀, K_d = 2ζω M₀ with M₀ the nominal
    closed-loop inertia at the reference's start (constant gains; rotor inertia of ``losses``
    included)."""

    def __init__(self, robot: Robot, desired: DesiredTrajectory, gains: Gains = Gains(),
                 losses: JointLosses | None = None):
        self.robot, self.desired, self.gains = robot, desired, gains
        self._ia = robot.actuated_v
        m0 = reduced_mass_matrix(_known(robot, losses), desired.q[0])
        self.kp, self.kd = gains.kp * m0, gains.kd * m0
        self._zero = np.zeros(robot.model.nv)

    def __call__(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        d, ia = self.desired, self._ia
        k = d.index(t)
        gravity = inverse_dynamics_sample(self.robot, q, self._zero, self._zero)[0]
        return gravity + self.kp @ (d.q[k, ia] - q[ia]) + self.kd @ (d.v[k, ia] - v[ia])


def _known(robot: Robot, losses: JointLosses | None) -> Robot:
    """``robot`` with the rotor inertia of ``losses`` in its ``model.armature`` (a copy)."""
    if losses is None or not np.any(losses.armature):
        return robot
    return perturbed_robot(robot, PlantErrors(losses=losses))


def make_controller(name: str, robot: Robot, desired: DesiredTrajectory,
                    gains: Gains = Gains(), losses: JointLosses | None = None) -> Controller:
    """A built-in controller by name: ``computed-torque`` or ``pd``; ``losses``: the joint
    losses it knows (build ``desired`` with the same)."""
    kinds = {"computed-torque": ComputedTorque, "pd": PDGravity}
    if name not in kinds:
        raise ControlError(f"unknown controller {name!r} (expected one of: "
                           f"{', '.join(CONTROLLERS)})")
    return kinds[name](robot, desired, gains, losses)


@dataclass
class TrackingResult:
    """A closed-loop simulation, one row per output sample (the input trajectory's times)."""

    t: np.ndarray
    q: np.ndarray  # (N, 12) plant joint positions [rad]
    v: np.ndarray  # (N, 12) [rad/s]
    a: np.ndarray  # (N, 12) plant accelerations under the applied torque [rad/s²]
    tau: np.ndarray  # (N, 6) applied (held, saturated) actuator torques [N·m]
    tip: np.ndarray  # (N, 3) tool-tip position [m]
    tip_desired: np.ndarray  # (N, 3) [m]
    tip_position_error: np.ndarray  # (N,) |p − p_d| [m]
    tip_orientation_error: np.ndarray  # (N,) |log(R R_dᵀ)| [rad]
    closure_residual: np.ndarray  # (N,) max |p_A − p_B| component [m]
    joint_names: tuple[str, ...]
    actuated: tuple[str, ...]
    saturation_time: float = 0.0  # s during which at least one actuator was saturated
    max_closure_residual: float = 0.0  # over every control tick [m]
    steps: int = 0  # RK4 steps
    wall: float = 0.0  # s spent integrating
    settings: dict = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.t)

    def columns(self) -> dict[str, np.ndarray]:
        cols = {"t": self.t}
        cols.update({n: self.q[:, i] for i, n in enumerate(self.joint_names)})
        cols.update({f"d_{n}": self.v[:, i] for i, n in enumerate(self.joint_names)})
        cols.update({f"dd_{n}": self.a[:, i] for i, n in enumerate(self.joint_names)})
        cols.update({f"tau_{n}": self.tau[:, i] for i, n in enumerate(self.actuated)})
        cols.update({c: self.tip[:, i] for i, c in enumerate("xyz")})
        cols.update({f"desired_{c}": self.tip_desired[:, i] for i, c in enumerate("xyz")})
        cols.update({"tip_position_error": self.tip_position_error,
                     "tip_orientation_error": self.tip_orientation_error,
                     "closure_residual": self.closure_residual})
        return cols

    def summary(self) -> dict:
        e, o = self.tip_position_error, self.tip_orientation_error
        peak = np.abs(self.tau).max(axis=0)
        return {"max_tip_position_error": float(e.max()),
                "rms_tip_position_error": float(np.sqrt(np.mean(e ** 2))),
                "max_tip_orientation_error": float(o.max()),
                "rms_tip_orientation_error": float(np.sqrt(np.mean(o ** 2))),
                "peak_torque": {n: float(p) for n, p in zip(self.actuated, peak)},
                "saturation_time": float(self.saturation_time),
                "max_closure_residual": float(self.max_closure_residual)}

    def summary_lines(self) -> list[str]:
        s = self.summary()
        lines = [f"tool-tip position error: max {s['max_tip_position_error']:.3g} m, "
                 f"RMS {s['rms_tip_position_error']:.3g} m",
                 f"tool orientation error: max {s['max_tip_orientation_error']:.3g} rad, "
                 f"RMS {s['rms_tip_orientation_error']:.3g} rad",
                 "peak |τ| [N·m]: " + ", ".join(f"{n} {p:.4g}"
                                                for n, p in s["peak_torque"].items()),
                 f"saturated {s['saturation_time']:.4g} s; max closure residual "
                 f"{s['max_closure_residual']:.3g} m",
                 f"{self.steps} RK4 steps in {self.wall:.2f} s wall"]
        return lines


def _start_state(plant: Plant, desired: DesiredTrajectory, trajectory, start):
    """(q0, v0): the reference's start, or ``start`` = q0 (at rest) checked against the path."""
    if start is None:
        return desired.q[0].copy(), desired.v[0].copy()
    q0 = np.asarray(start, dtype=float).reshape(-1)
    if q0.shape != (plant.robot.model.nq,) or not np.all(np.isfinite(q0)):
        raise ControlError(f"start configuration must be {plant.robot.model.nq} finite joint "
                           f"angles, got shape {q0.shape}")
    residual = plant.closure_residual(q0)
    if residual > 1e-9:
        raise ControlError(f"start configuration does not close the loops: residual "
                           f"{residual:.3g} m (> 1e-09 m)")
    M = tool_pose(plant.nominal, q0)
    p_err = float(np.linalg.norm(M.translation - trajectory.poses[0, :3]))
    o_err = float(np.linalg.norm(pin.log3(M.rotation @ rotation(trajectory.poses[0]).T)))
    rate = float(np.abs(trajectory.d_poses[0]).max())
    if rate > START_TOL >= max(p_err, o_err):
        # On the path but moving: say so, rather than "off the path" at 1e-16 m.
        raise ControlError(
            f"trajectory starts moving (pose rate {rate:.4g} > {START_TOL:g}) but a given start "
            "configuration is at rest: start the trajectory at rest or use --start path")
    if p_err > START_TOL or o_err > START_TOL or rate > START_TOL:
        raise ControlError(
            f"trajectory starts off the path: its first pose is {p_err:.4g} m and "
            f"{o_err:.4g} rad from the start configuration's tool pose, with rate "
            f"{rate:.4g} (the robot starts at rest; tolerance {START_TOL:g})")
    return q0, np.zeros(plant.robot.model.nv)


def _nearest(sorted_points: np.ndarray, x: np.ndarray) -> np.ndarray:
    j = np.clip(np.searchsorted(sorted_points, x), 1, len(sorted_points) - 1)
    return np.where(np.abs(sorted_points[j - 1] - x) <= np.abs(sorted_points[j] - x), j - 1, j)


def _grid(ticks: np.ndarray, samples: np.ndarray, dt: float):
    """Integration breakpoints: each control interval split in equal steps ≤ dt, output sample
    times inserted. Returns (points, tick flag, sample index or −1)."""
    pts = []
    for a, b in zip(ticks[:-1], ticks[1:]):
        n = max(1, int(math.ceil((b - a) / dt - 1e-9)))
        pts.append(a + (b - a) * np.arange(n) / n)
    pts.append(ticks[-1:])
    pts = np.concatenate(pts)
    is_tick = np.zeros(len(pts), bool)
    is_tick[np.searchsorted(pts, ticks)] = True
    # Snap each sample to a breakpoint within 1e-9·dt, else insert it.
    new = np.abs(pts[_nearest(pts, samples)] - samples) > 1e-9 * dt
    if new.any():
        pts = np.concatenate([pts, samples[new]])
        is_tick = np.concatenate([is_tick, np.zeros(int(new.sum()), bool)])
        order = np.argsort(pts, kind="stable")
        pts, is_tick = pts[order], is_tick[order]
    near = _nearest(pts, samples)
    sample = np.full(len(pts), -1)
    sample[near] = np.arange(len(samples))
    return pts, is_tick, sample


def simulate_tracking(robot: Robot, trajectory, controller: str | Controller = "computed-torque",
                      errors: PlantErrors | None = None, *, gains: Gains = Gains(),
                      dt: float = DT, control_period: float = CONTROL_PERIOD,
                      torque_limit=None, noise: MeasurementNoise | None = None, start=None,
                      baumgarte: tuple[float, float] = BAUMGARTE,
                      desired: DesiredTrajectory | None = None, curve=None,
                      known_losses: JointLosses | None = None,
                      progress: Callable[[int, int], None] | None = None) -> TrackingResult:
    """Simulate the closed loop along ``trajectory`` (``t``, ``poses``, ``d_poses``,
    ``dd_poses``, e.g. :class:`~pollard_pin.io.trajectory.Trajectory`).

    ``controller``: ``"computed-torque"``, ``"pd"`` or any :class:`Controller` callable.
    ``errors``: how the plant differs from ``robot`` (payload, mass error, losses). ``dt``: RK4
    step [s]; ``control_period`` [s]: the torque is computed at each tick and held;
    ``torque_limit`` [N·m]: a scalar or one per actuator, |τ| clipped to it; ``noise``:
    measurement noise on the actuated joints. ``start``: None (on the path, at the reference's
    state) or a closed configuration at rest whose tool pose is the trajectory's first pose.
    ``desired`` reuses a :func:`desired_trajectory` computed with the same period (and
    ``known_losses``). ``known_losses``: joint losses the built-in controllers know and
    compensate (e.g. the motors' reflected rotor inertia and friction); the plant's are in
    ``errors.losses``.
    """
    for name, value in (("time step --dt", dt), ("control period", control_period)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ControlError(f"{name} must be > 0 s, got {value}")
    limit = None
    if torque_limit is not None:
        limit = np.broadcast_to(np.asarray(torque_limit, dtype=float), (6,)).copy() \
            if np.size(torque_limit) in (1, 6) else None
        if limit is None:
            raise ControlError(f"torque limit: give one value or 6 (one per actuator), got "
                               f"{np.size(torque_limit)}")
        if not (np.all(np.isfinite(limit)) and np.all(limit > 0)):
            raise ControlError(f"torque limits must be > 0 N·m, got {limit.tolist()}")
    plant = Plant(robot, errors, baumgarte)
    if desired is None:
        desired = desired_trajectory(robot, trajectory, control_period, curve, known_losses)
    label = controller if isinstance(controller, str) else type(controller).__name__
    if isinstance(controller, str):
        controller = make_controller(controller, robot, desired, gains, known_losses)
    q, v = _start_state(plant, desired, trajectory, start)

    samples = np.asarray(trajectory.t, dtype=float)
    pts, is_tick, sample_of = _grid(desired.t, samples, dt)
    n = len(samples)
    nv = plant.robot.model.nv
    Q, V, A = np.empty((n, nv)), np.empty((n, nv)), np.empty((n, nv))
    TAU, RES = np.empty((n, 6)), np.empty(n)
    ia = plant.robot.actuated_v
    rng = np.random.default_rng(noise.seed) if noise is not None else None
    f = plant.acceleration
    tau = np.zeros(6)
    saturated_since, saturation, max_res = None, 0.0, 0.0
    clock = time.perf_counter()
    last = len(pts) - 1
    for i in range(len(pts)):
        t = pts[i]
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
            raise SimulationError(f"simulation diverged at t = {t:.6g} s: non-finite state; "
                                  "reduce --dt or raise the gains")
        if is_tick[i]:
            qm, vm = q, v
            if rng is not None:
                qm, vm = q.copy(), v.copy()
                qm[ia] += rng.normal(0.0, noise.position, 6) if noise.position else 0.0
                vm[ia] += rng.normal(0.0, noise.velocity, 6) if noise.velocity else 0.0
            command = np.asarray(controller(t, qm, vm), dtype=float).reshape(-1)
            if command.shape != (6,) or not np.all(np.isfinite(command)):
                raise ControlError(f"controller returned {command!r} at t = {t:.6g} s; "
                                   "expected 6 finite actuator torques")
            tau = command if limit is None else np.clip(command, -limit, limit)
            clipped = limit is not None and bool(np.any(np.abs(command) > limit))
            if saturated_since is not None and not clipped:
                saturation += t - saturated_since
                saturated_since = None
            elif clipped and saturated_since is None:
                saturated_since = t
            max_res = max(max_res, plant.closure_residual(q))
        a1 = f(q, v, tau)
        k = sample_of[i]
        if k >= 0:
            Q[k], V[k], A[k], TAU[k] = q, v, a1, tau
            RES[k] = plant.closure_residual(q)
            if progress is not None:
                progress(k + 1, n)
        if i == last:
            break
        h = pts[i + 1] - t
        v2 = v + 0.5 * h * a1
        a2 = f(q + 0.5 * h * v, v2, tau)
        v3 = v + 0.5 * h * a2
        a3 = f(q + 0.5 * h * v2, v3, tau)
        v4 = v + h * a3
        a4 = f(q + h * v3, v4, tau)
        q = q + h / 6.0 * (v + 2 * v2 + 2 * v3 + v4)
        v = v + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4)
    if saturated_since is not None:
        saturation += pts[-1] - saturated_since
    wall = time.perf_counter() - clock
    max_res = max(max_res, float(RES.max()))

    tip = np.empty((n, 3))
    o_err = np.empty(n)
    R_des = rotation(trajectory.poses)
    for k in range(n):
        M = tool_pose(plant.robot, Q[k])
        tip[k] = M.translation
        o_err[k] = np.linalg.norm(pin.log3(M.rotation @ R_des[k].T))
    tip_des = np.asarray(trajectory.poses, dtype=float)[:, :3]
    settings = {"controller": label,
                "wn": gains.wn, "zeta": gains.zeta, "dt": dt, "control_period": control_period,
                "payload": plant.errors.payload, "mass_error": plant.errors.mass_error,
                "torque_limit": None if limit is None else limit.tolist(),
                "noise": None if noise is None else [noise.position, noise.velocity,
                                                     noise.seed]}
    return TrackingResult(
        t=samples.copy(), q=Q, v=V, a=A, tau=TAU, tip=tip, tip_desired=tip_des,
        tip_position_error=np.linalg.norm(tip - tip_des, axis=1), tip_orientation_error=o_err,
        closure_residual=RES, joint_names=plant.robot.joint_names, actuated=robot.actuated,
        saturation_time=saturation, max_closure_residual=max_res, steps=last, wall=wall,
        settings=settings)
