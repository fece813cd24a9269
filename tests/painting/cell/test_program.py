"""One cell robot's program (paint/cell/program.py, docs/model.md §26.1, §26.3): a part's
cell of one robot at the origin is today's line part; a clipped pass is its parent's motion
over its arc; a robot turned 180° about z on the far side of the line paints the back of a
two-sided plate with its own program, in its base frame."""
import math

import numpy as np
import pytest
import trimesh
from cell_jobs import PLATE_CELL

from pollard_pin.painting.cell.plan import plan_cell_job
from pollard_pin.painting.cell.program import ClippedPass
from pollard_pin.painting.film.cell import cell_part_film
from pollard_pin.painting.job import load_job
from pollard_pin.painting.spray.occlusion import load_painted_part

PLATE = PLATE_CELL + """
[[robot]]
name = "far"
base = [1.42, 0.3, 0.0]
rotation = [0.0, 0.0, 180.0]
"""


def test_one_robot_at_the_origin_is_todays_line_part(line_part_cell, line_part_plan,
                                                     line_part_film):
    job, cell, (pts, f, painted, _) = line_part_cell
    p = cell.robots[0].plan
    assert np.array_equal(p.trajectory.t, line_part_plan.trajectory.t)
    assert np.array_equal(p.trajectory.poses, line_part_plan.trajectory.poses)
    assert np.array_equal(p.spray, line_part_plan.spray)
    _, today, today_painted, _ = line_part_film
    assert np.array_equal(painted, today_painted)
    # the same samples, weights and points: equal (seen 0.0)
    assert np.abs(f.thickness - today.thickness).max() <= 1e-12 * job.thickness


def test_a_clipped_pass_is_its_parents_motion_over_its_arc(line_part_plan):
    parent = next(p for p in line_part_plan.program.pieces if p.kind == "pass")
    s0, s1 = 0.3 * parent.length, 0.7 * parent.length
    clip = ClippedPass(parent, s0, s1)
    assert clip.duration == pytest.approx((s1 - s0) / parent.v, rel=1e-15)
    tau = np.linspace(0.0, clip.duration, 7)
    # the parent reaches arc s0 at τ = s0/v (forward) or (L − s0)/v (backward)
    shift = (s0 if parent.forward else parent.length - s1) / parent.v
    for a, b in zip(clip.evaluate(tau), parent.evaluate(tau + shift)):
        assert np.abs(a - b).max() <= 1e-9  # seen 1e-16 (the same spline)


@pytest.fixture(scope="module")
def two_sided(tmp_path_factory, robot, act):
    folder = tmp_path_factory.mktemp("two_sided")
    trimesh.creation.box((0.02, 0.2, 0.1)).export(folder / "plate.stl")
    (folder / "plate.toml").write_text(PLATE)
    job = load_job(folder / "plate.toml")
    part = load_painted_part(job)
    return job, plan_cell_job(robot, job, act, part)


def test_a_robot_on_the_far_side_paints_the_back(two_sided):
    job, cell = two_sided
    far = next(r for r in cell.robots if r.robot.name == "far")
    assert far.zone.facing == pytest.approx((1.0, 0.0, 0.0), abs=1e-12)
    assert math.isinf(far.zone.lo) and math.isinf(far.zone.hi)
    # in its own base frame the back faces it as the front faces the near robot
    assert far.plan.part.facing == pytest.approx((-1.0, 0.0, 0.0), abs=1e-12)
    near = next(r for r in cell.robots if r.robot.name == "near")
    assert np.abs(far.plan.trajectory.poses[:, 0]).max() < 0.7
    assert np.abs(near.plan.trajectory.poses[:, 0]).max() < 0.7
    pts, f, painted, _ = cell_part_film(cell)
    th = f.thickness[painted] / job.thickness
    front = pts.normals[painted] @ np.array([-1.0, 0.0, 0.0]) > 0.9
    back = pts.normals[painted] @ np.array([1.0, 0.0, 0.0]) > 0.9
    assert front.sum() > 100 and back.sum() > 100 and (front | back).all()
    # each face within ±5 % of the target (seen ±1 %)
    for side in (front, back):
        assert np.abs(th[side] - 1).max() <= 0.05


@pytest.mark.parametrize("run, smoothing", [(None, 0.0), (0.005, 0.06)])
def test_the_run_past_a_seam_and_the_averaging_are_the_policys(tmp_path, run, smoothing):
    """A robot's strokes run R (or ``PlannerPolicy.seam_run``) past its seam and average the
    normal over ``PlannerPolicy.smoothing`` at least (docs/model.md §26.5): a flat plate
    z 0.05…0.15 m, its zone below z 0.10 m; the passes' gun positions reach z 0.10 + run
    (spline sampling: seen < 1e-6 m; asserted 1 mm)."""
    from dataclasses import replace

    from pollard_pin.painting.cell.bands import job_strokes
    from pollard_pin.painting.cell.plan import robot_part
    from pollard_pin.painting.cell.program import ZoneView, part_program
    from pollard_pin.painting.cell.robots import CellRobot
    from pollard_pin.painting.cell.zones import Zone
    from pollard_pin.painting.policy import PlannerPolicy

    trimesh.creation.box((0.02, 0.2, 0.1)).export(tmp_path / "plate.stl")
    (tmp_path / "plate.toml").write_text(PLATE_CELL)
    job = load_job(tmp_path / "plate.toml")
    part = load_painted_part(job)
    part_b = robot_part(job.standoff, part, CellRobot("near"), None)
    policy = PlannerPolicy(seam_run=run, smoothing=smoothing)
    R = job_strokes(job, part).runout  # the split's
    view = ZoneView(Zone("near", -math.inf, 0.10), R, np.array([0.0, 0.0, 1.0]), 0.0)
    R = R if run is None else run
    program, _, layout, _ = part_program(replace(job, robots=()), part_b, view,
                                         np.array([0.0, 1.0, 0.0]), policy)
    rel = program.build(program.guess)
    t = np.concatenate([np.linspace(a, a + d, 50) for a, d, k in
                        zip(rel.start, rel.duration, rel.kind) if k == "pass"])
    assert rel.evaluate(t)[0][:, 2].max() == pytest.approx(0.10 + R, abs=1e-3)
    assert R == pytest.approx(0.04 if run is None else 0.005, abs=1e-12)
    assert layout.smoothing == (0.004 if smoothing == 0.0 else 0.06)  # flat: the least


def test_a_cells_strokes_run_across_from_the_policys_end():
    from pollard_pin.painting.cell.program import cell_strokes
    from pollard_pin.painting.line.strokes import Strokes
    from pollard_pin.painting.policy import PlannerPolicy

    auto = "auto: a cell's strokes run across the travel (along only when forced)"
    assert cell_strokes() == Strokes("across", "leading", why=auto)
    assert cell_strokes(PlannerPolicy(step_from="trailing")) == Strokes("across", "trailing",
                                                                        why=auto)
    assert cell_strokes(PlannerPolicy(strokes="across")) == Strokes("across", "leading",
                                                                    why="forced")
    assert cell_strokes(PlannerPolicy(strokes="along")) == Strokes("along", None, why="forced")
