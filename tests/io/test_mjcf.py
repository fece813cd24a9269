"""MJCF export (pollard_pin.io.mjcf.export_mjcf): a standalone MuJoCo file with the
URDF's joints, masses and inertias and the two loop closures as ``connect`` equalities
(docs/model.md §4). Along the default trajectory (docs/model.md §9) the project's IK closes its
loops to round-off and its closed-loop inverse dynamics gives the project's torques."""
import shutil
import xml.etree.ElementTree as ET

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

import pollard_pin  # noqa: E402
from pollard_pin.crosscheck.mujoco import (  # noqa: E402
    ACTUATED,
    JOINTS,
    build_mujoco,
    home_configuration,
    inverse_dynamics_mujoco,
)
from pollard_pin.io.mjcf import export_mjcf  # noqa: E402
from pollard_pin.model.paths import models_dir  # noqa: E402

URDF = models_dir() / "pollard.urdf"
TOL_MASS = 1e-12  # relative
TOL_CLOSURE = 1e-13  # m (achieves 6.3e-16)
TOL_TORQUE = 5e-13  # relative to the peak of each actuator / closure force (achieves 2.1e-15)



@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    return export_mjcf(tmp_path_factory.mktemp("mjcf") / "pollard.xml")


@pytest.fixture(scope="module")
def mj(exported):
    return mujoco.MjModel.from_xml_path(str(exported))


@pytest.fixture(scope="module")
def default_run(robot):
    return pollard_pin.run_pipeline(robot, pollard_pin.thesis_trajectory(samples=401))


def _urdf_inertials():
    out = {}
    for link in ET.parse(URDF).getroot().iter("link"):
        el = link.find("inertial")
        if el is None:
            continue
        assert el.find("origin").get("rpy") == "0 0 0"  # inertia in the link axes
        i = el.find("inertia")
        I = np.array([[float(i.get(k)) for k in row] for row in
                      (("ixx", "ixy", "ixz"), ("ixy", "iyy", "iyz"), ("ixz", "iyz", "izz"))])
        out[link.get("name")] = (float(el.find("mass").get("value")),
                                 np.array([float(x) for x in el.find("origin").get("xyz").split()]),
                                 I)
    return out


def test_export_loads_standalone(exported, tmp_path):
    text = exported.read_text()
    assert text.startswith("<mujoco")
    for word in ("file=", "meshdir", "texturedir", ".urdf", ".stl", ".obj", "<mesh"):
        assert word not in text, word  # primitive shapes only: nothing else on disk
    alone = tmp_path / "elsewhere" / "model.xml"
    alone.parent.mkdir()
    shutil.copy(exported, alone)
    model = mujoco.MjModel.from_xml_path(str(alone))
    assert model.nq == model.nv == 12 and model.neq == 2


def test_joints_equalities_and_actuators(mj):
    names = [mj.joint(i).name for i in range(mj.njnt)]
    assert sorted(names) == sorted(JOINTS)
    assert np.all(mj.jnt_type == mujoco.mjtJoint.mjJNT_HINGE)
    assert mj.neq == 2 and np.all(mj.eq_type == mujoco.mjtEq.mjEQ_CONNECT)
    assert np.all(mj.eq_objtype == mujoco.mjtObj.mjOBJ_SITE) and np.all(mj.eq_active0)
    for i, c in enumerate(("closure1", "closure2")):
        e = mj.equality(c)
        assert mj.site(int(e.obj1id[0])).name == f"{c}_A_site"
        assert mj.site(int(e.obj2id[0])).name == f"{c}_B_site"
        assert mj.body(int(mj.site(f"{c}_A_site").bodyid[0])).name == f"link_{i + 1}"
        assert mj.body(int(mj.site(f"{c}_B_site").bodyid[0])).name == "platform"
    assert mj.body(int(mj.site("tip_site").bodyid[0])).name == "gun"
    assert [mj.actuator(i).name for i in range(mj.nu)] == list(ACTUATED)
    assert [mj.joint(int(mj.actuator(n).trnid[0])).name for n in ACTUATED] == list(ACTUATED)
    assert np.array_equal(mj.opt.gravity, [0.0, 0.0, -9.81])
    assert mj.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT  # ideal: no collisions
    assert not np.any(mj.dof_damping) and not np.any(mj.dof_armature)
    assert not np.any(mj.dof_frictionloss) and not np.any(mj.jnt_stiffness)


def test_masses_and_inertias_equal_the_urdf(mj):
    ref = _urdf_inertials()
    assert len(ref) == 9
    for name, (mass, com, inertia) in ref.items():
        b = mj.body(name)
        R = np.empty(9)
        mujoco.mju_quat2Mat(R, b.iquat)
        R = R.reshape(3, 3)
        assert abs(b.mass[0] - mass) <= TOL_MASS * mass, name
        assert np.abs(b.ipos - com).max() <= TOL_MASS * np.abs(com).max(initial=1.0), name
        err = np.abs(R @ np.diag(b.inertia) @ R.T - inertia).max()
        assert err <= TOL_MASS * np.abs(inertia).max(), (name, err)
    # The massless U-joint crosses are fused into their parents: no mass appears or vanishes.
    names = {mj.body(i).name for i in range(mj.nbody)}
    assert not names & {"cross0", "cross_1", "cross_2"}
    assert mujoco.mj_getTotalmass(mj) == pytest.approx(sum(m for m, _, _ in ref.values()),
                                                      rel=1e-15)


def test_home_keyframe_closes_the_loops(mj):
    assert mj.nkey == 1 and mj.key(0).name == "home"
    home = home_configuration()
    qpos = mj.key("home").qpos
    assert [qpos[mj.joint(n).qposadr[0]] for n in JOINTS] == home.tolist()
    data = mujoco.MjData(mj)
    mujoco.mj_resetDataKeyframe(mj, data, 0)
    mujoco.mj_forward(mj, data)
    eq = data.efc_type[:data.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY
    assert eq.sum() == 6 == data.nefc  # inside the limits: no limit row
    assert np.abs(data.efc_pos[:data.nefc]).max() < 1e-11  # the SRDF keeps 12 decimals


def test_project_ik_closes_the_exported_loops(mj, default_run):
    # (b) MuJoCo's own constraint residual (efc_pos of the connect rows) at the project's IK.
    ik = default_run.ik
    assert tuple(ik.joint_names) == JOINTS
    data = mujoco.MjData(mj)
    adr = [mj.joint(n).qposadr[0] for n in JOINTS]
    worst, limit_rows = 0.0, 0
    for q in ik.q:
        data.qpos[adr] = q
        mujoco.mj_forward(mj, data)
        kind = data.efc_type[:data.nefc]
        eq = kind == mujoco.mjtConstraint.mjCNSTR_EQUALITY
        limit_rows += int((~eq).sum())
        worst = max(worst, np.abs(data.efc_pos[:data.nefc][eq]).max())
    print(f"\nmax |efc_pos| of the connect rows over {len(ik.q)} samples: {worst:.3g} m")
    assert worst <= TOL_CLOSURE
    assert limit_rows == 0  # the trajectory stays inside the exported joint ranges


def test_closed_loop_inverse_dynamics_matches_the_project(exported, default_run):
    # (c) mj_inverse on the exported file, then [Sᵀ Jcᵀ][τ; λ] = τ_tree with efc_J.
    ik, dyn = default_run.ik, default_run.dynamics
    out = inverse_dynamics_mujoco(ik.q, ik.v, ik.a, mjcf_path=exported)
    assert out["residual"].max() <= TOL_CLOSURE
    peak = np.abs(dyn.tau).max(0)
    err = np.abs(out["tau"] - dyn.tau).max(0)
    print(f"\nτ error / largest peak: {np.array2string(err / peak.max(), precision=2)}")
    assert np.all(err <= TOL_TORQUE * peak.max())
    f_peak = np.linalg.norm(dyn.closure_forces, axis=2).max()
    f_err = np.abs(out["closure_forces"] - dyn.closure_forces).max()
    print(f"closure force error / peak: {f_err / f_peak:.3g}")
    assert f_err <= TOL_TORQUE * f_peak


def test_export_agrees_with_the_peer_built_from_the_urdf(exported):
    a, _, ia = build_mujoco()
    b, _, ib = build_mujoco(mjcf_path=exported)
    assert ib["mjcf_path"] == str(exported) and ib["merged_bodies"] == ia["merged_bodies"]
    assert ib["sites"] == ia["sites"] and ib["tip"] == ia["tip"]
    assert ib["mass_rel_error"] == 0.0 and ib["inertia_error"] < 1e-14
    assert not np.any(b.jnt_limited)  # the peer reads the file but keeps ideal joints
    for field in ("body_mass", "body_pos", "body_quat", "jnt_axis", "jnt_pos", "site_pos"):
        assert np.array_equal(getattr(a, field), getattr(b, field)), field


def test_export_from_urdf_text_with_home(robot, tmp_path):
    # What `pollard-pin export` does: the loaded robot's URDF text (any --params).
    path = export_mjcf(tmp_path / "text.xml", urdf=robot.urdf,
                       home=robot.as_dict(robot.home()))
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, 0)
    mujoco.mj_forward(model, data)
    assert np.abs(data.efc_pos[:data.nefc]).max() < 1e-14  # full-precision home
    assert export_mjcf(tmp_path / "bare.xml", urdf=robot.urdf).read_text().count("<key") == 0


def test_export_rejects_a_urdf_without_closures(tmp_path):
    text = URDF.read_text()
    start = text.index("  <loop_closure name=")
    end = text.index("</robot>")
    with pytest.raises(ValueError, match="expected 2 <loop_closure>"):
        export_mjcf(tmp_path / "x.xml", urdf=text[:start] + text[end:])
    assert not (tmp_path / "x.xml").exists()


def test_build_rejects_an_mjcf_without_the_closures(exported, tmp_path):
    bad = tmp_path / "open.xml"
    text = exported.read_text()
    start, end = text.index("  <equality>"), text.index("</equality>") + len("</equality>")
    bad.write_text(text[:start] + text[end:])
    with pytest.raises(ValueError, match="no connect equality 'closure1'"):
        build_mujoco(mjcf_path=bad)
