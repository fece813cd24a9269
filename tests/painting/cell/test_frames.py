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


@pytest.mark.parametrize("turn, swapped", [((90.0, 0.0, 0.0), True),
                                            ((-90.0, 0.0, 0.0), True),
                                            ((180.0, 0.0, 0.0), False),
                                            ((0.0, 30.0, 45.0), False)])
def test_the_base_frames_panel_is_the_world_rectangle(turn, swapped):
    from pollard_pin.painting.cell.frames import check_panel_turn
    from pollard_pin.painting.workpiece.panel import panel_frame

    job = cell_job(panel_cell())
    cr = CellRobot("t", (0.0, 0.6, 0.17), turn)
    check_panel_turn(job, cr)
    b = panel_in_base(job, cr)
    assert (b.width, b.height) == ((job.height, job.width) if swapped else
                                   (job.width, job.height))
    w, fb = panel_frame(job), panel_frame(b)
    corners = [(s * w.width / 2, t * w.height / 2) for s in (-1, 1) for t in (-1, 1)]
    seen = [(s * fb.width / 2, t * fb.height / 2) for s in (-1, 1) for t in (-1, 1)]
    world = sorted(map(tuple, np.round([w.world(np.array(u), np.array(v)) for u, v in corners],
                                       12)))
    based = sorted(map(tuple, np.round([cr.to_world(fb.world(np.array(u), np.array(v)))
                                        for u, v in seen], 12)))
    assert np.allclose(world, based, atol=1e-12)


def test_a_base_turned_between_the_panels_edges_is_refused():
    from pollard_pin.painting.cell.frames import check_panel_turn
    from pollard_pin.painting.errors import CellError

    job = cell_job(panel_cell())
    with pytest.raises(CellError, match=r"'t'.*10° in its plane"):
        check_panel_turn(job, TURNED)
    with pytest.raises(CellError, match="its z along the panel's normal"):
        check_panel_turn(job, CellRobot("n", (0.0, 0.0, 0.0), (0.0, 90.0, 0.0)))


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
