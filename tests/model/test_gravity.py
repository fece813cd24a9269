"""Gravity in a robot's base frame (model/gravity.py, docs/model.md §26.1): a model copy with
another gravity, checked against the linearity of the gravity torques in g; the shared model
untouched; bad gravities refused in one line."""
import numpy as np
import pinocchio as pin
import pytest

from pollard_pin.errors import InputError
from pollard_pin.model.gravity import GRAVITY, check_gravity, with_gravity


def gravity_torques(robot, q):
    return pin.computeGeneralizedGravity(robot.model, robot.data, q).copy()


def test_a_model_copy_carries_its_gravity(robot):
    """The generalized gravity forces are linear in g (docs/model.md §2): for g = R·g0 they are
    the sum of the default model's, scaled per component; the shared model is left as is."""
    q = robot.home()
    g0 = gravity_torques(robot, q)  # g = (0, 0, −9.81)
    g = np.array([3.0, -4.0, 8.0])  # |g| 9.43 m/s²
    turned = with_gravity(robot, g)
    assert np.array_equal(robot.model.gravity.linear, GRAVITY)  # untouched
    assert turned.model is not robot.model and turned.data is not robot.data
    # brute force: one unit-axis model per component, the default's as the z one
    parts = []
    for axis in range(2):
        e = np.zeros(3)
        e[axis] = 1.0
        parts.append(gravity_torques(with_gravity(robot, e), q))
    want = g[0] * parts[0] + g[1] * parts[1] + g[2] * (g0 / -9.81)
    got = gravity_torques(turned, q)
    assert np.abs(got - want).max() <= 1e-14 * np.abs(want).max()  # seen 1.3e-16
    assert with_gravity(robot, GRAVITY.copy()) is robot


@pytest.mark.parametrize("g", [[0.0, 0.0, 9.81], [0.0, 0.0, -8.83], [10.79, 0.0, 0.0],
                               [6.0, 6.0, -4.5]])
def test_gravities_within_ten_percent_pass(g):
    assert np.array_equal(check_gravity(g, "here"), np.asarray(g, float))


@pytest.mark.parametrize("g, why", [([0.0, 0.0, -8.8], "10% off 9.81"),
                                    ([0.0, 0.0, -10.8], "10% off 9.81"),
                                    ([0.0, 0.0, 0.0], "100% off 9.81"),
                                    ([0.0, 0.0, float("inf")], "three finite numbers"),
                                    ([[0.0, 0.0, -9.81]], "three finite numbers"),
                                    ([0.0, "x", -9.81], "three numbers"),
                                    ([True, 0, -9.81], "not booleans"),
                                    ([0, 0, np.True_], "not booleans"),
                                    (np.array([True, False, True]), "not booleans"),
                                    (True, "not booleans"),
                                    ([0.0, 0.0, -1e308], "component of 1e+308"),
                                    ([1e200, 1e200, 1e200], "component of 1e+200"),
                                    (None, "three")])
def test_bad_gravities_are_one_line(g, why):
    """Booleans are refused as everywhere else; a huge component before any arithmetic (its
    square would overflow with a numpy warning)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError, match="^here: gravity") as info:
            check_gravity(g, "here")
    assert why in str(info.value) and "\n" not in str(info.value)
