"""The whole-trajectory run: IK, inverse dynamics and joint loads along a trajectory
(:func:`run_pipeline`), its named columns (:class:`RunResult`) and their table."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..checks import instance
from ..errors import InputError
from ..io.table import write_table
from ..kinematics.ik import IkOptions, IKResult, inverse_kinematics
from ..kinematics.limits import check_joint_limits
from ..kinematics.margins import Margins
from ..names import SPHERICAL
from ..paths.trajectory import Trajectory


@dataclass
class RunResult:
    """A whole-trajectory run, from :func:`~pollard_pin.run_pipeline`.

    Attributes
    ----------
    trajectory : Trajectory
        The input trajectory.
    ik : IKResult
        The joint motion and the singularity margins at each sample.
    dynamics : pollard_pin.dynamics.inverse.DynamicsResult or None
        Actuator torques, closure forces, powers and energies (None with
        ``dynamics=False``).
    loads : JointLoads or None
        The joint loads of docs/model.md §17 (``loads=True`` only).

    :meth:`columns` is every output column by name (the ``run`` CSV layout);
    :func:`~pollard_pin.write_run_table` writes them.
    """

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
    """IK (and inverse dynamics) along a trajectory: what ``pollard-pin run`` computes.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    traj : Trajectory
        The tool path (:func:`~pollard_pin.thesis_trajectory`,
        :func:`~pollard_pin.from_csv`, ...).
    progress : Callable or None, optional
        ``progress(done, total)`` as the IK solves samples.
    dynamics : bool, optional
        Also solve the inverse dynamics (default True).
    loads : bool, optional
        Also compute the joint loads of docs/model.md §17 (default False).
    margins : Margins or None, optional
        How close to a singularity a sample may come (default :class:`~pollard_pin.Margins`'
        defaults); with ``method``, passed to :func:`~pollard_pin.inverse_kinematics`.
    method : {"batch", "newton"} or None, optional
        The IK method (default batch).
    joint_limits : bool, optional
        Refuse a sample with a joint outside its limits (default True, the reach rule of
        ``workspace`` and ``paint``); False waives them.

    Returns
    -------
    RunResult
        The trajectory, its IK and (unless ``dynamics=False``) its dynamics and loads.

    Raises
    ------
    InputError
        ``traj`` is not a :class:`~pollard_pin.paths.trajectory.Trajectory`; ``dynamics``,
        ``loads`` or ``joint_limits`` is not a bool.
    KinematicsError
        A sample the kinematics cannot solve: out of reach, too close to a singularity, a
        branch flip, a joint out of its limits (the message names the sample, time and
        chain or joint).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> result = pp.run_pipeline(robot, pp.thesis_trajectory(samples=101))
    >>> result.dynamics.tau.shape, len(result.columns())
    ((101, 6), 85)
    """
    from ..dynamics.inverse import inverse_dynamics

    if not isinstance(traj, Trajectory):
        raise InputError(f"run_pipeline: traj is {type(traj).__name__}, not a Trajectory "
                         "(pollard_pin.thesis_trajectory, from_csv, …)")
    for flag, value in (("dynamics", dynamics), ("loads", loads), ("joint_limits", joint_limits)):
        instance(value, flag, bool, "True or False")  # "no" is truthy: a flag is a real bool
    ik = inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                            options=IkOptions(method=method, margins=margins),
                            progress=progress)
    if joint_limits:
        check_joint_limits(robot, ik.q, ik.t)
    dyn = inverse_dynamics(robot, ik) if dynamics or loads else None
    if not loads:
        return RunResult(traj, ik, dyn if dynamics else None)
    from ..dynamics.loads import joint_loads

    return RunResult(traj, ik, dyn, joint_loads(robot, ik, dyn))


def write_run_table(result: RunResult, path: str | Path, metadata: dict | None = None) -> None:
    """Write the result's columns (CSV, or Parquet for ``*.parquet``), atomically: a failed
    run never leaves a half-written file. What ``pollard-pin run --out`` writes.

    Parameters
    ----------
    result : RunResult
        From :func:`~pollard_pin.run_pipeline`.
    path : str or pathlib.Path
        ``*.csv`` (units and metadata in a ``.units.json`` sidecar) or ``*.parquet`` (inside).
    metadata : dict or None, optional
        More metadata to store with the table.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> result = pp.run_pipeline(pp.load(), pp.thesis_trajectory(samples=11))
    >>> pp.write_run_table(result, "run.csv")
    >>> open("run.csv").readline().split(",")[:4]
    ['t', 'x', 'y', 'z']
    """
    instance(result, "result", RunResult, "a RunResult (pollard_pin.run_pipeline)")
    write_table(path, result.columns(), metadata)
