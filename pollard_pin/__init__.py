"""pollard-pin: a verified multibody model of the Pollard spray-painting parallel robot.

Public API (imported lazily, so ``pollard_pin.thesis`` stays free of Pinocchio)::

    robot = pollard_pin.load()                       # model, data, closures, geometry
    traj = pollard_pin.thesis_trajectory()           # spec §9 painting curve
    ik = pollard_pin.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
"""
from __future__ import annotations

import importlib

__version__ = "0.1.0"

_API = {
    "load": "model", "Robot": "model", "ACTUATED": "model", "PASSIVE": "model",
    "ModelFileError": "model", "constraint_residual": "model", "constraint_jacobian": "model",
    "load_params": "params", "Params": "params", "ParameterError": "params",
    "solve_closure": "kinematics", "forward_kinematics": "kinematics",
    "inverse_kinematics": "kinematics", "tool_pose": "kinematics", "IKResult": "kinematics",
    "ClosureError": "kinematics", "KinematicsError": "kinematics",
    "UnreachablePoseError": "kinematics", "SingularityError": "kinematics",
    "BranchFlipError": "kinematics",
    "Trajectory": "trajectory", "thesis_trajectory": "trajectory", "from_csv": "trajectory",
    "TrajectoryError": "trajectory", "smooth_random_trajectory": "trajectory",
    "run_pipeline": "outputs", "write_csv": "outputs", "RunResult": "outputs",
    "write_figures": "plots", "write_html": "viewer", "sizing_report": "report",
    "load_grid": "sweep", "make_sweep": "sweep", "run_sweep": "sweep",
    "evaluate_variant": "sweep", "SweepError": "sweep",
}

__all__ = sorted(_API)


def __getattr__(name: str):
    if name in _API:
        return getattr(importlib.import_module(f".{_API[name]}", __name__), name)
    raise AttributeError(f"module 'pollard_pin' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
