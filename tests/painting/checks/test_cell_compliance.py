"""Compliance for a cell's robots (painting/checks/cell_compliance.py, docs/model.md §26.6):
a robot's deflection against stiffness_at projected by hand with its base-frame gravity, the cell's
film change against each robot's deflected film integrated on its own, a one-robot cell at
the origin against today's line job, and paint.json's entries."""
from dataclasses import replace

import numpy as np
import pinocchio as pin
import pytest
from cell_jobs import cell_job, panel_cell

import pollard_pin as pp
from pollard_pin.analytic.taskspace import rotation
from pollard_pin.dynamics.drives.stiffness import StiffnessOptions, stiffness_at
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.checks.cell_compliance import cell_compliance, robot_deflection
from pollard_pin.painting.checks.compliance import (
    compliance_entry,
    deflected_poses,
    program_deflection,
)
from pollard_pin.painting.film.cell import cell_panel_film
from pollard_pin.painting.options import PaintOptions

RECOIL = 3.0  # N


@pytest.fixture(scope="module")
def result(robot, act):
    """The two-robot test cell painted with a 3 N recoil, through pollard_pin.painting."""
    tables = panel_cell()
    tables["gun"]["recoil"] = RECOIL
    job = cell_job(tables)
    return pp.paint(robot, job, act, PaintOptions(resolution=job.sigma))


def test_a_turned_robots_deflection_is_stiffness_at_with_its_gravity(robot, act, result):
    """The 'high' robot's program on a base tilted 30° about world y: at a few sprayed
    samples (a seam's fraction of the trigger among them), stiffness_at on a model whose
    gravity is Ry(30°)ᵀ g written by hand, under the recoil −3 × trigger × a, projected on
    the spray axis (achieved 2e-19 m on ~1e-4 m: round-off); the weight's sag differs from
    the upright robot's (the test sees the gravity)."""
    rp = result.plan.robots[1]
    c, s = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    Ry = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    tilted = replace(rp, robot=CellRobot("high", rp.robot.base, (0.0, 30.0, 0.0)))
    k = act.stiffness()
    d = robot_deflection(robot, tilted, k, RECOIL)
    upright = robot_deflection(robot, rp, k, RECOIL)
    model = pin.Model(robot.model)
    model.gravity = pin.Motion(Ry.T @ np.array([0.0, 0.0, -9.81]), np.zeros(3))
    mine = replace(robot, model=model, data=model.createData(),
                   constraint_datas=[m.createData() for m in robot.constraint_models])
    tr = rp.plan.trajectory
    on = np.flatnonzero(rp.plan.spray > 0)
    idx = on[[0, len(on) // 2, -1]]
    q = pp.inverse_kinematics(robot, tr.poses[idx]).q
    for j, i in enumerate(idx):
        a = rotation(tr.poses[i])[:, 0]
        w = StiffnessOptions(wrench=(*(-RECOIL * rp.plan.spray[i] * a), 0.0, 0.0, 0.0))
        ref = stiffness_at(mine, q[j:j + 1], k, w).deflection[0]
        assert np.abs(d.deflection[i] - ref).max() <= 2e-17
        assert d.standoff[i] == pytest.approx(ref[:3] @ a, abs=1e-17)
        assert np.abs(d.deflection[i] - upright.deflection[i]).max() > 1e-6


def test_the_cells_film_change_is_each_robots_deflected_film_summed(robot, act, result):
    """Each robot's deflected program (program_deflection on its model, poses moved by hand)
    filmed alone as a one-robot cell, summed: paint.json's film_error is that sum's largest
    change from the rigid film, and each robot's entry its own film's (seen equal: 0.0 on ~1e-2);
    the worst standoff error is the worst robot's."""
    from pollard_pin.painting.cell.frames import robot_model_in_base

    cell, rep = result.plan, result.report.data
    target = cell.job.thickness
    rigid = cell_panel_film(cell, cell.job.sigma)[3].thickness
    total = np.zeros_like(rigid)
    for rp, entry in zip(cell.robots, rep["robots"]):
        tr = rp.plan.trajectory
        d = program_deflection(robot_model_in_base(robot, rp.robot), tr, act.stiffness(),
                               rp.plan.spray, RECOIL)
        moved = replace(tr, poses=deflected_poses(tr.poses, d.deflection))
        alone = replace(rp, plan=replace(rp.plan, trajectory=moved))
        mine = cell_panel_film(replace(cell, robots=(alone,)), cell.job.sigma)[3].thickness
        own = cell_panel_film(replace(cell, robots=(rp,)), cell.job.sigma)[3].thickness
        total += mine
        c = entry["compliance"]
        assert c["film_error"] == pytest.approx(np.abs(mine - own).max() / target, abs=1e-15)
        assert c["standoff_error_m"] == pytest.approx(np.abs(d.standoff[rp.plan.spray > 0]).max(),
                                                      abs=1e-18)
    worst = rep["compliance"]
    assert worst["film_error"] == pytest.approx(np.abs(total - rigid).max() / target, abs=1e-15)
    assert 1e-4 < worst["film_error"] < 0.05  # the weight and the recoil show, a few ‰
    per = [r["compliance"] for r in rep["robots"]]
    best = max(per, key=lambda c: c["standoff_error_m"])
    assert worst["standoff_error_m"] == best["standoff_error_m"]
    assert worst["standoff_error_robot"] == rep["robots"][per.index(best)]["name"]
    assert worst["tilt_rad"] == max(c["tilt_rad"] for c in per)
    assert worst["recoil_n"] == RECOIL and "compliance" in rep["timings"]


def test_one_robot_at_the_origin_is_todays_line_job(robot, line_plan, line_plan_film,
                                                    line_cell, act):
    """A cell of one robot at the origin: the compliance figures of today's line job, to
    round-off (seen equal: the same samples, poses and integration)."""
    cell = line_cell  # examples/line.toml as a cell of one robot at the origin
    assert [rp.robot for rp in cell.robots] == [CellRobot("only")]
    U, V, pts, f = line_plan_film
    today = compliance_entry(robot, line_plan, pts, f.thickness, act)
    ours, (mine,) = cell_compliance(robot, cell, pts, f.thickness, act)
    for key in ("standoff_error_m", "lateral_error_m", "tilt_rad", "film_error"):
        assert ours[key] == pytest.approx(today[key], rel=1e-12, abs=1e-18), key
        assert mine[key] == pytest.approx(today[key], rel=1e-12, abs=1e-18), key
    assert ours["standoff_error_at_t"] == today["standoff_error_at_t"]
    assert ours["standoff_error_robot"] == "only"


def test_without_stiffness_every_entry_says_so(robot, act, result):
    soft = replace(act, units=tuple(replace(u, stiffness=None) for u in act.units))
    pts, f = result.film.points, result.film.thickness
    ours, per = cell_compliance(robot, result.plan, pts, f, soft)
    assert ours["stiffness"] is False and "stiffness' is missing" in ours["note"]
    assert len(per) == 2 and all(c["stiffness"] is False for c in per)


def test_drives_beyond_the_linear_model_are_flagged_for_every_entry(robot, act, result):
    """Drives too soft for the linear model (docs/model.md §27.2): the cell's entry and each
    robot's say so, naming the robot and the bound, with no figures; the plan stands."""
    soft = replace(act, units=tuple(replace(u, stiffness=1.0) for u in act.units))
    pts, f = result.film.points, result.film.thickness
    ours, per = cell_compliance(robot, result.plan, pts, f, soft)
    assert ours["stiffness"] is True and set(ours) == {"recoil_n", "stiffness", "note"}
    name = result.plan.robots[0].robot.name
    assert ours["note"].startswith(f"not computed: robot '{name}': sample ")
    assert "beyond the linear model's 0.003 rad" in ours["note"]
    assert per == [ours] * len(result.plan.robots)


def test_a_part_cell_reuses_each_robots_rigid_film(robot, act, line_part_cell):
    """A part cell of one robot (examples/line_part.toml's): the compliance with each
    robot's rigid film and shadows reused (docs/model.md §27.7: tested again beside the
    shadows' edges) against everything integrated again with every ray cast: the same film
    error to 1e-4 of the target (the flat part casts no shadow on itself: achieved 0)."""
    _, cell, (pts, f, painted, _) = line_part_cell
    assert len(f.robots) == 1 and f.robots[0].shade is not None
    reused, per = cell_compliance(robot, cell, pts, f.thickness, act, painted, f.robots)
    again, per_again = cell_compliance(robot, cell, pts, f.thickness, act, painted)
    assert reused["film_error"] == pytest.approx(again["film_error"], abs=1e-4)
    assert per[0]["film_error"] == pytest.approx(per_again[0]["film_error"], abs=1e-4)
    assert 1e-5 < again["film_error"] < 0.05
