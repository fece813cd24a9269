"""pollard-pin: a verified multibody model of the Pollard spray-painting parallel robot.

The names a user calls, imported here explicitly; everything else public is in its subpackage's
``__all__`` (``pollard_pin.kinematics``, ``pollard_pin.dynamics``, ``pollard_pin.painting`` …)::

    robot = pollard_pin.load()                       # model, data, closures, geometry
    traj = pollard_pin.thesis_trajectory()           # docs/model.md §9 painting curve
    ik = pollard_pin.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    result = pollard_pin.paint(robot, pollard_pin.load_job("examples/paint.toml"))
    result.write("out", "csv")                       # what ``pollard-pin paint`` writes

The thesis' closed form (``pollard_pin.analytic``) and the Euler–Lagrange cross-check
(``pollard_pin.crosscheck.euler_lagrange``) do not need Pinocchio themselves (a test loads them
with Pinocchio hidden); importing this package root loads it.
"""
from __future__ import annotations

from .dynamics.cycle import time_optimal_path
from .dynamics.drives.stiffness import StiffnessOptions
from .dynamics.forward import forward_dynamics
from .dynamics.inverse import inverse_dynamics
from .dynamics.loads import joint_loads
from .dynamics.motors import Actuators, load_actuators
from .dynamics.sizing import actuator_sizing
from .dynamics.tracking import TrackingOptions, simulate_tracking
from .errors import DestinationError, InputError, PollardError, SolveError
from .io.table import read_result
from .io.trajectory import from_csv, to_csv
from .kinematics.closure import forward_kinematics
from .kinematics.ik import IkOptions, inverse_kinematics
from .kinematics.margins import Margins
from .model.build import Robot, load
from .model.params import Params, load_params
from .outputs import PaintResult, fewest_robots, paint
from .outputs.calibration import CalibrateOptions, Calibration, calibrate
from .painting import (
    LayoutOptions,
    PaintOptions,
    PlaceOptions,
    job_from_dict,
    load_job,
    place,
    propose_layout,
)
from .paths.curves import thesis_trajectory
from .paths.trajectory import Trajectory
from .run.pipeline import run_pipeline, write_run_table
from .run.stiffness import stiffness
from .run.stream import StreamOptions, stream_run
from .sweep import load_grid, make_sweep, run_sweep
from .synthesis import design
from .version import __version__ as __version__
from .viz.plots import write_figures
from .viz.viewer import write_html
from .workspace.grid import largest_panel, map_workspace
from .workspace.options import WorkspaceOptions

__all__ = [
    # the exception root and its families (pollard_pin.errors)
    "PollardError", "InputError", "SolveError", "DestinationError",
    # the model
    "load", "Robot", "load_params", "Params",
    # trajectories and their files
    "Trajectory", "thesis_trajectory", "from_csv", "to_csv", "read_result",
    # kinematics
    "inverse_kinematics", "forward_kinematics", "IkOptions", "Margins",
    # dynamics, motors, the fastest cycle
    "inverse_dynamics", "forward_dynamics", "joint_loads", "simulate_tracking",
    "TrackingOptions", "load_actuators", "Actuators", "actuator_sizing", "time_optimal_path",
    # whole runs
    "run_pipeline", "write_run_table", "stream_run", "StreamOptions", "stiffness",
    "StiffnessOptions",
    # the workspace
    "map_workspace", "largest_panel", "WorkspaceOptions",
    # painting
    "load_job", "job_from_dict", "paint", "PaintOptions", "PaintResult", "place",
    "PlaceOptions", "propose_layout", "fewest_robots", "LayoutOptions",
    "calibrate", "Calibration", "CalibrateOptions",  # the spray pattern from stripes
    # design sweeps, figures and the viewer page
    "load_grid", "make_sweep", "run_sweep", "write_figures", "write_html",
    "design",  # the robot designed for a paint job (docs/model.md §29; options: synthesis)
]

# Names this root exported before it listed only the above: each is public in its subpackage,
# and ``pollard_pin.<name>`` says where in one line (a pointer, not a resolver).
_MOVED = {
    **dict.fromkeys(("ACTUATED", "PASSIVE", "ModelFileError", "constraint_residual",
                     "constraint_jacobian", "ParameterError"), "model"),
    **dict.fromkeys(("solve_closure", "tool_pose", "IKResult", "MarginError", "ClosureError",
                     "KinematicsError", "UnreachablePoseError", "SingularityError",
                     "BranchFlipError", "link_capsules"), "kinematics"),
    **dict.fromkeys(("replay_open_loop", "desired_trajectory", "ComputedTorque",
                     "FeedforwardPD", "PDGravity", "Gains", "MeasurementNoise", "TrackingResult",
                     "Plant", "ModelMismatch", "PlantError", "JointLoads", "ActuatorError",
                     "TimeOptimal"), "dynamics"),
    **dict.fromkeys(("FlexibleDrives", "StiffnessResult", "StiffnessError", "stiffness_at",
                     "deflection_at"), "dynamics.drives"),
    **dict.fromkeys(("TrajectoryError", "smooth_random_trajectory", "thesis_curve",
                     "trajectory_curve", "QuinticHermite", "RetimedCurve", "ThesisTrajectory"),
                    "paths"),
    **dict.fromkeys(("RunResult", "stream_stiffness", "StiffnessRun"), "run"),
    **dict.fromkeys(("sizing_report",), "viz"),
    **dict.fromkeys(("WorkspaceMap", "WorkspaceError"), "workspace"),
    **dict.fromkeys(("evaluate_variant", "SweepError"), "sweep"),
    **dict.fromkeys(("PaintJob", "JobError", "PaintReport", "JobKindError", "PlaceResult",
                     "PlaceError", "paint_report", "PlanError"), "painting"),
    **dict.fromkeys(("plan_paint", "PaintPlan"), "painting.plan"),
    **dict.fromkeys(("plan_film",), "painting.film"),
    **dict.fromkeys(("program_deflection", "compliance_entry"), "painting.checks.compliance"),
    # a cell's rooms read the job, which reads the cell's robots: public in their modules
    **dict.fromkeys(("plan_cell", "CellPlan"), "painting.cell.plan"),
    **dict.fromkeys(("Split", "Zone"), "painting.cell.zones"),
    **dict.fromkeys(("split_cell",), "painting.cell.split"),
    **dict.fromkeys(("cell_clearance", "CellClearance", "MovingPart"),
                    "painting.checks.cell_clearance"),
    **dict.fromkeys(("Gun", "deposition_rate", "film"), "painting.spray"),
}


def __getattr__(name: str):
    if name in _MOVED:
        raise AttributeError(f"pollard_pin.{name} moved: use pollard_pin.{_MOVED[name]}.{name}")
    raise AttributeError(f"module 'pollard_pin' has no attribute {name!r}")
