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

__version__ = "0.1.0"

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
    "load_job": "paint.job", "job_from_dict": "paint.job", "PaintJob": "paint.job",
    "JobError": "paint.job",
    "plan_paint": "paint.plan.panel", "plan_film": "paint.film.grid",
    "PaintPlan": "paint.plan.panel",
    "paint": "paint", "PaintOptions": "paint.api", "PaintResult": "paint.api",
    "PaintReport": "paint.api", "JobKindError": "paint.errors",
    "place": "paint.place", "PlaceOptions": "paint.place", "PlaceResult": "paint.place",
    "PlaceError": "paint.place",
    "plan_cell": "paint.cell.plan", "CellPlan": "paint.cell.plan", "Split": "paint.cell.zones",
    "Zone": "paint.cell.zones",
    "paint_report": "paint.report", "PlanError": "paint.errors", "Gun": "paint.spray.deposition",
    "deposition_rate": "paint.spray.deposition", "film": "paint.spray.deposition",
    "program_deflection": "paint.plan.compliance", "compliance_entry": "paint.film.compliance",
    "split_cell": "paint.cell.split", "propose_layout": "paint.cell.layout",
    "fewest_robots": "paint.cell.layout", "LayoutOptions": "paint.cell.layout",
    "cell_clearance": "paint.cell.clearance", "CellClearance": "paint.cell.clearance",
    "MovingPart": "paint.cell.clearance", "link_capsules": "kinematics.capsules",
}

__all__ = sorted(_API)


def __getattr__(name: str):
    if name == "paint":  # the subpackage, callable as paint.api.paint (paint/__init__.py)
        return importlib.import_module(".paint", __name__)
    if name in _API:
        return getattr(importlib.import_module(f".{_API[name]}", __name__), name)
    raise AttributeError(f"module 'pollard_pin' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
