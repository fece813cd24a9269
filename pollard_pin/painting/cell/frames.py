"""A cell robot's view of the job (docs/model.md §26.1): the part, the line and gravity in
its base frame, so that today's line planner plans its program as it would for a robot at
the origin, and its path.csv is in its base frame."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...model.gravity import GRAVITY, with_gravity
from ..job import PaintJob
from ..workpiece.mesh import Part, make_part
from .robots import CellRobot


def line_in_base(line, robot: CellRobot):
    """The ``[line]`` with its direction in the robot's base frame."""
    e = robot.direction_to_base(line.direction)
    return replace(line, direction=tuple(float(c) for c in e))


def panel_in_base(job: PaintJob, robot: CellRobot) -> PaintJob:
    """The panel job seen from the robot's base: centre, normal and line direction turned
    and shifted (p_base = Rᵀ(p − base))."""
    c = robot.to_base(job.center)
    n = robot.direction_to_base(job.normal)
    return replace(job, center=tuple(float(x) for x in c), normal=tuple(float(x) for x in n),
                   line=line_in_base(job.line, robot), robots=())


def part_in_base(part: Part, robot: CellRobot, facing=None) -> Part:
    """The world part seen from the robot's base, painting the faces within its max_angle of
    the world ``facing`` (None: the part's)."""
    f = np.asarray(part.facing if facing is None else facing, dtype=float)
    return make_part(robot.to_base(part.vertices), part.faces, robot.direction_to_base(f),
                     part.max_angle, part.source)


def gravity_in_base(robot: CellRobot) -> np.ndarray:
    """Gravity in the robot's base frame, Rᵀ g [m/s²]."""
    return robot.direction_to_base(GRAVITY)


def robot_model_in_base(model_robot, robot: CellRobot):
    """The robot model with gravity Rᵀ g (its own model and data: the shared one is left
    as it is); itself when Rᵀ g is g (a base turned about z only)."""
    return with_gravity(model_robot, gravity_in_base(robot))


__all__ = ["GRAVITY", "gravity_in_base", "line_in_base", "panel_in_base", "part_in_base",
           "robot_model_in_base"]
