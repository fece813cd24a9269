"""A path's exact dynamics (dynamics/path.py, docs/model.md §19): τ = a·s̈ + b·ṡ² + c gives
the pipeline's torques at another duration, and between the samples (path_dynamics_at) the
analytic curve gives the samples' own coefficients."""
from functools import partial

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.dynamics.path import path_dynamics, path_dynamics_at
from pollard_pin.paths.curves import thesis_curve

SAMPLES = 801


@pytest.fixture(scope="module")
def thesis(robot):
    return pp.run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES))


def test_path_torques_are_exact_at_another_duration(robot, thesis):
    path = path_dynamics(robot, thesis.ik)
    D = 7.3
    res = pp.run_pipeline(robot, pp.thesis_trajectory(duration=D, samples=SAMPLES))
    # uniform: ṡ = 1/D, s̈ = 0
    np.testing.assert_allclose(res.dynamics.tau, path.b / D**2 + path.c, rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.ik.v[:, robot.actuated_v], path.q_s / D, atol=1e-12)


def test_coefficients_anywhere_are_those_at_the_samples(robot):
    # The thesis curve evaluated at a few of the samples' path points: the same IK and RNEA,
    # so the same coefficients (bit-equal here; asserted to 1e-12 of each array's peak, room
    # for another BLAS).
    traj = pp.thesis_trajectory(samples=201)
    at_samples = path_dynamics(robot, pp.run_pipeline(robot, traj, dynamics=False).ik)
    k = np.array([0, 37, 100, 163, 200])
    anywhere = path_dynamics_at(robot, partial(thesis_curve, duration=20.0), 0.0, 20.0,
                                at_samples.s[k])
    for name in ("a", "b", "c", "q_s", "q_ss"):
        want, got = getattr(at_samples, name)[k], getattr(anywhere, name)
        assert np.abs(got - want).max() <= 1e-12 * max(1.0, np.abs(want).max()), name
    assert anywhere.duration == 20.0 and np.array_equal(anywhere.s, at_samples.s[k])
