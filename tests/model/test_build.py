"""The foundation — parameters, URDF/SRDF, the Pinocchio model with its two loop
closures, and closure solving — checked against the numbers of docs/model.md §3–§5 and §9.

The expected values below are typed in from docs/model.md (§3–§5, §9), not read from the package,
so the tests
can fail when the package drifts from the spec.
"""
import json
import logging
import math
import os
import re
import shutil
import subprocess
import sys
import textwrap
import warnings
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from clean_run import run_clean

import pollard_pin
from pollard_pin.errors import InputError
from pollard_pin.kinematics.closure import forward_kinematics, solve_closure, tool_pose
from pollard_pin.kinematics.errors import ClosureError
from pollard_pin.model.build import (
    ModelFileError,
    build,
    check_robot,
    constraint_jacobian,
    constraint_residual,
    load,
)
from pollard_pin.model.params import ParameterError, load_params, params_from_dict, read_params_dict

REPO = Path(__file__).resolve().parents[2]
MODELS = REPO / "models"
URDF_PATH = MODELS / "pollard.urdf"
SRDF_PATH = MODELS / "pollard.srdf"
TOML_PATH = MODELS / "pollard.toml"

# --- spec numbers -------------------------------------------------------------------------
# §5 geometry [m, rad].
SPEC = dict(z10=0.05, x32=0.33, x65=0.37, x1514=0.10, x1918=0.06,
            y10=0.085, z32=0.035, x43=0.33, beta54=0.0, x87=0.325, x1211=0.015, z1312=0.02,
            beta1413=(math.radians(270.0), math.radians(90.0)), side=(-1, 1))
# §4: attachment points A_i in the platform frame.
SPEC_A = {1: (0.37, -0.015, -0.02), 2: (0.37, 0.015, -0.02)}
# §6 actuator order.
SPEC_ACTUATED = ("theta21", "theta21_1", "theta21_2", "theta1615", "theta1716", "theta1817")
# §9 home configuration [deg], rounded to 3 decimals.
HOME_DEG = {
    "theta21": -77.629, "theta43": 104.487, "theta54": 0.0,
    "theta1615": 90.0, "theta1716": 26.858, "theta1817": -90.0,
    "theta21_1": -26.390, "theta65_1": -92.623, "theta76_1": 46.778,
    "theta21_2": 26.390, "theta65_2": -92.623, "theta76_2": -46.778,
}
HOME_SPHERICAL_DEG = {1: (-33.820, 116.430, 119.725), 2: (33.820, 116.430, -119.725)}
HOME_TIP = (0.55, 0.0, 0.16)
# §5 masses [kg] and inertia tensors [kg·mm²] about the CoG, body axes.
_ARM = np.diag([20.988, 3027.487, 3016.058])
_WRIST = np.diag([1.681, 95.822, 95.822])
SPEC_BODIES = {  # body: (mass, CoG [m] from the §5 CoG table, inertia [kg·mm²])
    "arm0": (0.166, (0.33 / 2, 0, 0), _ARM),
    "platform": (0.188, ((0.37 + 0.10) / 2, 0, 0),
                 np.array([[199.423, -5.176, 1381.812], [-5.176, 45670, 0.314],
                           [1381.812, 0.314, 45670]])),
    "wrist1": (0.04, (0, 0, 0), _WRIST),
    "wrist2": (0.035, (0, 0, 0), _WRIST),
    "gun": (0.035, (0.06 / 2, 0, 0), _WRIST),
    "arm_1": (0.166, (0.33 / 2, 0, -0.035), _ARM),
    "arm_2": (0.166, (0.33 / 2, 0, -0.035), _ARM),
    "link_1": (0.062, (0.325 / 2, 0, 0), np.diag([2.62, 2322.307, 2322.307])),
    "link_2": (0.062, (0.325 / 2, 0, 0), np.diag([2.62, 2322.307, 2322.307])),
}
BODY_JOINT = {"arm0": "theta21", "platform": "theta54", "wrist1": "theta1615",
              "wrist2": "theta1716", "gun": "theta1817", "arm_1": "theta21_1",
              "arm_2": "theta21_2", "link_1": "theta76_1", "link_2": "theta76_2"}
MASSLESS_JOINTS = ("theta43", "theta65_1", "theta65_2")  # the U-joint crosses


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def spec_tree(g):
    """§3 table for geometry ``g``: joint → (parent joint, translation, rotation, axis)."""
    L = g["x65"] + g["x1514"]
    t = {
        "theta21": ("universe", (0, 0, g["z10"]), np.eye(3), "Y"),
        "theta43": ("theta21", (g["x32"], 0, 0), np.eye(3), "Y"),
        "theta54": ("theta43", (0, 0, 0), np.eye(3), "Z"),
        "theta1615": ("theta54", (L, 0, 0), np.eye(3), "X"),
        "theta1716": ("theta1615", (0, 0, 0), np.eye(3), "Z"),
        "theta1817": ("theta1716", (0, 0, 0), np.eye(3), "X"),
    }
    for i in (1, 2):
        leg = g[f"leg{i}"]
        t[f"theta21_{i}"] = ("universe", (0, leg["side"] * leg["y10"], 0), np.eye(3), "Z")
        t[f"theta65_{i}"] = (f"theta21_{i}", (leg["x43"], 0, -leg["z32"]), rx(leg["beta54"]), "Y")
        t[f"theta76_{i}"] = (f"theta65_{i}", (0, 0, 0), np.eye(3), "Z")
    return t


def spec_geometry(**chain0_over):
    g = {k: SPEC[k] for k in ("z10", "x32", "x65", "x1514", "x1918")}
    g.update(chain0_over)
    for i in (1, 2):
        g[f"leg{i}"] = {k: SPEC[k] for k in ("y10", "z32", "x43", "beta54", "x87", "x1211",
                                              "z1312")}
        g[f"leg{i}"].update(side=SPEC["side"][i - 1], beta1413=SPEC["beta1413"][i - 1])
    return g


def joint_axis(model, jid):
    """Axis letter of a revolute joint ('X', 'Y', 'Z'), or its short name otherwise."""
    m = re.fullmatch(r"JointModelR([XYZ])", model.joints[jid].shortname())
    return m.group(1) if m else model.joints[jid].shortname()


def chain_points(g, qd):
    """Independent numpy forward chain of docs/model.md §3: world tip pose, platform pose, elbow,
    the
    leg-side ball centres and link rotations, from joint values ``qd`` (name → rad)."""
    L = g["x65"] + g["x1514"]
    E = np.array([0, 0, g["z10"]]) + ry(qd["theta21"]) @ np.array([g["x32"], 0, 0])
    R_pl = ry(qd["theta21"] + qd["theta43"]) @ rz(qd["theta54"])
    W = E + R_pl @ np.array([L, 0, 0])
    R_tool = R_pl @ rx(qd["theta1615"]) @ rz(qd["theta1716"]) @ rx(qd["theta1817"])
    tip = W + R_tool @ np.array([g["x1918"], 0, 0])
    legs = {}
    for i in (1, 2):
        leg = g[f"leg{i}"]
        R1 = rz(qd[f"theta21_{i}"])
        elbow = np.array([0, leg["side"] * leg["y10"], 0]) + R1 @ np.array([leg["x43"], 0,
                                                                             -leg["z32"]])
        R_link = R1 @ rx(leg["beta54"]) @ ry(qd[f"theta65_{i}"]) @ rz(qd[f"theta76_{i}"])
        legs[i] = (elbow + R_link @ np.array([leg["x87"], 0, 0]), R_link)
    return dict(E=E, R_platform=R_pl, tip=tip, R_tool=R_tool, legs=legs)


def zyz(M):
    return np.degrees([math.atan2(M[1, 2], M[0, 2]), math.acos(np.clip(M[2, 2], -1, 1)),
                       math.atan2(M[2, 1], -M[2, 0])])


def residual_args(r):
    return r.model, r.data, r.constraint_models, r.constraint_datas


@pytest.fixture(scope="module")
def q_home(robot):
    return robot.home()


# --- §3 tree ------------------------------------------------------------------------------
def test_joint_names_axes_and_placements_match_spec_tree(robot):
    model = robot.model
    want = spec_tree(spec_geometry())
    assert model.nq == model.nv == 12
    assert sorted(robot.joint_names) == sorted(want)
    for name, (parent, xyz, R, axis) in want.items():
        jid = robot.joint_id(name)
        assert model.names[model.parents[jid]] == parent, name
        assert joint_axis(model, jid) == axis, name
        M = model.jointPlacements[jid]
        assert np.abs(M.translation - xyz).max() <= 1e-15, (name, M.translation, xyz)
        assert np.abs(M.rotation - R).max() <= 1e-15, name
    assert tuple(robot.actuated) == SPEC_ACTUATED
    assert set(robot.passive) == set(want) - set(SPEC_ACTUATED)


def test_body_frames_tip_and_closure_frames_match_spec(robot):
    model = robot.model
    for body, joint in list(BODY_JOINT.items()) + [("cross0", "theta43"),
                                                    ("cross_1", "theta65_1"),
                                                    ("cross_2", "theta65_2")]:
        f = model.frames[robot.frame_id(body)]
        assert model.names[f.parentJoint] == joint, body
        assert f.placement.isIdentity(1e-15), body  # the body frame is the joint frame
    expected = {"tip": ("theta1817", (0.06, 0, 0))}
    for i in (1, 2):
        expected[f"closure{i}_A"] = (f"theta76_{i}", (0.325, 0, 0))  # Tx(x87i) on link_i
        expected[f"closure{i}_B"] = ("theta54", SPEC_A[i])  # A_i on the platform
    for name, (joint, xyz) in expected.items():
        f = model.frames[robot.frame_id(name)]
        assert model.names[f.parentJoint] == joint, name
        assert np.abs(f.placement.translation - xyz).max() <= 1e-15, (name, f.placement)
        assert np.abs(f.placement.rotation - np.eye(3)).max() <= 1e-15, name
    assert [(c.name, c.frame_a, c.frame_b) for c in robot.closures] == [
        ("closure1", "closure1_A", "closure1_B"), ("closure2", "closure2_A", "closure2_B")]
    for cm in robot.constraint_models:
        assert cm.type == pin.ContactType.CONTACT_3D


# --- §5 masses and inertias -----------------------------------------------------------------
def test_total_mass_is_0_92_kg(robot):
    assert abs(pin.computeTotalMass(robot.model) - 0.92) <= 1e-14  # achieves 1.1e-16
    assert abs(robot.params.total_mass - 0.92) <= 1e-14


@pytest.mark.parametrize("body", list(SPEC_BODIES))
def test_body_inertia_read_back_from_pinocchio(robot, body):
    mass, com, I_mm = SPEC_BODIES[body]
    Y = robot.model.inertias[robot.joint_id(BODY_JOINT[body])]
    assert abs(Y.mass - mass) <= 1e-15
    assert np.abs(Y.lever - com).max() <= 1e-15
    np.testing.assert_allclose(Y.inertia, I_mm * 1e-6, rtol=1e-12, atol=1e-18)


def test_universal_joint_crosses_are_massless(robot):
    for j in MASSLESS_JOINTS:
        Y = robot.model.inertias[robot.joint_id(j)]
        assert Y.mass == 0.0 and np.all(Y.inertia == 0.0), j


# --- §9 home ---------------------------------------------------------------------------------
def test_home_matches_spec_table(robot, q_home):
    got = robot.as_dict(q_home)
    for name, deg in HOME_DEG.items():
        # The table has 3 decimals.
        assert abs(math.degrees(got[name]) - deg) <= 5e-4 + 1e-12, (name, math.degrees(got[name]))


def test_srdf_home_posture_is_the_reference_configuration(robot, q_home):
    q_ref = robot.model.referenceConfigurations["home"]
    for name, deg in HOME_DEG.items():
        assert abs(math.degrees(q_ref[robot.idx_q(name)]) - deg) <= 5e-4 + 1e-12, name  # 3 decimals
    # The SRDF holds the closed-form solution: it already closes the loops.
    r = constraint_residual(*residual_args(robot), np.array(q_ref))
    assert np.abs(r).max() <= 1e-12  # achieves 5.7e-14 (12 decimals in the SRDF)
    assert np.abs(q_home - q_ref).max() <= 5e-11  # achieves 2.7e-13


def test_home_tip_and_closure_points(robot, q_home):
    M = tool_pose(robot, q_home)
    assert np.abs(M.translation - HOME_TIP).max() <= 1e-13, M.translation  # achieves 1.4e-16
    assert np.abs(M.rotation - np.eye(3)).max() <= 1e-13  # θ = ψ = φ = 0: sprays along +x
    data = robot.data
    pin.framesForwardKinematics(robot.model, data, q_home)
    ref = chain_points(spec_geometry(), robot.as_dict(q_home))
    assert np.abs(ref["tip"] - HOME_TIP).max() <= 1e-13  # the spec chain agrees
    for i in (1, 2):
        pa = data.oMf[robot.frame_id(f"closure{i}_A")].translation
        pb = data.oMf[robot.frame_id(f"closure{i}_B")].translation
        assert np.abs(pa - pb).max() <= 1e-13, (i, pa - pb)  # achieves 3.1e-16
        # B from docs/model.md §4/§7: E + R_platform·A_i; A from the spec leg chain.
        # Achieves 2.8e-17 m.
        assert np.abs(pb - (ref["E"] + ref["R_platform"] @ SPEC_A[i])).max() <= 1e-14

        assert np.abs(pa - ref["legs"][i][0]).max() <= 1e-14
    r = constraint_residual(*residual_args(robot), q_home)
    assert np.abs(r).max() <= 1e-13


def test_home_spherical_joint_angles(robot, q_home):
    ref = chain_points(spec_geometry(), robot.as_dict(q_home))
    for i in (1, 2):
        R_link = ref["legs"][i][1]
        got = zyz(R_link.T @ ref["R_platform"] @ rz(-SPEC["beta1413"][i - 1]))
        assert np.abs(got - HOME_SPHERICAL_DEG[i]).max() <= 5e-4 + 1e-12, (i, got)


# --- closure Jacobian and solving -----------------------------------------------------------
@pytest.mark.parametrize("seed", [None, 0, 1, 2])
def test_closure_jacobian_matches_central_differences(robot, q_home, seed):
    if seed is None:
        q = q_home.copy()
    else:  # anywhere, not only on the constraint manifold
        q = np.random.default_rng(seed).uniform(-math.pi, math.pi, robot.model.nq)
    args = residual_args(robot)
    J = constraint_jacobian(*args, q)
    assert J.shape == (6, robot.model.nv)
    h = 1e-6
    Jfd = np.empty_like(J)
    for k in range(robot.model.nv):
        dq = np.zeros(robot.model.nv)
        dq[k] = h
        Jfd[:, k] = (constraint_residual(*args, pin.integrate(robot.model, q, dq))
                     - constraint_residual(*args, pin.integrate(robot.model, q, -dq))) / (2 * h)
    assert np.abs(J - Jfd).max() <= 2e-8  # achieves 1.5e-10


def test_forward_kinematics_from_home_actuators_reproduces_home(robot, q_home):
    act = q_home[robot.actuated_v]
    guess = q_home.copy()
    guess[robot.passive_v] += np.array([0.1, -0.08, 0.06, -0.1, 0.07, 0.09])  # not at home
    for q0 in (None, guess):
        qs, poses = forward_kinematics(robot, act, q_guess=q0)
        assert qs.shape == (1, 12) and poses.shape == (1, 6)
        assert np.abs(qs[0] - q_home).max() <= 5e-11  # achieves 2.7e-13 (12 decimals in the SRDF)
        assert np.abs(poses[0] - robot.params.home_pose).max() <= 2e-11  # achieves 1.2e-13
    q = solve_closure(robot, act, q_guess=guess)
    assert np.abs(q - q_home).max() <= 1e-13  # achieves 8.9e-16
    assert np.abs(constraint_residual(*residual_args(robot), q)).max() <= 1e-14  # achieves 5.6e-17


def test_forward_kinematics_inverts_the_closed_form_ik(robot, q_home):
    from pollard_pin.analytic.closed_form import JOINTS, position_ik

    home = np.asarray(robot.params.home_pose)
    poses = home + np.array([[0.0, 0, 0, 0, 0, 0], [-0.02, 0.05, 0.03, 0.1, -0.05, 0.2],
                             [0.01, -0.08, -0.04, -0.15, 0.1, -0.3]])
    q_ik = position_ik(robot.params, poses)
    order = [JOINTS.index(n) for n in robot.joint_names]
    qs, got = forward_kinematics(robot, q_ik[:, order][:, robot.actuated_v], q_guess=q_home)
    assert np.abs(got - poses).max() <= 1e-13  # achieves 5.3e-16
    assert np.abs(qs - q_ik[:, order]).max() <= 1e-13  # achieves 6.7e-16


@pytest.mark.parametrize("leg", [1, 2])
def test_unreachable_actuator_angles_raise_closure_error_naming_leg(robot, q_home, leg):
    act = q_home[robot.actuated_v].copy()
    act[leg] = math.pi if leg == 1 else -math.pi  # the leg's base arm turned backwards
    with pytest.raises(ClosureError) as ei:
        solve_closure(robot, act)
    e = ei.value
    msg = str(e)
    assert e.leg == leg
    assert e.residual > 0.05  # m; the arm points away from the platform
    assert f"leg {leg} cannot reach its attachment point" in msg
    assert f"{e.residual * 1e3:.4g} mm on leg {leg}" in msg
    # Actuator values are printed as plain numbers.
    assert re.search(rf"'theta21_{leg}': {'-' if leg == 2 else ''}3\.141593\b", msg), msg
    # Along a sequence, the error also names the sample.
    with pytest.raises(ClosureError, match=rf"^sample 1: .*leg {leg} cannot reach") as ei:
        forward_kinematics(robot, np.array([q_home[robot.actuated_v], act]))
    assert ei.value.leg == leg


@pytest.mark.parametrize("bad", [
    [math.nan, 0, 0, 0, 0, 0], [0, 0, 0, math.inf, 0, 0], [0, 0, 0, 0, 0], [0] * 7])
def test_bad_actuator_input_raises_value_error(robot, bad):
    with pytest.raises(ValueError, match="actuator angles must be 6 finite numbers"):
        solve_closure(robot, np.array(bad, dtype=float))


def test_modified_params_give_a_model_whose_placements_follow():
    over = {"chain0.x32": 0.34, "chain0.x1514": 0.11, "chain0.z10": 0.06,
            "leg1.beta54": 10.0, "leg2.y10": 0.09, "leg1.x43": 0.335, "leg2.z32": 0.03,
            "leg1.x87": 0.33, "leg2.x1211": 0.02, "leg1.z1312": 0.025}
    p = load_params(overrides=over)
    r = load(p)
    g = spec_geometry(x32=0.34, x1514=0.11, z10=0.06)
    g["leg1"].update(beta54=math.radians(10.0), x43=0.335, x87=0.33, z1312=0.025)
    g["leg2"].update(y10=0.09, z32=0.03, x1211=0.02)
    for name, (_parent, xyz, R, axis) in spec_tree(g).items():
        jid = r.joint_id(name)
        M = r.model.jointPlacements[jid]
        assert np.abs(M.translation - xyz).max() <= 1e-15, (name, M.translation, xyz)
        assert np.abs(M.rotation - R).max() <= 1e-15, name
        assert joint_axis(r.model, jid) == axis
    fr = r.model.frames
    assert np.abs(fr[r.frame_id("closure1_A")].placement.translation - (0.33, 0, 0)).max() == 0
    assert np.abs(fr[r.frame_id("closure1_B")].placement.translation
                  - (0.37, -0.015, -0.025)).max() <= 1e-15
    assert np.abs(fr[r.frame_id("closure2_B")].placement.translation
                  - (0.37, 0.02, -0.02)).max() <= 1e-15
    # The SRDF home is re-solved for the new geometry: the tip is still at the spec home.
    q = r.home()
    assert np.abs(tool_pose(r, q).translation - HOME_TIP).max() <= 1e-13  # achieves 2.2e-16
    assert np.abs(constraint_residual(*residual_args(r), q)).max() <= 1e-13
    ref = chain_points(g, r.as_dict(q))
    assert np.abs(ref["tip"] - HOME_TIP).max() <= 1e-13
    # Loading from a parameter file path takes the same route (only the source comment differs).
    strip = re.compile(r"Parameters: .*?\.toml\. ")
    assert strip.sub("", load(TOML_PATH).urdf) == strip.sub("", URDF_PATH.read_text())


# --- parameter validation -------------------------------------------------------------------
ROOT_KEYS = "chain0, leg1, leg2, bodies, home, branches, limits"
VALIDATION = [  # overrides, key named in the message, rule text
    ({"chain0.x32": math.nan}, "chain0.x32", "must be a finite number"),
    ({"chain0.z10": math.inf}, "chain0.z10", "must be a finite number"),
    ({"leg1.beta54": -math.inf}, "leg1.beta54", "must be a finite number"),
    ({"home.orientation": [0, 0, math.nan]}, "home.orientation[2]", "must be a finite number"),
    ({"bodies.gun.com": [0, math.nan, 0]}, "bodies.gun.com[1]", "must be a finite number"),
    ({"bodies.link_1.inertia": [[2.62, 0, 0], [0, 2322.307, 0], [0, 0, math.inf]]},
     "bodies.link_1.inertia[2][2]", "must be a finite number"),
    ({"chain0.x32": "0.33"}, "chain0.x32", "must be a number"),
    ({"bodies.arm0.mass": True}, "bodies.arm0.mass", "must be a number"),
    ({"chain0.x32": 0.0}, "chain0.x32", "must be > 0"),
    ({"chain0.x1918": -0.06}, "chain0.x1918", "must be > 0"),
    ({"leg2.x87": 0}, "leg2.x87", "must be > 0"),
    ({"leg1.y10": -0.085}, "leg1.y10", "must be > 0"),
    ({"leg1.x1211": -0.001}, "leg1.x1211", "must be >= 0"),
    ({"bodies.gun.mass": 0.0}, "bodies.gun.mass", "must be > 0"),
    ({"bodies.platform.mass": -0.188}, "bodies.platform.mass", "must be > 0"),
    ({"bodies.platform.mass": math.nan}, "bodies.platform.mass", "must be a finite number"),
    ({"leg1.side": 0}, "leg1.side", "must be -1 or +1"),
    ({"leg1.side": 1}, "leg2.side", "the two legs must stand on opposite sides"),
    ({"branches.leg2": 2}, "branches.leg2", "must be -1 or +1"),
    ({"bodies.gun.inertia": [[1.681, 0.5, 0], [0, 95.822, 0], [0, 0, 95.822]]},
     "bodies.gun.inertia", "inertia tensor must be symmetric"),
    ({"bodies.wrist1.inertia": [[1.681, 0, 0], [0, 95.822, 0], [0, 0, -95.822]]},
     "bodies.wrist1.inertia", "inertia tensor must be positive definite"),
    ({"bodies.arm_2.inertia": [[0, 0, 0], [0, 3027.487, 0], [0, 0, 3016.058]]},
     "bodies.arm_2.inertia", "inertia tensor must be positive definite"),
    ({"bodies.link_2.inertia": [[2.62, 0, 0], [0, 100, 0], [0, 0, 2322.307]]},
     "bodies.link_2.inertia", "principal moments violate the triangle inequality"),
]


@pytest.mark.parametrize("over, key, rule", VALIDATION,
                         ids=[f"{k}:{r.split(' ')[-1]}" for _, k, r in VALIDATION])
def test_parameter_rules(over, key, rule):
    with pytest.raises(ParameterError) as ei:
        load_params(overrides=over)
    msg = str(ei.value)
    assert msg.startswith(f"parameter '{key}' = "), msg
    assert rule in msg, msg
    assert isinstance(ei.value, ValueError)


@pytest.mark.parametrize("over, chain", [
    ({"home.tip": [2.0, 0.0, 0.16]}, "chain 0"),
    ({"chain0.x32": 0.01}, "chain 0"),
    ({"leg1.x87": 0.05}, "leg 1"),
    ({"leg2.x43": 0.05}, "leg 2"),
])
def test_unreachable_home_geometry_is_rejected(over, chain):
    with pytest.raises(ParameterError) as ei:
        load_params(overrides=over)
    msg = str(ei.value)
    assert "is unreachable with these parameters" in msg and "home.tip" in msg, msg
    assert re.search(rf"{chain} cannot reach .* \(short by [0-9.]+ mm\)", msg), msg
    assert "sample" not in msg, msg  # a single pose: no trajectory sample to speak of


def _toml_variant(tmp_path, edit):
    text = edit(TOML_PATH.read_text())
    path = tmp_path / "p.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("edit, pattern", [
    (lambda t: t.replace("x87 = 0.325", "x78 = 0.325", 1),  # a typo is not a partial file
     r"^parameter 'leg1\.x78' = 0\.325: unknown key \(expected keys: side, y10, "),
    (lambda t: t.replace("z10 = 0.05", "z10 = 0.05\nz11 = 0.01", 1),
     r"^parameter 'chain0\.z11' = 0\.01: unknown key \(expected keys: z10, "),
    (lambda t: t.replace("[bodies.gun]", "[bodies.gun]\ncolour = 'red'", 1),
     r"^parameter 'bodies\.gun\.colour' = 'red': unknown key \(expected keys: mass, com, "
     r"inertia\)$"),
    (lambda t: t.replace("[branches]", "[extras]\nx = 1\n[branches]", 1),
     rf"^parameter 'extras' = \{{'x': 1\}}: unknown key \(expected keys: {ROOT_KEYS}\)$"),
    (lambda t: t.replace("[bodies.wrist2]", "[bodies.wrist3]", 1),
     r"^parameter 'bodies\.wrist3' = \{.*\}: unknown key \(expected keys: arm0, "),
    (lambda t: t.replace("x32 = 0.33", "x32 = 330.0", 1),  # millimetres by mistake
     r"^parameter 'chain0\.x32' = 330\.0: must be at most 10 m \(lengths are in metres"),
    (lambda t: t.replace("x32 = 0.33", "x32 = 1e300", 1),
     r"^parameter 'chain0\.x32' = 1e\+300: must be at most 10 m"),
    (lambda t: t.replace("x32 = 0.33", "x32 = nan", 1),
     r"^parameter 'chain0\.x32' = nan: must be a finite number$"),
    (lambda t: t.replace("mass = 0.166", "mass = -inf", 1),
     r"^parameter 'bodies\.arm0\.mass' = -inf: must be a finite number$"),
    (lambda t: t.replace("x32 = 0.33", "x32 = 0.33 0.34", 1),
     r"^parameter file '.*p\.toml' is not valid TOML: "),
    (lambda t: t.replace("[leg2]", "[leg2", 1), r"is not valid TOML"),
    (lambda t: t + "\n[chain0]\nz10 = 0.05\n", r"is not valid TOML"),  # duplicate table
])
def test_parameter_file_rules(tmp_path, edit, pattern):
    path = _toml_variant(tmp_path, edit)
    with pytest.raises(ParameterError, match=pattern):
        load_params(path)


@pytest.mark.parametrize("drop, key", [
    (lambda d: d["chain0"].pop("x32"), r"chain0\.x32"),
    (lambda d: d["leg1"].pop("x87"), r"leg1\.x87"),
    (lambda d: d.pop("home"), "home"),
    (lambda d: d["bodies"].pop("wrist2"), r"bodies\.wrist2"),
])
def test_parameter_dictionary_must_be_complete(drop, key):
    d = read_params_dict()
    drop(d)
    with pytest.raises(ParameterError, match=rf"^parameter '{key}' = None: missing key"):
        params_from_dict(d)


def test_partial_parameter_file_overrides_the_shipped_values(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text("[chain0]\nx32 = 0.34\n[bodies.gun]\nmass = 0.05\n")
    mine = load_params(path)
    same = load_params(overrides={"chain0.x32": 0.34, "bodies.gun.mass": 0.05})
    assert mine.to_toml_dict() == same.to_toml_dict() and mine.source == str(path)
    assert (mine.x32, mine.body("gun").mass, mine.x65) == (0.34, 0.05, 0.37)
    # the whole shipped file is a "partial" file that overrides everything with itself
    assert load_params(TOML_PATH).to_toml_dict() == load_params().to_toml_dict()


def test_parameter_file_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes("# m\xfcde\n[chain0]\nx32 = 0.34\n".encode("latin-1"))
    with pytest.raises(ParameterError, match=r"is not UTF-8 text \(byte 3: b'\\xfc'\)"):
        load_params(path)


def test_parameter_file_missing_and_defaults(tmp_path):
    with pytest.raises(ParameterError, match=r"^parameter file '.*nope\.toml' does not exist$"):
        load_params(tmp_path / "nope.toml")
    # The shipped file itself is valid, SI-converted and round-trips.
    p = load_params()
    assert (p.z10, p.x32, p.x65, p.x1514, p.x1918) == (0.05, 0.33, 0.37, 0.10, 0.06)
    assert [leg.side for leg in p.legs] == [-1, 1]
    assert [math.degrees(leg.beta1413) for leg in p.legs] == pytest.approx([270.0, 90.0])
    for i in (1, 2):
        assert np.abs(p.attachment(i - 1) - SPEC_A[i]).max() <= 1e-15
    assert p.home_pose == (0.55, 0.0, 0.16, 0.0, 0.0, 0.0)
    assert read_params_dict() == read_params_dict(TOML_PATH)


# --- URDF / SRDF files ----------------------------------------------------------------------


def _xml_counts(tag):
    root = ET.parse(URDF_PATH).getroot()
    return {link.get("name"): len(link.findall(tag)) for link in root.findall("link")}


def test_urdf_loads_in_yourdfpy_with_all_geometry(robot, q_home, caplog):
    import yourdfpy

    caplog.set_level(logging.DEBUG)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        u = yourdfpy.URDF.load(str(URDF_PATH), build_scene_graph=True, load_meshes=True)
    assert [str(w.message) for w in caught] == []
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []
    assert u.validate()
    assert {link.name: len(link.visuals) for link in u.robot.links} == _xml_counts("visual")
    assert {link.name: len(link.collisions) for link in u.robot.links} == \
        _xml_counts("collision")
    # Every visual became a mesh in the scene, attached to its own link.
    parents = u.scene.graph.transforms.parents
    per_link = {}
    for node in u.scene.graph.nodes_geometry:
        per_link[parents[node]] = per_link.get(parents[node], 0) + 1
    assert per_link == {k: v for k, v in _xml_counts("visual").items() if v}
    assert all(len(g.vertices) > 0 for g in u.scene.geometry.values())
    # Same kinematics as Pinocchio at home.
    assert set(u.actuated_joint_names) == set(robot.joint_names)
    u.update_cfg({n: v for n, v in robot.as_dict(q_home).items()})
    T = u.get_transform("tip", "base")
    assert np.abs(T[:3, 3] - HOME_TIP).max() <= 1e-13  # achieves 1.7e-16
    with warnings.catch_warnings(record=True) as caught:  # the collision scene as well
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", r".*Scene\.dump\(concatenate=True\)",
                                DeprecationWarning)  # yourdfpy's own use of trimesh
        uc = yourdfpy.URDF.load(str(URDF_PATH), build_scene_graph=False,
                                build_collision_scene_graph=True, load_collision_meshes=True)
    assert [str(w.message) for w in caught] == []
    assert len(uc.collision_scene.geometry) == sum(
        1 for v in _xml_counts("collision").values() if v)  # one merged mesh per link
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []


def test_urdf_loads_in_mujoco_without_warnings(tmp_path, robot, q_home):
    qd = robot.as_dict(q_home)
    stdout = run_clean(tmp_path, f"""
        import json, mujoco, numpy as np
        spec = mujoco.MjSpec.from_file({str(URDF_PATH)!r})
        m = spec.compile()
        d = mujoco.MjData(m)
        for name, v in {qd!r}.items():
            d.qpos[m.jnt_qposadr[m.joint(name).id]] = v
        mujoco.mj_forward(m, d)
        gun = d.body("gun")
        tip = gun.xpos + gun.xmat.reshape(3, 3) @ np.array([0.06, 0, 0])
        for _ in range(20):
            mujoco.mj_step(m, d)
        print(json.dumps(dict(
            warnings=[int(d.warning[i].number) for i in range(len(d.warning))],
            njnt=m.njnt, nv=m.nv, ngeom=m.ngeom,
            mass={{m.body(i).name: float(m.body_mass[i]) for i in range(m.nbody)}},
            joints=sorted(m.joint(i).name for i in range(m.njnt)),
            types=sorted(set(int(t) for t in m.jnt_type)), tip=tip.tolist())))
    """)
    res = json.loads(stdout)
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
    assert res["warnings"] == [0] * len(res["warnings"]), res["warnings"]
    assert res["njnt"] == res["nv"] == 12
    assert res["joints"] == sorted(robot.joint_names)
    assert res["types"] == [3]  # mjJNT_HINGE
    # The URDF inertials come through unchanged. (Under MuJoCo's default inertiafromgeom="auto"
    # the massless crosses get a mass from their collision spheres; pollard_pin.mujoco_peer
    # turns that off and merges the crosses.)
    for body, (mass, _, _) in SPEC_BODIES.items():
        assert abs(res["mass"][body] - mass) <= 1e-15, body
    assert res["ngeom"] == sum(_xml_counts("collision").values())  # visuals are discarded
    assert np.abs(np.array(res["tip"]) - HOME_TIP).max() <= 1e-13  # achieves 1.7e-16


# --- malformed model files ------------------------------------------------------------------
SRDF = SRDF_PATH.read_text()
_ONE_CLOSURE = '  <loop_closure name="closure2" type="spherical" frame_a="closure2_A" ' \
               'frame_b="closure2_B"/>\n'


@pytest.mark.parametrize("edit, pattern", [
    (lambda u: re.sub(r"  <loop_closure[^\n]*\n", "", u),
     r"expected 2 <loop_closure> elements \(docs/model.md §4\), found 0"),
    (lambda u: u.replace(_ONE_CLOSURE, ""), r"expected 2 <loop_closure> elements.*found 1"),
    (lambda u: u.replace(_ONE_CLOSURE, _ONE_CLOSURE * 2),
     r"expected 2 <loop_closure> elements.*found 3"),
    (lambda u: u.replace('frame_a="closure1_A"', 'frame_a="bogus_frame"'),
     r"loop closure 'closure1' names frame 'bogus_frame', not in the URDF"),
    (lambda u: u.replace('frame_b="closure2_B"', 'frame_b="closure2_b"'),
     r"loop closure 'closure2' names frame 'closure2_b', not in the URDF"),
    (lambda u: u.replace(' frame_b="closure2_B"', ""), r"<loop_closure> .* lacks attribute"),
    (lambda u: u.replace('name="closure1" type="spherical"', 'name="closure1" type="revolute"'),
     r"loop closure 'closure1': only type='spherical' is supported"),
    (lambda u: u.replace('"theta43"', '"theta_43"'),
     r"URDF is not the Pollard tree of docs/model.md §3: missing joints \['theta43'\]"),
    (lambda u: u.replace("</robot>", ""), r"^Pinocchio cannot build the URDF|not well-formed"),
])
def test_malformed_urdf_raises_model_file_error(edit, pattern):
    urdf = URDF_PATH.read_text()
    bad = edit(urdf)
    assert bad != urdf
    with pytest.raises(ModelFileError, match=pattern):
        build(load_params(), bad, SRDF)


def test_srdf_without_home_raises_model_file_error():
    with pytest.raises(ModelFileError, match="SRDF has no group_state named 'home'"):
        build(load_params(), URDF_PATH.read_text(), SRDF.replace('name="home"', 'name="rest"'))


# --- packaging ------------------------------------------------------------------------------
def _copy_project(dst):
    for name in ("pyproject.toml", "setup.py", "README.md"):
        if (REPO / name).exists():
            shutil.copy2(REPO / name, dst / name)
    # no build products: the wheel compiles its own kernels (csrc/)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.so", "*.pyd")
    for name in ("pollard_pin", "models", "csrc"):
        shutil.copytree(REPO / name, dst / name, ignore=ignore)


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """``pip wheel --no-deps .`` of a copy of the project (the work tree stays clean)."""
    src = tmp_path_factory.mktemp("src")
    _copy_project(src)
    dist = tmp_path_factory.mktemp("dist")
    out = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", str(src),
                          "-w", str(dist)], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    (whl,) = dist.glob("pollard_pin-*.whl")
    return whl


def test_wheel_ships_the_models(wheel):
    with zipfile.ZipFile(wheel) as z:
        names = set(z.namelist())
        for f in ("pollard.urdf", "pollard.srdf", "pollard.toml"):
            assert f"pollard_pin/models/{f}" in names
            assert z.read(f"pollard_pin/models/{f}").decode() == (MODELS / f).read_text()
        package = MODELS.parent / "pollard_pin"
        sources = {f"pollard_pin/{f.relative_to(package).as_posix()}"
                   for f in package.rglob("*.py")}
        assert sources <= names, f"modules missing from the wheel: {sorted(sources - names)}"
        # the C kernels, compiled when the wheel was built (nothing compiles at run time)
        for ext in ("kinematics/_kernels", "painting/spray/_deposit"):
            assert any(re.fullmatch(rf"pollard_pin/{ext}\..*\.(so|pyd)", n)
                       for n in names), sorted(n for n in names if ".so" in n or ".pyd" in n)
        entry = z.read(next(n for n in names if n.endswith("entry_points.txt"))).decode()
    assert "pollard-pin = pollard_pin.cli:main" in entry


def _site_packages(venv):
    return next((venv / "lib").glob("python3*/site-packages"))


def _fresh_venv(wheel, venv):
    """A new venv with the wheel installed (and byte-compiled, as pip does). The heavy
    dependencies (pin, numpy, ...) come from this environment, after the venv's own
    site-packages, so pollard_pin can only come from the wheel."""
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True,
                   timeout=120)
    deps = [str(Path(pin.__file__).resolve().parents[1]), str(Path(np.__file__).parents[1])]
    (_site_packages(venv) / "_deps.pth").write_text("\n".join(dict.fromkeys(deps)) + "\n")
    py = venv / "bin" / "python"
    out = subprocess.run([sys.executable, "-m", "pip", "--python", str(py), "install", "-q",
                          "--no-deps", "--no-index", str(wheel)],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    return venv


@pytest.fixture(scope="module")
def fresh(wheel, tmp_path_factory):
    """One fresh venv with the wheel (:func:`_fresh_venv`) for this module's tests: "venv"
    its folder, "used" whether a command has run from it writably (a first-run test that
    comes later builds its own)."""
    return {"venv": _fresh_venv(wheel, tmp_path_factory.mktemp("fresh") / "venv"),
            "used": False}


def _read_only_namespace():
    """The command prefix of a private mount namespace (``unshare -m``; ``-r`` maps an
    unprivileged user to root in it), or None. Bind mounts made read-only there bind root too,
    where ``chmod`` does not."""
    probe = "mount --bind / / && mount -o remount,bind,ro / /"
    for cmd in (["unshare", "-m"], ["unshare", "-r", "-m"]):
        try:
            ok = subprocess.run([*cmd, "sh", "-c", probe], capture_output=True,
                                timeout=30).returncode == 0
        except (OSError, subprocess.SubprocessError):
            ok = False
        if ok:
            return cmd
    return None


def test_first_run_of_a_read_only_install_with_a_read_only_home(wheel, fresh, tmp_path):
    """A root install run by a user: the package and HOME read-only, never run before. It must
    neither crash (numba's `cannot cache function … no locator available` did) nor compile.
    Read-only, this run leaves the module's venv as it found it."""
    prefix = _read_only_namespace()
    if prefix is None:
        pytest.skip("no private mount namespace here (unshare -m) to make directories read-only")
    venv = fresh["venv"] if not fresh["used"] else _fresh_venv(wheel, tmp_path / "venv")
    home, work = tmp_path / "home", tmp_path / "w"
    home.mkdir()
    work.mkdir()
    ro = " && ".join(f"mount --bind {d} {d} && mount -o remount,bind,ro {d}" for d in
                     (venv, home))
    probe = f"touch {venv}/probe 2>/dev/null || touch {home}/probe 2>/dev/null"
    script = (f"{ro} && if {probe}; then echo writable >&2; exit 9; fi && "
              f"exec {venv}/bin/pollard-pin run --samples 201 --out run.csv")
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "VIRTUAL_ENV", "NUMBA_CACHE_DIR", "XDG_CACHE_HOME")}
    out = subprocess.run([*prefix, "sh", "-c", script], cwd=work, capture_output=True,
                         text=True, timeout=300, env={**env, "HOME": str(home)})
    assert out.returncode == 0 and "Traceback" not in out.stderr, out.stderr
    assert "wrote run.csv (201 rows)" in out.stderr
    assert not any(home.iterdir()) and not (venv / "probe").exists()


def test_load_works_from_the_installed_wheel_in_a_fresh_venv(fresh, tmp_path):
    fresh["used"] = True
    _check_installed(fresh["venv"], tmp_path)


# Commands from the installed package, in one interpreter (the console script runs `info`):
# an interpreter per command cost 1.2 s of imports each. The others (report, view, size,
# simulate, plot, ...) are left to scripts/check_install.py (`make install-check`, CI's next
# step), which runs every command through the console script of a plain install; here the
# CSV run and the Parquet run with joint loads, which it does not read back and compare.
INSTALLED_COMMANDS = (
    (["run", "--samples", "401", "--out", "r.csv"], "r.csv"),
    (["run", "--samples", "401", "--loads", "--out", "loads.parquet"], "loads.parquet"),
)


def _check_installed(venv, cwd):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    cli = subprocess.run([str(venv / "bin" / "pollard-pin"), "info"], cwd=cwd, env=env,
                         capture_output=True, text=True, timeout=300)
    assert cli.returncode == 0 and "Traceback" not in cli.stderr, cli.stderr
    assert "total mass 0.9200 kg" in cli.stdout
    code = textwrap.dedent("""
        import contextlib, io, json, sys, numpy as np, pollard_pin, pollard_pin as pp
        from pollard_pin.cli import main
        from pollard_pin.kinematics import tool_pose
        from pollard_pin.model.paths import models_dir
        r = pollard_pin.load()
        q = r.home()
        tip = tool_pose(r, q).translation
        codes = []
        for argv in json.loads(sys.argv[1]):
            with contextlib.redirect_stdout(io.StringIO()):
                codes.append(main(argv))
        # the CSV run and the Parquet run (with joint loads) read back
        a, b = pp.read_result("r.csv"), pp.read_result("loads.parquet")
        print(json.dumps(dict(file=pollard_pin.__file__, models=str(models_dir()), nq=r.model.nq,
                              tip=tip.tolist(), mass=r.params.total_mass, codes=codes,
                              rows=[len(a), len(b)],
                              loads=sum(c.startswith("F_") for c in b.columns),
                              dtau=float(np.abs(a["tau_theta21"] - b["tau_theta21"]).max()))))
    """)
    argv = json.dumps([args for args, _ in INSTALLED_COMMANDS])
    out = subprocess.run([str(venv / "bin" / "python"), "-c", code, argv], cwd=cwd, env=env,
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0 and "Traceback" not in out.stderr, out.stderr
    res = json.loads(out.stdout)
    site = str(_site_packages(venv).resolve())
    assert str(Path(res["file"]).resolve()).startswith(site), res["file"]
    assert str(Path(res["models"]).resolve()).startswith(site), res["models"]
    assert res["nq"] == 12 and abs(res["mass"] - 0.92) <= 1e-14
    assert np.abs(np.array(res["tip"]) - HOME_TIP).max() <= 1e-13
    # Each command works from the installed package.
    for (args, made), status in zip(INSTALLED_COMMANDS, res["codes"], strict=True):
        assert status == 0, (args, out.stderr)
        assert (Path(cwd) / made).stat().st_size > 0, (args, made)
    # The Parquet run (with joint loads) and the CSV run read back through the installed API
    # (polars and pyarrow resolved there) and agree on the torques.
    assert res["rows"] == [401, 401] and res["loads"] == 36 and res["dtau"] <= 1e-12, res


@pytest.mark.slow
def test_pip_install_with_dependencies_in_a_fresh_venv(wheel, tmp_path):
    """Full ``pip install`` of the wheel, resolving the declared dependencies (≈ 30–40 s)."""
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=120)
    out = subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "-q",
                          str(wheel)], capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stdout + out.stderr
    _check_installed(venv, tmp_path)


def test_load_refuses_a_urdf_stale_against_the_parameter_file(tmp_path, monkeypatch):
    import pollard_pin.model.build as model_mod
    import pollard_pin.model.params as params_mod
    from pollard_pin.model.paths import models_dir

    for f in ("pollard.toml", "pollard.urdf", "pollard.srdf"):
        shutil.copy(models_dir() / f, tmp_path / f)
    monkeypatch.setattr(model_mod, "models_dir", lambda: tmp_path)
    monkeypatch.setattr(params_mod, "models_dir", lambda: tmp_path)
    assert pollard_pin.load().params.body("gun").mass == 0.035  # the copy is consistent
    toml = tmp_path / "pollard.toml"
    toml.write_text(toml.read_text().replace("mass = 0.035        # kg  m5", "mass = 0.05"))
    with pytest.raises(ModelFileError,
                       match=r"pollard\.urdf and pollard\.srdf do not match .*pollard\.toml: "
                             r"regenerate them from the parameters"):
        pollard_pin.load()


def test_residual_and_jacobian_in_one_pass_and_the_constraint_vectors(robot):
    """constraint_residual_jacobian gives constraint_residual and constraint_jacobian bit for
    bit from one kinematics pass; the constraints live in Pinocchio's own vectors (a Python
    list is copied on every call), and robot_copy's lists become vectors too."""
    from pollard_pin.dynamics.forward import robot_copy
    from pollard_pin.model.build import constraint_residual_jacobian

    rng = np.random.default_rng(4)
    for _ in range(5):
        q = robot.home() + rng.normal(0.0, 0.3, robot.model.nq)
        r, J = constraint_residual_jacobian(robot, q)
        args = (robot.model, robot.data, robot.constraint_models, robot.constraint_datas, q)
        np.testing.assert_array_equal(r, constraint_residual(*args))
        np.testing.assert_array_equal(J, constraint_jacobian(*args))
    for r in (robot, robot_copy(robot)):
        assert isinstance(r.constraint_models, pin.StdVec_RigidConstraintModel)
        assert isinstance(r.constraint_datas, pin.StdVec_RigidConstraintData)
        assert len(r.constraint_pairs) == 2


def test_check_robot_names_the_argument(robot):
    """The public entry points' first check: a Robot as is, anything else one InputError
    line naming the argument."""
    assert check_robot(robot) is robot
    for wrong in (None, "robot", 3, float("nan")):
        with pytest.raises(InputError, match=r"^robot = .*expected a Robot \(pollard_pin.load"):
            check_robot(wrong)


@pytest.mark.parametrize("params", [{"chain0.x32": 0.34}, 3])
def test_load_refuses_what_is_no_parameters(params):
    """A dict or a number: one ParameterError line naming what load takes, not a TypeError."""
    with pytest.raises(pollard_pin.InputError, match=r"^params = .*: expected a Params, a "):
        pollard_pin.load(params)
