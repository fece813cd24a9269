"""A panel on a moving line (docs/model.md §24): the frames, the phases, the pass order, the
delay, the fastest speed (fixtures line_job, line_plan: tests/examples_planned.py)."""
from dataclasses import replace

import numpy as np
import pytest

from pollard_pin.painting.errors import LineSpeedError
from pollard_pin.painting.line.panel import (
    CATCH,
    line_shift,
    max_line_speed,
    plan_line,
    relative_motion,
    world_motion,
)
from pollard_pin.painting.report import line_table


def test_world_is_relative_plus_the_line(line_plan):
    """During the program the world path minus the line's displacement (and velocity) is the
    relative raster, exactly; the accelerations are the relative ones."""
    p = line_plan
    tr = p.trajectory
    on = p.spray > 0
    rel, d, dd = relative_motion(p.frame, p.job, p.segments, p.horizontal,
                                 tr.t[on] - p.times.delay)
    shift = p.speed * tr.t[on, None] * p.direction
    assert np.abs(tr.poses[on, :3] - shift - rel[:, :3]).max() < 1e-12
    assert np.abs(tr.d_poses[on, :3] - p.speed * p.direction - d[:, :3]).max() < 1e-12
    assert np.abs(tr.dd_poses[on] - dd).max() == 0.0


def test_speed_zero_is_the_still_motion(line_plan):
    p = line_plan
    rel, d, _ = relative_motion(p.frame, p.job, p.segments, p.horizontal,
                                np.linspace(0, p.segments.total, 50))
    w, wd = line_shift(rel, d, np.linspace(0, p.segments.total, 50), 0.0, p.direction)
    assert np.array_equal(w, rel) and np.array_equal(wd, d)


def test_world_path_is_smooth_and_returns(line_plan):
    """C¹ across the phases (finite differences of the positions match the rates), at rest
    at both ends, back at the start pose: the cycle."""
    p = line_plan
    T = p.times
    for tk in (T.delay - CATCH, T.delay, T.end, T.end + CATCH):
        h = 1e-6
        pm, dm, _, _ = world_motion(p.relative, p.speed, p.direction, T,
                                    np.array([tk - h, tk, tk + h]))
        fd = (pm[2, :3] - pm[0, :3]) / (2 * h)
        assert np.abs(fd - dm[1, :3]).max() < 1e-4 * (1 + p.speed), tk
        assert np.abs(dm[2] - dm[0]).max() < 1e-3, tk
    tr = p.trajectory
    assert np.abs(tr.poses[-1] - tr.poses[0]).max() < 1e-12
    assert np.abs(tr.d_poses[[0, -1]]).max() < 1e-12
    assert p.spray[0] == 0 and p.spray[-1] == 0


def test_leading_end_first_and_passes_across(line_plan, line_job):
    """Passes run along the panel's height (across the travel along +y = u), the first at
    the leading (largest u) end."""
    p = line_plan
    assert not p.horizontal
    assert p.offsets[0] > 0 > p.offsets[-1]
    assert np.all(np.diff(p.offsets) < 0)


def test_motors_and_reach_on_the_world_path(line_plan):
    r = line_plan.ratios
    assert r["peak_torque"].max() <= 1.0 and r["speed"].max() <= 1.0


def test_never_within_reach(robot, line_job, act):
    job = replace(line_job, center=(0.70, 2.5, 0.16))  # already past the robot
    with pytest.raises(Exception, match="never comes within reach"):
        plan_line(robot, job, act)


def test_fastest_plans_and_five_percent_more_is_refused(robot, line_job, act):
    fastest_speed, plan = max_line_speed(robot, line_job, act)
    assert plan.speed == fastest_speed
    assert line_table(plan)["upper_bound"] > fastest_speed
    with pytest.raises(LineSpeedError):
        plan_line(robot, line_job, act, 1.05 * fastest_speed)


def test_too_slow_and_too_fast_are_told_apart(robot, line_job, act):
    """A failure's side is the drift's sign (a slow line fails on the motors too, at the
    reach's edge), which --max-line-speed's bracketing needs."""
    with pytest.raises(LineSpeedError) as slow:
        plan_line(robot, line_job, act, 0.02)  # 104 % of a motor's peak: the reach's edge
    assert not slow.value.too_fast
    with pytest.raises(LineSpeedError) as fast:
        plan_line(robot, line_job, act, 0.06)
    assert fast.value.too_fast
