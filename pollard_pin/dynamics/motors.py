"""Motors and gearboxes on the six actuators: ratings, the motor model, and the shortest
uniformly time-scaled cycle of a path (docs/model.md §19).

Motor model, per actuator with gear ratio N (motor angle = N × joint angle)::

    τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇)        ωm = N·q̇

with τ, q̇, q̈ the joint's torque, velocity and acceleration. Limits: max |τm| ≤ peak,
RMS(τm) ≤ continuous (trapezoid rule), max |ωm| ≤ max speed.

At rest (q̇ = 0) the Coulomb term is the breakaway friction ±c, whichever loads the motor more.
Along a path s ∈ [0, 1] the closed-loop joint torques are exactly τ = a(s)·s̈ + b(s)·ṡ² + c(s)
(:mod:`.path`); :func:`uniform_min_duration` scales time uniformly (the time-optimal cycle:
:mod:`.timeopt`).
"""
from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..checks import file_path, instance
from ..errors import InputError
from ..model.params import did_you_mean
from ..model.values import fail, number, read_toml
from ..names import ACTUATED as ACTUATED_JOINTS
from ..names import TREE_JOINTS as JOINT_NAMES
from .averages import mean_weights
from .averages import time_rms as rms
from .inverse import JointLosses
from .path import PathDynamics

KEYS = ("gear_ratio", "rotor_inertia", "viscous", "coulomb", "peak_torque",
        "continuous_torque", "max_speed")
_POSITIVE = ("gear_ratio", "peak_torque", "continuous_torque", "max_speed")
# Every value (SI, motor side) in [0 or MIN_POSITIVE, MAX_VALUE]: outside, it is a unit slip,
# and the motor model's squares and roots overflow float64 (1e300 gave a traceback).
MIN_POSITIVE, MAX_VALUE = 1e-6, 1e6
UNITS = dict(zip(KEYS, ("", " kg·m²", " N·m·s/rad", " N·m", " N·m", " N·m", " rad/s")))
LIMITS = ("peak_torque", "rms_torque", "speed")  # the three checks, in report order
# s: the time a motor takes to bring its own rotor to full speed at peak torque,
# Jm·max_speed/peak_torque, is tens of ms for a servo motor (the examples' 0.05-0.08 s) and
# under a second for any motor that drives a machine; beyond this one Jm is a unit slip
# (g·cm² or kg·cm² written as kg·m²), docs/model.md §19
MAX_RUN_UP = 10.0
# Optional: the drive's torsional stiffness k [N·m/rad], joint side (docs/model.md §19); only
# the compliance and the flexible-joint simulation need it.
OPTIONAL = ("stiffness",)
MAX_STIFFNESS = 1e9  # N·m/rad: above it the drive is rigid for any use here, or a unit slip
# N·m/rad: below it the weight alone would turn a drive by ~10² rad (a unit slip); the
# examples' are 300 and 3000
MIN_STIFFNESS = 1e-3


class ActuatorError(InputError):
    """An actuator file breaks a rule, or no duration meets the ratings (one line)."""


@dataclass(frozen=True)
class Actuator:
    """One motor and gearbox, motor-side SI units (the actuator file of docs/model.md §19)."""

    gear_ratio: float  # N: motor angle = N × joint angle
    rotor_inertia: float  # Jm [kg·m²]
    viscous: float  # b [N·m·s/rad]
    coulomb: float  # c [N·m]
    peak_torque: float  # [N·m]
    continuous_torque: float  # RMS limit [N·m]
    max_speed: float  # [rad/s]
    stiffness: float | None = None  # k [N·m/rad], joint side; None: not given


@dataclass(frozen=True)
class Actuators:
    """The motors and gearboxes of the six actuators, in docs/model.md §6 order (``names``);
    from :func:`~pollard_pin.load_actuators`.

    Attributes
    ----------
    names : tuple of str
        The actuated joints.
    units : tuple of pollard_pin.dynamics.motors.Actuator
        Each one's gear ratio N, rotor inertia Jm [kg·m²], viscous b [N·m·s/rad] and Coulomb
        c [N·m] friction, peak and continuous torque [N·m] and maximum speed [rad/s], all
        motor side, and its optional stiffness [N·m/rad] (joint side).
    source : str
        The file they were read from.

    ``act[name]`` is one actuator, ``act.column(key)`` one rating of all six (6,),
    ``act.joint_losses()`` the motors seen from the joints (docs/model.md §19).
    """

    names: tuple[str, ...]
    units: tuple[Actuator, ...]
    source: str = "<python>"

    def __getitem__(self, name: str) -> Actuator:
        return self.units[self.names.index(name)]

    def column(self, key: str) -> np.ndarray:
        """One rating or constant of every actuator, shape (6,)."""
        return np.array([getattr(u, key) for u in self.units], dtype=float)

    def stiffness(self) -> np.ndarray:
        """The drives' torsional stiffnesses k [N·m/rad], shape (6,); an
        :class:`ActuatorError` naming the first actuator without one."""
        for name, u in zip(self.names, self.units):
            if u.stiffness is None:
                raise ActuatorError(f"{self.source}: '{name}.stiffness' is missing (the drives' "
                                    "torsional stiffness [N·m/rad] is needed here)")
        return self.column("stiffness")

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
    fail(ActuatorError, f"{where}: ", key, value, rule)


def check_run_up(values: Mapping, speed: str, key: str, value: Any, prefix: str,
                 error: type[Exception] = ActuatorError) -> None:
    """Refuse a rotor inertia whose motor would take longer than :data:`MAX_RUN_UP` to bring
    its own rotor to full speed at peak torque (docs/model.md §19): ``values`` the checked
    ``rotor_inertia``, ``peak_torque`` and maximum speed (under the key ``speed``), ``key``
    and ``value`` the rotor inertia's as written."""
    run_up = values["rotor_inertia"] * values[speed] / values["peak_torque"]
    if run_up > MAX_RUN_UP:
        fail(error, prefix, key, value,
             f"the motor would take {run_up:.3g} s to bring its own rotor to {speed} at "
             f"peak_torque (Jm·ω/τ), {run_up / MAX_RUN_UP:.3g} times the {MAX_RUN_UP:g} s of "
             "any motor: Jm in kg·m² (1 g·cm² = 1e-7 kg·m²)?")


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
        unknown = [k for k in table if k not in KEYS + OPTIONAL]
        if absent:
            raise ActuatorError(f"{source}: '{name}.{absent[0]}' is missing (every actuator "
                                f"needs {', '.join(KEYS)})")
        if unknown:
            _fail(source, f"{name}.{unknown[0]}", table[unknown[0]],
                  f"unknown key{did_you_mean(unknown[0], KEYS + OPTIONAL)}; expected "
                  f"{', '.join(KEYS)} (and optionally {', '.join(OPTIONAL)})")
        values = {}
        for k in KEYS:
            low = f"between {MIN_POSITIVE:g} and" if k in _POSITIVE else "at most"
            v = number(table[k], f"{name}.{k}", ActuatorError, f"{source}: ",
                       positive=k in _POSITIVE, nonnegative=True, limit=MAX_VALUE,
                       limit_rule=f"must be {low} {MAX_VALUE:g}{UNITS[k]} (motor side)")
            if k in _POSITIVE and v < MIN_POSITIVE:
                _fail(source, f"{name}.{k}", table[k], f"must be {low} {MAX_VALUE:g}{UNITS[k]} "
                                                       "(motor side)")
            values[k] = v
        if values["continuous_torque"] > values["peak_torque"]:
            _fail(source, f"{name}.continuous_torque", table["continuous_torque"],
                  f"exceeds {name}.peak_torque = {values['peak_torque']:.4g}")
        check_run_up(values, "max_speed", f"{name}.rotor_inertia", table["rotor_inertia"],
                     f"{source}: ")
        if "stiffness" in table:
            rule = (f"must be between {MIN_STIFFNESS:g} and {MAX_STIFFNESS:g} N·m/rad (joint "
                    "side)")
            values["stiffness"] = number(
                table["stiffness"], f"{name}.stiffness", ActuatorError, f"{source}: ",
                positive=True, limit=MAX_STIFFNESS, limit_rule=rule)
            if values["stiffness"] < MIN_STIFFNESS:
                _fail(source, f"{name}.stiffness", table["stiffness"], rule)
        units.append(Actuator(**values))
    return Actuators(tuple(names), tuple(units), source)


def load_actuators(path: str | Path | None = None,
                   names: tuple[str, ...] = ACTUATED_JOINTS) -> Actuators:
    """Read and validate an actuator TOML file (format: ``examples/actuators.toml``).

    Parameters
    ----------
    path : str or pathlib.Path or None, optional
        None: the package's own ratings (``examples/actuators.toml``, shipped as
        ``models/actuators.toml``). Else one table per actuator joint, every key required:
        ``gear_ratio``,
        ``rotor_inertia`` [kg·m²], ``viscous`` [N·m·s/rad], ``coulomb`` [N·m],
        ``peak_torque`` and ``continuous_torque`` [N·m], ``max_speed`` [rad/s] (motor side);
        optional ``stiffness`` [N·m/rad] (joint side).
    names : tuple of str, optional
        The actuators the file must hold (default the six of docs/model.md §6).

    Returns
    -------
    Actuators
        The validated motors.

    Raises
    ------
    ActuatorError
        A missing file, table or key, an unknown key, a value that is not finite or breaks its
        rule (the message names the file, the key and the rule).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> act = pp.load_actuators()  # the package's ratings
    >>> act["theta21"].gear_ratio, act.column("peak_torque").tolist()[:2]
    (100.0, [0.05, 0.05])
    """
    if path is None:
        from ..model.paths import models_dir

        path = models_dir() / "actuators.toml"
    file_path(path, "path", error=ActuatorError)  # checked; the messages show it as given
    if (not isinstance(names, (tuple, list)) or not names
            or not all(isinstance(n, str) for n in names)):
        raise ActuatorError(f"names = {names!r:.60}: expected a tuple of actuator names (str)")
    d = read_toml(path, "actuator file", ActuatorError)
    return actuators_from_dict(d, str(path), names)


def as_actuators(value, name: str = "actuators") -> Actuators | None:
    """The motor ratings an entry point was given: None as is (the default ratings), an
    :class:`Actuators`, or a file path (str or Path) read by :func:`load_actuators`; anything
    else one :class:`~pollard_pin.errors.InputError` line naming the argument ``name``."""
    if isinstance(value, (str, os.PathLike)):
        return load_actuators(value)
    return instance(value, name, Actuators, "Actuators, an actuator file's path or None",
                    none=True)


# --- the motor model -------------------------------------------------------------------------
def motor_torque(act: Actuators, tau, v, a) -> np.ndarray:
    """τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇), (..., 6) actuated-joint arrays in. At rest
    (q̇ = 0) the breakaway friction is ±c with the sign of the rest of τm: |τm| gets c added,
    not 0 (the motor must overcome it to start, and it flips when q̇ changes sign)."""
    n, jm, b, c = (act.column(k) for k in ("gear_ratio", "rotor_inertia", "viscous", "coulomb"))
    v = np.asarray(v)
    rest = np.asarray(tau) / n + jm * n * np.asarray(a) + b * n * v
    return rest + c * np.where(v != 0, np.sign(v), np.where(rest >= 0, 1.0, -1.0))


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
        return utilisation(self.actuators, self.torque, self.speed)


def utilisation(act: Actuators, torque, speed) -> np.ndarray:
    """The larger of |τm|/peak torque and |ωm|/max speed, per actuator (last axis)."""
    return np.maximum(np.abs(torque) / act.column("peak_torque"),
                      np.abs(speed) / act.column("max_speed"))


def motor_load(act: Actuators, t, tau, v, a) -> MotorLoad:
    """The motor model along a trajectory: actuated-joint τ, q̇, q̈ arrays (N, 6)."""
    return MotorLoad(np.asarray(t, dtype=float), motor_torque(act, tau, v, a),
                     motor_speed(act, v), act)


def motor_load_of(robot, act: Actuators, ik, dynamics) -> MotorLoad:
    """:func:`motor_load` of a pipeline result (IK and inverse dynamics)."""
    ia = robot.actuated_v
    return motor_load(act, ik.t, dynamics.tau, ik.v[:, ia], ik.a[:, ia])


def breakaway(q_s, at_rest=None, turns: bool = True) -> np.ndarray:
    """Where Coulomb friction counts with either sign, (n, 6) bool: a joint that stands
    (q_s = 0, or ṡ = 0 at the points ``at_rest``) or, with ``turns``, whose rate changes
    sign before the next point or after the previous one (q̇ crosses 0 between them)."""
    sign = np.sign(q_s)
    out = sign == 0
    if turns:
        flips = sign[1:] * sign[:-1] < 0
        out[1:] |= flips
        out[:-1] |= flips
    if at_rest is not None:
        out |= np.asarray(at_rest, dtype=bool)[:, None]
    return out


def motor_coefficients(act: Actuators, path: PathDynamics, at_rest=None, turns: bool = True):
    """Motor torque along the path: τm = α·s̈ + β·ṡ² + γ + δ·ṡ ± c·k (ṡ ≥ 0), each (n, 6), with
    k = :func:`breakaway` (Coulomb ±c where the joint stands or, with ``turns``, turns back;
    elsewhere it is in γ with the sign of q_s). Returns (α, β, γ, δ, k)."""
    n, jm, b, c = (act.column(k) for k in ("gear_ratio", "rotor_inertia", "viscous", "coulomb"))
    alpha = path.a / n + jm * n * path.q_s
    beta = path.b / n + jm * n * path.q_ss
    both = breakaway(path.q_s, at_rest, turns)
    gamma = path.c / n + c * np.sign(path.q_s) * ~both
    delta = b * n * path.q_s
    return alpha, beta, gamma, delta, both


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
    Σ w_k (β x² + δ x + γ)² = continuous² (trapezoid weights w in s). At the samples where a
    joint stands, Coulomb counts as ±c (peak − c on the rest of τm; in the RMS, with the
    static torque's sign). Raises :class:`ActuatorError` if gravity and Coulomb friction alone
    break a limit.
    """
    _, beta, gamma, delta, both = motor_coefficients(act, path, turns=False)
    peak, cont, wmax = (act.column(k) for k in ("peak_torque", "continuous_torque", "max_speed"))
    coulomb = act.column("coulomb") * both
    w = mean_weights(path.s)
    static_peak = (np.abs(gamma) + coulomb).max(0)
    gamma_rms = gamma + coulomb * np.where(gamma >= 0, 1.0, -1.0)
    static_rms = np.sqrt(w @ gamma_rms**2)
    for j, name in enumerate(act.names):
        for label, value, rating in (("peak", static_peak[j], peak[j]),
                                     ("RMS", static_rms[j], cont[j])):
            if value >= rating:
                raise ActuatorError(
                    f"{name}: the static {label} motor torque (gravity and Coulomb friction) "
                    f"{value:.4g} N·m already reaches the rating {rating:.4g} N·m; no duration "
                    "meets it")
    x_peak = np.minimum(_smallest_positive_root(beta, delta, gamma - (peak - coulomb)),
                        _smallest_positive_root(beta, delta, gamma + (peak - coulomb))).min(0)
    speed_s = np.abs(motor_speed(act, path.q_s)).max(axis=0)
    with np.errstate(divide="ignore"):
        x_speed = np.where(speed_s > 0, wmax / speed_s, np.inf)
    x_rms = np.empty(len(act.names))
    for j in range(len(act.names)):  # Σ w (βx² + δx + γ)² − cont², highest power first
        b_, d_, g_ = beta[:, j], delta[:, j], gamma_rms[:, j]
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


__all__ = [
    "KEYS",
    "OPTIONAL",
    "LIMITS",
    "Actuator",
    "MAX_RUN_UP",
    "check_run_up",
    "ActuatorError",
    "Actuators",
    "MotorLoad",
    "UniformScaling",
    "actuators_from_dict",
    "breakaway",
    "load_actuators",
    "motor_coefficients",
    "motor_load",
    "motor_load_of",
    "motor_speed",
    "motor_torque",
    "uniform_min_duration",
    "utilisation",
]
