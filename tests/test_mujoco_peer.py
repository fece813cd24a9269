"""MuJoCo as an independent engine (pollard_pin.mujoco_peer): model contents against the URDF,
loop closure of Pinocchio's IK, closed-loop torques against pollard_pin.dynamics, and
Pinocchio-free checks (sign of λ by applied forces, static torques by virtual work)."""
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

from pollard_pin._paths import models_dir  # noqa: E402
from pollard_pin.mujoco_peer import (ACTUATED, JOINTS, build_mujoco,  # noqa: E402
                                     inverse_dynamics_mujoco)

URDF = models_dir() / "pollard.urdf"
TOL_CLOSURE = 1e-10  # m
TOL_REL = 1e-8  # relative to the peak per actuator / per leg


@pytest.fixture(scope="module")
def built():
    return build_mujoco()


@pytest.fixture(scope="module")
def robot():
    pp = pytest.importorskip("pollard_pin")
    pytest.importorskip("pinocchio")
    return pp.load()


def _ik(robot, traj):
    from pollard_pin.kinematics import inverse_kinematics

    return inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)


@pytest.fixture(scope="module")
def iks(robot):
    from pollard_pin.trajectory import smooth_random_trajectory, thesis_trajectory

    return {"thesis": _ik(robot, thesis_trajectory()),
            "random0": _ik(robot, smooth_random_trajectory(0)),
            "random1": _ik(robot, smooth_random_trajectory(1))}


# --- (1) model contents (spec §2, §5) ----------------------------------------------------------
def test_masses_and_gravity_match_urdf(built):
    model, _, info = built
    assert mujoco.mj_getTotalmass(model) == pytest.approx(0.92, abs=1e-12)
    assert np.array_equal(model.opt.gravity, [0.0, 0.0, -9.81])
    root = ET.parse(URDF).getroot()
    urdf_mass = {link.get("name"): float(link.find("inertial/mass").get("value"))
                 for link in root.iter("link") if link.find("inertial") is not None}
    assert len(urdf_mass) == 9  # 5 bodies in chain 0, 2 per leg; crosses are massless
    for name, m in urdf_mass.items():
        assert model.body(name).mass[0] == pytest.approx(m, rel=1e-14), name
    assert {n: m for n, m in info["body_mass"].items() if m} == pytest.approx(urdf_mass)
    assert info["inertia_error"] < 1e-12  # full tensor, CoG, after MuJoCo's diagonalisation


def test_ideal_joints_and_only_closure_constraints(built):
    model, _, info = built
    D = mujoco.mjtDisableBit
    for bit in (D.mjDSBL_CONTACT, D.mjDSBL_LIMIT, D.mjDSBL_SPRING, D.mjDSBL_DAMPER):
        assert model.opt.disableflags & bit
    assert not np.any(model.dof_armature) and not np.any(model.dof_damping)
    assert not np.any(model.jnt_limited)
    assert model.neq == 2 and np.all(model.eq_type == mujoco.mjtEq.mjEQ_CONNECT)
    assert sorted(info["merged_bodies"]) == ["cross0", "cross_1", "cross_2"]
    # Sites where spec §4/§5 put them: Tx(x87i) on link_i, A_i on the platform.
    (a1, b1), (a2, b2) = info["sites"]
    assert a1[1:] == ("link_1", [0.325, 0.0, 0.0]) and a2[1:] == ("link_2", [0.325, 0.0, 0.0])
    assert b1[1] == b2[1] == "platform"
    assert np.allclose(b1[2], [0.37, -0.015, -0.02]) and np.allclose(b2[2], [0.37, 0.015, -0.02])
    assert np.array_equal(info["efc_sign"], [1.0, 1.0])


def test_joint_order_is_the_ik_order(robot):
    assert tuple(robot.joint_names) == JOINTS
    assert tuple(robot.actuated) == ACTUATED


def test_module_does_not_import_pinocchio():
    code = ("import sys, numpy as np; from pollard_pin.mujoco_peer import "
            "inverse_dynamics_mujoco as f; r = f(np.zeros(12), np.zeros(12), np.zeros(12)); "
            "assert r['tau'].shape == (1, 6) and r['closure_forces'].shape == (1, 2, 3); "
            "assert 'pinocchio' not in sys.modules, 'pinocchio imported'")
    subprocess.run([sys.executable, "-c", code], check=True, timeout=60)


def test_input_shapes(built):
    out = inverse_dynamics_mujoco(np.zeros(12), np.zeros(12), np.zeros(12), built=built)
    assert out["tree"].shape == (1, 12) and out["residual"].shape == (1, 2)
    with pytest.raises(ValueError, match="expected"):
        inverse_dynamics_mujoco(np.zeros((3, 12)), np.zeros((3, 12)), np.zeros((3, 11)))


# --- (2) Pinocchio's IK closes the loops in MuJoCo (spec §4) ------------------------------------
def test_closure_residual_at_ik_configurations(iks, built):
    for name, ik in iks.items():
        out = inverse_dynamics_mujoco(ik.q, ik.v, ik.a, built=built)
        assert out["residual"].max() <= TOL_CLOSURE, name


# --- (3) against pollard_pin.dynamics (Pinocchio RNEA + closure Jacobian) -----------------------
def _pin_dynamics():
    dyn = pytest.importorskip("pollard_pin.dynamics")
    if not hasattr(dyn, "inverse_dynamics"):
        pytest.skip("pollard_pin.dynamics.inverse_dynamics not written yet")
    return dyn.inverse_dynamics


def _rel_errors(got, want, axis):
    peak = np.abs(want).max(axis=axis)
    # An identically ~0 torque (θ1817 on the thesis curve: gun CoG on its roll axis) has no
    # relative scale of its own: floor it at 1e-3 of the largest peak.
    scale = np.maximum(peak, 1e-3 * peak.max())
    return np.abs(got - want).max(axis=axis) / scale


@pytest.mark.parametrize("name", ["thesis", "random0", "random1"])
def test_torques_and_closure_forces_match_pinocchio(name, iks, robot, built):
    inverse_dynamics = _pin_dynamics()
    ik = iks[name]
    pin = inverse_dynamics(robot, ik)
    out = inverse_dynamics_mujoco(ik.q, ik.v, ik.a, built=built)
    if hasattr(pin, "tau_tree"):  # open-tree RNEA
        assert np.abs(out["tree"] - pin.tau_tree).max() <= TOL_REL * np.abs(pin.tau_tree).max()
    e_tau = _rel_errors(out["tau"], pin.tau, axis=0)
    assert e_tau.max() <= TOL_REL, dict(zip(ACTUATED, e_tau))
    f_pin = pin.closure_forces
    peak_f = np.linalg.norm(f_pin, axis=2).max(axis=0)  # per leg
    e_f = np.abs(out["closure_forces"] - f_pin).max(axis=(0, 2)) / peak_f
    assert e_f.max() <= TOL_REL, e_f


# --- Pinocchio-free checks -----------------------------------------------------------------------
def test_closure_force_sign_by_applied_forces(iks, built):
    """τ on the actuators, λ_i at the ball centre on link_i and −λ_i on the platform, applied to
    the OPEN tree in forward dynamics, reproduce the commanded accelerations: λ_i is the force ON
    link_i (spec §4), in MuJoCo's own force convention."""
    model, data, info = build_mujoco()  # private copy: the equality flag is toggled below
    model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_EQUALITY
    ik = iks["random0"]
    ks = np.arange(0, len(ik.t), 40)
    out = inverse_dynamics_mujoco(ik.q[ks], ik.v[ks], ik.a[ks], built=built)
    dadr, qadr = info["dof_adr"], info["qpos_adr"]
    act = dadr[info["actuated_idx"]]
    a_scale = np.abs(ik.a[ks]).max()
    for j, k in enumerate(ks):
        data.qpos[qadr], data.qvel[dadr] = ik.q[k], ik.v[k]
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        data.qfrc_applied[:] = 0.0
        data.qfrc_applied[act] = out["tau"][j]
        for i, (sa, sb) in enumerate(info["site_ids"]):
            f = out["closure_forces"][j, i]
            for site, sign in ((sa, 1.0), (sb, -1.0)):
                mujoco.mj_applyFT(model, data, sign * f, np.zeros(3), data.site_xpos[site],
                                  model.site_bodyid[site], data.qfrc_applied)
        mujoco.mj_forward(model, data)
        assert data.nefc == 0
        assert np.abs(data.qacc[dadr] - ik.a[k]).max() <= 1e-7 * a_scale, k


def _close_loops(model, data, info, q, tol=1e-14):
    """Newton on the passive joints with MuJoCo's site Jacobians (q in JOINTS order)."""
    qadr, dadr = info["qpos_adr"], info["dof_adr"]
    passive = np.setdiff1d(np.arange(12), info["actuated_idx"])
    q = q.copy()
    jA, jB = np.zeros((3, model.nv)), np.zeros((3, model.nv))
    for _ in range(30):
        data.qpos[qadr] = q
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        r, J = [], []
        for sa, sb in info["site_ids"]:
            r.append(data.site_xpos[sa] - data.site_xpos[sb])
            mujoco.mj_jacSite(model, data, jA, None, sa)
            mujoco.mj_jacSite(model, data, jB, None, sb)
            J.append((jA - jB)[:, dadr])
        r, J = np.concatenate(r), np.vstack(J)
        if np.abs(r).max() <= tol:
            return q
        q[passive] -= np.linalg.solve(J[:, passive], r)
    raise AssertionError(f"closure Newton stalled at {np.abs(r).max():.3g} m")


def _potential(model, data, info, q):
    data.qpos[info["qpos_adr"]] = q
    mujoco.mj_kinematics(model, data)
    return -float(model.body_mass @ (data.xipos @ model.opt.gravity))


def test_static_torques_by_virtual_work(built):
    """At rest, τ_i = ∂U/∂θ_i along the closed-loop manifold (spec §8, virtual work). Home comes
    from the closed-form IK (pollard_pin.thesis, no Pinocchio), closed by Newton in MuJoCo."""
    from pollard_pin.params import load_params
    from pollard_pin.thesis.ik import JOINTS as THESIS_JOINTS, position_ik

    model, _, info = built
    data = mujoco.MjData(model)
    p = load_params()
    q18 = position_ik(p, np.asarray(p.home_pose)[None, :])[0]
    q0 = _close_loops(model, data, info, np.array([q18[THESIS_JOINTS.index(n)] for n in JOINTS]))
    out = inverse_dynamics_mujoco(q0, np.zeros(12), np.zeros(12), built=built)
    assert out["residual"].max() <= 1e-13
    h, grad, q = 1e-3, np.empty(6), q0.copy()
    for i, j in enumerate(info["actuated_idx"]):
        U = []
        for s in (-2, -1, 1, 2):  # 4th-order central difference
            qs = q0.copy()
            qs[j] += s * h
            q = _close_loops(model, data, info, qs)
            U.append(_potential(model, data, info, q))
        grad[i] = (U[0] - 8 * U[1] + 8 * U[2] - U[3]) / (12 * h)
    tau = out["tau"][0]
    assert np.abs(tau - grad).max() <= 1e-8 * np.abs(tau).max(), (tau, grad)
