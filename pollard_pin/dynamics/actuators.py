"""Motors and gearboxes on the six actuators: ratings, the motor model, and the fastest cycle
along a given path (docs/model.md §19).

Motor model, per actuator with gear ratio N (motor angle = N × joint angle)::

    τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇)        ωm = N·q̇

with τ, q̇, q̈ the joint's torque, velocity and acceleration. Limits: max |τm| ≤ peak,
RMS(τm) ≤ continuous (trapezoid rule), max |ωm| ≤ max speed.

Along a path s ∈ [0, 1] the closed-loop joint torques are exactly τ = a(s)·s̈ + b(s)·ṡ² + c(s)
(:func:`path_dynamics`); :func:`uniform_min_duration` scales time uniformly, and
:func:`time_optimal` solves the time-optimal parameterisation with TOPP-RA (``toppra``).
"""
from __future__ import annotations

import contextlib
import logging
import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from ..model.names import ACTUATED as ACTUATED_JOINTS, TREE_JOINTS as JOINT_NAMES
from ..model.params import did_you_mean, read_toml
from .averages import time_rms as rms, trapezoid_weights
from .inverse import JointLosses, inverse_dynamics

KEYS = ("gear_ratio", "rotor_inertia", "viscous", "coulomb", "peak_torque",
        "continuous_torque", "max_speed")
_POSITIVE = ("gear_ratio", "peak_torque", "continuous_torque", "max_speed")
# Every value (SI, motor side) in [0 or MIN_POSITIVE, MAX_VALUE]: outside, it is a unit slip,
# and the motor model's squares and roots overflow float64 (1e300 gave a traceback).
MIN_POSITIVE, MAX_VALUE = 1e-6, 1e6
UNITS = dict(zip(KEYS, ("", " kg·m²", " N·m·s/rad", " N·m", " N·m", " N·m", " rad/s")))
LIMITS = ("peak_torque", "rms_torque", "speed")  # the three checks, in report order


class ActuatorError(ValueError):
    """An actuator file breaks a rule, or no duration meets the ratings (one line)."""


@dataclass(frozen=True)
class Actuator:
    """One motor and gearbox, motor-side SI units (issue 15 file format)."""

    gear_ratio: float  # N: motor angle = N × joint angle
    rotor_inertia: float  # Jm [kg·m²]
    viscous: float  # b [N·m·s/rad]
    coulomb: float  # c [N·m]
    peak_torque: float  # [N·m]
    continuous_torque: float  # RMS limit [N·m]
    max_speed: float  # [rad/s]


@dataclass(frozen=True)
class Actuators:
    """The six actuators, in docs/model.md §6 order (``names``)."""

    names: tuple[str, ...]
    units: tuple[Actuator, ...]
    source: str = "<python>"

    def __getitem__(self, name: str) -> Actuator:
        return self.units[self.names.index(name)]

    def column(self, key: str) -> np.ndarray:
        """One rating or constant of every actuator, shape (6,)."""
        return np.array([getattr(u, key) for u in self.units], dtype=float)

    def joint_losses(self, joint_names=JOINT_NAMES) -> JointLosses:
        """The motors seen from the joints, for forward dynamics/simulation: armature N²·Jm,
        viscous N²·b, Coulomb N·c on each actuated tree joint, zero elsewhere
        (docs/model.md §19; JointLosses smooths Coulomb with tanh)."""
        arm, visc, coul = (np.zeros(len(joint_names)) for _ in range(3))
        for name, u in zip(self.names, self.units):
            j = list(joint_names).index(name)
            n = u.gear_ratio
            arm[j], visc[j], coul[j] = n * n * u.rotor_inertia, n * n * u.viscous, n * u.coulomb
        return JointLosses(viscous=visc, coulomb=coul, armature=arm)


# --- the actuator file -----------------------------------------------------------------------
def _fail(where: str, key: str, value: Any, rule: str):
    raise ActuatorError(f"{where}: '{key}' = {value!r}: {rule}")


def actuators_from_dict(d: Mapping, source: str = "<python>",
                        names: tuple[str, ...] = ACTUATED_JOINTS) -> Actuators:
    """Validate a parsed actuator file: one table per actuator, every key of :data:`KEYS`."""
    if not isinstance(d, Mapping):
        raise ActuatorError(f"{source}: expected one table per actuator")
    for name in d:
        if name not in names:
            raise ActuatorError(f"{source}: [{name}] is not an actuator"
                                f"{did_you_mean(name, names)}; expected "
                                f"one table for each of {', '.join(names)}")
    missing = [n for n in names if n not in d]
    if missing:
        raise ActuatorError(f"{source}: missing table(s) [{'], ['.join(missing)}] (every "
                            f"actuator needs one: {', '.join(names)})")
    units = []
    for name in names:
        table = d[name]
        if not isinstance(table, Mapping):
            _fail(source, name, table, "must be a table [" + name + "]")
        absent = [k for k in KEYS if k not in table]
        unknown = [k for k in table if k not in KEYS]
        if absent:
            raise ActuatorError(f"{source}: '{name}.{absent[0]}' is missing (every actuator "
                                f"needs {', '.join(KEYS)})")
        if unknown:
            _fail(source, f"{name}.{unknown[0]}", table[unknown[0]],
                  f"unknown key{did_you_mean(unknown[0], KEYS)}; expected {', '.join(KEYS)}")
        values = {}
        for k in KEYS:
            v, key = table[k], f"{name}.{k}"
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                _fail(source, key, v, "must be a number")
            if not math.isfinite(v):
                _fail(source, key, v, "must be finite")
            if k in _POSITIVE and v <= 0:
                _fail(source, key, v, "must be > 0")
            if v < 0:
                _fail(source, key, v, "must be >= 0")
            if (k in _POSITIVE and v < MIN_POSITIVE) or v > MAX_VALUE:
                low = f"between {MIN_POSITIVE:g} and" if k in _POSITIVE else "at most"
                _fail(source, key, v, f"must be {low} {MAX_VALUE:g}{UNITS[k]} (motor side)")
            values[k] = float(v)
        if values["continuous_torque"] > values["peak_torque"]:
            _fail(source, f"{name}.continuous_torque", table["continuous_torque"],
                  f"exceeds {name}.peak_torque = {table['peak_torque']!r}")
        units.append(Actuator(**values))
    return Actuators(tuple(names), tuple(units), source)


def load_actuators(path: str | Path, names: tuple[str, ...] = ACTUATED_JOINTS) -> Actuators:
    """Read and validate an actuator TOML file (format: ``examples/actuators.toml``)."""
    d = read_toml(path, "actuator file", ActuatorError)
    return actuators_from_dict(d, str(path), names)


# --- the motor model -------------------------------------------------------------------------
def motor_torque(act: Actuators, tau, v, a) -> np.ndarray:
    """τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇), (..., 6) actuated-joint arrays in."""
    n, jm, b, c = (act.column(k) for k in ("gear_ratio", "rotor_inertia", "viscous", "coulomb"))
    return (np.asarray(tau) / n + jm * n * np.asarray(a) + b * n * np.asarray(v)
            + c * np.sign(v))


def motor_speed(act: Actuators, v) -> np.ndarray:
    """ωm = N·q̇ [rad/s]."""
    return act.column("gear_ratio") * np.asarray(v)


@dataclass(frozen=True)
class MotorLoad:
    """Motor-side torque and speed along a trajectory, (N, 6), and the three checks."""

    t: np.ndarray
    torque: np.ndarray  # τm [N·m]
    speed: np.ndarray  # ωm [rad/s]
    actuators: Actuators

    @property
    def peak_torque(self) -> np.ndarray:
        return np.abs(self.torque).max(axis=0)

    @property
    def rms_torque(self) -> np.ndarray:
        return rms(self.t, self.torque)

    @property
    def peak_speed(self) -> np.ndarray:
        return np.abs(self.speed).max(axis=0)

    def ratios(self) -> dict[str, np.ndarray]:
        """Each check over its rating (≤ 1 passes): ``peak_torque``, ``rms_torque``,
        ``speed``."""
        a = self.actuators
        return {"peak_torque": self.peak_torque / a.column("peak_torque"),
                "rms_torque": self.rms_torque / a.column("continuous_torque"),
                "speed": self.peak_speed / a.column("max_speed")}

    def utilisation(self) -> np.ndarray:
        """Per sample and actuator, the larger of |τm|/peak and |ωm|/max speed, (N, 6)."""
        a = self.actuators
        return np.maximum(np.abs(self.torque) / a.column("peak_torque"),
                          np.abs(self.speed) / a.column("max_speed"))


def motor_load(act: Actuators, t, tau, v, a) -> MotorLoad:
    """The motor model along a trajectory: actuated-joint τ, q̇, q̈ arrays (N, 6)."""
    return MotorLoad(np.asarray(t, dtype=float), motor_torque(act, tau, v, a),
                     motor_speed(act, v), act)


def motor_load_of(robot, act: Actuators, ik, dynamics) -> MotorLoad:
    """:func:`motor_load` of a pipeline result (IK and inverse dynamics)."""
    ia = robot.actuated_v
    return motor_load(act, ik.t, dynamics.tau, ik.v[:, ia], ik.a[:, ia])


# --- the path and its dynamics ---------------------------------------------------------------
@dataclass(frozen=True)
class PathDynamics:
    """Closed-loop actuator torques along a path s ∈ [0, 1] (docs/model.md §19):
    τ = a(s)·s̈ + b(s)·ṡ² + c(s), and q̇ = q_s·ṡ, q̈ = q_s·s̈ + q_ss·ṡ² for the actuated
    joints. Arrays (n, 6) at the grid ``s`` (n,)."""

    s: np.ndarray
    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    q_s: np.ndarray
    q_ss: np.ndarray
    duration: float  # of the trajectory the path came from, s = (t − t0) / duration


def path_dynamics(robot, ik) -> PathDynamics:
    """The path of an IK result, parameterised by s = (t − t0)/T ∈ [0, 1], with its exact
    torque coefficients.

    The IK is exact in the task rates, so q_s = T·q̇ and q_ss = T²·q̈ at every sample for any
    trajectory. RNEA plus the closure split is linear in the tree torque at fixed q, so
    c = τ(q, 0, 0) (gravity), a = τ(q, 0, q_s) − c and b = τ(q, q_s, q_ss) − c.
    """
    t = np.asarray(ik.t, dtype=float)
    duration = float(t[-1] - t[0])
    v_s, a_s = duration * ik.v, duration * duration * ik.a
    zero = np.zeros_like(v_s)

    def tau(v, a):
        return inverse_dynamics(robot, replace(ik, v=v, a=a), energies=False).tau

    c = tau(zero, zero)
    ia = robot.actuated_v
    return PathDynamics(s=(t - t[0]) / duration, a=tau(zero, v_s) - c, b=tau(v_s, a_s) - c,
                        c=c, q_s=v_s[:, ia], q_ss=a_s[:, ia], duration=duration)


def _motor_coefficients(act: Actuators, path: PathDynamics, at_rest=None):
    """Motor torque along the path: τm = α·s̈ + β·ṡ² + γ + δ·ṡ (ṡ ≥ 0), each (n, 6); no
    Coulomb term at the samples ``at_rest`` (ṡ = 0 there, sign(q̇) = 0)."""
    n, jm, b, c = (act.column(k) for k in ("gear_ratio", "rotor_inertia", "viscous", "coulomb"))
    alpha = path.a / n + jm * n * path.q_s
    beta = path.b / n + jm * n * path.q_ss
    moving = np.ones(len(path.s)) if at_rest is None else ~np.asarray(at_rest)
    gamma = path.c / n + c * np.sign(path.q_s) * moving[:, None]
    delta = b * n * path.q_s
    return alpha, beta, gamma, delta


# --- uniform time scaling --------------------------------------------------------------------
@dataclass(frozen=True)
class UniformScaling:
    """The shortest uniformly time-scaled duration meeting every limit at it and beyond."""

    duration: float  # [s]
    actuator: str  # the one whose limit binds
    limit: str  # peak_torque, rms_torque or speed
    by_limit: dict  # the same for each limit alone: {peak_torque: D, rms_torque: D, speed: D}


def _smallest_positive_root(p2, p1, p0) -> np.ndarray:
    """Smallest root x > 0 of p2·x² + p1·x + p0 (elementwise), +inf where none."""
    p2, p1, p0 = np.broadcast_arrays(*(np.asarray(p, dtype=float) for p in (p2, p1, p0)))
    disc = p1 * p1 - 4 * p2 * p0
    sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
    with np.errstate(divide="ignore", invalid="ignore"):
        q = -0.5 * (p1 + np.where(p1 >= 0, sq, -sq))  # stable pair: q/p2 and p0/q
        r1 = np.where(p2 != 0, q / p2, np.nan)
        r2 = np.where(q != 0, p0 / q, np.nan)
        lin = np.where((p2 == 0) & (p1 != 0), -p0 / p1, np.nan)
    roots = np.stack([r1, r2, lin])
    roots = np.where(roots > 0, roots, np.inf)
    return np.nan_to_num(roots, nan=np.inf).min(axis=0)


def uniform_min_duration(act: Actuators, path: PathDynamics) -> UniformScaling:
    """Smallest D such that the path traversed uniformly in time D (ṡ = 1/D, s̈ = 0) meets
    peak, RMS and speed limits at D and at every longer duration (docs/model.md §19).

    With x = 1/D, τm = β·x² + δ·x + γ and ωm = N·q_s·x at every sample: the peak limit fails
    first at the smallest positive root of β x² + δ x + γ = ±peak, the speed limit at
    max_speed / max|N q_s|, and the RMS limit at the smallest positive root of the quartic
    Σ w_k (β x² + δ x + γ)² = continuous² (trapezoid weights w in s). Raises
    :class:`ActuatorError` if gravity and Coulomb friction alone break a limit.
    """
    _, beta, gamma, delta = _motor_coefficients(act, path)
    peak, cont, wmax = (act.column(k) for k in ("peak_torque", "continuous_torque", "max_speed"))
    w = trapezoid_weights(path.s)
    static_peak, static_rms = np.abs(gamma).max(0), np.sqrt(w @ gamma**2)
    for j, name in enumerate(act.names):
        for label, value, rating in (("peak", static_peak[j], peak[j]),
                                     ("RMS", static_rms[j], cont[j])):
            if value >= rating:
                raise ActuatorError(
                    f"{name}: the static {label} motor torque (gravity and Coulomb friction) "
                    f"{value:.4g} N·m already reaches the rating {rating:.4g} N·m; no duration "
                    "meets it")
    x_peak = np.minimum(_smallest_positive_root(beta, delta, gamma - peak),
                        _smallest_positive_root(beta, delta, gamma + peak)).min(axis=0)
    speed_s = np.abs(motor_speed(act, path.q_s)).max(axis=0)
    with np.errstate(divide="ignore"):
        x_speed = np.where(speed_s > 0, wmax / speed_s, np.inf)
    x_rms = np.empty(len(act.names))
    for j in range(len(act.names)):  # Σ w (βx² + δx + γ)² − cont², highest power first
        b_, d_, g_ = beta[:, j], delta[:, j], gamma[:, j]
        quartic = [w @ (b_ * b_), 2 * w @ (b_ * d_), w @ (d_ * d_ + 2 * b_ * g_),
                   2 * w @ (d_ * g_), w @ (g_ * g_) - cont[j] ** 2]
        roots = np.roots(quartic) if any(quartic[:-1]) else np.array([])
        real = roots.real[(np.abs(roots.imag) <= 1e-9 * np.abs(roots)) & (roots.real > 0)]
        x_rms[j] = real.min() if len(real) else np.inf
    table = np.stack([x_peak, x_rms, x_speed])  # (3 limits, 6)
    with np.errstate(divide="ignore"):
        by_limit = {lim: float(1.0 / x) for lim, x in zip(LIMITS, table.min(axis=1))}
    k, j = np.unravel_index(np.argmin(table), table.shape)
    if not np.isfinite(table[k, j]):  # the path does not move the actuators at all
        return UniformScaling(0.0, "", "", by_limit)
    return UniformScaling(by_limit[LIMITS[k]], act.names[j], LIMITS[k], by_limit)


# --- time-optimal parameterisation (TOPP-RA) ---------------------------------------------------
@dataclass(frozen=True)
class TimeOptimal:
    """The time-optimal traversal of a path: at the grid ``s`` (n,), times ``t``, path rate
    ``s_dot`` and path acceleration ``s_ddot``: constant between samples, so at a sample it
    jumps; ``s_ddot`` holds the one-sided value (before or after) that loads the motors more."""

    s: np.ndarray
    t: np.ndarray
    s_dot: np.ndarray
    s_ddot: np.ndarray
    iterations: int  # TOPP-RA solves (viscous friction is re-linearised between them)

    @property
    def duration(self) -> float:
        return float(self.t[-1] - self.t[0])

    def joint_motion(self, path: PathDynamics):
        """Actuated-joint (τ, q̇, q̈) at the grid samples, each (n, 6)."""
        sd, sdd = self.s_dot[:, None], self.s_ddot[:, None]
        return (path.a * sdd + path.b * sd**2 + path.c, path.q_s * sd,
                path.q_s * sdd + path.q_ss * sd**2)


def _toppra():
    try:
        import toppra
        import toppra.algorithm
        import toppra.constraint
    except ImportError as exc:
        raise ImportError(f"the time-optimal cycle needs TOPP-RA ({exc}): pip install "
                          "'toppra>=0.6.10,<0.7' (a core dependency of pollard-pin)") from None
    return toppra


def _toppra_constraints(act: Actuators, path: PathDynamics, s_dot_viscous: np.ndarray,
                        at_rest: np.ndarray):
    toppra = _toppra()
    DiscretizationType = toppra.constraint.DiscretizationType
    LinearConstraint = toppra.constraint.LinearConstraint
    canlinear_colloc_to_interpolate = toppra.constraint.canlinear_colloc_to_interpolate

    alpha, beta, gamma, delta = _motor_coefficients(act, path, at_rest)
    # viscous δ·ṡ = δ·√x, linearised in x = ṡ² about the last ṡ_v(s) (its tangent, exact at
    # x = ṡ_v²): δ·(x + ṡ_v²)/(2 ṡ_v); δ·ṡ_v = 0 where ṡ_v = 0
    sv = s_dot_viscous[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        beta = beta + np.where(sv > 0, delta / (2 * sv), 0.0)
    gamma = gamma + delta * sv / 2
    peak = act.column("peak_torque")
    m, n = len(peak), len(path.s)
    F = np.broadcast_to(np.vstack([np.eye(m), -np.eye(m)]), (n, 2 * m, m))
    g = np.broadcast_to(np.concatenate([peak, peak]), (n, 2 * m))
    speed_s = np.abs(motor_speed(act, path.q_s)) / act.column("max_speed")
    with np.errstate(divide="ignore"):
        x_max = np.where(speed_s.max(1) > 0, 1.0 / speed_s.max(1) ** 2, 1e12)
    xbound = np.column_stack([np.zeros(n), np.minimum(x_max, 1e12)])

    class MotorTorque(LinearConstraint):
        def __init__(self):
            super().__init__()
            self.set_discretization_type(DiscretizationType.Interpolation)

        def compute_constraint_params(self, _path, gridpoints, *args, **kwargs):
            return canlinear_colloc_to_interpolate(alpha, beta, gamma, F, g, None, None,
                                                   gridpoints)[:5] + (None, None)

    class MotorSpeed(LinearConstraint):
        def compute_constraint_params(self, _path, gridpoints, *args, **kwargs):
            return None, None, None, None, None, None, xbound  # (…, ubound, xbound)

    return [MotorTorque(), MotorSpeed()]


@contextlib.contextmanager
def _quiet(logger_name: str):
    logger = logging.getLogger(logger_name)
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


def time_optimal(act: Actuators, path: PathDynamics, s_dot_start: float = 0.0,
                 s_dot_end: float = 0.0, max_iterations: int = 50,
                 tol: float = 1e-9) -> TimeOptimal:
    """Shortest traversal of the path under the peak-torque and speed limits (TOPP-RA,
    interpolation discretisation on the path's own samples; rest to rest by default).

    TOPP-RA needs constraints of the form α s̈ + β ṡ² + γ; the viscous term b·N·q_s·ṡ is
    linear in ṡ = √(ṡ²), so it enters linearised in ṡ² about the previous solution's ṡ(s)
    (docs/model.md §19), repeated until ṡ(s) changes by less than ``tol`` (relative): the
    limits then hold at the final profile. Not converging is an :class:`ActuatorError`.
    """
    toppra = _toppra()
    s = np.asarray(path.s, dtype=float)
    if len(s) < 3 and s_dot_start == 0 and s_dot_end == 0:  # one interval: ṡ = 0 all along
        raise ActuatorError(f"the time-optimal traversal, rest to rest, needs at least 3 "
                            f"samples of the path, got {len(s)}")
    dummy = toppra.SplineInterpolator([0.0, 1.0], [[0.0], [1.0]])  # the grid is all it uses
    at_rest = np.zeros(len(s), dtype=bool)
    at_rest[[0, -1]] = s_dot_start == 0, s_dot_end == 0
    has_viscous = bool(np.any(act.column("viscous") > 0))
    # Viscous friction enters at ṡ_v(s): the last solution, or, where that is so fast that
    # its viscous torque leaves no traversal, a step back towards the last ṡ_v that solved
    # (halved until one solves); converged when the solution equals the ṡ_v it was given.
    s_dot_v = solved_at = np.zeros(len(s))
    step, it, change = 1.0, 0, np.inf
    while it < max_iterations and step >= 1.0 / 64:
        it += 1
        constraints = _toppra_constraints(act, path, s_dot_v, at_rest)
        solver = toppra.algorithm.TOPPRA(constraints, dummy, gridpoints=s,
                                         solver_wrapper="seidel")
        with _quiet("toppra"):  # its failure warnings; the error below says it in one line
            s_ddot_new, sd, _ = solver.compute_parameterization(s_dot_start, s_dot_end)
        if sd is None or np.any(~np.isfinite(sd)):
            if it == 1:  # no viscous term yet: the path itself is uncontrollable
                raise ActuatorError(
                    "no traversal of the path meets the peak-torque and speed ratings "
                    "(TOPP-RA found the path uncontrollable: gravity alone may exceed a peak "
                    "torque)")
            step /= 2
            s_dot_v = solved_at + step * (s_dot - solved_at)  # noqa: F821 (set by iteration 1)
            continue
        s_ddot, s_dot, solved_at = s_ddot_new, np.maximum(sd, 0.0), s_dot_v
        change = np.abs(s_dot - s_dot_v).max() / max(s_dot.max(), 1e-300)
        if not has_viscous or change <= tol:
            break
        s_dot_v = solved_at + step * (s_dot - solved_at)
    if has_viscous and change > tol:
        raise ActuatorError(
            f"the time-optimal traversal with viscous friction did not converge in {it} "
            f"TOPP-RA solves (ṡ(s) still changes by {change:.2g}, relative): the viscous "
            "torque b·ωm at the motors' speeds is too close to their peak torque")
    ds = np.diff(s)
    with np.errstate(divide="ignore"):
        dt = 2.0 * ds / (s_dot[:-1] + s_dot[1:])
    if not np.all(np.isfinite(dt)):
        k = int(np.argmax(~np.isfinite(dt)))
        raise ActuatorError(f"the time-optimal traversal stops between samples {k} and "
                            f"{k + 1} of the path (ṡ = 0 at both): no finite duration")
    t = np.concatenate([[0.0], np.cumsum(dt)])
    # s̈ jumps at the samples; both one-sided values are exact and within the limits. Keep
    # the one that loads the motors more (the worse side), so that a replay checks it.
    left = np.concatenate([s_ddot[:1], s_ddot])
    right = np.concatenate([s_ddot, s_ddot[-1:]])
    alpha, beta, gamma, delta = _motor_coefficients(act, path, at_rest)
    sd = s_dot[:, None]
    base = beta * sd**2 + gamma + delta * sd
    peak = act.column("peak_torque")
    worse = (np.abs(alpha * left[:, None] + base) / peak).max(1) > \
        (np.abs(alpha * right[:, None] + base) / peak).max(1)
    return TimeOptimal(s=s, t=t, s_dot=s_dot, s_ddot=np.where(worse, left, right),
                       iterations=it)


__all__ = ["Actuator", "Actuators", "ActuatorError", "KEYS", "LIMITS", "MotorLoad",
           "PathDynamics", "TimeOptimal", "UniformScaling", "actuators_from_dict",
           "load_actuators", "motor_load", "motor_load_of", "motor_speed", "motor_torque",
           "path_dynamics", "rms", "time_optimal", "trapezoid_weights", "uniform_min_duration"]
