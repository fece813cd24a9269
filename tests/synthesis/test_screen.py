"""The design's screen (synthesis/screen.py, docs/model.md §31.3): its coarse band against the
planner's own reference band, and the holding torques against the motors' ratings."""
from dataclasses import replace

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.painting.cell.bands import job_strokes
from pollard_pin.painting.layout.cell import reference_band
from pollard_pin.synthesis.screen import held_poses, motors, reach


@pytest.fixture(scope="module")
def case():
    robot = pp.load()
    strokes = job_strokes(pp.load_job("examples/design/job.toml"))
    return robot, strokes, reference_band(robot, strokes)


def test_screen_band_agrees_with_the_planners(case):
    robot, strokes, ref = case
    middle = replace(strokes, samples=(strokes.samples[len(strokes.samples) // 2],))
    off, fig, band = reach(robot, middle, 1)
    # the planner's band at 5 mm steps: 0.30 m; the screen's at 20 mm, shifts 50 mm apart
    assert abs(band.width - ref.width) <= 0.03 and abs(band.lo - ref.lo) <= 0.03
    assert fig["robots_needed"] == 2  # the thesis robot takes two for the 0.38 m door
    assert off == pytest.approx(0.38 + 2 * 0.04 - band.width)  # one zone: the door + run-ons
    assert reach(robot, middle, 2)[0] < 0


def test_holding_torques_over_the_ratings(case):
    robot, strokes, ref = case
    poses = held_poses(robot, strokes, ref)
    assert poses.shape == (3, 6)
    np.testing.assert_allclose(poses[:, 0], 0.55, atol=1e-9)  # the tip at the standoff
    act = load_actuators()
    off, fig = motors(robot, act, poses)
    # the weight alone takes a fraction of the base motors' peak (paint's plans reach 97 %
    # with the accelerations)
    assert 0.05 < fig["static_peak_use"] < 1.0 and off < 0
    weak = replace(act, units=tuple(replace(u, peak_torque=u.peak_torque / 100,
                                            continuous_torque=u.continuous_torque / 100)
                                    for u in act.units))
    assert motors(robot, weak, poses)[0] > 0


def test_screen_and_planner_agree_one_robot_is_too_few(case):
    """The screen says the thesis robot needs two for the door; the planner's layout refuses
    one robot, naming two."""
    from pollard_pin.painting.errors import CellError
    from pollard_pin.painting.layout.cell import propose_layout

    robot, strokes, ref = case
    with pytest.raises(CellError, match="at least 2 robots"):
        propose_layout(robot, pp.load_job("examples/design/job.toml"), 1)


def test_still_panel_reach_agrees_with_the_planner(case):
    from pollard_pin.painting.errors import PlanError
    from pollard_pin.synthesis.screen import panel_reach

    robot = case[0]
    off, fig = panel_reach(robot, pp.load_job("examples/paint.toml"))
    assert off == 0.0 and fig["reached_share"] == 1.0  # the example paints
    big = pp.job_from_dict({
        "panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.9,
                  "height": 0.5},
        "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7}, "job": {"thickness": 25e-6}})
    off, fig = panel_reach(robot, big)
    assert 0.5 < off < 1.0  # most of a 0.9 × 0.5 m panel is beyond the 0.6 × 0.25 m rectangle
    with pytest.raises(PlanError, match="reach"):
        pp.paint(robot, big)


def test_turnaround_runon_is_the_planners_raster():
    """A panel's gun runs past its passes' ends by the ramp's v·τ/2 (the turnaround's quintic
    x − 2x³ + x⁴ peaks at 5/16 v·τ), τ the duration search's first guess 4v/10 s."""
    from pollard_pin.painting.plan.layout import panel_layout
    from pollard_pin.synthesis.screen import turn_runon

    job = pp.load_job("examples/design/job.toml")
    v = panel_layout(job).speed
    tau = 4 * v / 10.0
    assert turn_runon(job) == pytest.approx(max(v * tau / 2, 5 / 16 * v * tau), rel=1e-4)
    assert 0.015 < turn_runon(job) < 0.03  # some 2 cm at the door's 0.33 m/s
    assert turn_runon(pp.load_job("examples/line_part.toml")) == 0.0
