"""MuJoCo as an independent engine (pollard_pin.mujoco_peer): model contents against the URDF,
loop closure of Pinocchio's IK, closed-loop torques against pollard_pin.dynamics, and
Pinocchio-free checks (sign of λ by applied forces, static torques by virtual work)."""
import xml.etree.ElementTree as ET

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

from bare_modules import run_bare  # noqa: E402

import pollard_pin as pp  # noqa: E402
from pollard_pin.crosscheck.mujoco import (  # noqa: E402
    ACTUATED,
    JOINTS,
    MujocoIKError,
    build_mujoco,
    home_configuration,
    inverse_dynamics_mujoco,
    inverse_kinematics_mujoco,
    pipeline_mujoco,
)
from pollard_pin.dynamics.inverse import inverse_dynamics  # noqa: E402
from pollard_pin.model.paths import models_dir  # noqa: E402

URDF = models_dir() / "pollard.urdf"
TOL_CLOSURE = 1e-13  # m (achieves 7.6e-16)
TOL_REL = 5e-12  # relative to the peak per actuator / per leg (achieves 2.5e-14)


@pytest.fixture(scope="module")
def built():
    return build_mujoco()


@pytest.fixture(scope="module")
def robot():
    return pp.load()


def _ik(robot, traj):
    from pollard_pin.kinematics.ik import inverse_kinematics

    return inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)


@pytest.fixture(scope="module")
def iks(robot):
    from pollard_pin.paths.curves import smooth_random_trajectory, thesis_trajectory

    return {"thesis": _ik(robot, thesis_trajectory()),
            "random0": _ik(robot, smooth_random_trajectory(0)),
            "random1": _ik(robot, smooth_random_trajectory(1))}


# --- (1) model contents (docs/model.md §2, §5)
# ----------------------------------------------------------
def test_masses_and_gravity_match_urdf(built):
    model, _, info = built
    assert mujoco.mj_getTotalmass(model) == pytest.approx(0.92, abs=1e-14)  # 1.1e-16

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
    # Sites where docs/model.md §4/§5 put them: Tx(x87i) on link_i, A_i on the platform.
    (a1, b1), (a2, b2) = info["sites"]
    assert a1[1:] == ("link_1", [0.325, 0.0, 0.0]) and a2[1:] == ("link_2", [0.325, 0.0, 0.0])
    assert b1[1] == b2[1] == "platform"
    assert np.abs(np.array([b1[2], b2[2]]) - [[0.37, -0.015, -0.02], [0.37, 0.015, -0.02]]).max() \
        <= 1e-15  # achieves 0

    assert np.array_equal(info["efc_sign"], [1.0, 1.0])


def test_joint_order_is_the_ik_order(robot):
    assert tuple(robot.joint_names) == JOINTS
    assert tuple(robot.actuated) == ACTUATED


def test_module_does_not_import_pinocchio():
    """The MuJoCo peer runs with Pinocchio hidden and the package ``__init__`` files (the root
    imports every layer) bypassed: its own imports never reach Pinocchio."""
    code = ("import numpy as np; from pollard_pin.crosscheck.mujoco import "
            "inverse_dynamics_mujoco as f, pipeline_mujoco as p; "
            "r = f(np.zeros(12), np.zeros(12), np.zeros(12)); "
            "assert r['tau'].shape == (1, 6) and r['closure_forces'].shape == (1, 2, 3); "
            "r = p(np.array([[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]])); "
            "assert r['q'].shape == (1, 12) and r['tau'].shape == (1, 6); "
            "assert not [m for m in sys.modules if m.startswith('pinocchio.')]")
    r = run_bare(code, timeout=60)
    assert r.returncode == 0, r.stderr


def test_input_shapes(built, robot):
    out = inverse_dynamics_mujoco(np.zeros(12), np.zeros(12), np.zeros(12), built=built)
    assert out["tree"].shape == (1, 12) and out["residual"].shape == (1, 2)
    # One sample at rest at q = 0: the open tree's torques are Pinocchio's gravity torques.
    import pinocchio

    g = pinocchio.computeGeneralizedGravity(robot.model, robot.model.createData(),
                                            np.zeros(robot.model.nq))
    want = g[[robot.idx_v(n) for n in JOINTS]]
    assert np.abs(want).max() > 1.0  # N·m: a real load
    # Achieves 2e-14 of the peak.
    assert np.abs(out["tree"][0] - want).max() <= 2e-12 * np.abs(want).max()


    with pytest.raises(ValueError, match="expected"):
        inverse_dynamics_mujoco(np.zeros((3, 12)), np.zeros((3, 12)), np.zeros((3, 11)))


# --- (2) Pinocchio's IK closes the loops in MuJoCo (docs/model.md §4)
# ------------------------------------
def test_closure_residual_at_ik_configurations(iks, built):
    for name, ik in iks.items():
        out = inverse_dynamics_mujoco(ik.q, ik.v, ik.a, built=built)
        assert out["residual"].max() <= TOL_CLOSURE, name


# --- (3) against pollard_pin.dynamics (Pinocchio RNEA + closure Jacobian) -----------------------
def _rel_errors(got, want, axis):
    peak = np.abs(want).max(axis=axis)
    # An identically ~0 torque (θ1817 on the thesis curve: gun CoG on its roll axis) has no
    # relative scale of its own: floor it at 1e-3 of the largest peak.
    scale = np.maximum(peak, 1e-3 * peak.max())
    return np.abs(got - want).max(axis=axis) / scale


@pytest.mark.parametrize("name", ["thesis", "random0", "random1"])
def test_torques_and_closure_forces_match_pinocchio(name, iks, robot, built):
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
    link_i (docs/model.md §4), in MuJoCo's own force convention."""
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
        assert np.abs(data.qacc[dadr] - ik.a[k]).max() <= 1e-12 * a_scale, k  # 8.5e-15 × scale


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
    """At rest, τ_i = ∂U/∂θ_i along the closed-loop manifold (docs/model.md §8, virtual work). Home
    comes
    from the closed-form IK (pollard_pin.analytic.closed_form, no Pinocchio), closed by Newton
    in MuJoCo."""
    from pollard_pin.analytic.closed_form import JOINTS as THESIS_JOINTS
    from pollard_pin.analytic.closed_form import position_ik
    from pollard_pin.model.params import load_params

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
    # Achieves 2.4e-13 × the peak.
    assert np.abs(tau - grad).max() <= 5e-11 * np.abs(tau).max(), (tau, grad)


# --- (4) MuJoCo constrained IK (inverse_kinematics_mujoco, pipeline_mujoco) ----------------------
# Against Pinocchio's IK: achieves 3.6e-15 rad, 9.8e-15 rad/s, 1.7e-13 rad/s².
TOL_Q, TOL_V, TOL_A = 5e-13, 2e-12, 2e-11


def _wrap(x):
    return (x + np.pi) % (2 * np.pi) - np.pi


@pytest.fixture(scope="module")
def short_trajs():
    from pollard_pin.paths.curves import smooth_random_trajectory, thesis_trajectory

    return {"thesis201": thesis_trajectory(samples=201),
            "random0": smooth_random_trajectory(0, samples=101),
            "random1": smooth_random_trajectory(1, samples=101)}


@pytest.mark.parametrize("name", ["thesis201", "random0", "random1"])
def test_mujoco_ik_and_pipeline_match_pinocchio(name, short_trajs, robot, built):
    traj = short_trajs[name]
    ik = _ik(robot, traj)
    timings = {}
    out = pipeline_mujoco(traj.poses, traj.d_poses, traj.dd_poses, timings=timings, built=built)
    assert set(timings) == {"position", "velocity", "acceleration", "dynamics"}
    assert all(t > 0 for t in timings.values())
    n = len(traj)
    for key in ("q", "v", "a"):
        assert out[key].shape == (n, 12)
    assert out["closure_residual"].shape == (n,)
    assert np.abs(_wrap(out["q"] - ik.q)).max() <= TOL_Q
    assert np.abs(out["v"] - ik.v).max() <= TOL_V
    assert np.abs(out["a"] - ik.a).max() <= TOL_A
    assert out["closure_residual"].max() <= TOL_CLOSURE
    assert out["tool_error"].max() <= 5e-13  # achieves 3e-15
    # The dynamics half of the pipeline sees closed loops too.
    assert out["residual"].max() <= TOL_CLOSURE
    pin = inverse_dynamics(robot, ik)
    e_tau = _rel_errors(out["tau"], pin.tau, axis=0)
    assert e_tau.max() <= TOL_REL, dict(zip(ACTUATED, e_tau))
    peak_f = np.linalg.norm(pin.closure_forces, axis=2).max(axis=0)
    e_f = np.abs(out["closure_forces"] - pin.closure_forces).max(axis=(0, 2)) / peak_f
    assert e_f.max() <= TOL_REL, e_f


def test_home_configuration_from_srdf(robot):
    q = home_configuration()
    root = ET.parse(models_dir() / "pollard.srdf").getroot()
    (gs,) = [g for g in root.iter("group_state") if g.get("name") == "home"]
    assert {j.get("name"): float(j.get("value")) for j in gs.iter("joint")} == dict(zip(JOINTS, q))
    # docs/model.md §9 table (degrees, rounded to 1e-3).
    deg = np.degrees(q)
    assert deg[JOINTS.index("theta21")] == pytest.approx(-77.629, abs=1e-3)
    assert deg[JOINTS.index("theta76_2")] == pytest.approx(-46.778, abs=1e-3)


def test_mujoco_ik_at_home_pose_returns_srdf_home(built):
    home = home_configuration()
    out = inverse_kinematics_mujoco(np.array([0.55, 0.0, 0.16, 0.0, 0.0, 0.0]), built=built)
    # The SRDF values are rounded to 1e-12 rad; Newton lands within a few of those.
    assert np.abs(out["q"][0] - home).max() <= 5e-11  # achieves 2.7e-13
    assert np.abs(out["v"]).max() == 0.0 and np.abs(out["a"]).max() <= 1e-14  # achieves 0


def test_mujoco_ik_warm_start_options_agree(short_trajs, built):
    """q_start and the secant predictor change the iterates, not the solution."""
    traj = short_trajs["random1"]
    ref = inverse_kinematics_mujoco(traj.poses, traj.d_poses, traj.dd_poses, built=built)
    sec = inverse_kinematics_mujoco(traj.poses, traj.d_poses, traj.dd_poses, built=built,
                                    predictor="secant")
    start = inverse_kinematics_mujoco(traj.poses, traj.d_poses, traj.dd_poses, built=built,
                                      q_start=ref["q"][0] + 0.02)
    for other in (sec, start):
        assert np.abs(other["q"] - ref["q"]).max() <= 5e-13  # achieves 3.3e-15
        assert np.abs(other["a"] - ref["a"]).max() <= 2e-12  # achieves 1.3e-14
    assert sec["iterations"].sum() < ref["iterations"].sum()
    assert np.all(ref["iterations"] <= 6)


def test_mujoco_ik_accelerations_by_finite_differences_in_time(built):
    """Pinocchio-free: v and a are the time derivatives of the IK positions along the thesis
    curve (exact poses at t ± h from pollard_pin.trajectory.thesis_curve)."""
    from pollard_pin.paths.curves import thesis_curve

    h = 1e-4
    t0 = np.linspace(0.3, 19.7, 7)
    ts = (t0[:, None] + h * np.array([-2, -1, 0, 1, 2])[None, :]).reshape(-1)
    out = inverse_kinematics_mujoco(*thesis_curve(ts), built=built)
    q = out["q"].reshape(len(t0), 5, 12)
    v, a = out["v"].reshape(len(t0), 5, 12)[:, 2], out["a"].reshape(len(t0), 5, 12)[:, 2]
    dq = (q[:, 0] - 8 * q[:, 1] + 8 * q[:, 3] - q[:, 4]) / (12 * h)
    vv = out["v"].reshape(len(t0), 5, 12)
    dv = (vv[:, 0] - 8 * vv[:, 1] + 8 * vv[:, 3] - vv[:, 4]) / (12 * h)
    # 5-point differences achieve 7.3e-12 × |v| and 4.9e-12 × |a|.
    assert np.abs(dq - v).max() <= 1e-9 * np.abs(v).max()
    assert np.abs(dv - a).max() <= 5e-10 * np.abs(a).max()


def test_objectacceleration_drift_is_classical_by_finite_differences(built):
    """The drift recipe (qacc = 0, mj_rnePostConstraint, mj_objectAcceleration flg_local=0,
    gravity added back) is K̇ v: the derivative of K(q) v along q + s v (4th-order central
    differences), at random states, gravity on."""
    from pollard_pin.crosscheck.mujoco import site_drifts

    model, _, info = built
    data = mujoco.MjData(model)
    assert not np.array_equal(model.opt.gravity, 0.0)
    sites = (*info["site_ids"].reshape(-1), info["tip_site"])

    def K(q):
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        J = np.zeros((len(sites), 6, model.nv))
        for i, s in enumerate(sites):
            mujoco.mj_jacSite(model, data, J[i, :3], J[i, 3:], s)
        return np.vstack([J[0, :3] - J[1, :3], J[2, :3] - J[3, :3], J[4, :3], J[4, 3:]])

    rng = np.random.default_rng(3)
    h = 1e-3
    for _ in range(5):
        q, v = rng.uniform(-2, 2, model.nv), rng.uniform(-3, 3, model.nv)
        fd = (K(q - 2 * h * v) @ v - 8 * K(q - h * v) @ v + 8 * K(q + h * v) @ v
              - K(q + 2 * h * v) @ v) / (12 * h)
        got = site_drifts(model, data, sites, q, v, np.empty(12))
        assert np.abs(got - fd).max() <= 1e-8 * np.abs(fd).max(), (got, fd)
        # The ω × ṗ term separates classical from spatial acceleration: it is far above the
        # tolerance, so a spatial acceleration would fail the check above.
        Kq = K(q)
        wxv = np.cross(Kq[9:12] @ v, Kq[6:9] @ v)
        assert np.abs(wxv).max() > 1e-3 * np.abs(fd).max()


def test_mujoco_ik_errors(built):
    with pytest.raises(ValueError, match="shape"):
        inverse_kinematics_mujoco(np.zeros((3, 5)), built=built)
    with pytest.raises(ValueError, match="predictor"):
        inverse_kinematics_mujoco(np.zeros(6), built=built, predictor="cubic")
    with pytest.raises(MujocoIKError) as exc:  # 2 m away: out of reach
        inverse_kinematics_mujoco(np.array([2.5, 0.0, 0.16, 0.0, 0.0, 0.0]), built=built)
    assert exc.value.sample == 0 and exc.value.residual > 0.1
