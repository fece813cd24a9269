"""The whole-trajectory run: IK, inverse dynamics and joint loads along a trajectory
(:func:`run_pipeline`), its named columns (:class:`RunResult`) and their table."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..io.table import write_table
from ..kinematics.ik import IkOptions, IKResult, inverse_kinematics
from ..kinematics.limits import check_joint_limits
from ..kinematics.margins import Margins
from ..names import SPHERICAL
from ..paths.trajectory import Trajectory


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
    its defaults) and ``method`` go to :func:`~pollard_pin.inverse_kinematics`.
    ``loads`` adds the joint loads of docs/model.md §17 (needs ``dynamics``).
    ``joint_limits``: refuse a sample with a joint outside its limits (the reach rule of
    ``workspace`` and ``paint``, kinematics.limits); False waives them."""
    from ..dynamics.inverse import inverse_dynamics

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
    """Write the result's columns (CSV, or Parquet for ``*.parquet``) through
    :mod:`pollard_pin.io.table`, atomically: a failed run never leaves a half-written file."""
    write_table(path, result.columns(), metadata)
