"""A cell robot's view of the job (docs/model.md §26.1): the part, the line and gravity in
its base frame, so that today's line planner plans its program as it would for a robot at
the origin, and its path.csv is in its base frame."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...model.gravity import GRAVITY, with_gravity
from ..errors import CellError
from ..job import PaintJob
from ..workpiece.mesh import Part, make_part
from .robots import CellRobot


def line_in_base(line, robot: CellRobot):
    """The ``[line]`` with its direction in the robot's base frame."""
    e = robot.direction_to_base(line.direction)
    return replace(line, direction=tuple(float(c) for c in e))


def _up_on_panel(job: PaintJob, robot: CellRobot) -> tuple[float, float, float]:
    """(|cos|, |sin|, length) of the base's z projected on the panel against the panel's
    height axis (world z projected): how the base sees the panel's edges."""
    from ..workpiece.panel import panel_frame

    world = panel_frame(job)
    up = robot.R[:, 2] - (robot.R[:, 2] @ world.n) * world.n
    size = float(np.linalg.norm(up))
    if size <= 1e-9:
        return 0.0, 0.0, size
    return abs(float(up @ world.v)) / size, abs(float(up @ world.u)) / size, size


def panel_in_base(job: PaintJob, robot: CellRobot) -> PaintJob:
    """The panel job seen from the robot's base: centre, normal and line direction turned
    and shifted (p_base = Rᵀ(p − base)), its width and height swapped when the base's z
    lies nearer the panel's width than its height (a panel's frame takes its height along
    the z of the frame it is given in: :func:`check_panel_turn` refuses the turns between)."""
    c = robot.to_base(job.center)
    n = robot.direction_to_base(job.normal)
    turned = replace(job, center=tuple(float(x) for x in c), normal=tuple(float(x) for x in n),
                     line=line_in_base(job.line, robot), robots=())
    along_v, along_u, _ = _up_on_panel(job, robot)
    return replace(turned, width=job.height, height=job.width) if along_u > along_v else \
        turned


def check_panel_turn(job: PaintJob, robot: CellRobot) -> None:
    """Refuse, in one line, a base whose z lies neither along nor across the panel's edges
    (projected on its plane): the base-frame panel would not be the world's rectangle."""
    along_v, along_u, size = _up_on_panel(job, robot)
    if max(along_v, along_u) > 1 - 1e-9:
        return
    what = (f"turns the panel {math.degrees(math.atan2(along_u, along_v)):.3g}° in its plane"
            if size > 1e-9 else "has its z along the panel's normal")
    raise CellError(f"{job.source}: robot {robot.name!r}: its base {what}; a panel cell plans "
                    "bases whose z lies along or across the panel's edges")


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


__all__ = ["GRAVITY", "check_panel_turn", "gravity_in_base", "line_in_base", "panel_in_base",
           "part_in_base", "robot_model_in_base"]
