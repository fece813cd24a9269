"""The motor sizing (dynamics/sizing.py, docs/model.md §19): a path that does not move the
actuators is refused. (Its figure and table: tests/viz/test_torque_speed.py; the command:
tests/cli/test_size.py.)"""
import numpy as np
import pytest
from motor_model import EXAMPLE

import pollard_pin as pp
from pollard_pin.dynamics import motors as M
from pollard_pin.dynamics.sizing import actuator_sizing


def test_a_path_that_does_not_move_the_actuators_is_refused(robot):
    # A constant pose sampled 50 times (rates zero here, round-off ≈ 1e-14 rad per unit of
    # path from a spline): the sizing printed a "shortest cycle" of 6e-7 s instead of refusing.
    t = np.linspace(0.0, 0.98, 50)
    pose = np.tile(robot.params.home_pose, (50, 1))
    still = pp.Trajectory(t, pose, np.zeros_like(pose), np.zeros_like(pose), name="still")
    with pytest.raises(M.ActuatorError, match=r"^the path does not move the actuators \(each "
                                              r"travels at most .* rad over its 50 samples\)$"):
        actuator_sizing(robot, pp.run_pipeline(robot, still), M.load_actuators(EXAMPLE))


def _stroke(n=201, duration=4.0):
    """The thesis curve once over, timed by the smooth step 10x³ − 15x⁴ + 6x⁵: at rest at
    both ends (exact rates and accelerations by the chain rule)."""
    from pollard_pin.paths.curves import thesis_curve

    x = np.linspace(0.0, 1.0, n)
    u = duration * (10 * x**3 - 15 * x**4 + 6 * x**5)
    du = 30 * x**2 - 60 * x**3 + 30 * x**4
    ddu = (60 * x - 180 * x**2 + 120 * x**3) / duration
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
    from pollard_pin.dynamics.timeopt import moving_span

    assert moving_span(full) == (before, before + len(t))  # the rest ends are the stroke's
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
