"""The planner's sizes (docs/model.md §21): the largest panel it suggests plans, budgets are
checked before anything is built, and reach is checked without dynamics where the motors are
not the question."""
import math
import time
from dataclasses import replace
from pathlib import Path

import pytest

import pollard_pin.dynamics.inverse as inverse
from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.paint import plan as planner
from pollard_pin.paint.errors import BudgetError, PlanError, ReachError
from pollard_pin.paint.job import load_job
from pollard_pin.paint.motion import motion, reach

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def act():
    return load_actuators(EXAMPLES / "actuators.toml")


@pytest.fixture(scope="module")
def job():
    return load_job(EXAMPLES / "paint.toml")


def yawed(job, degrees):
    a = math.radians(degrees)
    return replace(job, normal=(-math.cos(a), -math.sin(a), 0.0))


def test_the_suggested_panel_plans(robot, act, job):
    # Yawed −30° the panel is out of reach; the bisection's crude raster said 0.516 of it
    # fits, and that panel (0.134 × 0.062 m) left the workspace in a turnaround when planned.
    far = yawed(job, -30)
    with pytest.raises(PlanError) as err:
        planner.plan_paint(robot, far, act)
    scale = planner.largest_scale(robot, far, act)
    assert 0 < scale < 1
    w, h = scale * far.width, scale * far.height
    assert f"is {w:.3f} × {h:.3f} m" in str(err.value)
    plan = planner.plan_paint(robot, replace(far, width=w, height=h), act)  # must not raise
    assert plan.cycle_time > 0


def test_reach_only_is_motions_ik_without_dynamics(robot, act, job, monkeypatch):
    frame, offsets, half, speed, coats, _ = planner._layout(job)
    poses, d, dd = planner.task_motion(frame, job.standoff, [-half, 0.0, half],
                                       [offsets[0]] * 3, [speed] * 3, [0.0] * 3, [0.0] * 3,
                                       [0.0] * 3)
    full = motion(robot, act, poses, d, dd)
    only = reach(robot, poses, d, dd)
    assert (only.q == full.ik.q).all() and (only.v == full.ik.v).all()
    vmax = planner.max_pass_speed(robot, act, frame, job, offsets, half, True)

    def refused(*args, **kwargs):
        raise AssertionError("inverse dynamics where only reach is asked")

    # max_pass_speed's own motor question is path_dynamics'; its reach check needs none
    monkeypatch.setattr(inverse, "inverse_dynamics", refused)
    assert planner.max_pass_speed(robot, act, frame, job, offsets, half, True) == vmax
    with pytest.raises(ReachError, match="cannot reach"):
        reach(robot, *planner.task_motion(frame, job.standoff, [3.0], [0.0], [0.0], [0.0],
                                          [0.0], [0.0]))


@pytest.mark.parametrize("change, says", [
    ({"thickness": 0.1}, "the path needs 1.57e+07 samples"),  # 7.6 GB of samples, then more
    ({"flow": 1e-300}, "samples"),  # overflowed the sample count
    ({"flow": 5e-324}, "the path needs inf samples"),  # a speed that underflows
    ({"thickness": 0.1, "speed": 0.001, "coats": 3}, "fewer coats or a faster gun"),
    ({"spacing": 1e-5}, "passes"),
    ({"coats": 10**9}, "passes"),
])
def test_budgets_are_checked_before_the_path_is_built(robot, act, job, change, says):
    t0 = time.perf_counter()
    with pytest.raises(BudgetError) as err:
        planner.plan_paint(robot, replace(job, **change), act)
    assert time.perf_counter() - t0 < 5.0
    msg = str(err.value)
    assert says in msg and "budget" in msg and "\n" not in msg and len(msg) < 250, msg
