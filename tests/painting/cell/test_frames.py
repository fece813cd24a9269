"""A cell robot's view of the job (paint/cell/frames.py, docs/model.md §26.1): the job and the
part in its base frame, and gravity Rᵀg in its model."""
import numpy as np
import pinocchio as pin
import pytest
from cell_jobs import cell_job, panel_cell

from pollard_pin.painting.cell.frames import (
    gravity_in_base,
    panel_in_base,
    part_in_base,
    robot_model_in_base,
)
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.workpiece.mesh import panel_part

TURNED = CellRobot("t", (1.42, 0.3, 0.1), (10.0, -20.0, 180.0))


def test_the_panel_seen_from_a_base_is_the_world_panel():
    job = cell_job(panel_cell())
    b = panel_in_base(job, TURNED)
    assert np.allclose(TURNED.to_world(b.center), job.center, atol=1e-15)
    assert np.allclose(TURNED.R @ b.normal, job.normal, atol=1e-15)
    assert np.allclose(TURNED.R @ b.line.direction, job.line.direction, atol=1e-15)
    assert b.robots == ()


def test_the_part_seen_from_a_base_is_the_world_part():
    part = panel_part(cell_job(panel_cell()))
    b = part_in_base(part, TURNED)
    assert np.allclose(TURNED.to_world(b.vertices), part.vertices, atol=1e-15)
    assert np.allclose(b.normals @ TURNED.R.T, part.normals, atol=1e-15)
    assert np.array_equal(b.painted, part.painted)
    assert b.painted_area == pytest.approx(part.painted_area, rel=1e-12)


def test_an_upside_down_base_turns_gravity_over(robot):
    flipped = CellRobot("u", (0.0, 0.0, 1.0), (180.0, 0.0, 0.0))
    assert np.allclose(gravity_in_base(flipped), [0.0, 0.0, 9.81], atol=1e-12)
    m = robot_model_in_base(robot, flipped)
    q = pin.neutral(robot.model)
    q[:] = np.linspace(-0.3, 0.3, len(q))
    g0 = pin.computeGeneralizedGravity(robot.model, robot.model.createData(), q)
    g1 = pin.computeGeneralizedGravity(m.model, m.model.createData(), q)
    assert np.allclose(g1, -g0, rtol=1e-12, atol=1e-12)  # g reversed: torques reversed
    assert np.allclose(robot.model.gravity.linear, [0.0, 0.0, -9.81])  # the shared one
    assert robot_model_in_base(robot, CellRobot("s", (0.0, 1.0, 0.0))) is robot
