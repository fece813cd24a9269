"""The singularity margins (docs/model.md §12): one value (Margins), validated once, and one
rule (Margins.violations: a value equal to its limit passes; below it, or NaN, fails) that
the IK, the workspace map and the paint planner all apply, so they give the same verdict on
the same pose, even one exactly at the margin."""
import math

import numpy as np
import pytest
from poses import path_to_wrist_singularity  # tests/poses.py

import pollard_pin as pp
from pollard_pin.analytic import closed_form
from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.errors import InputError
from pollard_pin.kinematics.errors import SingularityError
from pollard_pin.kinematics.ik import inverse_kinematics
from pollard_pin.kinematics.margins import (
    CHECKS,
    SERIAL_FLOOR,
    SIGMA_FLOOR,
    MarginError,
    Margins,
)
from pollard_pin.painting.checks.motion import ReachError, motion
from pollard_pin.workspace.reach import REASONS, ReachOptions, evaluate

EXAMPLES = pp.__path__[0] + "/../examples"
up = math.inf
down = 0.0


def _around(x):
    """x one ulp below, x, x one ulp above."""
    return np.nextafter(x, down), x, np.nextafter(x, up)


# --- the rule ---------------------------------------------------------------------------------
def test_rule_at_just_below_and_just_above_equality():
    m = Margins(wrist=0.3, singularity=0.01)
    below, at, above = _around(0.3)
    got = m.violations(wrist=np.array([below, at, above, np.nan]))
    assert got["wrist"].tolist() == [True, False, False, True]  # equal passes, NaN fails
    s_below, s_at, s_above = _around(0.01)
    vals = np.array([s_below, s_at, s_above, np.nan])
    got = m.violations(parallel=vals, serial=vals)
    for check in ("parallel", "serial"):
        assert got[check].tolist() == [True, False, False, True]
    assert set(got) == {"parallel", "serial"}  # only the checks given


def test_rule_raises_each_margin_to_its_floor():
    # Margins 0: the floors alone, the σ floors relative to the map's σ_max (here 2).
    m = Margins(wrist=0.0, singularity=0.0)
    sp = np.array(_around(2.0 * SIGMA_FLOOR))
    ss = np.array(_around(2.0 * SERIAL_FLOOR))
    w = np.array(_around(SERIAL_FLOOR))
    sph = np.array(_around(SIGMA_FLOOR))
    got = m.violations(wrist=w, parallel=sp, serial=ss, parallel_max=2.0, serial_max=2.0,
                       spherical=(sph, sph))
    assert list(got) == list(CHECKS)
    for check in CHECKS:
        assert got[check].tolist() == [True, False, False], check
    # A margin above its floor is the limit itself.
    assert Margins(wrist=0.2).limits()["wrist"] == 0.2


# --- every caller agrees ----------------------------------------------------------------------
@pytest.fixture(scope="module")
def at_margin(robot):
    """A pose (home towards the wrist singularity, |sin θ1716| ≈ 0.2) and its |sin θ1716| as
    the IK reports it; the workspace map computes the very same number."""
    _, poses, _ = path_to_wrist_singularity(robot.params, 1.0, 400, 1.0)
    pose = poses[220:221]
    w = float(inverse_kinematics(robot, pose, options=pp.IkOptions(margins=Margins(0.0, 0.0)))
              .wrist_margin[0])
    assert 0.1 < w < 0.3
    reach = evaluate(robot, pose, ReachOptions(Margins(0.0, 0.0)))
    assert reach["wrist_margin"][0] == w  # bit for bit (before: a few ulps apart)
    q = closed_form.position_ik(robot.params, pose)
    assert abs(abs(math.sin(q[0, closed_form.JOINTS.index("theta1716")])) - w) <= 1e-15
    return pose, w


def _verdicts(robot, pose, margins):
    """Does the pose fail the wrist margin? for the IK, the workspace map, the paint planner."""
    try:
        inverse_kinematics(robot, pose, options=pp.IkOptions(margins=margins))
        ik = False
    except SingularityError as e:
        assert e.chain == "wrist" and e.sample == 0
        ik = True
    reason = REASONS[int(evaluate(robot, pose, ReachOptions(margins))["reason"][0])]
    assert reason in ("reachable", "wrist margin")
    act = load_actuators(f"{EXAMPLES}/actuators.toml")
    zero = np.zeros_like(pose)
    try:
        motion(robot, act, pose, zero, zero, margins=margins)
        paint = False
    except ReachError as e:
        assert "wrist" in str(e)
        paint = True
    return ik, reason == "wrist margin", paint


def test_every_caller_gives_the_same_verdict_at_the_margin(robot, at_margin):
    # The wrist margin set to the pose's own |sin θ1716|, one ulp below and one above. Before
    # one rule, at equality the map (and the IK's closed-form start: ≤ fails) said "wrist
    # margin" while the IK's final check and Newton (< fails) passed.
    pose, w = at_margin
    below, at, above = _around(w)
    assert _verdicts(robot, pose, Margins(wrist=below, singularity=0.0)) == (False,) * 3
    assert _verdicts(robot, pose, Margins(wrist=at, singularity=0.0)) == (False,) * 3
    assert _verdicts(robot, pose, Margins(wrist=above, singularity=0.0)) == (True,) * 3


def test_newton_judges_the_value_it_reports(robot, at_margin):
    # Newton's own solution differs from the closed form's by round-off: its early stop and
    # its final check apply the same rule to the value it reports (the closed-form start is
    # only a start).
    pose, _ = at_margin
    w = float(inverse_kinematics(robot, pose, options=pp.IkOptions(
        method="newton", margins=Margins(0.0, 0.0))).wrist_margin[0])
    below, at, above = _around(w)
    for m in (below, at):
        r = inverse_kinematics(robot, pose,
                               options=pp.IkOptions(method="newton", margins=Margins(m, 0.0)))
        assert r.wrist_margin[0] == w
    with pytest.raises(SingularityError) as ei:
        inverse_kinematics(robot, pose,
                           options=pp.IkOptions(method="newton", margins=Margins(above, 0.0)))
    assert ei.value.chain == "wrist" and ei.value.amount == above - w


def test_the_serial_margin_at_equality_passes_everywhere(robot, at_margin):
    pose, _ = at_margin
    ss = float(inverse_kinematics(robot, pose, options=pp.IkOptions(margins=Margins(0.0, 0.0)))
               .sigma_serial[0])
    for m, fails in zip(_around(ss), (False, False, True)):
        try:
            inverse_kinematics(robot, pose, options=pp.IkOptions(margins=Margins(0.0, m)))
            ik = False
        except SingularityError as e:
            ik = e.chain == "serial"
        reach = REASONS[int(evaluate(robot, pose, ReachOptions(Margins(0.0, m)))["reason"][0])]
        assert (ik, reach == "serial margin") == (fails, fails), m


# --- validation: once, one line ---------------------------------------------------------------
@pytest.mark.parametrize("field, value, words", [
    ("wrist", math.nan, "must be a finite number"), ("wrist", -0.1, "must be >= 0"),
    ("wrist", 1.5, "must be at most 1"), ("wrist", math.inf, "must be a finite number"),
    ("wrist", "0.05", "is not a number"), ("wrist", None, "is not a number"),
    ("wrist", True, "is not a number"),
    ("singularity", math.nan, "must be a finite number"),
    ("singularity", -1e-3, "must be >= 0"), ("singularity", math.inf, "must be a finite"),
    ("singularity", "x", "is not a number")])
def test_a_bad_margin_cannot_be_made(field, value, words):
    with pytest.raises(MarginError) as ei:
        Margins(**{field: value})
    msg = str(ei.value)
    assert isinstance(ei.value, InputError) and "\n" not in msg and len(msg) < 200
    assert msg.startswith(f"{field} margin = {value!r}: {words}"), msg


def test_margins_are_frozen_and_keep_numbers():
    m = Margins(np.float64(0.1), 0)
    assert (m.wrist, m.singularity) == (0.1, 0.0) and type(m.singularity) is float
    with pytest.raises(AttributeError):
        m.wrist = 0.2
    assert m.as_dict() == {"wrist_margin": 0.1, "singularity_margin": 0.0}


def test_anything_but_margins_is_refused_wherever_it_enters(robot):
    pose = np.asarray(robot.params.home_pose, dtype=float)[None]
    zero = np.zeros_like(pose)
    act = load_actuators(f"{EXAMPLES}/actuators.toml")
    traj = pp.Trajectory(np.array([0.0, 1.0]), np.vstack([pose, pose]),
                         np.zeros((2, 6)), np.zeros((2, 6)))
    for call in (lambda: inverse_kinematics(robot, pose, options=pp.IkOptions(margins=0.05)),
                 lambda: pp.run_pipeline(robot, traj, margins={"wrist": 0.05}),
                 lambda: motion(robot, act, pose, zero, zero, margins=0.05),
                 lambda: pp.map_workspace(robot, "x=0.55",
                                                  pp.WorkspaceOptions(margins=(0.05, 1e-3)))):
        with pytest.raises(MarginError) as ei:
            call()
        assert "Margins(" in str(ei.value) and "\n" not in str(ei.value)
