"""Tool-pose trajectories: the thesis painting curve (docs/model.md §9) and user CSV files.

A :class:`Trajectory` holds times and task poses q = (x, y, z, ψ, θ, φ) (docs/model.md §2) with
their
first and second time derivatives, SI units and radians.
"""
from __future__ import annotations

import csv
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..errors import InputError
from ..kinematics.ik_common import MIN_TIME_STEP
from ..model.params import did_you_mean
from ..model.values import open_regular, parse_float, shorten, shown_path

THESIS_DURATION = 20.0  # s (docs/model.md §9)
THESIS_SAMPLES = 2001
U_RANGE = 60.0 * math.pi  # u ∈ [−60π, 60π], thesis appendix B (mm)
MAX_LENGTH = 3.0  # m: a coordinate beyond this is almost surely in mm
MAX_ANGLE = 2.0 * math.pi  # rad: an angle beyond this is almost surely in degrees
# Sample budgets of the thesis trajectory, checked before anything is allocated: solved whole
# (view, plot, report, size, simulate, sweep) a sample costs ≈ 3 KB; streamed window by window
# (run) it costs ≈ 11 µs and 30-300 bytes of output (README: a million samples in 11 s).
MAX_SAMPLES = 1_000_000  # ≈ 3 GB solved
MAX_STREAMED_SAMPLES = 100_000_000  # ≈ 20 min and 3-30 GB of output
MAX_TIME = 1e6  # s: a time beyond this (11.6 days) is a unit slip, and its squares overflow
PARQUET_MAGIC = b"PAR1"  # the first (and last) four bytes of every Parquet file
# Given d_* columns must agree with the positions: the largest gap between q(t) − q(t0) and
# the running trapezoid integral of q̇, relative to the largest excursion |q(t) − q(t0)| (the
# motion's scale), at most this. Exact rates give < 0.05; wrong units (deg/s: ×57), zeros
# (1) or a flipped sign (2) are refused.
DERIVATIVE_TOLERANCE = 0.5
# The same for dd_* against d_*, looser: a time-optimal retiming's s̈ jumps at every sample
# and a file holds one side of each jump (up to 2.2 seen); deg/s² (×57) is refused, and so is
# an all-zero dd_* column whose rates change.
ACCELERATION_TOLERANCE = 10.0


class TrajectoryError(InputError):
    """A trajectory (file) is malformed; the message names the row and column."""


@dataclass(frozen=True)
class Trajectory:
    t: np.ndarray  # (N,) s, strictly increasing
    poses: np.ndarray  # (N, 6)
    d_poses: np.ndarray  # (N, 6)
    dd_poses: np.ndarray  # (N, 6)
    name: str = "trajectory"
    derivatives: str = "analytic"  # or "quintic spline", ...
    # the exact path between the samples, times -> (poses, rates, accelerations); None: the
    # quintic Hermite spline through the samples (see :func:`trajectory_curve`)
    curve: Callable | None = None

    def __len__(self) -> int:
        return len(self.t)

    def window(self, start: int, stop: int) -> Trajectory:
        """Samples ``start:stop`` as a trajectory of their own (views, no copy)."""
        return Trajectory(self.t[start:stop], self.poses[start:stop],
                          self.d_poses[start:stop], self.dd_poses[start:stop], self.name,
                          self.derivatives, self.curve)

    def windows(self, size: int):
        """``(start, window)`` pairs of at most ``size`` samples, in order (streaming)."""
        for start in range(0, len(self), size):
            yield start, self.window(start, start + size)

    def __post_init__(self):
        n = len(self.t)
        for label, arr in (("poses", self.poses), ("d_poses", self.d_poses),
                           ("dd_poses", self.dd_poses)):
            if np.shape(arr) != (n, 6):
                raise TrajectoryError(f"{self.name}: {label} has shape {np.shape(arr)}, "
                                      f"expected ({n}, 6)")


def thesis_curve(t, duration: float = THESIS_DURATION,
                 home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0)):
    """Poses, rates and accelerations (each (N, 6)) of the thesis curve at times ``t`` [s].

    Appendix B: x = −0.001u², y = u, z = 100 sin(0.3u) [mm], u linear in t from −60π at
    t = 0 to 60π at ``duration``, added to the home pose (docs/model.md §9). Exact derivatives.
    """
    t = np.atleast_1d(np.asarray(t, dtype=float))
    ud = 2.0 * U_RANGE / duration
    u = -U_RANGE + ud * t
    mm = 1e-3
    poses = np.tile(np.asarray(home_pose, dtype=float), (len(t), 1))
    d, dd = np.zeros_like(poses), np.zeros_like(poses)
    poses[:, 0] += -0.001 * u**2 * mm
    poses[:, 1] += u * mm
    poses[:, 2] += 100.0 * np.sin(0.3 * u) * mm
    d[:, 0] = -0.002 * u * ud * mm
    d[:, 1] = ud * mm
    d[:, 2] = 30.0 * np.cos(0.3 * u) * ud * mm
    dd[:, 0] = -0.002 * ud**2 * mm
    dd[:, 2] = -9.0 * np.sin(0.3 * u) * ud**2 * mm
    return poses, d, dd


def check_samples(samples, budget: int, how: str = "") -> None:
    """An integer sample count >= 2 within ``budget`` (checked before anything is allocated)."""
    whole = isinstance(samples, (int, np.integer)) and not isinstance(samples, bool) or (
        isinstance(samples, float) and math.isfinite(samples) and samples.is_integer())
    if not whole or samples < 2:
        raise TrajectoryError(f"samples must be an integer >= 2, got {samples!r}")
    if samples > budget:
        raise TrajectoryError(f"{count_text(samples)} samples are over the{how} budget of "
                              f"{budget:.4g}: use fewer samples")


def count_text(n) -> str:
    """A count, however large, as a short number (no 700-digit integers in messages)."""
    return f"{n:.4g}" if n < 1e300 else "more than 1e300"


def thesis_trajectory(duration: float = THESIS_DURATION, samples: int = THESIS_SAMPLES,
                      home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0)) -> Trajectory:
    """The default painting trajectory (docs/model.md §9) sampled at ``samples`` points."""
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration > 0):
        raise TrajectoryError(f"duration must be a positive number of seconds, got {duration}")
    if not 2.0 * U_RANGE / duration < 1e150:  # the accelerations grow as 1/duration²
        raise TrajectoryError(f"duration {duration} s is too short: the curve's accelerations "
                              "overflow")
    check_samples(samples, MAX_SAMPLES)
    t = np.linspace(0.0, duration, int(samples))
    return Trajectory(t, *thesis_curve(t, duration, home_pose), name="thesis",
                      derivatives="analytic",
                      curve=partial(thesis_curve, duration=duration, home_pose=home_pose))


class ThesisTrajectory:
    """The thesis trajectory evaluated window by window, never whole: a million samples cost
    one window's memory. ``windows(size)`` yields exactly the slices of
    :func:`thesis_trajectory` with the same arguments (same bits: ``np.linspace``'s rule)."""

    def __init__(self, duration: float = THESIS_DURATION, samples: int = THESIS_SAMPLES,
                 home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0)):
        thesis_trajectory(duration, 2, home_pose)  # the same argument checks
        check_samples(samples, MAX_STREAMED_SAMPLES, " streamed")
        self.duration, self.samples = float(duration), int(samples)
        self.home_pose = tuple(float(x) for x in home_pose)
        self.name, self.derivatives = "thesis", "analytic"

    def __len__(self) -> int:
        return self.samples

    def window(self, start: int, stop: int) -> Trajectory:
        stop = min(stop, self.samples)
        t = np.arange(start, stop, dtype=float) * (self.duration / (self.samples - 1))
        if stop == self.samples:
            t[-1] = self.duration  # as np.linspace: the end point exactly
        return Trajectory(t, *thesis_curve(t, self.duration, self.home_pose), name=self.name,
                          derivatives=self.derivatives)

    def windows(self, size: int):
        for start in range(0, self.samples, size):
            yield start, self.window(start, start + size)


class _QuinticSpline:
    """The quintic interpolating spline (not-a-knot ends) as a curve: times -> (poses,
    rates, accelerations); a class, so that a trajectory holding it pickles."""

    def __init__(self, t: np.ndarray, y: np.ndarray):
        from scipy.interpolate import make_interp_spline

        self.spline = make_interp_spline(t, y, k=5, axis=0)

    def __call__(self, times):
        times = np.atleast_1d(np.asarray(times, dtype=float))
        return self.spline(times), self.spline(times, 1), self.spline(times, 2)


def trajectory_curve(traj: Trajectory) -> Callable:
    """The path between the samples: the trajectory's own ``curve`` (the thesis curve, the
    spline a CSV's derivatives came from), else the C² quintic Hermite spline through its
    poses, rates and accelerations."""
    from ..dynamics.path import quintic_hermite

    if traj.curve is not None:
        return traj.curve
    return quintic_hermite(traj.t, traj.poses, traj.d_poses, traj.dd_poses)


def from_csv(path: str | Path) -> Trajectory:
    """Read ``t,x,y,z,psi,theta,phi`` (+ optional ``d_*`` and ``dd_*``) from a CSV file.

    Without derivative columns, derivatives come from a quintic interpolating spline and a
    :class:`UserWarning` says so.
    """
    path = Path(path)
    try:
        with open_regular(path, "rb") as f:  # not a FIFO: it would block forever
            magic = f.read(4)
        # -sig: a BOM is no column
        with open_regular(path, "r", newline="", encoding="utf-8-sig") as f:
            reader = csv.reader(f)
            rows, lines = [], []  # lines: 1-based file line of each kept row
            for r in reader:
                if r and not r[0].lstrip().startswith("#"):
                    rows.append(r)
                    lines.append(reader.line_num)
    except OSError as exc:
        raise TrajectoryError(f"cannot read trajectory file {shown_path(path)}: "
                              f"{exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        if magic == PARQUET_MAGIC:
            raise TrajectoryError(f"{path}: a Parquet file; trajectories are read from CSV "
                                  "text (t,x,y,z,psi,theta,phi)") from None
        raise TrajectoryError(f"{path}: not UTF-8 text (byte {exc.start}: "
                              f"{exc.object[exc.start:exc.start + 1]!r}); save it as UTF-8 "
                              "CSV") from None
    except csv.Error as exc:  # a field over the csv module's limit: not a trajectory
        raise TrajectoryError(f"{path}: line {reader.line_num + 1}: not CSV ({exc})") from None
    if magic == PARQUET_MAGIC:  # Parquet bytes that happen to decode as UTF-8
        raise TrajectoryError(f"{path}: a Parquet file; trajectories are read from CSV text "
                              "(t,x,y,z,psi,theta,phi)")
    nul = next((i for i, r in enumerate(rows) if any("\0" in c for c in r)), None)
    if nul is not None:
        raise TrajectoryError(f"{path}: line {lines[nul]} holds NUL bytes: a binary file, "
                              "not CSV text")
    if not rows:
        raise TrajectoryError(f"{path}: empty file (expected a header t,x,y,z,psi,theta,phi)")
    header = [h.strip() for h in rows[0]]
    base = ("t",) + TASK_NAMES
    allowed = base + tuple(f"d_{n}" for n in TASK_NAMES) + tuple(f"dd_{n}" for n in TASK_NAMES)
    for h in header:
        if h not in allowed:
            raise TrajectoryError(f"{path}: unknown column {shorten(h)}{did_you_mean(h, allowed)}; "
                                  f"expected {', '.join(base)} and optional d_*, dd_*")
    if len(set(header)) != len(header):
        raise TrajectoryError(f"{path}: duplicate column names in header {shorten(header)}")
    missing = [c for c in base if c not in header]
    if missing:
        raise TrajectoryError(f"{path}: missing column(s) {', '.join(missing)}")
    data = np.empty((len(rows) - 1, len(header)))
    for r, row in enumerate(rows[1:]):
        line = lines[r + 1]  # file line, comment and blank lines counted
        if len(row) != len(header):
            raise TrajectoryError(f"{path}: row {line} has {len(row)} fields, "
                                  f"expected {len(header)}")
        for c, cell in enumerate(row):
            try:
                data[r, c] = parse_float(cell)
            except ValueError as exc:
                why = "" if "float" in str(exc) else f" ({exc})"  # float()'s own: no news
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"{shorten(cell)} is not a number{why}") from None
            if not math.isfinite(data[r, c]):
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"value {shorten(cell)} is not finite")
    if len(data) < 2:
        raise TrajectoryError(f"{path}: need at least 2 samples, found {len(data)}")
    col = {h: data[:, i] for i, h in enumerate(header)}
    t = col["t"]
    big = np.abs(t) > MAX_TIME
    if np.any(big):
        r = int(np.argmax(big))
        raise TrajectoryError(f"{path}: row {lines[r + 1]}, column 't': {float(t[r]):.4g} s is "
                              f"beyond ±{MAX_TIME:g} s (seconds, not ms?)")
    dt = np.diff(t)
    if np.any(dt <= 0):
        r = int(np.argmax(dt <= 0))
        kind = "duplicate" if dt[r] == 0 else "decreasing"
        raise TrajectoryError(f"{path}: row {lines[r + 2]}, column 't': {kind} time "
                              f"{float(t[r + 1])!r} after {float(t[r])!r} (times must "
                              "increase strictly)")
    small = dt < MIN_TIME_STEP  # the solver's rule (ik_common); the spline would overflow
    if np.any(small):
        r = int(np.argmax(small))
        raise TrajectoryError(f"{path}: row {lines[r + 2]}, column 't': time step too small: "
                              f"{float(t[r + 1])!r} after {float(t[r])!r} is "
                              f"{float(dt[r]):.3g} s, below {MIN_TIME_STEP:g} s (times in "
                              "seconds?)")
    poses = np.column_stack([col[n] for n in TASK_NAMES])
    for c, name in enumerate(TASK_NAMES):
        limit, unit = (MAX_LENGTH, "millimetres (expected m)") if c < 3 else \
            (MAX_ANGLE, "degrees (expected rad)")
        big = np.abs(poses[:, c]) > limit
        if np.any(big):
            r = int(np.argmax(big))
            raise TrajectoryError(f"{path}: row {lines[r + 1]}, column {name!r}: "
                                  f"{float(poses[r, c])!r} looks like {unit}; "
                                  f"|value| > {limit:.4g}")
    check_angle_wraps(path, t, poses, lines)
    derivs = []
    for prefix in ("d_", "dd_"):
        names = [prefix + n for n in TASK_NAMES]
        present = [n for n in names if n in col]
        if present and len(present) != 6:
            absent = [n for n in names if n not in col]
            raise TrajectoryError(f"{path}: derivative columns must come as a full set; "
                                  f"missing {', '.join(absent)}")
        derivs.append(np.column_stack([col[n] for n in names]) if present else None)
    source, curve = "file columns", None
    derivs_given = [d is not None for d in derivs]
    if not all(derivs_given):
        if len(t) < 6:
            raise TrajectoryError(f"{path}: {len(t)} samples are too few for the quintic spline "
                                  "that supplies missing derivatives (need >= 6)")
        spline = _QuinticSpline(t, poses)
        _, d_spl, dd_spl = spline(t)
        if derivs[0] is None and derivs[1] is None:
            curve = spline  # the path between the samples is the spline itself
        if derivs[0] is None:
            derivs[0] = d_spl
        if derivs[1] is None:
            derivs[1] = dd_spl
        source = "quintic spline"
        absent = "/".join(p + "*" for p, d in zip(("d_", "dd_"), derivs_given) if not d)
        warnings.warn(f"{path}: no {absent} columns; derivatives taken from a quintic "
                      "interpolating spline through the samples", UserWarning, stacklevel=2)
    check_derivatives(path, t, poses, derivs[0], derivs[1], *derivs_given)
    return Trajectory(t, poses, derivs[0], derivs[1], name=path.stem, derivatives=source,
                      curve=curve)


def check_angle_wraps(path, t: np.ndarray, poses: np.ndarray, lines) -> None:
    """Refuse an angle that jumps by more than π between consecutive samples: a wrap at ±π
    (the robot's angles never turn half a revolution in one step), which a spline or the given
    rates would read as a spin of ~2π per step."""
    jumps = np.abs(np.diff(poses[:, 3:], axis=0))
    if np.any(jumps > math.pi):
        r, c = np.unravel_index(int(np.argmax(jumps > math.pi)), jumps.shape)
        name = TASK_NAMES[3 + c]
        raise TrajectoryError(
            f"{path}: row {lines[r + 2]}, column {name!r}: jumps by "
            f"{poses[r + 1, 3 + c] - poses[r, 3 + c]:.4g} rad from the previous sample "
            f"(t = {t[r]:.6g} -> {t[r + 1]:.6g} s): an angle wrap at ±π? unwrap the angles so "
            "consecutive samples differ by less than π rad")


def _mismatch(step: np.ndarray, integral: np.ndarray) -> np.ndarray:
    """Per column: max |Σ (integral − step)| over the running sums, over max |Σ step| (the
    excursion), each column's scale floored at 1e-2 of its group's (lengths, angles) largest,
    so a nearly still column is not judged by its own round-off. Running sums: one-sided
    values at jumps (a retiming's s̈) err by turns and cancel."""
    with np.errstate(all="ignore"):  # absurd columns (1e200) give inf: refused, no warning
        scale = np.abs(np.cumsum(step, axis=0)).max(axis=0)
        err = np.abs(np.cumsum(integral - step, axis=0)).max(axis=0)
    for g in (slice(0, 3), slice(3, 6)):
        scale[g] = np.maximum(scale[g], max(1e-2 * scale[g].max(), 1e-300))
    return np.where(np.isfinite(err), err / scale, np.inf)


def check_derivatives(path, t: np.ndarray, poses: np.ndarray, d: np.ndarray, dd: np.ndarray,
                      given_d: bool = True, given_dd: bool = True) -> None:
    """Refuse given (``given_d``, ``given_dd``) ``d_*``/``dd_*`` columns that do not integrate
    to the positions (rates) within :data:`DERIVATIVE_TOLERANCE`
    (:data:`ACCELERATION_TOLERANCE`) of the motion's scale: wrong units, zeros, another
    curve's derivatives. The running trapezoid rule (for the rates Euler–Maclaurin corrected
    with the accelerations)."""
    h = np.diff(t)[:, None]
    checks = []
    if given_d:
        integral = 0.5 * h * (d[1:] + d[:-1]) + h * h / 12.0 * (dd[:-1] - dd[1:])
        checks.append(("d_", np.diff(poses, axis=0), integral, "positions",
                       DERIVATIVE_TOLERANCE))
    if given_dd:
        still = ~np.any(dd, axis=0) & np.any(np.diff(d, axis=0), axis=0)
        if np.any(still):
            raise TrajectoryError(f"{path}: column dd_{TASK_NAMES[int(np.argmax(still))]} is "
                                  "all zero while its rate changes: missing accelerations? "
                                  "(leave the dd_* columns out to have them from a spline)")
        checks.append(("dd_", np.diff(d, axis=0), 0.5 * h * (dd[1:] + dd[:-1]), "d_* rates",
                       ACCELERATION_TOLERANCE))
    for prefix, step, integral, against, tolerance in checks:
        rel = _mismatch(step, integral)
        c = int(np.argmax(rel))
        if rel[c] > tolerance:
            unit = ("m/s" if c < 3 else "rad/s") + ("²" if prefix == "dd_" else "")
            raise TrajectoryError(
                f"{path}: column {prefix}{TASK_NAMES[c]!s} disagrees with the {against} by "
                f"{rel[c]:.3g}× the motion's scale (its running integral vs the excursion; "
                f"tolerance {tolerance:g}): wrong units (expected {unit}), zeros or another "
                "curve's derivatives?")


def to_csv(traj: Trajectory, path: str | Path) -> None:
    """Write the trajectory in the ``run`` input format (``t``, poses, ``d_*``, ``dd_*``; every
    float64 exact) through :mod:`pollard_pin.io.table`, atomically, units in the sidecar."""
    from .table import write_table

    cols = {"t": traj.t}
    for prefix, arr in (("", traj.poses), ("d_", traj.d_poses), ("dd_", traj.dd_poses)):
        cols.update({prefix + n: arr[:, i] for i, n in enumerate(TASK_NAMES)})
    write_table(path, cols, {"trajectory": traj.name, "derivatives": traj.derivatives},
                fmt="csv")


def sinusoid_curve(t, home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0),
                   amplitude=(0.04, 0.05, 0.04, 0.25, 0.3, 0.35),
                   freq=(0.31, 0.23, 0.41, 0.37, 0.29, 0.19),
                   phase=(0.3, 1.1, 2.0, 0.7, 2.5, 1.6)):
    """Poses, rates, accelerations of a_k sin(2π f_k t + φ_k) about the home pose [m, rad, Hz]."""
    t = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
    a, w, ph = np.asarray(amplitude), 2 * math.pi * np.asarray(freq), np.asarray(phase)
    arg = w * t + ph
    return (np.asarray(home_pose, dtype=float) + a * np.sin(arg), a * w * np.cos(arg),
            -a * w * w * np.sin(arg))


def smooth_random_trajectory(seed: int = 0, duration: float = 4.0, samples: int = 401,
                             home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0),
                             amplitude=(0.04, 0.06, 0.05, 0.2, 0.2, 0.3)) -> Trajectory:
    """Random sum-of-sines motion of all six task coordinates about home, exact derivatives."""
    rng = np.random.default_rng(seed)
    amp = np.asarray(amplitude) * rng.uniform(0.5, 1.0, 6)
    freq = rng.uniform(0.5, 2.5, 6) / duration
    phase = rng.uniform(0, 2 * math.pi, 6)
    t = np.linspace(0.0, duration, samples)
    pose, d, dd = sinusoid_curve(t, home_pose, amp, freq, phase)
    pose -= amp * np.sin(phase)  # start exactly at home
    return Trajectory(t, pose, d, dd, name=f"random{seed}", derivatives="analytic")


__all__ = [
    "Trajectory",
    "TrajectoryError",
    "check_angle_wraps",
    "check_derivatives",
    "from_csv",
    "sinusoid_curve",
    "smooth_random_trajectory",
    "thesis_curve",
    "thesis_trajectory",
    "to_csv",
    "trajectory_curve",
]

