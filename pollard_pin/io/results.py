"""Run a trajectory through the pipeline and turn the results into named columns / CSV."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .atomic import atomic_open
from ..kinematics.pipeline import SPHERICAL, IKResult, inverse_kinematics
from ..kinematics.taskspace import TASK_NAMES
from .trajectory import Trajectory


@dataclass
class RunResult:
    trajectory: Trajectory
    ik: IKResult
    dynamics: object | None = None  # dynamics.DynamicsResult once computed

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
        return cols


def run_pipeline(robot, traj: Trajectory, progress=None, dynamics: bool = True,
                 **ik_options) -> RunResult:
    """IK (and inverse dynamics) along a trajectory. ``ik_options`` go to
    :func:`~pollard_pin.kinematics.inverse_kinematics` (margins, ``tol``, ``method``)."""
    from ..dynamics.inverse import inverse_dynamics

    ik = inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                            progress=progress, **ik_options)
    return RunResult(traj, ik, inverse_dynamics(robot, ik) if dynamics else None)


def write_csv(result: RunResult, path: str | Path) -> None:
    """Write atomically: a failed run never leaves a half-written file behind."""
    cols = result.columns()
    with atomic_open(path) as f:
        np.savetxt(f, np.column_stack(list(cols.values())), delimiter=",",
                   header=",".join(cols), comments="", fmt="%.17g")


def summary(result: RunResult, wall: float) -> str:
    ik = result.ik
    lines = [
        f"trajectory {result.trajectory.name}: {len(ik)} samples over {ik.t[-1] - ik.t[0]:.4g} s"
        f" (derivatives: {result.trajectory.derivatives})",
        f"max closure residual {ik.closure_residual.max():.3g} m, "
        f"max tool-pose error {ik.tool_error.max():.3g}",
        f"wrist margin |sin θ1716| in [{ik.wrist_margin.min():.4f}, {ik.wrist_margin.max():.4f}]"
        f" (θ1716 in [{np.degrees(np.arcsin(ik.wrist_margin.min())):.2f}°, "
        f"{np.degrees(np.arcsin(ik.wrist_margin.max())):.2f}°])",
        f"worst conditioning: σ_min parallel {ik.sigma_parallel.min():.4g}, "
        f"serial {ik.sigma_serial.min():.4g}",
    ]
    if result.dynamics is not None:
        lines += result.dynamics.summary_lines()
    lines.append(f"wall time {wall:.3f} s ({1e6 * wall / len(ik):.1f} µs/sample)")
    return "\n".join(lines)
