"""A panel on a moving line (docs/model.md §24): the [line] table, the frames, the film in the
part's frame, the delay, the fastest speed."""
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.analytic.taskspace import rotation
from pollard_pin.model.params import read_toml
from pollard_pin.paint.deposition import film
from pollard_pin.paint.job import JobError, job_from_dict, load_job
from pollard_pin.paint.line import (
    CATCH,
    LineSpeedError,
    line_shift,
    max_line_speed,
    plan_line,
    relative_motion,
    world_motion,
)
from pollard_pin.paint.line_job import MAX_LINE_SPEED
from pollard_pin.paint.line_report import line_film, line_table
from pollard_pin.paint.plan import gun_of

ROOT = Path(__file__).resolve().parents[2]
LINE = ROOT / "examples" / "line.toml"


@pytest.fixture(scope="module")
def line_job():
    return load_job(LINE)


@pytest.fixture(scope="module")
def line_plan(robot, line_job, act):
    return plan_line(robot, line_job, act)


def _raw():
    return read_toml(LINE, "paint job file", JobError)


@pytest.mark.parametrize("line, words", [
    ({"speed": 0.03, "direction": [0.0, 0.0, 0.0]}, "zero length"),
    ({"speed": 0.0, "direction": [0.0, 1.0, 0.0]}, "must be > 0"),
    ({"speed": -0.1, "direction": [0.0, 1.0, 0.0]}, "must be > 0"),
    ({"speed": 30.0, "direction": [0.0, 1.0, 0.0]}, f"at most {MAX_LINE_SPEED:g} m/s"),
    ({"speed": float("inf"), "direction": [0.0, 1.0, 0.0]}, "finite"),
    ({"speed": 0.03, "direction": [0.0, 1.0]}, "3 finite numbers"),
    ({"speed": 0.03}, "'line.direction' is missing"),
    ({"speed": 0.03, "direction": [0.0, 1.0, 0.0], "pitch": 1}, "unknown key"),
])
def test_bad_line_tables(line, words):
    d = _raw()
    d["line"] = line
    with pytest.raises(JobError, match="line") as info:
        job_from_dict(d, "j.toml")
    assert words in str(info.value) and "\n" not in str(info.value)


def test_line_table_read(line_job):
    d = _raw()
    d["line"] = {"speed": 0.02, "direction": [0.0, 3.0, 4.0]}
    job = job_from_dict(d, "j.toml")
    assert job.line.direction == (0.0, 0.6, 0.8) and job.line.speed == 0.02
    assert job.to_dict()["line"] == {"speed": 0.02, "direction": [0.0, 0.6, 0.8]}
    assert line_job.line.speed == 0.03 and line_job.line.direction == (0.0, 1.0, 0.0)
    del d["line"]
    assert job_from_dict(d, "j.toml").line is None


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
    parts = (p.frame, p.job, p.segments, p.horizontal, p.speed, p.direction)
    T = p.times
    for tk in (T.delay - CATCH, T.delay, T.end, T.end + CATCH):
        h = 1e-6
        pm, dm, _, _ = world_motion(parts, T, np.array([tk - h, tk, tk + h]))
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


def test_film_in_the_parts_frame(line_plan):
    """Moving the part and the gun by the same motion gives the film of the relative motion
    over a still part (docs/model.md §24), to 1e-12."""
    p = line_plan
    U, V, pts, f = line_film(p, p.job.sigma)
    tr = p.trajectory
    on = p.spray > 0
    rel, _, _ = relative_motion(p.frame, p.job, p.segments, p.horizontal,
                                tr.t[on] - p.times.delay)
    still = film(gun_of(p.job), tr.t[on] - p.times.delay, rel[:, :3],
                 rotation(rel)[:, :, 0], pts.reshape(-1, 3), p.frame.n, origin=p.frame.c)
    assert np.abs(f.thickness - still.thickness).max() <= 1e-12 * p.job.thickness
    # and the film is the target's: ≥ 99 % within ±5 %, all within ±10 %
    dev = np.abs(f.thickness / p.job.thickness - 1)
    assert np.mean(dev <= 0.05) >= 0.99 and dev.max() <= 0.10


def test_line_table_numbers(line_plan):
    t = line_table(line_plan)
    assert t["cycle"] == pytest.approx(line_plan.trajectory.t[-1])
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
