"""The compiled closed-loop state of a control tick (pollard_pin/kinematics/sensing.py,
csrc/sense.c) against Pinocchio's: close_loops, the velocity map and the closures' drift."""
import numpy as np
import pytest
from thesis_curves import thesis_head

from pollard_pin.dynamics.control import desired_trajectory
from pollard_pin.kinematics.closure import CLOSURE_TOL, MAX_ITER, close_loops
from pollard_pin.kinematics.errors import ClosureError
from pollard_pin.kinematics.sensing import LoopSensor, reference_state

RNG = np.random.default_rng(20261125)


@pytest.fixture(scope="module")
def states(robot):
    """(θ, θ̇, warm start) along the thesis curve's head, off it by up to 2 mrad and 0.5 rad/s
    (what sensing sees under noise and tracking errors), warm-started a tick back."""
    desired = desired_trajectory(robot, thesis_head(0.05))
    ia = robot.actuated_v
    out = []
    for k in range(1, len(desired.t), 4):
        theta = desired.q[k, ia] + RNG.uniform(-2e-3, 2e-3, 6)
        dtheta = desired.v[k, ia] + RNG.uniform(-0.5, 0.5, 6)
        out.append((theta, dtheta, desired.q[k - 1] + 1e-3 * desired.v[k - 1]))
    return out


def test_compiled_state_matches_pinocchio(robot, states):
    sensor = LoopSensor(robot)
    assert sensor.compiled
    worst = np.zeros(5)
    for theta, dtheta, guess in states:
        got = sensor(theta, dtheta, guess)
        ref = reference_state(robot, theta, dtheta, guess)
        for i, (a, b) in enumerate(zip(got, ref)):
            assert a.shape == b.shape
            worst[i] = max(worst[i], np.abs(a - b).max() / max(np.abs(b).max(), 1.0))
        q, v, Jc = got[:3]
        assert np.all(q[robot.actuated_v] == theta)
        assert np.all(v[robot.actuated_v] == dtheta)
        assert np.abs(Jc @ v).max() <= 1e-12 * np.abs(v).max()
    # achieved: q, v, Jc, N ≤ 1e-15, a₀ 1.4e-15 (relative to the largest entry, or 1)
    assert worst.max() <= 1e-13


def test_compiled_state_falls_back_with_the_reference_errors(robot, states):
    """Where the compiled Newton does not find the state, the Pinocchio path runs and raises
    what close_loops raises, word for word."""
    sensor = LoopSensor(robot)
    theta, dtheta, guess = states[0]
    for bad in (np.r_[theta[:5], np.nan], theta[:5]):
        with pytest.raises(ValueError) as ref:
            close_loops(robot, bad, guess)
        with pytest.raises(ValueError, match="actuator angles must be 6 finite numbers") as got:
            sensor(bad, dtheta, guess)
        assert str(got.value) == str(ref.value)
    far = theta.copy()
    far[1] = np.pi  # leg 1's base arm turned backwards: no assembly (tests/model/test_build.py)
    with pytest.raises(ClosureError) as ref:
        close_loops(robot, far, guess)
    with pytest.raises(ClosureError) as got:
        sensor(far, dtheta, guess)
    assert str(got.value) == str(ref.value)


def test_near_singular_states_take_the_reference_path(robot, states, monkeypatch):
    """Below σ_min/σ_max = GRAM_TRUSTED the compiled Gram value is not trusted: Pinocchio's
    path (SVD and the floor of close_loops) decides, so its result comes back bit for bit."""
    from pollard_pin.kinematics import sensing

    monkeypatch.setattr(sensing, "_TRUSTED", 2.0)  # λ_min > 2 λ_max never holds
    theta, dtheta, guess = states[2]
    for a, b in zip(LoopSensor(robot)(theta, dtheta, guess),
                    reference_state(robot, theta, dtheta, guess)):
        np.testing.assert_array_equal(a, b)


def test_kernel_reports_no_convergence(robot, states):
    """The kernel's own refusals: −1 after max_iter steps short of the tolerance, or on a
    non-finite input; Newton's step count otherwise (one or two from a tick-old start)."""
    kernel = LoopSensor(robot)._kernel
    theta, dtheta, guess = states[1]
    steps = kernel(theta, dtheta, guess, CLOSURE_TOL, MAX_ITER)[0]
    assert 1 <= steps <= 3
    assert kernel(theta, dtheta, guess, CLOSURE_TOL, steps - 1)[0] == -1
    assert kernel(theta, dtheta, np.full(12, np.inf), CLOSURE_TOL, MAX_ITER)[0] == -1
    with pytest.raises(ValueError, match="kernels: guess holds 88 bytes"):
        kernel(theta, dtheta, guess[:11], CLOSURE_TOL, MAX_ITER)

