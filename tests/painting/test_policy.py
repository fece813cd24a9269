"""The planners' policy (painting/policy.py): the duration search's first turnaround reverses
a pass at a deceleration set by ``first_deceleration`` whatever the pass speed, measured on
the panel's raster by finite differences of its along-pass rate; the defaults are the
planners' figures; a bad value is one line; every planner entry obeys the policy it is given
(a budget too small for the job, refused before anything is built)."""
import math
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.errors import InputError
from pollard_pin.painting.errors import PlanError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.passes.raster import raster_segments
from pollard_pin.painting.policy import DEFAULT_POLICY, PlannerPolicy

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("speed", [0.05, 0.33, 1.5])
def test_first_turnaround_reverses_at_the_set_deceleration(speed):
    """The raster's turnaround shape peaks at 3·(2v)/(2τ) = 0.75 × first_deceleration at
    τ = first_guess(v), for any v (central differences on 4001 samples: achieved 3e-7
    relative; asserted 1e-4), and reverses the pass rate from +v to −v."""
    for policy in (DEFAULT_POLICY, PlannerPolicy(first_deceleration=4.0)):
        tau = policy.first_guess(speed)
        seg = raster_segments([0.0, 0.02], 0.1, speed, tau, (tau, tau))
        k = list(seg.kind).index("turn")
        assert seg.duration[k] == tau
        t = np.linspace(seg.start[k], seg.start[k] + tau, 4001)
        _, _, du, _, _, _ = seg.evaluate(t)
        assert du[0] == pytest.approx(speed, rel=1e-12)
        assert du[-1] == pytest.approx(-speed, rel=1e-12)
        peak = np.abs(np.gradient(du, t)).max()
        assert peak == pytest.approx(0.75 * policy.first_deceleration, rel=1e-4)


def test_defaults_are_the_planners_figures():
    p = PlannerPolicy()
    assert p == DEFAULT_POLICY
    assert (p.utilisation, p.turn_samples, p.check_refine, p.max_step, p.step_sigma,
            p.max_path_samples, p.max_passes, p.first_deceleration) == (
        0.97, 48, 4, 0.002, 0.25, 250_000, 1000, 10.0)
    assert p.clearance_stride == 1  # every sample: the planners' own check
    assert p.name_speeds is True  # a refused line speed names the interval that paints
    # a cell's run past a seam R, its averaging the planner's, its seams the bands'
    assert (p.seam_run, p.smoothing, p.seams) == (None, 0.0, None)
    cell = PlannerPolicy(seam_run=0, smoothing=0.06, seams=[0.1, 0.2])
    assert (cell.seam_run, cell.smoothing, cell.seams) == (0.0, 0.06, (0.1, 0.2))
    # the time step: max_step, or step_sigma σ of travel if that is shorter
    assert p.step(0.01, 0.1) == 0.002 and p.step(0.01, 2.0) == 0.25 * 0.01 / 2.0
    with pytest.raises(AttributeError):
        p.utilisation = 0.5  # frozen


@pytest.mark.parametrize("field, value, rule", [
    ("utilisation", 0.0, "> 0"), ("utilisation", 1.2, "at most 1"),
    ("utilisation", math.nan, "finite"), ("utilisation", "0.9", "not a number"),
    ("turn_samples", 1, ">= 2"), ("turn_samples", 48.0, "not an integer"),
    ("turn_samples", True, "not an integer"), ("check_refine", 0, ">= 1"),
    # repr() of it raised ValueError (over 4300 digits): now shortened, one line
    pytest.param("turn_samples", -10**5000, "= -1e+5000 (a 5001-digit integer): must be >= 2",
                 id="turn_samples-huge"),
    ("max_step", -0.001, "> 0"), ("max_step", math.inf, "finite"), ("step_sigma", 0, "> 0"),
    ("max_path_samples", 1, ">= 2"), ("max_passes", 0, ">= 1"),
    ("clearance_stride", 0, ">= 1"), ("clearance_stride", 2.0, "not an integer"),
    ("first_deceleration", 0.0, "> 0"), ("first_deceleration", None, "not a number"),
    ("strokes", "diagonal", "one of auto, across, along"),
    ("step_from", "middle", "one of leading, trailing"), ("strokes", None, "one of auto"),
    ("name_speeds", 1, "true or false"), ("name_speeds", "no", "true or false"),
    ("seam_run", -0.001, ">= 0"), ("seam_run", "5", "not a number"),
    ("smoothing", math.inf, "finite"), ("smoothing", None, "not a number"),
    ("seams", (), "expected 1-15 seams"), ("seams", 0.1, "expected 1-15 seams"),
    ("seams", (0.2, 0.1), "must increase"), ("seams", (0.1, math.nan), "seams[1]")])
def test_a_bad_value_is_one_line(field, value, rule):
    with pytest.raises(InputError) as exc:
        PlannerPolicy(**{field: value})
    msg = str(exc.value)
    assert f"PlannerPolicy.{field}" in msg and rule in msg and "\n" not in msg, msg


def test_strokes_along_step_from_no_end():
    """Strokes along the travel step across it: a trailing end forced with them is refused
    (docs/model.md §24.2); the defaults are auto from the leading end."""
    assert (PlannerPolicy().strokes, PlannerPolicy().step_from) == ("auto", "leading")
    with pytest.raises(InputError, match="^PlannerPolicy.step_from = 'trailing': strokes "
                       "along the travel step across it"):
        PlannerPolicy(strokes="along", step_from="trailing")
    assert PlannerPolicy(strokes="auto", step_from="trailing").step_from == "trailing"


def test_every_planner_obeys_the_policy_it_is_given(robot):
    """A budget too small for each example, passed as a policy (not patched into a module),
    refuses the job at each entry point, naming that budget; the same entries plan the
    examples under the default policy (tests of each planner)."""
    from pollard_pin.dynamics.motors import load_actuators
    from pollard_pin.painting.cell.plan import max_cell_speed, plan_cell, plan_cell_job
    from pollard_pin.painting.layout.place import place
    from pollard_pin.painting.line.panel import max_line_speed, plan_line, plan_line_job
    from pollard_pin.painting.plan.panel import plan_paint
    from pollard_pin.painting.plan.part import plan_surface

    act = load_actuators(EXAMPLES / "actuators.toml")
    few = PlannerPolicy(max_path_samples=2)
    panel, line = load_job(EXAMPLES / "paint.toml"), load_job(EXAMPLES / "line.toml")
    part, cell = load_job(EXAMPLES / "parts" / "bent_plate.toml"), load_job(
        EXAMPLES / "cell.toml")
    calls = [lambda: plan_paint(robot, panel, act, policy=few),
             lambda: plan_line(robot, line, act, policy=few),
             lambda: plan_line_job(robot, line, act, policy=few),
             lambda: max_line_speed(robot, line, act, policy=few),
             lambda: plan_surface(robot, part, act, policy=PlannerPolicy(max_passes=1)),
             lambda: place(robot, part, policy=PlannerPolicy(max_passes=1)),
             lambda: plan_cell(robot, cell, act, policy=few),
             lambda: plan_cell_job(robot, cell, act, policy=few),
             lambda: max_cell_speed(robot, cell, act, policy=few)]
    for call in calls:
        with pytest.raises(PlanError) as exc:
            call()
        msg = str(exc.value)
        assert "budget 2" in msg or "budget 1:" in msg, msg


@pytest.mark.parametrize("dt, speed_set, says", [
    (0.002, False, "a thinner film, more flow"),  # the step is max_step: a faster gun helps
    (0.002, True, "a faster gun (job.speed)"),
    (0.002, None, "a faster gun (a thinner film, more flow or job.speed)"),
    (0.001, False, "a wider spray (gun.sigma)"),  # step_sigma·σ: the speed cancels out
    (0.001, True, "a wider spray (gun.sigma)"),
])
def test_the_sample_advice_follows_the_step(dt, speed_set, says):
    assert PlannerPolicy().coarser(dt, speed_set) == says
