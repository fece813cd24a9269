"""What a closed-loop simulation takes (docs/model.md §18): :class:`TrackingOptions`, validated
once, the measurement noise, and the RK4 step rules shared with the CLI's estimates."""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..checks import float_array, is_real, shorten
from .control import CONTROL_PERIOD, CONTROLLERS, ControlError, Controller, DesiredTrajectory, Gains
from .drives.flexible import FlexibleDrives
from .inverse import JointLosses
from .plant import BAUMGARTE, ModelMismatch

DT = 1e-3  # s, longest RK4 step
# Wall time per RK4 step and per control tick (sensing by forward kinematics and the built-in
# controllers), for estimates only: measured on a shared 2-core machine (scripts/benchmark.py;
# 24–34 µs and 31–62 µs as the other load varied).
STEP_SECONDS, TICK_SECONDS = 30e-6, 45e-6
# m: the plant's largest loop-closure residual (max |p_A − p_B| component) at a control tick
# that a simulation may reach; beyond it the RK4 step is too long for the motion and the
# loops no longer hold (docs/model.md §18). Seen: 1e-13–1e-11 m at normal speeds, 1.4e-6 m
# for the thesis curve in 1 s at 1 ms steps (2e-5 m at 2 ms).
LOOP_TOLERANCE = 1e-5
# RK4 steps one simulation may take: its grid is held in memory (≈ 50 bytes a step as Python
# lists: 2.5 GB), and at STEP_SECONDS it runs for 25 min
MAX_STEPS = 50_000_000


@dataclass(frozen=True)
class MeasurementNoise:
    """Gaussian noise on the measured actuator angles and rates, seeded.

    Parameters
    ----------
    position : float, optional
        Standard deviation of the angle noise [rad], ≥ 0 (default 0).
    velocity : float, optional
        Standard deviation of the rate noise [rad/s], ≥ 0 (default 0).
    seed : int or None, optional
        The random generator's seed (default 0; None: unseeded).

    Raises
    ------
    pollard_pin.dynamics.control.ControlError
        A standard deviation that is negative or not finite.
    """

    position: float = 0.0
    velocity: float = 0.0
    seed: int | None = 0

    def __post_init__(self):
        for name, value in (("position noise", self.position),
                            ("velocity noise", self.velocity)):
            if not is_real(value, 0.0):
                raise ControlError(f"{name} standard deviation must be >= 0, got "
                                   f"{shorten(value)}")


@dataclass(frozen=True, eq=False)
class TrackingOptions:
    """How :func:`~pollard_pin.simulate_tracking` runs, checked once here.

    Parameters
    ----------
    controller : str or Callable, optional
        ``"computed-torque"`` (default), ``"feedforward-pd"``, ``"pd"``, or any callable
        ``controller(t, q, v) → τ (6,)``; it sees the sensed state at each tick.
    errors : ModelMismatch or None, optional
        How the plant differs from the robot (payload, mass error, losses).
    gains : Gains, optional
        The built-in controllers' ω [rad/s] and ζ.
    dt : float or None, optional
        The longest RK4 step [s], at most ``control_period`` (default ``DT`` (1 ms) or the
        period, the shorter; :attr:`step`).
    control_period : float, optional
        The controller's tick [s] (default 1 ms); the torque is computed at each tick and
        held.
    torque_limit : float or ndarray or None, optional
        [N·m], a scalar or one per actuator: |τ| clipped to it (:attr:`limits`).
    noise : MeasurementNoise or None, optional
        Measurement noise on the actuator angles and rates.
    start : ndarray or None, optional
        None (on the path, at the reference's state) or a closed configuration (12,) at rest
        whose tool pose is the trajectory's first pose.
    baumgarte : tuple of float, optional
        The plant's loop stabilisation ``(Kp, Kd)``.
    desired : pollard_pin.dynamics.control.DesiredTrajectory or None, optional
        A reference from :func:`~pollard_pin.dynamics.desired_trajectory` with the same period (and
        ``known_losses``), reused.
    curve : Callable or None, optional
        The path between samples the reference follows.
    known_losses : pollard_pin.dynamics.inverse.JointLosses or None, optional
        Joint losses the built-in controllers know and compensate.
    joint_limits : bool, optional
        Stop where a joint leaves its limits (default True).
    loop_tolerance : float, optional
        Stop where the plant's loops open beyond it [m] (default 1e-5).
    progress : Callable or None, optional
        ``progress(done, total)``, called per output sample.
    drives : FlexibleDrives or None, optional
        Flexible drives (docs/model.md §28): the motors then sit behind springs, the
        controller reads them, and ``errors`` carry no losses; the default ``dt`` then also
        resolves the drives' fastest mode.

    Raises
    ------
    pollard_pin.dynamics.control.ControlError
        An unknown controller name, gains that are not a
        :class:`~pollard_pin.dynamics.Gains`, a step or period that is not > 0 or a step over
        the period, a bad torque limit or loop tolerance, drives that are not a
        :class:`~pollard_pin.dynamics.drives.FlexibleDrives`.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> from pollard_pin.dynamics import ModelMismatch
    >>> opts = pp.TrackingOptions("pd", ModelMismatch(payload=0.05), torque_limit=2.0)
    >>> opts.label, opts.step, opts.limits.tolist()
    ('pd', 0.001, [2.0, 2.0, 2.0, 2.0, 2.0, 2.0])
    """

    controller: str | Controller = "computed-torque"
    errors: ModelMismatch | None = None
    gains: Gains = Gains()
    dt: float | None = None
    control_period: float = CONTROL_PERIOD
    torque_limit: Any = None
    noise: MeasurementNoise | None = None
    start: Any = None
    baumgarte: tuple[float, float] = BAUMGARTE
    desired: DesiredTrajectory | None = None
    curve: Callable | None = None
    known_losses: JointLosses | None = None
    joint_limits: bool = True
    loop_tolerance: float = LOOP_TOLERANCE
    progress: Callable[[int, int], None] | None = None
    drives: FlexibleDrives | None = None

    def __post_init__(self):
        check_steps(self.step, self.control_period)
        if isinstance(self.controller, str):
            if self.controller not in CONTROLLERS:
                raise ControlError(f"unknown controller {self.controller!r} (expected one of: "
                                   f"{', '.join(CONTROLLERS)})")
        elif not callable(self.controller):
            raise ControlError(f"controller must be a name or a callable, got "
                               f"{type(self.controller).__name__}")
        if not isinstance(self.gains, Gains):
            raise ControlError(f"gains must be a Gains, got {type(self.gains).__name__}")
        tol = self.loop_tolerance
        if not (is_real(tol, 0.0, above=True) or tol == math.inf):  # inf: no check
            raise ControlError(f"loop tolerance must be > 0 m, got {shorten(self.loop_tolerance)}")
        for name, value, kind in (("drives", self.drives, FlexibleDrives),
                                  ("noise", self.noise, MeasurementNoise),
                                  ("errors", self.errors, ModelMismatch),
                                  ("known_losses", self.known_losses, JointLosses)):
            if value is not None and not isinstance(value, kind):
                raise ControlError(f"{name} must be a {kind.__name__}, got "
                                   f"{type(value).__name__}")
        object.__setattr__(self, "_limits", _torque_limit(self.torque_limit))

    @property
    def step(self) -> float:
        """The longest RK4 step [s]: ``dt``, or ``default_step`` of the period."""
        return default_step(self.control_period) if self.dt is None else self.dt

    @property
    def limits(self) -> np.ndarray | None:
        """The torque limit per actuator (6,) [N·m], or None."""
        return self._limits

    @property
    def label(self) -> str:
        """The controller's name, or its class's."""
        c = self.controller
        return c if isinstance(c, str) else type(c).__name__


def _torque_limit(torque_limit) -> np.ndarray | None:
    if torque_limit is None:
        return None
    limit = float_array(torque_limit, "torque limit", error=ControlError)
    if limit.size not in (1, 6):
        raise ControlError(f"torque limit: give one value or 6 (one per actuator), got "
                           f"{limit.size}")
    limit = np.broadcast_to(limit, (6,)).copy()
    if not (np.all(np.isfinite(limit)) and np.all(limit > 0)):
        raise ControlError(f"torque limits must be > 0 N·m, got {limit.tolist()}")
    return limit


def default_step(control_period: float) -> float:
    """The default longest RK4 step: :data:`DT`, or the control period if shorter."""
    # a bad period is refused by check_steps
    return min(DT, control_period) if is_real(control_period, 0.0, above=True) else DT


def check_steps(dt: float, control_period: float) -> None:
    """Raise :class:`ControlError` unless 0 < dt ≤ control period (both finite, in s)."""
    for name, value in (("time step", dt), ("control period", control_period)):
        if not is_real(value, 0.0, above=True):
            raise ControlError(f"{name} must be > 0 s, got {shorten(value)}")
    if dt > control_period * (1 + 1e-9):
        raise ControlError(
            f"time step {dt:g} s is longer than the control period {control_period:g} s (each "
            "period is integrated in equal RK4 steps of at most the time step): give a time "
            "step <= the control period")


def integration_steps(duration: float, dt: float, control_period: float) -> int | float:
    """The number of RK4 steps :func:`simulate_tracking` takes over ``duration`` [s], each
    control period in ⌈T/dt⌉ equal steps (computed without building the grid; output samples
    off that grid add one step each); ``math.inf`` past what a float counts (a period or a
    step of 5e-324 s), which every budget refuses."""
    check_steps(dt, control_period)
    periods, within = duration / control_period - 1e-9, control_period / dt - 1e-9
    if math.isinf(periods) or math.isinf(within):  # math.ceil(inf) raised OverflowError
        return math.inf
    return int(math.ceil(periods) * math.ceil(within))


def check_step_count(duration: float, dt: float, control_period: float) -> None:
    """Raise :class:`ControlError` past :data:`MAX_STEPS` RK4 steps (before any work)."""
    steps = integration_steps(duration, dt, control_period)
    if steps > MAX_STEPS:
        shown = f"{steps:,}" if steps < 10 ** 12 else f"{steps:.3g}"
        raise ControlError(f"{shown} RK4 steps ({duration:g} s, control period "
                           f"{control_period:g} s, time step {dt:g} s): more than a simulation "
                           f"can hold ({MAX_STEPS:.3g}); give a longer period or time step")


def estimated_wall(duration: float, dt: float, control_period: float) -> float:
    """A rough wall time [s] of :func:`simulate_tracking` over ``duration`` [s] (reference and
    output excluded), from :data:`STEP_SECONDS` and :data:`TICK_SECONDS`."""
    ticks = duration / control_period - 1e-9
    ticks = math.ceil(ticks) if math.isfinite(ticks) else math.inf  # a period of 5e-324 s
    return (integration_steps(duration, dt, control_period) * STEP_SECONDS
            + ticks * TICK_SECONDS)


def step_used(dt: float, control_period: float) -> float:
    """The RK4 step [s] inside a control period: T / ⌈T/dt⌉ (≤ dt)."""
    check_steps(dt, control_period)
    return control_period / math.ceil(control_period / dt - 1e-9)
