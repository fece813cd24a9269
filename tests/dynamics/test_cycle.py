"""A path with waits (dynamics/cycle.py, docs/model.md §19): its moving segments, each solved
on its own, give the cycle, exactly the strokes' own solved alone (so the shortcut can fail),
and the sizing and the retimed file are of that cycle."""
import re

import numpy as np
from motor_model import EXAMPLE

import pollard_pin as pp
from pollard_pin.dynamics import motors as M
from pollard_pin.dynamics.cycle import moving_segments
from pollard_pin.dynamics.sizing import actuator_sizing
from pollard_pin.io.retime import retime_metadata, retimed_trajectory


def _stroke(n=201, duration=4.0, share=0.25):
    """The first ``share`` of the thesis curve, timed by the smooth step 10x³ − 15x⁴ + 6x⁵:
    at rest at both ends (exact rates and accelerations by the chain rule). A quarter: the
    time-optimal grid, the cost, follows the arc length; the equalities hold at any."""
    from pollard_pin.paths.curves import thesis_curve

    x = np.linspace(0.0, 1.0, n)
    u = share * duration * (10 * x**3 - 15 * x**4 + 6 * x**5)
    du = share * (30 * x**2 - 60 * x**3 + 30 * x**4)
    ddu = share * (60 * x - 180 * x**2 + 120 * x**3) / duration
    p, d, dd = thesis_curve(u, duration)
    return x * duration, p, d * du[:, None], dd * du[:, None] ** 2 + d * ddu[:, None]


def test_waits_at_the_ends_are_left_out_of_the_time_optimal_cycle(robot):
    """A line job's path: a wait (here 300 samples at 2 ms), the strokes, a wait. Its
    time-optimal cycle is exactly that of the strokes alone, solved on their own samples
    (the wait is not solved at all: with it the path stops inside, so the solve fell back to
    the samples' time for all 600 samples); its given motion still counts the waits."""
    act = M.load_actuators(EXAMPLE)
    t, p, d, dd = _stroke()
    before, after = 300, 100
    zero = np.zeros((1, 6))
    full = pp.Trajectory(
        np.concatenate([t[0] - 2e-3 * np.arange(before, 0, -1), t,
                        t[-1] + 2e-3 * np.arange(1, after + 1)]),
        np.vstack([np.repeat(p[:1], before, 0), p, np.repeat(p[-1:], after, 0)]),
        *(np.vstack([np.repeat(zero, before, 0), x, np.repeat(zero, after, 0)])
          for x in (d, dd)), name="waits")
    assert moving_segments(full) == [(before, before + len(t))]  # the stroke's rest ends
    waits = actuator_sizing(robot, pp.run_pipeline(robot, full), act)
    alone = actuator_sizing(robot, pp.run_pipeline(robot, pp.Trajectory(t, p, d, dd)), act)
    for key in ("t", "s", "s_dot", "s_ddot"):
        np.testing.assert_array_equal(getattr(waits.timing, key), getattr(alone.timing, key))
    for name in act.names:
        got, want = waits.report["actuators"][name], alone.report["actuators"][name]
        for key in want:
            if key.startswith("time_optimal"):
                assert got[key] == want[key], (name, key)
    assert waits.report["trajectory"]["duration"] > alone.report["trajectory"]["duration"]


def test_a_wait_inside_splits_the_cycle_into_its_strokes(robot):
    """Two strokes (the thesis curve's first quarters, rest to rest) with a 400-sample wait
    between: the time-optimal cycle is the strokes' own, each solved alone, one after the
    other (bit for bit; with the wait solved along, the path stopped inside and all 800
    samples were TOPP-RA's grid); the retimed file has their rows once, times increasing."""
    act = M.load_actuators(EXAMPLE)
    from pollard_pin.paths.curves import thesis_curve

    # the curve's first two quarters (u from 0 to 5 s and 5 to 10 s of the 20 s curve; a
    # quarter each, not a half: the time-optimal grid, the cost, follows the arc length)
    x = np.linspace(0.0, 1.0, 201)
    w, dw = 10 * x**3 - 15 * x**4 + 6 * x**5, 30 * x**2 - 60 * x**3 + 30 * x**4
    ddw = 60 * x - 180 * x**2 + 120 * x**3
    T = 4.0
    p2, d2, dd2 = thesis_curve(5.0 + 5.0 * w, 20.0)
    p1, d1, dd1 = thesis_curve(5.0 * w, 20.0)
    du, ddu = 5.0 * dw / T, 5.0 * ddw / T**2
    one = pp.Trajectory(x * T, p1, d1 * du[:, None], dd1 * du[:, None] ** 2 + d1 * ddu[:, None])
    two = pp.Trajectory(x * T, p2, d2 * du[:, None], dd2 * du[:, None] ** 2 + d2 * ddu[:, None])
    wait = 400
    tw = T + 2e-3 * np.arange(1, wait + 1)
    zero = np.zeros((wait, 6))
    full = pp.Trajectory(np.concatenate([one.t, tw, tw[-1] + 2e-3 + two.t]),
                         np.vstack([one.poses, np.repeat(one.poses[-1:], wait, 0), two.poses]),
                         np.vstack([one.d_poses, zero, two.d_poses]),
                         np.vstack([one.dd_poses, zero, two.dd_poses]), name="two")
    n = len(one.t)
    assert moving_segments(full) == [(0, n), (n + wait, 2 * n + wait)]
    sized = actuator_sizing(robot, pp.run_pipeline(robot, full), act)
    later = pp.Trajectory(full.t[n + wait:], two.poses, two.d_poses, two.dd_poses)
    parts = [pp.time_optimal_path(robot, act, half) for half in (one, later)]
    timing = sized.timing
    assert len(timing.parts) == 2
    for got, want in zip(timing.parts, parts):
        for key in ("t", "s", "s_dot", "s_ddot"):
            np.testing.assert_array_equal(getattr(got, key), getattr(want, key))
    assert timing.duration == parts[0].duration + parts[1].duration
    assert timing.between == max(p.between for p in parts)
    retimed = retimed_trajectory(full, timing)
    k = len(parts[0].t)
    assert len(retimed.t) == k + len(parts[1].t) - 1 and np.all(np.diff(retimed.t) > 0)
    # the second stroke's times, offset (achieved 4e-16 s)
    np.testing.assert_allclose(retimed.t[k - 1:] - retimed.t[k - 1], parts[1].t, rtol=0,
                               atol=5e-14)
    meta = retime_metadata(full, timing)
    assert [s["rows"] for s in meta["segments"]] == [[0, k - 1], [k - 1, len(retimed.t) - 1]]


def test_time_optimal_path_refuses_wrong_arguments(robot):
    """A string for the motors or the trajectory, a dict for the options: one InputError line
    naming the argument, not an AttributeError from inside."""
    act, traj = pp.load_actuators(), pp.thesis_trajectory(samples=11)
    for args, says in (((None, act, traj), "^robot = None: expected a Robot"),
                       ((robot, "x", traj), r"^act = 'x': expected Actuators \("),
                       ((robot, act, "x"), "^traj = 'x': expected a Trajectory"),
                       ((robot, act, traj, {}), "^options = {}: expected pollard_pin.dynamics")):
        try:
            pp.time_optimal_path(*args)
        except pp.InputError as exc:
            assert re.search(says, str(exc)), exc
        else:
            raise AssertionError(f"{says} not raised")
