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



def test_actuator_sizing_refuses_wrong_arguments(robot):
    """None for the robot or the run's result, a string for the motors: one InputError line
    naming the argument, not an AttributeError from inside."""
    act = M.load_actuators(EXAMPLE)
    for args, says in (((None, None, act), "^robot = None: expected a Robot"),
                       ((robot, None, "x"), r"^act = 'x': expected Actuators \("),
                       ((robot, "x", act), r"^result = 'x': expected a run's result")):
        with pytest.raises(pp.InputError, match=says):
            actuator_sizing(*args)
