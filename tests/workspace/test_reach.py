"""The reach rule of a workspace point (workspace/reach.py, docs/model.md §22) against the
per-sample solvers and direct computations: where ``run``'s IK fails, each reason on a
constructed point, the closed form's unreachable leg, and the conditioning index and payload
capacity point by point.

Achieved errors (this machine): map margins vs the IK's columns ≤ 4e-14 (tolerance 4e-12);
conditioning index vs a per-point SVD of J_tool·N ≤ 1e-14 relative (1e-12); payload capacity:
the per-point motor utilisation (Pinocchio RNEA with the mass added to the gun, through
the motor model of dynamics/motors.py at rest) at the
capacity is 1 within 1.3e-15 (1e-13).
"""

from pathlib import Path

import numpy as np
import pytest
from poses import wrist_singular_pose  # tests/poses.py

import pollard_pin as pp
from pollard_pin.analytic import closed_form
from pollard_pin.dynamics import ActuatorError
from pollard_pin.dynamics.inverse import inverse_dynamics_sample
from pollard_pin.dynamics.motors import load_actuators, motor_torque
from pollard_pin.dynamics.plant import ModelMismatch, perturbed_robot
from pollard_pin.kinematics.errors import KinematicsError
from pollard_pin.kinematics.margins import Margins
from pollard_pin.kinematics.singularity import actuator_velocity_map
from pollard_pin.model.build import constraint_jacobian
from pollard_pin.model.params import load_params
from pollard_pin.workspace.grid import map_workspace
from pollard_pin.workspace.options import WorkspaceOptions
from pollard_pin.workspace.reach import REASONS, ReachOptions, evaluate

ACTUATORS = __file__.rsplit("/tests/", 1)[0] + "/examples/actuators.toml"


def line(a, b, n=801):
    """Poses along the straight segment a → b (positions), default orientation."""
    s = np.linspace(0.0, 1.0, n)[:, None]
    pts = np.asarray(a) + s * (np.asarray(b) - np.asarray(a))
    return np.concatenate([pts, np.zeros((n, 3))], axis=1)


def first_unreachable(robot, poses):
    cols = evaluate(robot, poses)
    bad = np.flatnonzero(cols["reachable"] == 0)
    return (int(bad[0]) if len(bad) else None), cols


# --- against run's per-sample solver ----------------------------------------------------------
INSIDE = (0.55, 0.0, 0.1)


@pytest.mark.parametrize("end, reason", [
    ((0.55, -0.5, 0.05), "chain 0 out of reach"),
    ((0.55, -0.3, 0.4), "leg 2 out of reach"),
    ((0.55, 0.3, 0.4), "leg 1 out of reach"),
    ((0.55, 0.45, -0.3), "parallel margin"),  # crosses a parallel singularity curve
    ((0.90, 0.0, 0.1), "leg 1 out of reach"),
    ("wrist", "wrist margin"),  # towards θ1716 = 0 (tests/poses.py)
    ((0.30, 0.0, 0.1), None)])  # stays inside
def test_run_fails_exactly_where_the_map_says(wide, end, reason):
    """From a reachable point outwards: ``run``'s IK solves every sample before the first
    the map marks unreachable (same margins), and fails at that sample, naming its chain."""
    if end == "wrist":
        s = np.linspace(0.0, 1.0, 1001)[:, None]
        home = np.asarray(wide.params.home_pose)
        poses = home + s * (wrist_singular_pose(wide.params) - home)
    else:
        poses = line(INSIDE, end, 1001)
    t = np.arange(len(poses)) * 0.01
    k, cols = first_unreachable(wide, poses)
    n = len(poses) if k is None else k
    ik = pp.inverse_kinematics(wide, poses[:n], t=t[:n])
    for name in ("wrist_margin", "sigma_parallel", "sigma_serial"):
        np.testing.assert_allclose(cols[name][:n], getattr(ik, name), rtol=0, atol=4e-12)
    if reason is None:
        assert k is None
        return
    assert REASONS[cols["reason"][k]] == reason
    with pytest.raises(KinematicsError) as err:
        pp.inverse_kinematics(wide, poses[:k + 1], t=t[:k + 1])
    assert err.value.sample == k, str(err.value)
    assert err.value.chain == reason.replace(" out of reach", "").replace(" margin", "")


def test_a_path_through_the_map_solves_and_leaves_at_a_joint_limit(robot):
    """The shipped limits: a path inside the map solves; where it leaves at a joint limit
    (not an error in run), the IK's own angles, taken modulo 2π, cross that limit there."""
    poses = line((0.55, 0.0, 0.1), (0.55, 0.45, 0.1), 901)
    k, cols = first_unreachable(robot, poses)
    reason = REASONS[cols["reason"][k]]
    joint, side = reason.split()[0], reason.split()[3]
    ik = pp.inverse_kinematics(robot, poses[:k + 1], t=np.arange(k + 1) * 0.01)
    j = robot.joint_names.index(joint)
    lim = robot.params.joint_limits(joint)
    turns = np.arange(-3, 4) * 2 * np.pi
    inside = [bool(np.any((lim.lower <= q + turns) & (q + turns <= lim.upper)))
              for q in ik.q[:, j]]
    assert all(inside[:k]) and not inside[k]
    q_k = ik.q[k, j] + turns
    assert side == ("upper" if np.min(np.abs(q_k - lim.upper)) < np.min(np.abs(q_k - lim.lower))
                    else "lower")


# --- each reason on a constructed point -------------------------------------------------------
def reason_at(robot, pose, **margins):
    opts = ReachOptions(Margins(**margins))
    return REASONS[int(evaluate(robot, np.atleast_2d(pose), opts)["reason"][0])]


def test_reasons_on_constructed_points(robot):
    home = np.asarray(robot.params.home_pose)
    assert reason_at(robot, home) == "reachable"
    assert reason_at(robot, home + [2.0, 0, 0, 0, 0, 0]) == "chain 0 out of reach"
    # σ at home: parallel 0.165, serial 0.130 (docs/model.md §12)
    assert reason_at(robot, home, singularity=0.15) == "serial margin"
    assert reason_at(robot, home, singularity=0.2) == "parallel margin"
    assert reason_at(robot, home, wrist=0.5) == "wrist margin"  # |sin θ1716| = 0.452
    assert reason_at(robot, wrist_singular_pose(robot.params)) == "wrist margin"


def test_leg_reasons_agree_with_the_closed_form(wide):
    """Points the map puts out of a leg's reach: the raising closed form names that leg."""
    ws = map_workspace(wide, "x=0.55", WorkspaceOptions(resolution=0.02))
    c = ws.columns
    for chain in ("leg 1", "leg 2"):
        idx = np.flatnonzero(c["reason"] == REASONS.index(f"{chain} out of reach"))
        assert len(idx)
        for k in idx[:: max(1, len(idx) // 5)]:
            pose = [c[n][k] for n in ("x", "y", "z", "psi", "theta", "phi")]
            with pytest.raises(closed_form.UnreachableError) as err:
                closed_form.position_ik(wide.params, pose)
            assert err.value.chain == chain


@pytest.mark.parametrize("joint, limits, expect", [
    ("theta21", (-105.0, -80.0), "theta21 above its upper limit"),  # home θ21 = −77.6°
    ("theta21", (-75.0, -35.0), "theta21 below its lower limit"),
    ("theta1615", (440.0, 460.0), "reachable"),  # home θ1615 = 90° = 450° − 360°
    ("theta1615", (100.0, 300.0), "theta1615 below its lower limit")])
def test_joint_limit_reasons(joint, limits, expect):
    params = load_params(overrides={f"limits.{joint}.lower": limits[0],
                                    f"limits.{joint}.upper": limits[1]})
    robot = pp.load(params)
    assert reason_at(robot, np.asarray(params.home_pose)) == expect


# --- conditioning index and payload, point by point -------------------------------------------
def per_point_serial_map(robot, q):
    m, d = robot.model, robot.data
    import pinocchio as pin

    Jc = constraint_jacobian(m, d, robot.constraint_models, robot.constraint_datas, q)
    pin.computeJointJacobians(m, d, q)
    pin.updateFramePlacements(m, d)
    Jt = pin.getFrameJacobian(m, d, robot.tip_frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return Jt @ actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)


def test_conditioning_and_payload_per_point(robot):
    act = load_actuators(ACTUATORS)
    ws = map_workspace(robot, "x=0.55", WorkspaceOptions(resolution=0.03, actuators=act))
    c = ws.columns
    idx = np.flatnonzero(c["reachable"] == 1)
    assert len(idx) > 20
    L = robot.params.x65 + robot.params.x1514 + robot.params.x1918
    worst = worst_util = 0.0
    for k in idx[:: max(1, len(idx) // 12)]:
        pose = np.array([c[n][k] for n in ("x", "y", "z", "psi", "theta", "phi")])
        q = pp.inverse_kinematics(robot, pose[None]).q[0]
        A = per_point_serial_map(robot, q)
        s = np.linalg.svd(A * np.array([1 / L] * 3 + [1.0] * 3)[:, None], compute_uv=False)
        worst = max(worst, abs(s[-1] / s[0] - c["conditioning"][k]) / (s[-1] / s[0]))
        cap = c["payload_capacity"][k]
        assert 0 < cap < np.inf

        def utilisation(m, q=q):
            heavy = perturbed_robot(robot, ModelMismatch(payload=m))
            tau = inverse_dynamics_sample(heavy, q, np.zeros(12), np.zeros(12))[0]
            zero = np.zeros(6)  # at rest: the motor model counts Coulomb as breakaway ±c
            return np.max(np.abs(motor_torque(act, tau, zero, zero)) / act.column("peak_torque"))

        worst_util = max(worst_util, abs(utilisation(cap) - 1.0))
        assert utilisation(cap * (1 - 1e-6)) < 1.0
    assert worst <= 1e-12
    assert worst_util <= 1e-13


def test_stiffness_columns_are_those_of_the_ik(robot):
    """With stiffnesses, kmin, f1 and sag at the reachable points equal stiffness_at on the
    constrained IK's configurations (the map starts from the closed form; achieved 2e-15
    relative, tolerance 1e-12), NaN elsewhere; without them, no such columns; some but not all
    is one line naming the first drive without."""
    from dataclasses import replace

    from pollard_pin.dynamics.drives.stiffness import stiffness_at

    act = load_actuators(Path(__file__).resolve().parents[2] / "examples" / "actuators.toml")
    ys, zs = np.meshgrid(np.linspace(-0.3, 0.3, 9), np.linspace(-0.1, 0.3, 7))
    poses = np.column_stack([np.full(ys.size, 0.55), ys.ravel(), zs.ravel(),
                             np.zeros((ys.size, 3))])
    cols = evaluate(robot, poses, ReachOptions(actuators=act))
    ok = cols["reason"] == 0
    assert 10 < ok.sum() < len(poses)
    ref = stiffness_at(robot, pp.inverse_kinematics(robot, poses[ok]).q, act.stiffness())
    for name, want in (("kmin", ref.kmin), ("f1", ref.frequencies[:, 0]),
                       ("sag", np.linalg.norm(ref.deflection[:, :3], axis=1))):
        assert np.abs(cols[name][ok] / want - 1).max() < 1e-12, name
        assert np.isnan(cols[name][~ok]).all()
    bare = replace(act, units=tuple(replace(u, stiffness=None) for u in act.units))
    assert "kmin" not in evaluate(robot, poses[:3], ReachOptions(actuators=bare))
    part = replace(act, units=(*act.units[:4], replace(act.units[4], stiffness=None),
                               act.units[5]))
    with pytest.raises(ActuatorError, match=r"'theta1716\.stiffness' is missing"):
        evaluate(robot, poses[:3], ReachOptions(actuators=part))


def test_the_sag_is_blank_where_the_linear_model_ends(robot):
    """stiffness_columns leaves the sag NaN exactly where a drive turns beyond MAX_TURN under
    the weight (docs/model.md §27.2, §27.6), stiffness_at's figure elsewhere; kmin and f1
    stay at every reachable point."""
    from pollard_pin.dynamics.drives.stiffness import MAX_TURN, stiffness_at
    from pollard_pin.workspace.reach import stiffness_columns

    zs = np.linspace(-0.04, 0.27, 11)
    poses = np.column_stack([np.full(11, 0.55), np.zeros(11), zs, np.zeros((11, 3))])
    q = pp.inverse_kinematics(robot, poses).q
    k = np.array([200.0, 200.0, 200.0, 20.0, 20.0, 20.0])  # 15 × softer than the examples'
    ok = np.ones(11, dtype=bool)
    cols = stiffness_columns(robot, k, q, ok)
    ref = stiffness_at(robot, q, k)
    beyond = ref.turn > MAX_TURN
    assert beyond.any() and not beyond.all(), ref.turn
    assert np.isnan(cols["sag"][beyond]).all()
    assert np.array_equal(cols["sag"][~beyond], np.linalg.norm(ref.deflection[~beyond, :3],
                                                                axis=1))
    assert np.isfinite(cols["kmin"]).all() and np.isfinite(cols["f1"]).all()
