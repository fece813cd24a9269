"""``pollard-pin size`` end to end: the sizing's figure and table, and destinations checked
before the work (docs/model.md §19)."""
import numpy as np
import pytest
from motor_model import EXAMPLE, NAMES, RATINGS
from motor_model import cli as _cli

import pollard_pin as pp
from pollard_pin.dynamics import motors as M
from pollard_pin.dynamics.sizing import actuator_sizing
from pollard_pin.viz.sizing import to_markdown, torque_speed_figure


def test_torque_speed_figure_draws_points_and_envelopes(robot):
    act = M.load_actuators(EXAMPLE)
    sized = actuator_sizing(robot, pp.run_pipeline(robot, pp.thesis_trajectory(samples=401)),
                            act)
    fig = torque_speed_figure(sized)
    lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines() if ln.get_gid()}
    for j, name in enumerate(NAMES):
        np.testing.assert_array_equal(lines[f"given_{name}"].get_ydata(),
                                      sized.given.torque[:, j])
        np.testing.assert_array_equal(lines[f"time_optimal_{name}"].get_xdata(),
                                      sized.optimal.speed[:, j])
        env = lines[f"envelope_{name}"]
        assert np.abs(env.get_ydata()).max() == RATINGS[name]["peak_torque"]
        assert np.abs(env.get_xdata()).max() == RATINGS[name]["max_speed"]
    text = to_markdown(sized.report)
    assert "time-optimal" in text and f"{sized.timing.duration:.4g} s" in text
    assert f"is {sized.timing.between:.5f}" in text  # the between-sample check it verified


@pytest.mark.parametrize("extra", [["--retime", "{d}/afile/x.csv"], ["--plot", "{d}/afile"],
                                   ["--actuators", "{d}/none.toml"]])
def test_size_checks_destinations_before_the_work(tmp_path, capsys, extra):
    (tmp_path / "afile").write_text("x")
    extra = [x.format(d=tmp_path) for x in extra]
    code, _, err = _cli(["size", "--actuators", str(EXAMPLE), *extra], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1, err


def test_a_path_that_does_not_move_the_actuators_is_refused(robot):
    # A constant pose sampled 50 times (rates zero here, round-off ≈ 1e-14 rad per unit of
    # path from a spline): the sizing printed a "shortest cycle" of 6e-7 s instead of refusing.
    t = np.linspace(0.0, 0.98, 50)
    pose = np.tile(robot.params.home_pose, (50, 1))
    still = pp.Trajectory(t, pose, np.zeros_like(pose), np.zeros_like(pose), name="still")
    with pytest.raises(M.ActuatorError, match=r"^the path does not move the actuators \(each "
                                              r"travels at most .* rad over its 50 samples\)$"):
        actuator_sizing(robot, pp.run_pipeline(robot, still), M.load_actuators(EXAMPLE))
