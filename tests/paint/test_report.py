"""The numbers of paint.json (paint/report.py): each against the plan, the film and the motor
check it comes from, and the swept lower bound against the time the passes take."""
import json

import numpy as np
import pytest

from pollard_pin.paint.report import paint_report
from pollard_pin.paint.stats import film_stats


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
