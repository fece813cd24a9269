"""The fastest traversal of a path under the motors' peak torque and speed, at its samples and
between them (TOPP-RA, ``toppra``; docs/model.md §19); one moving segment (a path with waits:
:mod:`.cycle`).

TOPP-RA holds s̈ constant over each interval of the grid, so ṡ² = ṡ_i² + 2·s̈_i·(s − s_i)
there. Each interval's limits are imposed at ``per_interval`` + 1 check points on the exact
path (the interpolation scheme generalised: the sample's own constraint and the interval's
end are two of them), then the motion is evaluated at the points halfway between the check
points; where it uses a limit by more than ``TARGET``, the check points double and TOPP-RA
solves again (:func:`time_optimal_segment`). Rows are scaled to unit coefficients: TOPP-RA's
Seidel solver compares products of coefficients with an absolute 1e-10.
"""
from __future__ import annotations

import contextlib
import logging
from dataclasses import dataclass, replace

import numpy as np

from ..paths import const_accel
from ..paths.arc_length import arc_length_path
from ..paths.trajectory import trajectory_curve
from .motors import ActuatorError, Actuators, motor_coefficients, motor_speed
from .motors import utilisation as motor_utilisation
from .path import PathDynamics, path_dynamics_at

PER_INTERVAL = 4  # check points per interval to start with
TARGET = 1.001  # worst verified utilisation between samples accepted (the promise: 1.002)
MAX_PER_INTERVAL = 64
TIGHTEN_BELOW = 1.01  # a smaller overshoot halfway is met by tightening its interval's limits
TIGHTEN_ROUNDS = 3
X_CAP = 1e8  # ṡ² bound where nothing else bounds it (TOPP-RA's Seidel clips at 1e8)
# The arc-length grid: GRID_DENSITY points per unit of ∫√(1 + κ) dσ (ArcLengthPath.extent),
# within [MIN_GRID, MAX_GRID]; a property of the path, not of its samples. TOPP-RA's error on
# arc length is O(1/n), ≈ 8× larger than on the thesis curve's own time (docs/model.md §19).
GRID_DENSITY = 240
MIN_GRID, MAX_GRID = 201, 20001
MARGIN = 1e-6  # limits imposed this much tighter: TOPP-RA's absolute 1e-8 on ṡ² (seen 3e-7)


@dataclass(frozen=True)
class TimeOptimal:
    """The time-optimal traversal of a path: at the grid ``s`` (n,), times ``t``, path rate
    ``s_dot`` and path acceleration ``s_ddot``: constant between samples, so at a sample it
    jumps; ``s_ddot`` holds the one-sided value (before or after) that loads the motors more.
    ``between`` is the worst utilisation (max of |τm|/peak and |ωm|/max speed) found at the
    check points and halfway between them, ``between_at`` its s; NaN when not checked.
    ``tightened``: intervals whose ratings were scaled down to hold halfway.

    Attributes
    ----------
    s, t : ndarray
        The path grid (n,), 0 to 1 per segment, and its times [s].
    s_dot, s_ddot : ndarray
        Path rate [1/s] and acceleration [1/s²] at the grid.
    iterations : int
        TOPP-RA solves (viscous friction is re-linearised between them).
    per_interval : int
        Check points per interval imposed.
    between, between_at : float
        The worst utilisation between the samples and its s.
    tightened : int
        Intervals whose ratings were tightened to hold halfway.
    path : pollard_pin.dynamics.path.PathDynamics or None
        The path's dynamics τ = a(s)s̈ + b(s)ṡ² + c(s) at the grid.
    curve, t0, span
        The path the grid lies on: ``curve(t0 + s·span) → (poses, rates, accelerations)``.
    parts : tuple
        A path with waits: the traversals of its moving segments, joined here.
    planned : object
        A stretch kept as planned (a paint program's passes): its trajectory.
    """

    s: np.ndarray
    t: np.ndarray
    s_dot: np.ndarray
    s_ddot: np.ndarray
    iterations: int  # TOPP-RA solves (viscous friction is re-linearised between them)
    per_interval: int = 1  # check points per interval imposed
    between: float = float("nan")
    between_at: float = float("nan")
    tightened: int = 0  # intervals whose ratings were tightened to hold halfway
    # the path the grid lies on (time_optimal_segment): its dynamics at the grid, and
    # ``curve(t0 + s·span) -> (poses, rates, accelerations)``, rates per unit of that parameter
    path: PathDynamics | None = None
    curve: object = None
    t0: float = 0.0
    span: float = 1.0
    # a path with waits (dynamics.cycle): the traversals of its moving segments, one after the
    # other; the arrays above join theirs (s = k + the k-th one's s, a rest sample at each
    # junction twice, both sides of s̈), ``curve`` None
    parts: tuple = ()
    # a stretch kept as planned (dynamics.passes): its trajectory, whose rows and times the
    # traversal is (s = (t − t0)/span, ṡ = 1/span, s̈ = 0)
    planned: object = None

    @property
    def duration(self) -> float:
        return float(self.t[-1] - self.t[0])

    @property
    def interval_acceleration(self) -> np.ndarray:
        """s̈ of each interval, (n − 1,): (ṡ_{i+1}² − ṡ_i²) / (2 Δs_i)."""
        return const_accel.interval_acceleration(self.s, self.s_dot)

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


@contextlib.contextmanager
def _quiet(logger_name: str):
    logger = logging.getLogger(logger_name)
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


def _x_max(act: Actuators, path: PathDynamics) -> np.ndarray:
    """The speed limit as a bound on ṡ² at each point (inf where the joints stand)."""
    speed_s = (np.abs(motor_speed(act, path.q_s)) / act.column("max_speed")).max(1)
    with np.errstate(divide="ignore"):
        return np.where(speed_s > 0, 1.0 / speed_s**2, np.inf)


def _layout(s: np.ndarray, m: int):
    """Dense index (n − 1, m + 1) of each interval's check points and their θ ∈ [0, 1]."""
    n = len(s)
    idx = np.arange(n - 1)[:, None] * m + np.arange(m + 1)[None, :]
    return idx, np.arange(m + 1) / m


def _rows(act: Actuators, dense: PathDynamics, s: np.ndarray, m: int, at_rest, s_dot_v,
          tight=None):
    """TOPP-RA's stage constraints A·u + B·x + C ≤ 0 (x = ṡ_i², u = s̈_i), (n, k) each: the
    peak torque (both signs) at every check point θ of the interval, where ṡ² = x + 2θΔu,
    and the speed at the interior ones, each interval's ratings times ``tight`` (n − 1,);
    rows scaled to max(|A|, |B|) = 1."""
    alpha, beta, gamma, delta, both = motor_coefficients(act, dense, at_rest)
    # viscous δ·ṡ = δ·√x, linearised in x about the last ṡ_v (its tangent, exact at ṡ_v²)
    sv = s_dot_v[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        beta = beta + np.where(sv > 0, delta / (2 * sv), 0.0)
    gamma = gamma + delta * sv / 2
    idx, theta = _layout(s, m)
    # the last sample is a stage of its own: its point, repeated (duplicate rows are harmless)
    idx = np.vstack([idx, np.full(m + 1, len(dense.s) - 1)])
    factor = (1 - MARGIN) * np.append(np.ones(len(s) - 1) if tight is None else tight, 1.0)
    peak = factor[:, None, None] * act.column("peak_torque")  # (n, 1, 6)
    limit = peak - act.column("coulomb") * both[idx]  # breakaway ±c
    step = 2.0 * theta * np.append(np.diff(s), 0.0)[:, None]  # 2θΔ, (n, m + 1)
    sign = np.array([1.0, -1.0])[:, None, None, None]

    def flat(x):  # (2 signs, n, m + 1, 6) -> (n, rows)
        return np.moveaxis(x, 0, 1).reshape(len(s), -1)

    x_max = _x_max(act, dense)[idx[:, 1:-1]] * factor[:, None] ** 2
    finite = np.isfinite(x_max)
    A = np.hstack([flat(sign * (alpha[idx] + step[..., None] * beta[idx])),
                   np.where(finite, step[:, 1:-1], 0.0)])
    B = np.hstack([flat(sign * beta[idx]), finite * 1.0])
    C = np.hstack([flat(sign * gamma[idx] - limit), np.where(finite, -x_max, -1.0)])
    scale = np.maximum(np.abs(A), np.abs(B))
    const = scale <= 1e-12 * np.maximum(np.abs(C), 1e-300)  # statics hold such a row
    scale = np.where(const, 1.0, scale)
    A, B = np.where(const, 0.0, A / scale), np.where(const, 0.0, B / scale)
    C = np.where(const, -1.0, C / scale)
    x_grid = _x_max(act, dense)[::m] * (1 - MARGIN) ** 2
    xbound = np.column_stack([np.zeros(len(s)), np.minimum(x_grid, X_CAP)])
    return A, B, C, xbound


def _constraint(A, B, C, xbound):
    toppra = _toppra()

    class Rows(toppra.constraint.LinearConstraint):
        def __init__(self):
            super().__init__()
            self.identical = True  # one F (the identity) for every stage: vectorised setup

        def compute_constraint_params(self, _path, gridpoints, *args, **kwargs):
            k = A.shape[1]
            return A, B, C, np.eye(k), np.zeros(k), None, xbound

    return Rows()


def _check_statics(act: Actuators, dense: PathDynamics, at_rest) -> None:
    """Gravity (and Coulomb at rest) alone over a peak torque: no traversal at all."""
    _, _, gamma, _, both = motor_coefficients(act, dense, at_rest)
    static = np.abs(gamma) + act.column("coulomb") * both
    over = static / (act.column("peak_torque") * (1 - MARGIN))
    if over.max() >= 1.0:
        k, j = np.unravel_index(np.argmax(over), over.shape)
        raise ActuatorError(
            f"{act.names[j]}: the static motor torque (gravity and Coulomb friction) "
            f"{static[k, j]:.4g} N·m at s = {dense.s[k]:.6g} reaches the peak rating "
            f"{act.column('peak_torque')[j]:.4g} N·m; no traversal of the path meets it")


def time_optimal(act: Actuators, path: PathDynamics, options: Options | None = None, *,
                 s_dot_guess=None, tight=None) -> TimeOptimal:
    """Shortest traversal of the path under the peak-torque and speed limits (TOPP-RA on the
    grid ``path.s[::per_interval]``, every point of ``path`` a check point; rest to rest by
    default; :class:`Options`, default ``per_interval = 1``: the limits at the samples only).

    TOPP-RA needs constraints of the form α s̈ + β ṡ² + γ; the viscous term b·N·q_s·ṡ is
    linear in ṡ = √(ṡ²), so it enters linearised in ṡ² about the previous solution's ṡ(s)
    (docs/model.md §19), repeated until ṡ(s) changes by less than ``tol`` (relative): the
    limits then hold at the final profile. Not converging in ``max_iterations`` solves is an
    :class:`ActuatorError`.
    ``s_dot_guess`` (at the points of ``path``) starts that iteration nearer its end;
    ``tight`` (n − 1,) scales each interval's ratings (default 1).
    """
    toppra = _toppra()
    options = options or Options(per_interval=1)
    m, tol = options.per_interval, options.tol
    s_dot_start, s_dot_end = options.s_dot_start, options.s_dot_end
    s = np.asarray(path.s, dtype=float)[::m]
    if (len(path.s) - 1) % m or len(s) < 2:
        raise ValueError(f"a path of {len(path.s)} points is not (n − 1)·{m} + 1 points")
    _check_count(len(s), s_dot_start, s_dot_end)
    if not np.any(path.q_s):
        raise ActuatorError("the path does not move the actuators (their rates along it are 0 "
                            "at every point): no time-optimal cycle")
    at_rest = np.zeros(len(path.s), dtype=bool)
    at_rest[[0, -1]] = s_dot_start == 0, s_dot_end == 0
    _check_statics(act, path, at_rest)
    dummy = toppra.SplineInterpolator([0.0, 1.0], [[0.0], [1.0]])  # the grid is all it uses
    idx, theta = _layout(s, m)
    has_viscous = bool(np.any(act.column("viscous") > 0))
    # Viscous friction enters at ṡ_v(s): the last solution, or, where that is so fast that
    # its viscous torque leaves no traversal, a step back towards the last ṡ_v that solved
    # (halved until one solves); converged when the solution equals the ṡ_v it was given.
    solved_at = np.zeros(len(path.s))
    aim = solved_at if s_dot_guess is None or not has_viscous else np.asarray(s_dot_guess)
    s_dot_v, s_dot = aim, None
    step, it, change = 1.0, 0, np.inf
    while it < options.max_iterations and step >= 1.0 / 64:
        it += 1
        solver = toppra.algorithm.TOPPRA(
            [_constraint(*_rows(act, path, s, m, at_rest, s_dot_v, tight))], dummy,
            gridpoints=s,
            solver_wrapper="seidel")
        with _quiet("toppra"):  # its failure warnings; the error below says it in one line
            _, sd, _, K = solver.compute_parameterization(s_dot_start, s_dot_end,
                                                          return_data=True)
        if sd is None or np.any(~np.isfinite(sd)):
            if not np.any(s_dot_v):  # no viscous term yet: the path itself
                raise ActuatorError(_uncontrollable(K, s))
            step /= 2
            s_dot_v = solved_at + step * (aim - solved_at)
            continue
        s_dot = np.maximum(sd, 0.0)
        x = const_accel.rate_squared(s, s_dot, theta)
        dense_s_dot = np.empty(len(path.s))
        dense_s_dot[idx] = np.sqrt(np.maximum(x, 0.0))
        solved_at = s_dot_v
        change = np.abs(dense_s_dot - s_dot_v).max() / max(dense_s_dot.max(), 1e-300)
        if not has_viscous or change <= tol:
            break
        aim = dense_s_dot
        s_dot_v = solved_at + step * (aim - solved_at)
    if s_dot is None or (has_viscous and change > tol):
        raise ActuatorError(
            f"the time-optimal traversal with viscous friction did not converge in {it} "
            f"TOPP-RA solves (ṡ(s) changes by {change:.2g}): the viscous torque b·ωm at the "
            "motors' speeds is too close to their peak torque")
    return _timing(act, path.take(slice(None, None, m)), s_dot, at_rest[::m], it, m)


def _check_count(n: int, s_dot_start: float, s_dot_end: float) -> None:
    if n < 3 and s_dot_start == 0 and s_dot_end == 0:  # one interval: ṡ = 0 all along
        raise ActuatorError(f"the time-optimal traversal, rest to rest, needs at least 3 "
                            f"samples of the path, got {n}")


def _uncontrollable(K, s) -> str:
    """TOPP-RA found no traversal, though the motors hold every point at rest (statics are
    checked first), so standing still is feasible everywhere and a slow traversal exists."""
    empty = np.flatnonzero(~np.all(np.isfinite(K), axis=1)) if K is not None else []
    where = (f"its set of controllable path rates came out empty at sample {int(empty[-1])} "
             f"of {len(s)} (s = {s[int(empty[-1])]:.6g})" if len(empty) else
             "the start at rest came out outside its set of controllable path rates")
    return ("TOPP-RA failed numerically: " + where + ", though the motors hold every point "
            "of the path at rest, so a slow traversal exists (try another sampling of the "
            "path)")


def _timing(act, path: PathDynamics, s_dot, at_rest, iterations, m) -> TimeOptimal:
    s = path.s
    dt = const_accel.interval_durations(s, s_dot)
    if not np.all(np.isfinite(dt)):
        k = int(np.argmax(~np.isfinite(dt)))
        raise ActuatorError(f"the time-optimal traversal stops between samples {k} and "
                            f"{k + 1} of the path (ṡ = 0 at both): no finite duration")
    t = np.concatenate([[0.0], np.cumsum(dt)])
    u = const_accel.interval_acceleration(s, s_dot)
    # s̈ jumps at the samples; both one-sided values are exact and within the limits. Keep
    # the one that loads the motors more (the worse side), so that a replay checks it.
    left, right = np.concatenate([u[:1], u]), np.concatenate([u, u[-1:]])
    use = [utilisation(act, path, sdd, s_dot, at_rest, turns=False).max(1)
           for sdd in (left, right)]
    return TimeOptimal(s=s, t=t, s_dot=s_dot, s_ddot=np.where(use[0] > use[1], left, right),
                       iterations=iterations, per_interval=m)


def utilisation(act: Actuators, path: PathDynamics, s_ddot, s_dot, at_rest=None,
                turns: bool = True) -> np.ndarray:
    """max(|τm|/peak, |ωm|/max speed) per point and actuator, (n, 6), of the motion
    (ṡ, s̈) at the points of ``path``; Coulomb ±c where a joint stands (or, with ``turns``,
    turns back before the next point: conservative)."""
    alpha, beta, gamma, delta, both = motor_coefficients(act, path, at_rest, turns)
    sdd, sd = np.asarray(s_ddot)[:, None], np.asarray(s_dot)[:, None]
    torque = np.abs(alpha * sdd + beta * sd**2 + gamma + delta * sd) \
        + act.column("coulomb") * both
    return motor_utilisation(act, torque, motor_speed(act, path.q_s * sd))


def motion_at(timing: TimeOptimal, s) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, ṡ, s̈) of the traversal at any points ``s`` ∈ [0, 1] (s̈ constant per interval;
    at a sample, the interval that starts there)."""
    return const_accel.at_path(timing.t, timing.s, timing.s_dot, s)


@dataclass(frozen=True)
class Options:
    """How ``time_optimal_segment`` solves, validated once: ``per_interval`` check points per
    interval to start with, the worst utilisation ``target`` accepted between them, the path
    rates at the ends (rest to rest by default; ``end_rates``: the trajectory's own rates at
    its first and last samples, on whichever parameter the path is traversed by, so that the
    traversal joins the motion before and after it C¹), and the viscous iteration's
    ``max_iterations`` TOPP-RA solves and relative ``tol`` on ṡ(s)."""

    per_interval: int = PER_INTERVAL
    target: float = TARGET
    s_dot_start: float = 0.0
    s_dot_end: float = 0.0
    end_rates: bool = False
    max_iterations: int = 50
    tol: float = 1e-6

    def __post_init__(self):
        for key in ("per_interval", "max_iterations"):
            if not (isinstance(getattr(self, key), int) and getattr(self, key) >= 1):
                raise ValueError(f"{key} must be an integer >= 1, got {getattr(self, key)!r}")
        if not self.target >= 1.0:
            raise ValueError(f"target must be >= 1 (a utilisation), got {self.target!r}")
        for key in ("s_dot_start", "s_dot_end", "tol"):
            value = getattr(self, key)
            if not (np.isfinite(value) and value >= 0):
                raise ValueError(f"{key} must be finite and >= 0, got {value!r}")


def time_optimal_segment(robot, act: Actuators, traj, options: Options | None = None
                         ) -> TimeOptimal:
    """The time-optimal traversal, rest to rest, of the path of ``traj`` (``t`` (n,), task
    ``poses``, rates, accelerations (n, 6), and ``curve``, the exact path between the samples,
    default the quintic Hermite spline through them: :func:`trajectory_curve`), holding
    between the samples (:class:`Options`).

    The limits are imposed at ``per_interval`` + 1 check points per interval, then checked
    halfway between them; while the worst utilisation found exceeds ``target``, the offending
    intervals' ratings are tightened by their overshoot when it is below ``TIGHTEN_BELOW`` (up
    to ``TIGHTEN_ROUNDS`` times), else the check points double (up to ``MAX_PER_INTERVAL``).
    ``between`` reports the worst utilisation verified.

    The path is traversed by its arc length (:func:`~.arc_length_path`), on a grid of
    GRID_DENSITY points per unit of ∫√(1 + κ) dσ, evenly spaced in it: the answer depends
    neither on how the samples are timed nor on how many there are. A path that stops inside
    (or on which TOPP-RA fails) keeps its samples' parameter s = (t − t0)/T. The result's
    ``s``, ``t`` are at the grid on that parameter (``curve``, ``t0``, ``span``, ``path``).
    """
    options = options or Options()
    t = np.asarray(traj.t, dtype=float)
    curve = trajectory_curve(traj)
    # kept from the grid on the samples (a 2-sample path, rest to rest, is refused: tested)
    _check_count(len(t), options.s_dot_start, options.s_dot_end)
    arc = arc_length_path(curve, t)
    if arc is not None:
        try:
            n = int(np.clip(np.ceil(GRID_DENSITY * arc.extent) + 1, MIN_GRID, MAX_GRID))
            on = (arc, 0.0, arc.length)
            return _solve(robot, act, on, arc.grid(n), _ends(options, traj, on))
        except ActuatorError:  # e.g. too few samples for its bends: the samples' parameter
            pass
    t0, T = float(t[0]), float(t[-1] - t[0])
    on = (curve, t0, T)
    return _solve(robot, act, on, (t - t0) / T, _ends(options, traj, on))


def _ends(options: Options, traj, on) -> Options:
    """``options`` with ``end_rates`` resolved: ṡ at each end such that p'(s)·ṡ is the
    trajectory's rate there (least squares in the path's scaled norm: p' is parallel to it)."""
    if not options.end_rates:
        return options
    curve, t0, T = on
    p_s = T * curve(np.array([t0, t0 + T]))[1]
    w = 1.0 / np.asarray(getattr(curve, "scale", np.ones(6)))
    rates = np.asarray(traj.d_poses)[[0, -1]]
    with np.errstate(divide="ignore", invalid="ignore"):
        sd = ((p_s * w) * (rates * w)).sum(1) / ((p_s * w) ** 2).sum(1)
    sd = np.where(np.isfinite(sd), np.maximum(sd, 0.0), 0.0)
    return replace(options, s_dot_start=float(sd[0]), s_dot_end=float(sd[1]), end_rates=False)


def _solve(robot, act, on, grid, options: Options) -> TimeOptimal:
    """:func:`time_optimal_segment` on the path ``curve(t0 + s·T)``, ``on = (curve, t0, T)``,
    TOPP-RA's grid ``grid``."""
    curve, t0, T = on
    m, target = options.per_interval, options.target
    rest = (options.s_dot_start == 0, options.s_dot_end == 0)
    dense = path_dynamics_at(robot, curve, t0, T, _points(grid, m, 0.0))
    iterations, guess, half, tight, rounds = 0, None, None, np.ones(len(grid) - 1), 0
    while True:
        timing = time_optimal(act, dense, replace(options, per_interval=m), s_dot_guess=guess,
                              tight=tight)
        iterations += timing.iterations
        if half is None:
            half = path_dynamics_at(robot, curve, t0, T, _points(grid, m, 0.5))
            both = _interleave(dense, half, len(grid), m)
        use = _dense_use(act, both, timing, 2 * m, rest)
        worst = int(np.argmax(use))
        if use[worst] <= target:
            break
        per = use[:-1].reshape(len(grid) - 1, 2 * m).max(1)  # halfway: in its interval
        per[-1] = max(per[-1], use[-1])
        if use[worst] <= TIGHTEN_BELOW and rounds < TIGHTEN_ROUNDS:
            # a small overshoot in a few intervals: tighten them, same check points
            bad = per > target
            tight[bad] /= per[bad] * (1 + 1e-4)
            rounds += 1
            guess = motion_at(timing, dense.s)[1]
            continue
        if 2 * m > MAX_PER_INTERVAL:
            break
        dense, m, guess = both, 2 * m, motion_at(timing, both.s)[1]
        half, tight, rounds = None, np.ones(len(grid) - 1), 0
    return TimeOptimal(timing.s, timing.t, timing.s_dot, timing.s_ddot, iterations, m,
                       float(use[worst]), float(both.s[worst]), int(np.sum(tight < 1)),
                       dense.take(slice(None, None, m)), curve, t0, T)


def _points(grid, m: int, offset: float) -> np.ndarray:
    """Each interval's points (j + offset)/m, j = 0…m − 1, plus the end (offset 0)."""
    theta = (np.arange(m) + offset) / m
    s = (grid[:-1, None] + theta * np.diff(grid)[:, None]).ravel()
    return np.append(s, grid[-1]) if offset == 0 else s


def _interleave(dense: PathDynamics, half: PathDynamics, n: int, m: int) -> PathDynamics:
    """The check points and the points halfway between them, in order: (n − 1)·2m + 1."""
    fields = {}
    for k in ("s", "a", "b", "c", "q_s", "q_ss"):
        d, h = getattr(dense, k), getattr(half, k)
        out = np.empty((len(d) + len(h),) + d.shape[1:])
        out[0::2], out[1::2] = d, h
        fields[k] = out
    return PathDynamics(**fields, duration=dense.duration)


def _dense_use(act, dense: PathDynamics, timing: TimeOptimal, m: int, rest) -> np.ndarray:
    """Worst utilisation at each dense point, each interval with its own s̈ (at a sample,
    both sides of the jump)."""
    grid, s_dot = timing.s, timing.s_dot
    idx, theta = _layout(grid, m)
    u = timing.interval_acceleration
    x = const_accel.rate_squared(grid, s_dot, theta, u)
    at_rest = np.zeros(len(dense.s), dtype=bool)
    at_rest[[0, -1]] = rest
    alpha, beta, gamma, delta, both = motor_coefficients(act, dense, at_rest)
    sd = np.sqrt(np.maximum(x, 0.0))[..., None]
    torque = np.abs(alpha[idx] * u[:, None, None] + beta[idx] * sd**2 + gamma[idx]
                    + delta[idx] * sd) + act.column("coulomb") * both[idx]
    use = motor_utilisation(act, torque,
                            motor_speed(act, dense.q_s[idx] * sd)).max(2)  # (n − 1, m + 1)
    out = np.zeros(len(dense.s))
    np.maximum.at(out, idx.ravel(), use.ravel())
    return out


__all__ = ["MAX_PER_INTERVAL", "PER_INTERVAL", "TARGET", "Options", "TimeOptimal",
           "motion_at", "time_optimal", "time_optimal_segment", "utilisation"]
