"""Streaming: solve and write a trajectory window by window (docs/model.md §15), in
overlapping windows, optionally in worker threads, each with its own Pinocchio data."""
from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks import callback, instance, shorten
from ..errors import InputError
from ..io.table import TableWriter
from ..kinematics.ik import BATCH_CHUNK
from ..model.build import check_robot
from ..paths.curves import ThesisTrajectory
from ..paths.trajectory import Trajectory
from .pipeline import run_pipeline
from .stats import RunStats

STREAM_CHUNK = BATCH_CHUNK  # samples per solve (overlap included): bounded memory
WRITE_ROWS = 1024  # rows written at once at least (smaller windows are held until then)


@dataclass(frozen=True)
class StreamOptions:
    """How :func:`~pollard_pin.stream_run` cuts and solves, checked once.

    Parameters
    ----------
    chunk : int, optional
        Samples per window (the overlap sample included), ≥ 2 (default 4096).
    workers : int, optional
        Solver threads, ≥ 1 (default 1).
    fmt : {"csv", "parquet"} or None, optional
        The table's format (None: from the file name).

    Raises
    ------
    pollard_pin.errors.InputError
        A chunk below 2 or a worker count below 1.
    """

    chunk: int = STREAM_CHUNK
    workers: int = 1
    fmt: str | None = None

    def __post_init__(self):
        if not (isinstance(self.chunk, int) and self.chunk >= 2):
            raise InputError(f"chunk must be an integer >= 2, got {shorten(self.chunk)}")
        if not (isinstance(self.workers, int) and self.workers >= 1):
            raise InputError(f"workers must be an integer >= 1, got {shorten(self.workers)}")


def _overlapping_windows(traj, size: int):
    """(start, window, skip): windows of ``size`` new samples; each after the first starts with
    the previous window's last sample (skip = 1), so that the pipeline sees every pair of
    consecutive samples (branch flips) and the cumulative work carries on."""
    last = None
    for start, win in traj.windows(size):
        if last is None:
            yield start, win, 0
        else:
            yield start, Trajectory(*(np.concatenate([a, b]) for a, b in zip(
                (last.t, last.poses, last.d_poses, last.dd_poses),
                (win.t, win.poses, win.d_poses, win.dd_poses))), win.name, win.derivatives), 1
        last = win.window(len(win) - 1, len(win))


def worker_robot(robot):
    """The same model with its own Pinocchio data (one per thread: ``Data`` is a workspace)."""
    import dataclasses

    return dataclasses.replace(robot, data=robot.model.createData(),
                               constraint_datas=[cm.createData()
                                                 for cm in robot.constraint_models])


def stream_options(stream) -> StreamOptions:
    """``stream`` when a :class:`StreamOptions`, its defaults for None; else one InputError
    line."""
    return instance(stream, "stream", StreamOptions, "StreamOptions or None",
                    none=True) or StreamOptions()


def solve_windows(robot, traj, stream: StreamOptions | None = None, **options):
    """Yield ``(start, result, columns)`` for the windows of ``traj`` in order: ``result`` the
    :class:`RunResult` of the window (overlap sample included), ``columns`` its output columns
    without the overlap sample, cumulative work carried across windows.

    ``stream``: :class:`StreamOptions` (default its defaults); ``options`` go to
    :func:`run_pipeline`. ``workers`` > 1 solves that many windows at once in threads, each
    with its own Pinocchio
    data (numpy and LAPACK release the GIL, so this uses the cores); at most ``workers + 1``
    windows are in flight, so memory stays bounded. An error is raised at its window, in order,
    with sample numbers counted from the trajectory's start."""
    import threading
    from collections import deque
    from concurrent.futures import ThreadPoolExecutor
    from itertools import islice

    from ..kinematics.errors import SAMPLE_ERRORS

    stream = stream_options(stream)
    chunk, workers = stream.chunk, stream.workers
    local = threading.local()

    def solve(item):
        start, win, skip = item
        if workers > 1 and not hasattr(local, "robot"):
            local.robot = worker_robot(robot)
        try:
            result = run_pipeline(getattr(local, "robot", robot), win, **options)
        except SAMPLE_ERRORS as exc:  # the solve's errors and the input's say where
            raise exc.shifted(start - skip) from None
        cols = result.columns()
        return start, result, {k: v[skip:] for k, v in cols.items()} if skip else cols

    # windows of chunk − 1 new samples: with the overlap sample, one IK block each
    items = _overlapping_windows(traj, chunk - 1)
    work = None
    with ThreadPoolExecutor(workers) if workers > 1 else _Inline() as pool:
        pending = deque(pool.submit(solve, item) for item in islice(items, workers + 1))
        while pending:
            start, result, cols = pending.popleft().result()
            nxt = next(items, None)
            if nxt is not None:
                pending.append(pool.submit(solve, nxt))
            if work:
                for k, w in work.items():
                    cols[k] = cols[k] + w
            work = {k: v[-1] for k, v in cols.items() if k.startswith("work_")}
            yield start, result, cols


class _Inline:
    """A pool of no threads: ``submit`` runs at once (``workers=1``, the plain loop)."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return None

    @staticmethod
    def submit(fn, *args):
        from concurrent.futures import Future

        future = Future()
        try:
            future.set_result(fn(*args))
        except BaseException as exc:  # re-raised by .result(), in order
            future.set_exception(exc)
        return future


def stream_run(robot, traj, path: str | Path, stream: StreamOptions | None = None, *,
               metadata: dict | None = None, progress=None, timings: dict | None = None,
               **options) -> RunStats:
    """Solve ``traj`` window by window and write each window's columns to ``path`` as it is
    done (windows of fewer than WRITE_ROWS rows held until that many); memory stays that of a
    few windows. What ``pollard-pin run`` does.

    The same rows as ``write_run_table(run_pipeline(robot, traj, **options), path)``
    (``workers`` threads solve while this thread writes). Errors count samples from the
    trajectory's start; the file appears only if every window is solved (atomic).

    Parameters
    ----------
    robot : Robot
        The model.
    traj : Trajectory or ThesisTrajectory
        The tool path; a :class:`~pollard_pin.paths.ThesisTrajectory` is never held whole.
    path : str or pathlib.Path
        The table to write (CSV or Parquet).
    stream : StreamOptions or None, optional
        Window size, threads and table format.
    metadata : dict or None, optional
        More metadata to store with the table.
    progress : Callable or None, optional
        ``progress(done, total)`` after each window.
    timings : dict or None, optional
        Gets ``wall`` (solving and writing) and ``write`` (this thread's writing, overlapped
        with the solving) seconds.
    **options
        Passed to :func:`~pollard_pin.run_pipeline` (``dynamics``, ``loads``, ``margins``,
        ``method``, ``joint_limits``).

    Returns
    -------
    pollard_pin.run.stats.RunStats
        The summary figures (peaks, margins, works), accumulated without keeping the samples.

    Raises
    ------
    KinematicsError
        A sample the kinematics cannot solve (its number counted from the trajectory's
        start); nothing is written.
    KinematicsInputError
        A sample the kinematics cannot take (numbered the same way); nothing is written.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> from pollard_pin.paths import ThesisTrajectory
    >>> stats = pp.stream_run(pp.load(), ThesisTrajectory(samples=10_001), "big.csv",
    ...                       pp.StreamOptions(chunk=4096, workers=2))
    >>> stats.samples, len(pp.read_result("big.csv"))
    (10001, 10001)
    """
    check_robot(robot)
    instance(traj, "traj", (Trajectory, ThesisTrajectory), "a Trajectory (or the lazy thesis "
             "curve)")
    callback(progress, "progress")
    instance(metadata, "metadata", dict, "a dict or None", none=True)
    timings = {} if timings is None else timings
    stream = stream_options(stream)
    stats = RunStats(traj.name, traj.derivatives)
    n = len(traj)
    write = 0.0
    held: list[dict] = []  # small windows' columns, written together (one write per window
    # costs ≈ 1 ms whatever its rows)

    def flush():
        nonlocal write
        t1 = time.perf_counter()
        writer.write(held[0] if len(held) == 1 else
                     {k: np.concatenate([c[k] for c in held]) for k in held[0]})
        write += time.perf_counter() - t1
        held.clear()

    with TableWriter(path, metadata, stream.fmt) as writer:  # imports its library: not timed
        t0 = time.perf_counter()
        for start, result, cols in solve_windows(robot, traj, stream, **options):
            stats.add(result.ik, cols)
            held.append(cols)
            if sum(len(c["t"]) for c in held) >= WRITE_ROWS:
                flush()
            if progress is not None:
                progress(min(start + stream.chunk - 1, n), n)
        if held:
            flush()
    timings["wall"] = timings.get("wall", 0.0) + time.perf_counter() - t0
    timings["write"] = timings.get("write", 0.0) + write
    return stats


