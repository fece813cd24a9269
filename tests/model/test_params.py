"""Joint limits (docs/model.md §3): design values, not placeholders. Position limits are the
range the closed-form IK needs over the design workspace (recomputed here), effort and velocity
twice the group's peak on the default trajectory (docs/model.md §9); the URDF, the Pinocchio
model and the MJCF export carry them, the MuJoCo peer keeps its joints ideal (no limits). The
SRDF's home posture is a named reference configuration inside the limits."""
import math
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

import pollard_pin
from pollard_pin.model.params import ParameterError, load_params, params_from_dict, read_params_dict
from pollard_pin.model.paths import models_dir
from pollard_pin.model.urdf import position_limits
from pollard_pin.names import ACTUATED, TREE_JOINTS
from pollard_pin.paths import smooth_random_trajectory

URDF = models_dir() / "pollard.urdf"
SRDF = models_dir() / "pollard.srdf"
PASSIVE = ("theta43", "theta54", "theta65_1", "theta76_1", "theta65_2", "theta76_2")
GROUPS = {"base": ("theta21", "theta21_1", "theta21_2"),
          "wrist": ("theta1615", "theta1716", "theta1817"), "passive": PASSIVE}
FACTOR = 2.0  # rating = FACTOR × the group's peak on the default trajectory, rounded up


@pytest.fixture(scope="module")
def params():
    return load_params()


@pytest.fixture(scope="module")
def limits(params):
    """name → (lower, upper, effort, velocity) in rad, rad, N·m, rad/s."""
    return {n: (lim.lower, lim.upper, lim.effort, lim.velocity) for n, lim in params.limits}


@pytest.fixture(scope="module")
def default_run(robot):
    return pollard_pin.run_pipeline(robot, pollard_pin.thesis_trajectory())


def test_joint_lists_agree_with_the_model(robot):
    assert TREE_JOINTS == robot.joint_names
    assert ACTUATED == robot.actuated
    assert set(PASSIVE) == set(robot.passive)


def test_position_limits_are_the_workspace_ranges(params):
    # The shipped numbers are what the documented procedure gives for the shipped parameters.
    computed = position_limits(params)
    shipped = {n: (round(math.degrees(lim.lower), 9), round(math.degrees(lim.upper), 9))
               for n, lim in params.limits}
    assert shipped == computed


def test_limits_are_not_placeholders(limits):
    for n, (lo, hi, effort, velocity) in limits.items():
        assert all(math.isfinite(x) for x in (lo, hi, effort, velocity)), n
        assert hi - lo <= 2 * math.pi + 1e-12, n  # at most one turn
        assert velocity < 20.0 and effort < 50.0, n  # the old placeholders
    for n in PASSIVE:  # the U-joint angles: far narrower than ±2π
        lo, hi, effort, _ = limits[n]
        assert -2 * math.pi < lo < hi < 2 * math.pi and hi - lo <= math.pi, n
        assert effort == 0.0, n  # no actuator
    for n in ACTUATED:
        assert limits[n][2] > 0.0, n
    # θ1716 stays on the wrist branch of the closed form (0 is the wrist singularity).
    assert limits["theta1716"][0] >= 0.0 and limits["theta1716"][1] <= math.pi


def test_default_trajectory_stays_inside_the_limits(robot, default_run, limits):
    ik = default_run.ik
    assert tuple(ik.joint_names) == TREE_JOINTS
    lo = np.array([limits[n][0] for n in TREE_JOINTS])
    hi = np.array([limits[n][1] for n in TREE_JOINTS])
    margin = math.radians(5.0)  # the widening of docs/model.md §3
    assert np.all(ik.q >= lo + margin) and np.all(ik.q <= hi - margin)
    home = robot.home()
    assert np.all(home > lo) and np.all(home < hi)


@pytest.mark.parametrize("group", sorted(GROUPS))
def test_effort_and_velocity_are_twice_the_default_peaks(default_run, limits, group):
    names = GROUPS[group]
    idx = [TREE_JOINTS.index(n) for n in names]
    peak_v = np.abs(default_run.ik.v[:, idx]).max()
    velocity = {limits[n][3] for n in names}
    assert len(velocity) == 1, "one rating per group"
    (velocity,) = velocity
    assert FACTOR * peak_v <= velocity <= (FACTOR + 0.5) * peak_v, (group, peak_v, velocity)
    if group == "passive":
        return
    tau = default_run.dynamics.tau[:, [ACTUATED.index(n) for n in names]]
    peak_tau = np.abs(tau).max()
    (effort,) = {limits[n][2] for n in names}
    assert FACTOR * peak_tau <= effort <= (FACTOR + 0.5) * peak_tau, (group, peak_tau, effort)


@pytest.mark.parametrize("seed", range(4))
def test_the_random_test_trajectories_stay_inside_too(robot, limits, seed):
    traj = smooth_random_trajectory(seed)
    ik = pollard_pin.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    lo = np.array([limits[n][0] for n in TREE_JOINTS])
    hi = np.array([limits[n][1] for n in TREE_JOINTS])
    assert np.all(ik.q > lo) and np.all(ik.q < hi)


def test_urdf_and_pinocchio_carry_the_limits(robot, limits):
    root = ET.parse(URDF).getroot()
    found = {}
    for j in root.iter("joint"):
        el = j.find("limit")
        if j.get("type") != "fixed":
            assert j.get("type") == "revolute" and el is not None, j.get("name")
            found[j.get("name")] = tuple(float(el.get(k))
                                         for k in ("lower", "upper", "effort", "velocity"))
    assert found == limits  # exact: written with repr()
    m = robot.model
    idx = [robot.idx_q(n) for n in TREE_JOINTS]
    for k, attr in enumerate(("lowerPositionLimit", "upperPositionLimit")):
        assert np.array_equal(getattr(m, attr)[idx], [limits[n][k] for n in TREE_JOINTS])
    idx = [robot.idx_v(n) for n in TREE_JOINTS]
    assert np.array_equal(m.effortLimit[idx], [limits[n][2] for n in TREE_JOINTS])
    assert np.array_equal(m.velocityLimit[idx], [limits[n][3] for n in TREE_JOINTS])


def test_srdf_home_is_a_named_reference_configuration(robot, limits):
    model = pin.buildModelFromUrdf(str(URDF))
    pin.loadReferenceConfigurations(model, str(SRDF), False)
    assert "home" in model.referenceConfigurations
    q = np.array(model.referenceConfigurations["home"])
    values = {j.get("name"): float(j.get("value"))
              for j in ET.parse(SRDF).getroot().find("group_state[@name='home']")}
    assert q.tolist() == [values[n] for n in model.names[1:]]
    assert np.array_equal(q, robot.q_reference)
    assert np.abs(q - robot.home()).max() < 1e-11  # 12 decimals in the file
    assert np.all(q > model.lowerPositionLimit) and np.all(q < model.upperPositionLimit)
    assert np.all(q == pin.normalize(model, q))  # a valid configuration, nq = nv = 12


def test_mujoco_peer_keeps_ideal_joints_and_export_mirrors_limits(tmp_path, limits):
    mujoco = pytest.importorskip("mujoco")
    from pollard_pin.crosscheck.mujoco import build_mujoco
    from pollard_pin.io.mjcf import export_mjcf

    model, _, _ = build_mujoco()  # the peer: limits off (docs/model.md §13, ideal joints)
    assert not np.any(model.jnt_limited)
    assert model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_LIMIT
    exported = mujoco.MjModel.from_xml_path(str(export_mjcf(tmp_path / "p.xml")))
    assert np.all(exported.jnt_limited)  # the export: the URDF's ranges, enforced
    assert not exported.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_LIMIT
    for n in TREE_JOINTS:
        assert exported.joint(n).range.tolist() == list(limits[n][:2]), n


@pytest.mark.parametrize("edit, pattern", [
    (lambda d: d["limits"].pop("theta54"), r"^parameter 'limits\.theta54' = None: missing key"),
    (lambda d: d["limits"]["theta43"].pop("velocity"),
     r"^parameter 'limits\.theta43\.velocity' = None: missing key"),
    (lambda d: d["limits"]["theta21"].update(upper=-110.0),
     r"^parameter 'limits\.theta21\.upper' = -110\.0: must be greater than"),
    # the bound that is off is named (the upper one was blamed for a lower -1e300)
    (lambda d: d["limits"]["theta21"].update(lower=-400.0),
     r"^parameter 'limits\.theta21\.lower' = -400, 'limits\.theta21\.upper' = -35: the "
     r"range 365 deg exceeds one turn \(360\)$"),
    (lambda d: d["limits"]["theta21"].update(lower=-1e300),
     r"^parameter 'limits\.theta21\.lower' = -1e\+300: must be within ±720 deg"),
    (lambda d: d["limits"]["theta1615"].update(lower=-100.0),
     r"^parameter 'limits\.theta1615\.lower' = -100, 'limits\.theta1615\.upper' = 270: "
     r"the range 370 deg exceeds one turn"),
    (lambda d: d["limits"]["theta54"].update(effort=1.0),
     r"^parameter 'limits\.theta54\.effort' = 1\.0: must be 0 \(a passive joint"),
    (lambda d: d["limits"]["theta21_1"].update(effort=0.0),
     r"^parameter 'limits\.theta21_1\.effort' = 0\.0: must be > 0 N·m"),
    (lambda d: d["limits"]["theta1716"].update(velocity=-1.0),
     r"^parameter 'limits\.theta1716\.velocity' = -1\.0: must be > 0$"),
    (lambda d: d["limits"]["theta1716"].update(velocity=float("inf")),
     r"^parameter 'limits\.theta1716\.velocity' = inf: must be a finite number$"),
])
def test_limit_rules(edit, pattern):
    d = read_params_dict()
    edit(d)
    with pytest.raises(ParameterError, match=pattern):
        params_from_dict(d)


@pytest.mark.parametrize("edit, key", [
    (lambda d: d["chain0"].update(x32=400.0), "chain0.x32"),
    (lambda d: d["chain0"].update(x32="a"), "chain0.x32"),
    (lambda d: d["home"].update(tip=[0.5, float("nan"), 0.1]), "home.tip[1]"),
    (lambda d: d["limits"]["theta1716"].update(velocity=-1.0), "limits.theta1716.velocity"),
    # a joint's range over one turn: the key its message names first
    (lambda d: d["limits"]["theta21"].update(lower=-400.0), "limits.theta21.lower"),
    # no one key's rule: the home pose out of reach
    (lambda d: d["home"].update(tip=[5.0, 0.0, 0.0]), None),
], ids=["length", "not a number", "list entry", "velocity", "range", "home pose"])
def test_a_parameter_error_carries_the_key_whose_rule_it_is(edit, key):
    """What a design space asks to tell a bound's own rule from another key's (synthesis/
    space.py), without reading the message's words."""
    d = read_params_dict()
    edit(d)
    with pytest.raises(ParameterError) as e:
        params_from_dict(d)
    assert e.value.key == key, str(e.value)


def test_limits_round_trip_and_override():
    p = load_params(overrides={"limits.theta21.effort": 3.0, "limits.theta43.lower": 60.0})
    assert p.joint_limits("theta21").effort == 3.0
    assert p.joint_limits("theta43").lower == math.radians(60.0)
    again = params_from_dict(p.to_toml_dict())
    assert again.limits == p.limits
    assert 'effort="3.0"' in pollard_pin.load(p).urdf


def test_load_params_refuses_what_names_no_file():
    with pytest.raises(ParameterError, match=r"^path = 3: expected a file path \(str or "):
        load_params(3)
    with pytest.raises(ParameterError, match=r"^path = 3: expected a file path \(str or "):
        read_params_dict(3)  # the one home of the check (make_sweep's params too)
