"""The torque–speed figure and the sizing table (viz/torque_speed.py): each plotted line is the
sizing's own array, the envelopes are the ratings, the Markdown names the cycle and its check."""
import numpy as np
from motor_model import EXAMPLE, NAMES, RATINGS

import pollard_pin as pp
from pollard_pin.dynamics import motors as M
from pollard_pin.dynamics.sizing import actuator_sizing
from pollard_pin.viz.torque_speed import to_markdown, torque_speed_figure


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
