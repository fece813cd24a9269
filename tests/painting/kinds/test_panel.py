"""A still panel (painting/kinds/panel.py): pp.paint's film and report are plan_paint's,
plan_film's and paint_report's (equal); paint_report's numbers against the plan, the film and
the motor check they come from, the swept lower bound against the time the passes take; the
lines paint prints."""
import json

import numpy as np
import pytest

from pollard_pin.outputs import PaintResult
from pollard_pin.painting.film.stats import film_stats
from pollard_pin.painting.kinds.panel import paint_report, summary_lines


@pytest.fixture(scope="module")
def result(panel_result):
    """pp.paint of examples/paint.toml, painted once per session (tests/examples_planned.py)."""
    return panel_result


def test_panel_is_the_panel_planners(result, plan, film, act):
    """examples/paint.toml: the plan, the film and paint.json's statistics are those of
    plan_paint, plan_film and paint_report called directly (equal, not close)."""
    U, V, pts, f = film
    assert result.kind == "panel" and isinstance(result, PaintResult)
    assert np.array_equal(result.plan.trajectory.poses, plan.trajectory.poses)
    assert np.array_equal(result.film.thickness, f.thickness)
    assert np.array_equal(result.film.grid[0], U) and np.array_equal(result.film.points, pts)
    direct = paint_report(plan, f, act)
    assert result.report.thickness == direct["thickness"]
    assert result.report.cycle_time == direct["cycle_time"] == plan.cycle_time
    assert result.report.motors == direct["motors"]


@pytest.fixture(scope="module")
def report(plan, film, act):
    return paint_report(plan, film[3], act)


def test_report_is_plain_json(report):
    """Only numbers, strings, lists and dicts, no NaN: json.dumps (strict) writes it."""
    assert json.loads(json.dumps(report, allow_nan=False))["target"] == report["target"]


def test_swept_lower_bound_is_the_time_on_the_passes(plan, report):
    """Painting the swept strips (passes × their length × spacing) at the target takes
    exactly as long as the passes at constant speed: film = flow/(speed·spacing) per coat."""
    on_passes = sum(d for d, k in zip(plan.segments.duration, plan.segments.kind) if k == "pass")
    assert report["swept_lower_bound"] == pytest.approx(on_passes, rel=1e-12)
    assert report["lower_bound"] < report["swept_lower_bound"] < report["cycle_time"]
    assert report["cycle_time"] == plan.trajectory.t[-1]


def test_layout_film_and_motors_come_from_the_plan(plan, film, act, report):
    assert report["thickness"] == film_stats(film[3].thickness, plan.job.thickness)
    assert report["passes"] == len(plan.offsets) * plan.coats == len(report["turnarounds"]) + 1
    assert report["samples"] == len(plan.trajectory)
    assert set(report["motors"]) == set(act.names)
    for i, name in enumerate(act.names):
        assert report["motors"][name]["peak_torque"] == plan.ratios["peak_torque"][i]
    steps = np.linalg.norm(np.diff(plan.trajectory.poses[:, :3], axis=0), axis=1)
    assert report["integration"]["largest_step_over_sigma"] == steps.max() / plan.job.sigma
    assert report["integration"]["largest_step_over_sigma"] <= 0.25 * (1 + 1e-9)


def test_summary_lines(result):
    """The five lines of a still panel: passes, cycle and bounds, film, motors, timing."""
    rep, names = result.report.data, result.actuators.names
    lines = summary_lines(rep, names)
    assert len(lines) == 5 and lines[0].startswith(f"passes {rep['passes']} (horizontal)")
    assert f"{rep['swept_lower_bound']:.3f} s over the swept passes" in lines[1]
    assert lines[3].startswith("motor peak torque") and all(n in lines[3] for n in names)
    assert f"({rep['grid']['nu']} × {rep['grid']['nv']} points" in lines[4]
