"""Joint loads (docs/model.md §17): the stacked RNEA against Pinocchio's own ``data.f``, against
free bodies with the closed-form kinematics (numpy only), against MuJoCo's ``cfrc_int``, and
exact identities: axis moment = joint torque, equal wrenches across a massless cross, and a
static case counted by hand."""

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.crosscheck import newton_euler
from pollard_pin.dynamics.loads import joint_loads, joint_loads_rnea
from pollard_pin.io.table import column_unit
from pollard_pin.paths import smooth_random_trajectory
from pollard_pin.run import RunResult

G = 9.81
# Relative to the peak force / moment over the trajectory; the three engines and
# the closed-form free body achieve 1.9e-15.
AGREE = 2e-13
EXACT = 1e-13  # identities that hold to round-off (achieve 1.1e-15)


@pytest.fixture(scope="module", params=["thesis", "random"])
def case(request, robot):
    traj = (pp.thesis_trajectory(samples=801) if request.param == "thesis"
            else smooth_random_trajectory(3, samples=301))
    ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    dyn = pp.inverse_dynamics(robot, ik)
    return traj, ik, dyn, joint_loads(robot, ik, dyn)


def _rel(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


def test_stacked_rnea_equals_pinocchio_data_f(robot, case):
    _, ik, dyn, loads = case
    ref = joint_loads_rnea(robot, ik, dyn)
    assert _rel(loads.force, ref.force) < EXACT
    assert _rel(loads.moment, ref.moment) < EXACT
    assert np.abs(loads.axis - ref.axis).max() < EXACT


def test_axis_moment_is_the_actuator_torque_and_zero_when_passive(robot, case):
    _, _, dyn, loads = case
    expected = np.zeros_like(loads.torque)
    for i, name in enumerate(robot.actuated):
        expected[:, robot.joint_names.index(name)] = dyn.tau[:, i]
    assert np.abs(loads.torque - expected).max() < EXACT * np.abs(dyn.tau).max()
    passive = [robot.joint_names.index(n) for n in robot.passive]
    assert np.abs(loads.torque[:, passive]).max() < EXACT * np.abs(loads.moment).max()


def test_massless_cross_joints_carry_the_same_wrench(robot, case):
    loads = case[3]
    for a, b in (("theta43", "theta54"), ("theta65_1", "theta76_1"), ("theta65_2", "theta76_2")):
        i, j = robot.joint_names.index(a), robot.joint_names.index(b)
        assert np.abs(loads.force[:, i] - loads.force[:, j]).max() < EXACT
        assert np.abs(loads.moment[:, i] - loads.moment[:, j]).max() < EXACT
        # the one wrench has no moment about either axis of the cross (both passive)
        for k in (i, j):
            assert np.abs(np.einsum("ni,ni->n", loads.moment[:, i], loads.axis[:, k])).max() \
                < EXACT * np.abs(loads.moment).max()


def test_free_bodies_with_closed_form_kinematics_agree(robot, case):
    traj, _, dyn, loads = case
    ne = newton_euler.joint_loads(robot.params, traj.poses, traj.d_poses, traj.dd_poses)
    assert ne["joints"] == robot.joint_names
    assert _rel(ne["force"], loads.force) < AGREE
    assert _rel(ne["moment"], loads.moment) < AGREE
    assert _rel(ne["closure_forces"], dyn.closure_forces) < AGREE  # solved, not given


def test_mujoco_cfrc_int_agrees(robot, case):
    pytest.importorskip("mujoco")
    from pollard_pin.crosscheck.mujoco_loads import joint_loads_mujoco

    _, ik, _, loads = case
    k = slice(None, None, 4)
    mj = joint_loads_mujoco(ik.q[k], ik.v[k], ik.a[k])  # MuJoCo's own closure forces
    assert tuple(mj["joints"]) == robot.joint_names
    assert _rel(mj["force"], loads.force[k]) < AGREE
    assert _rel(mj["moment"], loads.moment[k]) < AGREE
    assert np.abs(mj["axis"] - loads.axis[k]).max() < EXACT


def test_static_loads_are_subtree_weights_and_closure_forces(robot):
    """At rest at home: forces counted from the masses of docs/model.md §5 and λ."""
    p = robot.params
    pose = np.array([p.home_pose])
    ik = pp.inverse_kinematics(robot, pose, np.zeros((1, 6)), np.zeros((1, 6)), np.zeros(1))
    dyn = pp.inverse_dynamics(robot, ik)
    loads = joint_loads(robot, ik, dyn)
    F, M = loads.force[0], loads.moment[0]
    lam = dyn.closure_forces[0]
    m = {name: p.body(name).mass for name in newton_euler.BODIES}
    ez = np.array([0.0, 0.0, 1.0])
    idx = robot.joint_names.index

    def weight(*bodies):
        return G * sum(m[b] for b in bodies) * ez

    hand = {"theta1817": weight("gun"), "theta1716": weight("wrist2", "gun"),
            "theta1615": weight("wrist1", "wrist2", "gun"),
            "theta43": weight("platform", "wrist1", "wrist2", "gun") + lam[0] + lam[1],
            "theta21": weight("arm0", "platform", "wrist1", "wrist2", "gun") + lam[0] + lam[1],
            "theta76_1": weight("link_1") - lam[0], "theta21_1": weight("arm_1", "link_1") - lam[0],
            "theta76_2": weight("link_2") - lam[1], "theta21_2": weight("arm_2", "link_2") - lam[1]}
    for name, f in hand.items():
        assert np.abs(F[idx(name)] - f).max() < EXACT, name
    # The base carries the whole weight, 0.920 kg (closure forces are internal) …
    base = [idx(n) for n in ("theta21", "theta21_1", "theta21_2")]
    assert np.abs(F[base].sum(0) - G * p.total_mass * ez).max() < EXACT
    # … and its moment about the world origin is that of the weights at the CoGs.
    frames = pp.analytic.closed_form.forward_frames(p, ik.q[0])
    origin = {"theta21": "arm0", "theta21_1": "arm_1", "theta21_2": "arm_2"}
    moment = sum(M[idx(j)] + np.cross(frames[f][1], F[idx(j)]) for j, f in origin.items())
    cog = {b: frames[b][1] + frames[b][0] @ np.asarray(p.body(b).com) for b in m}
    expected = sum(np.cross(cog[b], G * m[b] * ez) for b in m)
    assert np.abs(moment - expected).max() < EXACT
    # The free-body static solution (numpy only) says the same.
    ne = newton_euler.static_loads(p, pose)
    assert np.abs(ne["force"][0] - F).max() < EXACT and np.abs(ne["moment"][0] - M).max() < EXACT


def test_columns_units_and_bearing_table(robot, case):
    traj, ik, dyn, loads = case
    cols = loads.columns()
    assert len(cols) == 72 and list(cols)[:3] == ["F_theta21_x", "F_theta21_y", "F_theta21_z"]
    assert column_unit("F_theta21_1_x") == "N" and column_unit("M_theta65_2_z") == "N·m"
    assert column_unit("f1_x") == "N" and column_unit("theta21_1") == "rad"
    run = RunResult(traj, ik, dyn, loads).columns()
    assert list(run)[-72:] == list(cols) and len(run) == 85 + 72
    tab = loads.bearing_table()
    j = robot.joint_names.index("theta21_1")
    row = tab["joints"]["theta21_1"]
    assert row["peak_radial"] == loads.radial[:, j].max()
    assert row["peak_axial"] == np.abs(loads.axial[:, j]).max()
    assert row["peak_radial"] >= row["equivalent_radial"] > 0
    assert tab["spherical"]["leg 1"]["peak_force"] == pytest.approx(
        np.linalg.norm(dyn.closure_forces[:, 0], axis=1).max(), rel=1e-15)
    # radial² + axial² = |F|², bending² + torque² = |M|²
    assert np.allclose(loads.radial ** 2 + loads.axial ** 2,
                       (loads.force ** 2).sum(-1), rtol=1e-12, atol=1e-24)
    assert np.allclose(loads.bending ** 2 + loads.torque ** 2,
                       (loads.moment ** 2).sum(-1), rtol=1e-12, atol=1e-24)


def test_sweep_row_has_the_peak_bearing_loads(robot):
    from pollard_pin.names import TREE_JOINTS
    from pollard_pin.sweep import LOAD_METRICS, evaluate_variant

    assert TREE_JOINTS == robot.joint_names
    spec = {"name": "base", "trajectory": {"kind": "thesis", "duration": 20.0, "samples": 201}}
    row = evaluate_variant(spec)
    traj = pp.thesis_trajectory(duration=20.0, samples=201, home_pose=robot.params.home_pose)
    ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    tab = joint_loads(robot, ik, pp.inverse_dynamics(robot, ik)).bearing_table()["joints"]
    for m in LOAD_METRICS:
        for j in TREE_JOINTS:
            assert row[f"{m}_{j}"] == pytest.approx(tab[j][m], rel=1e-12, abs=1e-15)


def test_streamed_run_writes_the_same_loads(robot, tmp_path):
    from pollard_pin.io.table import read_result
    from pollard_pin.run import StreamOptions, run_pipeline, stream_run

    traj = pp.thesis_trajectory(samples=301)
    whole = run_pipeline(robot, traj, loads=True).columns()
    path = tmp_path / "s.parquet"
    stream_run(robot, traj, path, StreamOptions(chunk=64), loads=True)
    table = read_result(path)
    for name in whole:
        if name.startswith(("F_", "M_")):
            # windows are solved apart: equal to round-off (as every streamed column)
            scale = max(1.0, np.abs(whole[name]).max())  # 1 N, 1 N·m: components near 0
            assert np.abs(table[name] - whole[name]).max() <= 1e-12 * scale, name  # 3e-15
    assert table.units["M_theta21_y"] == "N·m"


def test_leg_cross_moment_is_the_link_torsion(robot, case):
    """A leg link has its CoG and ball centre on its axis ℓ: the cross's moment, along
    n = u65 × u76, is ℓ·(I α + ω × I ω)_link / cos θ76 (docs/model.md §17)."""
    from pollard_pin.analytic.closed_form import body_kinematics

    traj, ik, _, loads = case
    kin = body_kinematics(robot.params, traj.poses, traj.d_poses, traj.dd_poses)
    for leg in (1, 2):
        k, body = kin[f"link_{leg}"], robot.params.body(f"link_{leg}")
        R = k["R"]
        Iw = R @ body.inertia_matrix @ np.swapaxes(R, -1, -2)
        h = np.einsum("nij,nj->ni", Iw, k["alpha"]) + np.cross(
            k["omega"], np.einsum("nij,nj->ni", Iw, k["omega"]))
        i, j = (robot.joint_names.index(f"theta{a}_{leg}") for a in (65, 76))
        n = np.cross(loads.axis[:, i], loads.axis[:, j])
        expected = (np.einsum("ni,ni->n", R[:, :, 0], h) / np.cos(ik.q[:, j]))[:, None] * n
        # The torsion is small (7e-6 N·m): round-off of the whole moment (achieves 4.4e-16).
        assert np.abs(loads.moment[:, j] - expected).max() < 1e-13 * np.abs(loads.moment).max()


def test_report_has_the_bearing_table_and_the_three_way_agreement(robot):
    from pollard_pin.viz.report import sizing_report, to_markdown

    result = pp.run_pipeline(robot, pp.thesis_trajectory(samples=201))
    rep = sizing_report(robot, result)
    loads = joint_loads(robot, result.ik, result.dynamics)
    assert rep["bearings"] == loads.bearing_table()
    assert rep["units"]["peak_bending"] == "N·m" and rep["units"]["equivalent_radial"] == "N"
    checks = [rep["cross_check"]["thesis"]]
    if rep["cross_check"]["mujoco"]["available"]:
        checks.append(rep["cross_check"]["mujoco"])
    for check in checks:
        assert check["joint_force"]["relative"] < AGREE
        assert check["joint_moment"]["relative"] < AGREE
    md = to_markdown(rep)
    assert "## Bearings and pins" in md and "| theta65_1 |" in md


def test_joint_loads_refuse_what_is_not_their_arguments(robot):
    """None for the robot, a string for the dynamics, an IK result of other samples: one
    InputError line, not an AttributeError or a bare ValueError."""
    ik = pp.inverse_kinematics(robot, [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]] * 2, t=[0.0, 1.0])
    dyn = pp.inverse_dynamics(robot, ik)
    one = pp.inverse_kinematics(robot, [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]])
    for args, says in (((None, ik, dyn), "^robot = None: expected a Robot"),
                       ((robot, "x", dyn), "^ik = 'x': expected an IKResult"),
                       ((robot, ik, "x"), "^dyn = 'x': expected a DynamicsResult"),
                       ((robot, one, dyn), r"^closure forces of shape \(2, 2, 3\) do not")):
        with pytest.raises(pp.InputError, match=says):
            joint_loads(*args)
    with pytest.raises(pp.InputError, match=r"^closure forces of shape \(2, 2, 3\) do not"):
        joint_loads_rnea(robot, one, dyn)  # the rule the two share
