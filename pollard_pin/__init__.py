"""pollard-pin: a verified multibody model of the Pollard spray-painting parallel robot.

Public API (imported lazily: ``pollard_pin.analytic.closed_form`` and
``pollard_pin.crosscheck.euler_lagrange`` stay free of Pinocchio)::

    robot = pollard_pin.load()                       # model, data, closures, geometry
    traj = pollard_pin.thesis_trajectory()           # docs/model.md §9 painting curve
    ik = pollard_pin.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    result = pollard_pin.paint(robot, pollard_pin.load_job("examples/paint.toml"))
    result.write("out", "csv")                       # what ``pollard-pin paint`` writes
"""
from __future__ import annotations

import importlib

from .version import __version__ as __version__

_API = {
    "load": "model.build", "Robot": "model.build", "ACTUATED": "model.build",
    "PASSIVE": "model.build", "ModelFileError": "model.build",
    "constraint_residual": "model.build", "constraint_jacobian": "model.build",
    "load_params": "model.params", "Params": "model.params", "ParameterError": "model.params",
    "solve_closure": "kinematics.closure", "forward_kinematics": "kinematics.closure",
    "tool_pose": "kinematics.closure",
    "inverse_kinematics": "kinematics.ik", "IKResult": "kinematics.ik",
    "IkOptions": "kinematics.ik",
    "Margins": "kinematics.margins", "MarginError": "kinematics.margins",
    "ClosureError": "kinematics.errors", "KinematicsError": "kinematics.errors",
    "UnreachablePoseError": "kinematics.errors", "SingularityError": "kinematics.errors",
    "BranchFlipError": "kinematics.errors",
    "inverse_dynamics": "dynamics.inverse", "forward_dynamics": "dynamics.forward",
    "replay_open_loop": "dynamics.forward", "joint_loads": "dynamics.loads",
    "simulate_tracking": "dynamics.tracking", "desired_trajectory": "dynamics.control",
    "ComputedTorque": "dynamics.control", "FeedforwardPD": "dynamics.control",
    "PDGravity": "dynamics.control", "Gains": "dynamics.control",
    "MeasurementNoise": "dynamics.tracking", "TrackingResult": "dynamics.tracking_result",
    "TrackingOptions": "dynamics.tracking",
    "FlexibleDrives": "dynamics.drives.flexible",
    "Plant": "dynamics.plant", "ModelMismatch": "dynamics.plant", "PlantError": "dynamics.plant",
    "JointLoads": "dynamics.loads",
    "Trajectory": "paths.trajectory", "thesis_trajectory": "paths.curves",
    "from_csv": "io.trajectory", "to_csv": "io.trajectory",
    "TrajectoryError": "paths.trajectory", "smooth_random_trajectory": "paths.curves",
    "thesis_curve": "paths.curves", "trajectory_curve": "paths.trajectory",
    "QuinticHermite": "paths.splines", "RetimedCurve": "paths.const_accel",
    "run_pipeline": "run", "write_run_table": "run", "RunResult": "run",
    "stream_run": "run", "StreamOptions": "run", "read_result": "io.table",
    "ThesisTrajectory": "paths.curves",
    "load_actuators": "dynamics.motors", "Actuators": "dynamics.motors",
    "ActuatorError": "dynamics.motors", "actuator_sizing": "dynamics.sizing",
    "stiffness": "run.stiffness", "stream_stiffness": "run.stiffness",
    "StiffnessRun": "run.stiffness", "StiffnessOptions": "dynamics.drives.stiffness",
    "StiffnessResult": "dynamics.drives.stiffness", "StiffnessError": "dynamics.drives.stiffness",
    "stiffness_at": "dynamics.drives.stiffness", "deflection_at": "dynamics.drives.stiffness",
    "time_optimal_path": "dynamics.cycle", "TimeOptimal": "dynamics.timeopt",
    "write_figures": "viz.plots", "write_html": "viz.viewer", "sizing_report": "viz.report",
    "map_workspace": "workspace.grid", "largest_panel": "workspace.grid",
    "WorkspaceOptions": "workspace.options",
    "WorkspaceMap": "workspace.grid", "WorkspaceError": "workspace.grid",
    "load_grid": "sweep", "make_sweep": "sweep", "run_sweep": "sweep",
    "evaluate_variant": "sweep", "SweepError": "sweep",
    "load_job": "painting.job", "job_from_dict": "painting.job", "PaintJob": "painting.job",
    "JobError": "painting.errors",
    "plan_paint": "painting.plan.panel", "plan_film": "painting.film.grid",
    "PaintPlan": "painting.plan.panel",
    "paint": "painting.api", "PaintOptions": "painting.options", "PaintResult": "painting.result",
    "PaintReport": "painting.result", "JobKindError": "painting.errors",
    "place": "painting.layout.place", "PlaceOptions": "painting.layout.place",
    "PlaceResult": "painting.layout.place",
    "PlaceError": "painting.errors",
    "plan_cell": "painting.cell.plan", "CellPlan": "painting.cell.plan",
    "Split": "painting.cell.zones",
    "Zone": "painting.cell.zones",
    "paint_report": "painting.kinds.panel", "PlanError": "painting.errors",
    "Gun": "painting.spray.deposition",
    "deposition_rate": "painting.spray.deposition", "film": "painting.spray.deposition",
    "program_deflection": "painting.checks.compliance",
    "compliance_entry": "painting.checks.compliance",
    "split_cell": "painting.cell.split", "propose_layout": "painting.layout.cell",
    "fewest_robots": "painting.layout.cell", "LayoutOptions": "painting.layout.cell",
    "cell_clearance": "painting.checks.cell_clearance",
    "CellClearance": "painting.checks.cell_clearance",
    "MovingPart": "painting.checks.cell_clearance", "link_capsules": "kinematics.capsules",
}

__all__ = sorted(_API)


def __getattr__(name: str):
    if name in _API:
        return getattr(importlib.import_module(f".{_API[name]}", __name__), name)
    raise AttributeError(f"module 'pollard_pin' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
