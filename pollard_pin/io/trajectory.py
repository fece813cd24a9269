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
PARQUET_MAGIC = b"PAR1"  # the first (and last) four bytes of every Parquet file


# The paint gun's trigger: the fraction of its flow sprayed, in [0, 1] (absent: 1 throughout).
SPRAY = "spray"


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
        with open(path, "rb") as f:
            magic = f.read(4)
        with open(path, newline="", encoding="utf-8-sig") as f:  # -sig: a BOM is no column
            reader = csv.reader(f)
            rows, lines = [], []  # lines: 1-based file line of each kept row
            for r in reader:
                if r and not r[0].lstrip().startswith("#"):
                    rows.append(r)
                    lines.append(reader.line_num)
    except OSError as exc:
        raise TrajectoryError(f"cannot read trajectory file {str(path)!r}: "
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
    allowed = (base + tuple(f"d_{n}" for n in TASK_NAMES) + tuple(f"dd_{n}" for n in TASK_NAMES)
               + (SPRAY,))
    for h in header:
        if h not in allowed:
            raise TrajectoryError(f"{path}: unknown column {h!r}{did_you_mean(h, allowed)}; "
                                  f"expected {', '.join(base)} and optional d_*, dd_*, "
                                  f"{SPRAY}")
    if len(set(header)) != len(header):
        raise TrajectoryError(f"{path}: duplicate column names in header {header}")
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
                data[r, c] = float(cell)
            except ValueError:
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"{cell!r} is not a number") from None
            if not math.isfinite(data[r, c]):
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"value {cell!r} is not finite")
    if len(data) < 2:
        raise TrajectoryError(f"{path}: need at least 2 samples, found {len(data)}")
    col = {h: data[:, i] for i, h in enumerate(header)}
    if SPRAY in col:  # the gun's trigger (paint): the motion does not depend on it
        bad = (col[SPRAY] < 0) | (col[SPRAY] > 1)
        if bad.any():
            r = int(np.argmax(bad))
            raise TrajectoryError(f"{path}: row {lines[r + 1]}, column {SPRAY!r}: "
                                  f"{float(col[SPRAY][r])!r} is outside [0, 1] (the fraction "
                                  "of the gun's flow)")
    t = col["t"]
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
    return Trajectory(t, poses, derivs[0], derivs[1], name=path.stem, derivatives=source,
                      curve=curve)


def to_csv(traj: Trajectory, path: str | Path, spray=None) -> None:
    """Write the trajectory in the ``run`` input format (``t``, poses, ``d_*``, ``dd_*``; every
    float64 exact) through :mod:`pollard_pin.io.table`, atomically, units in the sidecar;
    ``spray`` (N,): the gun's trigger in [0, 1] as a last column (absent: on throughout)."""
    from .table import write_table

    cols = {"t": traj.t}
    for prefix, arr in (("", traj.poses), ("d_", traj.d_poses), ("dd_", traj.dd_poses)):
        cols.update({prefix + n: arr[:, i] for i, n in enumerate(TASK_NAMES)})
    if spray is not None:
        cols[SPRAY] = np.asarray(spray, dtype=float)
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
    "from_csv",
    "sinusoid_curve",
    "smooth_random_trajectory",
    "thesis_curve",
    "thesis_trajectory",
    "to_csv",
    "trajectory_curve",
]

