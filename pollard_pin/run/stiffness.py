"""Stiffness and vibration along a trajectory (docs/model.md §27): the closed-loop IK window by
window, then the deflection, natural frequencies and kmin of each sample, whole
(:func:`stiffness`) or streamed to a table (:func:`stream_stiffness`) in bounded memory."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..checks import instance
from ..dynamics.drives.stiffness import (
    DEFLECTION,
    FREQUENCIES,
    UNITS,
    StiffnessOptions,
    StiffnessResult,
    check_linear,
    check_stiffness,
    stiffness_at,
)
from ..io.table import TableWriter, write_table
from ..kinematics.margins import Margins
from ..model.build import check_robot
from ..paths.curves import ThesisTrajectory
from ..paths.trajectory import Trajectory
from .stream import StreamOptions, solve_windows


class StiffnessRun(StiffnessResult):
    """:class:`~pollard_pin.dynamics.drives.stiffness.StiffnessResult` along a trajectory, with the
    table writer of ``pollard-pin stiffness`` (:meth:`write`).

    Attributes
    ----------
    t : numpy.ndarray
        (N,) the samples' times [s].
    deflection : numpy.ndarray
        (N, 6) dx, dy, dz [m] and rx, ry, rz [rad], world axes.
    frequencies : numpy.ndarray
        (N, 6) the natural frequencies [Hz], ascending.
    kmin : numpy.ndarray
        (N,) the tip's stiffness in its softest direction [N/m].
    turn : numpy.ndarray
        (N,) the largest drive turn [rad] (at most the linear model's bound: refused beyond).
    """

    def write(self, path: str | Path, metadata: dict | None = None) -> None:
        """The table (CSV with its units sidecar, or Parquet for ``*.parquet``), all or
        nothing."""
        write_table(path, self.columns(), metadata)


def drive_stiffness(drives) -> np.ndarray:
    """k (6,) [N·m/rad] from an :class:`~pollard_pin.dynamics.motors.Actuators` (its
    ``stiffness()`` names the first actuator without one) or six numbers."""
    return check_stiffness(drives.stiffness() if hasattr(drives, "stiffness") else drives)


def stiffness_windows(robot, traj, drives, options: StiffnessOptions | None = None,
                      stream: StreamOptions | None = None, *, margins: Margins | None = None,
                      joint_limits: bool = True):
    """Yield ``(start, StiffnessResult)`` window by window along ``traj`` (a
    :class:`~pollard_pin.paths.trajectory.Trajectory` or the lazy thesis curve). The IK and
    its checks are ``run``'s (errors name the sample counted from the start); ``drives``: see
    :func:`drive_stiffness`. A drive turned beyond the linear model's bound is refused,
    naming the sample (:func:`~pollard_pin.dynamics.drives.stiffness.check_linear`)."""
    check_robot(robot)
    instance(traj, "traj", (Trajectory, ThesisTrajectory), "a Trajectory (or the lazy thesis "
             "curve)")
    k = drive_stiffness(drives)
    options = instance(options, "options", StiffnessOptions, "StiffnessOptions or None",
                       none=True) or StiffnessOptions()
    instance(margins, "margins", Margins, "Margins or None", none=True)
    for start, result, cols in solve_windows(robot, traj, stream, dynamics=False,
                                             margins=margins, joint_limits=joint_limits):
        m = len(cols["t"])  # the window without its overlap sample
        r = stiffness_at(robot, result.ik.q[-m:], k, options, t=cols["t"])
        check_linear(r.turn, r.t, start)
        yield start, r


def stiffness(robot, traj, drives, options: StiffnessOptions | None = None, *,
              margins: Margins | None = None, joint_limits: bool = True) -> StiffnessRun:
    """Deflection under ``options.wrench`` plus the weight, the six natural frequencies and
    kmin at every sample of ``traj`` (docs/model.md §27): what ``pollard-pin stiffness``
    computes; ``result.write(path)`` writes its table.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    traj : Trajectory
        The tool's path (a :class:`~pollard_pin.paths.trajectory.Trajectory` or the lazy
        thesis curve); the IK and its checks are ``run``'s.
    drives : Actuators or ArrayLike
        An :class:`~pollard_pin.dynamics.motors.Actuators` whose every actuator has a
        ``stiffness``, or six stiffnesses k [N·m/rad], docs/model.md §6 order.
    options : StiffnessOptions or None, optional
        The wrench on the tool (default none: the weight alone).
    margins : Margins or None, optional
        The IK's singularity margins (default ``run``'s).
    joint_limits : bool, optional
        Check the joint limits (default True).

    Returns
    -------
    StiffnessRun
        Per sample the deflection [m, rad], the frequencies [Hz] and kmin [N/m].

    Raises
    ------
    StiffnessError
        A stiffness missing, not finite or not positive (naming the actuator or the key); a
        drive turned beyond the linear model's bound, naming the sample.
    KinematicsError
        A pose out of reach or singular, naming the sample (as ``run``).
    """
    parts = [r for _, r in stiffness_windows(robot, traj, drives, options, margins=margins,
                                             joint_limits=joint_limits)]
    return StiffnessRun(*(np.concatenate([getattr(p, f) for p in parts])
                             for f in ("t", "deflection", "frequencies", "kmin", "turn")))


@dataclass
class StiffnessStats:
    """The worst sample of each column seen so far: the largest |deflection| component, the
    lowest of each frequency and the lowest kmin, as (value, sample, t)."""

    samples: int = 0
    worst: dict = field(default_factory=dict)

    def add(self, start: int, result: StiffnessResult) -> None:
        cols = result.columns()
        for name in (*DEFLECTION, *FREQUENCIES, "kmin"):
            x = cols[name]
            k = int(np.argmax(np.abs(x))) if name in DEFLECTION else int(np.argmin(x))
            value = float(x[k])
            best = self.worst.get(name)
            if best is None or _worse(name, value, best[0]):
                self.worst[name] = (value, start + k, float(result.t[k]))
        self.samples += len(result)

    def summary(self) -> str:
        lines = [f"{self.samples} samples; the worst of each (value, sample, t):"]
        for name, (value, k, t) in self.worst.items():
            scale, unit = (1e6, "µm") if UNITS[name] == "m" else (
                (1e3, "mrad") if UNITS[name] == "rad" else (1.0, UNITS[name]))
            lines.append(f"  {name:5s} {scale * value:12.5g} {unit:5s} sample {k} "
                         f"(t = {t:.6g} s)")
        return "\n".join(lines)


def _worse(name: str, value: float, old: float) -> bool:
    if name in DEFLECTION:
        return abs(value) > abs(old)
    return value < old or math.isnan(value)


def stream_stiffness(robot, traj, drives, path: str | Path,
                     options: StiffnessOptions | None = None,
                     stream: StreamOptions | None = None, *, metadata: dict | None = None,
                     timings: dict | None = None, progress=None, **ik_options
                     ) -> StiffnessStats:
    """:func:`stiffness` written window by window to ``path``, all or nothing; memory stays
    that of a few windows (10⁶ samples in bounded memory).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    traj : Trajectory
        The tool's path, as for :func:`stiffness`.
    drives : Actuators or ArrayLike
        As for :func:`stiffness`: stiffnesses k [N·m/rad].
    path : str or pathlib.Path
        The table: CSV with its units sidecar, or Parquet for ``*.parquet``.
    options : StiffnessOptions or None, optional
        The wrench on the tool (default none).
    stream : StreamOptions or None, optional
        The window size (default ``run``'s).
    metadata : dict or None, optional
        Extra entries for the table's metadata.
    timings : dict or None, optional
        Filled with ``wall`` [s].
    progress : Callable or None, optional
        Called with (done, total) samples.
    **ik_options
        ``margins``, ``joint_limits``, as for :func:`stiffness`.

    Returns
    -------
    StiffnessStats
        The worst sample of each column: ``worst[name]`` = (value, sample, t);
        ``summary()`` is what the command prints.

    Raises
    ------
    StiffnessError
        A stiffness missing or invalid; a drive turned beyond the linear model's bound, naming
        the sample; nothing is written.
    KinematicsError
        A pose out of reach or singular, naming the sample; nothing is written.
    """
    timings = {} if timings is None else timings
    stream = StreamOptions() if stream is None else stream
    drives = drive_stiffness(drives)  # before any file is opened
    stats = StiffnessStats()
    n = len(traj)
    with TableWriter(path, metadata, stream.fmt) as writer:
        t0 = time.perf_counter()
        for start, result in stiffness_windows(robot, traj, drives, options, stream,
                                               **ik_options):
            stats.add(start, result)
            writer.write(result.columns())
            if progress is not None:
                progress(min(start + len(result), n), n)
    timings["wall"] = timings.get("wall", 0.0) + time.perf_counter() - t0
    return stats
