"""Run a trajectory through the pipeline and turn the results into named columns / CSV."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .analytic.taskspace import TASK_NAMES
from .dynamics.averages import time_mean, time_rms
from .io.table import TableWriter, write_table
from .kinematics.ik import BATCH_CHUNK, IKResult, inverse_kinematics
from .kinematics.limits import check_joint_limits
from .kinematics.margins import Margins
from .model.names import SPHERICAL
from .paths.trajectory import Trajectory


@dataclass
class RunResult:
    trajectory: Trajectory
    ik: IKResult
    dynamics: object | None = None  # dynamics.DynamicsResult once computed
    loads: object | None = None  # dynamics.loads.JointLoads (run --loads, docs/model.md §17)

    def columns(self) -> dict[str, np.ndarray]:
        """Every output column by name, SI units and radians (the ``run`` CSV layout)."""
        ik, names = self.ik, self.ik.joint_names
        cols = {"t": ik.t}
        cols.update({n: ik.poses[:, i] for i, n in enumerate(TASK_NAMES)})
        cols.update({n: ik.q[:, i] for i, n in enumerate(names)})
        cols.update({n: ik.spherical[:, i] for i, n in enumerate(SPHERICAL)})
        cols.update({f"d_{n}": ik.v[:, i] for i, n in enumerate(names)})
        cols.update({f"d_{n}": ik.d_spherical[:, i] for i, n in enumerate(SPHERICAL)})
        cols.update({f"dd_{n}": ik.a[:, i] for i, n in enumerate(names)})
        cols.update({"closure_residual": ik.closure_residual, "wrist_margin": ik.wrist_margin,
                     "sigma_parallel": ik.sigma_parallel, "sigma_serial": ik.sigma_serial})
        if self.dynamics is not None:
            cols.update(self.dynamics.columns())
        if self.loads is not None:
            cols.update(self.loads.columns())
        return cols


def run_pipeline(robot, traj: Trajectory, progress=None, dynamics: bool = True,
                 loads: bool = False, *, margins: Margins | None = None,
                 method: str | None = None, joint_limits: bool = True) -> RunResult:
    """IK (and inverse dynamics) along a trajectory: ``margins`` (:class:`Margins`, default
    its defaults) and ``method`` go to :func:`~pollard_pin.kinematics.inverse_kinematics`.
    ``loads`` adds the joint loads of docs/model.md §17 (needs ``dynamics``).
    ``joint_limits``: refuse a sample with a joint outside its limits (the reach rule of
    ``workspace`` and ``paint``, kinematics.limits); False waives them."""
    from .dynamics.inverse import inverse_dynamics

    ik = inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                            progress=progress, margins=margins, method=method)
    if joint_limits:
        check_joint_limits(robot, ik.q, ik.t)
    dyn = inverse_dynamics(robot, ik) if dynamics or loads else None
    if not loads:
        return RunResult(traj, ik, dyn if dynamics else None)
    from .dynamics.loads import joint_loads

    return RunResult(traj, ik, dyn, joint_loads(robot, ik, dyn))


def write_run_table(result: RunResult, path: str | Path, metadata: dict | None = None) -> None:
    """Write the result's columns (CSV, or Parquet for ``*.parquet``) through
    :mod:`pollard_pin.io.table`, atomically: a failed run never leaves a half-written file."""
    write_table(path, result.columns(), metadata)


# --- streaming: solve and write window by window (docs/model.md §15) ------------------------
STREAM_CHUNK = BATCH_CHUNK  # samples per solve (overlap included): bounded memory
_PEAK = ("tau_", "power_")


@dataclass
class RunStats:
    """What the summary needs, accumulated window by window (nothing per sample is kept)."""

    name: str
    derivatives: str
    samples: int = 0
    t_first: float = math.nan
    t_last: float = math.nan
    closure_residual: float = 0.0
    tool_error: float = 0.0
    wrist: tuple[float, float] = (math.inf, -math.inf)
    sigma_parallel: float = math.inf
    sigma_serial: float = math.inf
    actuated: tuple[str, ...] = ()
    peak: dict = field(default_factory=dict)  # column → max |value|
    work: dict = field(default_factory=dict)  # work column → last value
    closure_force: list = field(default_factory=lambda: [0.0, 0.0])
    joint_load: dict = field(default_factory=dict)  # joint → [peak |F| N, peak |M| N·m]

    def add(self, ik: IKResult, cols: dict) -> None:
        n = len(cols["t"])
        if not n:
            return
        skip = len(ik) - n  # the overlap sample of a window is counted once
        if not self.samples:
            self.t_first = float(cols["t"][0])
        self.samples += n
        self.t_last = float(cols["t"][-1])
        self.closure_residual = max(self.closure_residual, float(cols["closure_residual"].max()))
        self.tool_error = max(self.tool_error, float(ik.tool_error[skip:].max()))
        w = cols["wrist_margin"]
        self.wrist = (min(self.wrist[0], float(w.min())), max(self.wrist[1], float(w.max())))
        self.sigma_parallel = min(self.sigma_parallel, float(cols["sigma_parallel"].min()))
        self.sigma_serial = min(self.sigma_serial, float(cols["sigma_serial"].min()))
        for name, col in cols.items():
            if name.startswith(_PEAK):
                self.peak[name] = max(self.peak.get(name, 0.0), float(np.abs(col).max()))
            elif name.startswith("work_"):
                self.work[name] = float(col[-1])
        for i in range(2):
            if f"f{i + 1}_x" in cols:
                self.closure_force[i] = max(self.closure_force[i], _peak_norm(cols, f"f{i + 1}"))
        for name in cols:  # run --loads: F_<joint>_x … M_<joint>_z (docs/model.md §17)
            if name.startswith("F_") and name.endswith("_x"):
                joint = name[2:-2]
                peak = self.joint_load.setdefault(joint, [0.0, 0.0])
                for i, kind in enumerate("FM"):
                    peak[i] = max(peak[i], _peak_norm(cols, f"{kind}_{joint}"))
        if not self.actuated:
            self.actuated = tuple(c[4:] for c in cols if c.startswith("tau_"))

    def lines(self) -> list[str]:
        wmin, wmax = self.wrist
        lines = [
            f"trajectory {self.name}: {self.samples} samples over "
            f"{self.t_last - self.t_first:.4g} s (derivatives: {self.derivatives})",
            f"max closure residual {self.closure_residual:.3g} m, "
            f"max tool-pose error {self.tool_error:.3g}",
            f"wrist margin |sin θ1716| in [{wmin:.4f}, {wmax:.4f}] "
            f"(θ1716 in [{math.degrees(math.asin(wmin)):.2f}°, "
            f"{math.degrees(math.asin(wmax)):.2f}°])",
            f"worst conditioning: σ_min parallel {self.sigma_parallel:.4g}, "
            f"serial {self.sigma_serial:.4g}",
        ]
        if self.actuated:
            lines.append("actuator        peak |τ| [N·m]   peak |power| [W]   net work [J]")
            for n in self.actuated:
                lines.append(f"  {n:12s} {self.peak[f'tau_{n}']:14.5g} "
                             f"{self.peak[f'power_{n}']:18.5g} {self.work[f'work_{n}']:14.5g}")
            f = self.closure_force
            lines.append(f"peak closure force: leg 1 {f[0]:.4g} N, leg 2 {f[1]:.4g} N")
        if self.joint_load:
            lines.append("joint          peak |force| [N]  peak |moment| [N·m]  (pollard-pin "
                         "report: axial/radial/bending)")
            for joint, (fmax, mmax) in self.joint_load.items():
                lines.append(f"  {joint:12s} {fmax:16.5g} {mmax:20.5g}")
        return lines


def _peak_norm(cols: dict, stem: str) -> float:
    """Largest magnitude of the vector columns ``<stem>_x``, ``_y``, ``_z``."""
    return float(np.sqrt(sum(cols[f"{stem}_{c}"] ** 2 for c in "xyz")).max())


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


def solve_windows(robot, traj, *, chunk: int = STREAM_CHUNK, workers: int = 1, **options):
    """Yield ``(start, result, columns)`` for the windows of ``traj`` in order: ``result`` the
    :class:`RunResult` of the window (overlap sample included), ``columns`` its output columns
    without the overlap sample, cumulative work carried across windows.

    ``workers`` > 1 solves that many windows at once in threads, each with its own Pinocchio
    data (numpy and LAPACK release the GIL, so this uses the cores); at most ``workers + 1``
    windows are in flight, so memory stays bounded. An error is raised at its window, in order,
    with sample numbers counted from the trajectory's start."""
    import threading
    from collections import deque
    from concurrent.futures import ThreadPoolExecutor
    from itertools import islice

    from .kinematics.errors import KinematicsError

    if not (isinstance(chunk, int) and chunk >= 2):
        raise ValueError(f"chunk must be an integer >= 2, got {chunk!r}")
    if not (isinstance(workers, int) and workers >= 1):
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    local = threading.local()

    def solve(item):
        start, win, skip = item
        if workers > 1 and not hasattr(local, "robot"):
            local.robot = worker_robot(robot)
        try:
            result = run_pipeline(getattr(local, "robot", robot), win, **options)
        except KinematicsError as exc:
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


def stream_run(robot, traj, path: str | Path, *, chunk: int = STREAM_CHUNK, workers: int = 1,
               metadata: dict | None = None, fmt: str | None = None, progress=None,
               timings: dict | None = None, **options) -> RunStats:
    """Solve ``traj`` (a :class:`Trajectory` or :class:`ThesisTrajectory`) window by window and
    write each window's columns to ``path`` as it is done; memory stays that of a few windows.

    The same rows as ``write_run_table(run_pipeline(robot, traj, **options), path)`` (see
    :func:`solve_windows`; ``workers`` threads solve while this thread writes). Errors count
    samples from the trajectory's start; the file appears only if every window is solved
    (atomic). ``options`` go to :func:`run_pipeline`; ``timings`` gets ``wall`` (solving and
    writing) and ``write`` (this thread's writing, overlapped with the solving) seconds.
    """
    timings = {} if timings is None else timings
    stats = RunStats(traj.name, traj.derivatives)
    n = len(traj)
    write = 0.0
    with TableWriter(path, metadata, fmt) as writer:  # imports its library: not timed
        t0 = time.perf_counter()
        for start, result, cols in solve_windows(robot, traj, chunk=chunk, workers=workers,
                                                 **options):
            stats.add(result.ik, cols)
            t1 = time.perf_counter()
            writer.write(cols)
            write += time.perf_counter() - t1
            if progress is not None:
                progress(min(start + chunk - 1, n), n)
    timings["wall"] = timings.get("wall", 0.0) + time.perf_counter() - t0
    timings["write"] = timings.get("write", 0.0) + write
    return stats


def summary(result: RunResult | RunStats) -> str:
    """The run's summary text."""
    if isinstance(result, RunResult):
        stats = RunStats(result.trajectory.name, result.trajectory.derivatives)
        stats.add(result.ik, result.columns())
    else:
        stats = result
    return "\n".join(stats.lines())


def run_sizing(columns: dict, actuated) -> dict:
    """Sizing figures (peaks, time-weighted RMS, energy) from run columns
    (:meth:`RunResult.columns` or a ``run`` CSV read back)."""
    t = np.asarray(columns["t"], dtype=float)
    acts = {}
    for n in actuated:
        tau, qd = np.asarray(columns[f"tau_{n}"]), np.asarray(columns[f"d_{n}"])
        p = np.asarray(columns[f"power_{n}"])
        acts[n] = {
            "peak_torque": float(np.max(np.abs(tau))),
            "rms_torque": float(time_rms(t, tau)),
            "peak_speed": float(np.max(np.abs(qd))),
            "peak_power": float(np.max(np.abs(p))),
            "energy": float((t[-1] - t[0]) * time_mean(t, np.abs(p))),
            "net_work": float(np.asarray(columns[f"work_{n}"])[-1]),
        }
    joints = {}
    for i in (1, 2):  # the two spherical joints (closures), docs/model.md §8
        f = np.sqrt(sum(np.square(np.asarray(columns[f"f{i}_{c}"])) for c in "xyz"))
        k = int(np.argmax(f))
        joints[f"spherical_{i}"] = {"peak_force": float(f[k]), "peak_time": float(t[k]),
                                    "rms_force": float(time_rms(t, f))}
    return {"actuators": acts, "spherical_joints": joints}
