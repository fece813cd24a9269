"""The shared numbers of paint.json (painting/report.py), a part's and a line's: each against
the plan, the film and the motor check it comes from; the invariants every report keeps (a
still panel's report: tests/painting/kinds/test_panel.py)."""

import numpy as np
import pytest

from pollard_pin.painting.film.part import surface_film
from pollard_pin.painting.report import line_table, surface_report


@pytest.fixture(scope="module")
def part_report(panel_part_plan, act, job):
    plan = panel_part_plan  # the example panel as a two-triangle mesh, planned once
    pts, film, painted, te = surface_film(plan, job.sigma)
    return plan, surface_report(plan, pts, film, painted, te, act), pts, film


def test_part_report_numbers(part_report, act):
    plan, rep, pts, film = part_report
    th = rep["thickness"]
    assert th["min"] <= th["mean"] <= th["max"]
    assert 0 <= th["within_5pct"] <= th["within_10pct"] <= 1
    # a flat panel: the thickness is the area-weighted mean of the film points
    assert th["mean"] == pytest.approx(np.average(film.thickness, weights=pts.areas), rel=1e-12)
    job = plan.job
    assert rep["lower_bound"] == pytest.approx(plan.part.painted_area * job.thickness / job.flow)
    assert rep["largest_incidence_deg"] < 1e-6  # a flat panel: the gun is normal
    assert 0 < rep["transfer_efficiency"] < 1
    assert set(rep["motors"]) == set(act.names)
    assert rep["passes"] == len(plan.layout.passes)
    # the spline through the 1 mm samples: its speed within 1e-6 of the spot's (measured)
    assert rep["tip_speed_range"][0] == pytest.approx(plan.speed, rel=1e-4)


def test_line_table_numbers(line_plan):
    t = line_table(line_plan)
    # the cycle: from leaving the start pose (the first sample that moves, to one step) to
    # the path's end, the wait before it left out
    tr = line_plan.trajectory
    first = int(np.argmax(np.abs(tr.d_poses).max(axis=1) > 0))
    assert tr.t[-1] - tr.t[first] <= t["cycle"] <= tr.t[-1] - tr.t[first - 1]
    assert t["path_time"] == tr.t[-1] > t["cycle"] + 5.0  # the example waits 7.8 s
    assert t["min_pitch"] == pytest.approx(line_plan.speed * t["cycle"], rel=1e-15)
    assert t["parts_per_hour"] == pytest.approx(3600 / t["cycle"], rel=1e-15)
    j = line_plan.job
    assert t["upper_bound"] == pytest.approx((0.9 + t["window_length"]) / (
        0.9 * 0.1 * j.thickness / j.flow), rel=1e-12)
    # the window: the world interval the sprayed tips span along the line
    on = line_plan.spray > 0
    y = line_plan.trajectory.poses[on, 1]
    assert t["window"] == [y.min(), y.max()]
    assert line_plan.speed < t["upper_bound"]


@pytest.mark.parametrize("rep, says", [
    ({"cycle_time": 2.0, "lower_bound": 2.5}, "lower bound 2.5 s exceeds the cycle 2 s"),
    ({"cycle_time": 2.0, "lower_bound": 1.0, "transfer_efficiency": 1.1},
     "transfer efficiency 110 % exceeds 100 %"),
])
def test_a_report_breaking_an_invariant_is_an_internal_error(rep, says):
    from pollard_pin.painting.errors import ReportError
    from pollard_pin.painting.report import check_report

    with pytest.raises(ReportError, match=says):
        check_report(rep, "job.toml")
    ok = {"cycle_time": 2.0, "lower_bound": 2.0, "transfer_efficiency": 1.0}
    assert check_report(ok, "job.toml") is ok
