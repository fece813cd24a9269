"""dynamics/tracking_options.py: TrackingOptions checked once (one-line errors), the RK4 step
rules and the hard cap on a run's steps; the runs it stops before any work."""
import math
import warnings

import numpy as np
import pytest
from thesis_curves import thesis_head

from pollard_pin.dynamics.control import ControlError, Gains
from pollard_pin.dynamics.forward import SimulationError
from pollard_pin.dynamics.inverse import JointLosses
from pollard_pin.dynamics.plant import ModelMismatch
from pollard_pin.dynamics.tracking import simulate_tracking
from pollard_pin.dynamics.tracking_options import (
    DT,
    MAX_STEPS,
    STEP_SECONDS,
    TICK_SECONDS,
    MeasurementNoise,
    TrackingOptions,
    check_step_count,
    estimated_wall,
    integration_steps,
)


@pytest.mark.parametrize("kwargs, says", [
    ({"controller": "lqr"}, "unknown controller 'lqr' (expected one of: computed-torque"),
    ({"controller": 3}, "controller must be a name or a callable, got int"),
    ({"gains": (60, 1)}, "gains must be a Gains, got tuple"),
    ({"dt": 2e-3}, "time step 0.002 s is longer than the control period 0.001 s"),
    ({"control_period": math.inf}, "control period must be > 0 s, got inf"),
    ({"torque_limit": [1, 2]}, "give one value or 6 (one per actuator), got 2"),
    ({"torque_limit": -1}, "torque limits must be > 0 N·m"),
    ({"loop_tolerance": 0.0}, "loop tolerance must be > 0 m, got 0.0"),
    # an integer beyond a float, a string, a bool: the same line, not OverflowError/TypeError
    ({"dt": 10**400}, "time step must be > 0 s, got 1e+400 (a 401-digit integer)"),
    ({"dt": "0.001"}, "time step must be > 0 s, got '0.001'"),
    ({"control_period": "x"}, "control period must be > 0 s, got 'x'"),
    ({"control_period": True}, "control period must be > 0 s, got True"),
    ({"noise": "n"}, "noise must be a MeasurementNoise"),
    ({"torque_limit": "x"}, "torque limit = 'x': expected an array of real numbers"),
    ({"torque_limit": [10**400] * 6}, "torque limit = [1000"),
])
def test_bad_options_are_one_line_at_construction(kwargs, says):
    with pytest.raises(ControlError) as err:
        TrackingOptions(**kwargs)
    assert says in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("value", ["x", 10**400, math.nan, -1.0], ids=["str", "1e400", "nan", "-1"])
def test_bad_noise_is_one_line(value):
    with pytest.raises(ControlError, match="^position noise standard deviation must be >= 0"):
        MeasurementNoise(position=value)


def test_the_step_and_the_limits_as_the_run_uses_them():
    assert TrackingOptions().step == DT
    assert TrackingOptions(control_period=4e-4).step == 4e-4  # the period, if shorter
    assert TrackingOptions(dt=2e-4, control_period=4e-4).step == 2e-4
    assert TrackingOptions().limits is None
    np.testing.assert_array_equal(TrackingOptions(torque_limit=2.5).limits, np.full(6, 2.5))
    assert TrackingOptions(controller=lambda t, q, v: np.zeros(6)).label == "function"
    assert TrackingOptions(gains=Gains(10, 0.5)).gains.kp == 100


def test_the_estimate_counts_steps_and_ticks():
    # 0.1 s at 1 ms ticks, each in ⌈1e-3 / 4e-4⌉ = 3 steps: 300 steps, 100 ticks
    assert integration_steps(0.1, 4e-4, 1e-3) == 300
    assert estimated_wall(0.1, 4e-4, 1e-3) == pytest.approx(
        300 * STEP_SECONDS + 100 * TICK_SECONDS, rel=1e-15)


def test_the_step_cap_refuses_past_it_and_not_at_it():
    check_step_count(MAX_STEPS * 1e-3, 1e-3, 1e-3)  # exactly the cap: allowed
    with pytest.raises(ControlError, match=r"50,001,000 RK4 steps .* more than a simulation "
                                           r"can hold \(5e\+07\)"):
        check_step_count((MAX_STEPS + 1000) * 1e-3, 1e-3, 1e-3)
    with pytest.raises(ControlError, match=r"^2\.2e\+299 RK4 steps"):  # not 300 digits
        check_step_count(0.22, 1e-300, 1e-300)
    # a step or a period of 5e-324 s: the count's ceil overflowed (an OverflowError traceback
    # from simulate --dt 5e-324)
    for dt, period in ((5e-324, 1e-3), (5e-324, 5e-324)):
        assert integration_steps(6.0, dt, period) == math.inf
        with pytest.raises(ControlError, match=r"^inf RK4 steps .* more than a simulation"):
            check_step_count(6.0, dt, period)
    assert estimated_wall(6.0, 5e-324, 1e-3) == math.inf


def test_a_run_past_the_cap_or_with_one_tick_stops_before_any_work(robot):
    traj = thesis_head(0.2)
    with pytest.raises(ControlError, match="more than a simulation can hold"):
        simulate_tracking(robot, traj, TrackingOptions(dt=1e-12, control_period=1e-12))
    # a period longer than the trajectory: one tick, the controller would act once
    with pytest.raises(ControlError, match=r"control period 1e\+300 s is longer than the "
                                           r"trajectory \(0\.2 s\)"):
        simulate_tracking(robot, traj, TrackingOptions(control_period=1e300))
    with pytest.raises(ControlError, match="must be a TrackingOptions, got str"):
        simulate_tracking(robot, traj, "pd")


def test_a_plant_that_runs_away_is_named_once_without_numpy_warnings(robot):
    # viscous friction of 1e300 N·m·s: the divergence named once, numpy's overflow silent
    losses = JointLosses(viscous=np.where(np.isin(np.arange(12), robot.actuated_v), 1e300, 0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning fails the test
        with pytest.raises(SimulationError, match=r"simulation diverged at t = 0\.001 s"):
            simulate_tracking(robot, thesis_head(0.05),
                              TrackingOptions(errors=ModelMismatch(losses=losses)))
