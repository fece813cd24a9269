"""Closed-loop dynamics: Pinocchio vs the thesis' Euler–Lagrange method, energy
balance, forward-dynamics round trip and replay, statics by virtual work."""
import os

import numpy as np
import pinocchio as pin
import pytest

import pollard_pin as pp
from pollard_pin.crosscheck import euler_lagrange as lagrange
from pollard_pin.dynamics.forward import forward_dynamics, replay_open_loop, trajectory_torques
from pollard_pin.dynamics.inverse import JointLosses, inverse_dynamics, inverse_dynamics_sample
from pollard_pin.kinematics import solve_closure, tool_pose
from pollard_pin.paths.curves import smooth_random_trajectory, thesis_curve, thesis_trajectory


@pytest.fixture(scope="module")
def robot():
    return pp.load()


def _solve(robot, traj):
    ik = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    return ik, inverse_dynamics(robot, ik)


@pytest.fixture(scope="module")
def thesis_run(robot):
    traj = thesis_trajectory(samples=1001)
    return (traj, *_solve(robot, traj))


@pytest.mark.parametrize("seed", [None, 1, 2])
def test_torques_match_thesis_euler_lagrange(robot, thesis_run, seed):
    if seed is None:
        traj, _, dyn = thesis_run
    else:
        traj = smooth_random_trajectory(seed, samples=201)
        dyn = _solve(robot, traj)[1]
    ref = lagrange.inverse_dynamics(robot.params, traj.poses, traj.d_poses, traj.dd_poses)["tau"]
    peak = np.abs(ref).max()
    assert peak > 0.1  # a real load, not a trivial zero
    assert np.abs(dyn.tau - ref).max() <= 1e-12 * peak  # achieves 5e-15 × peak


def test_power_balance_converges(robot):
    """Σ τ·q̇ = d(K + U)/dt; the central-difference error shrinks as dt² (independent of IK)."""
    errs = []
    for n in (401, 801, 1601):
        traj = smooth_random_trajectory(3, samples=n)
        dyn = _solve(robot, traj)[1]
        dE = (dyn.energy[2:] - dyn.energy[:-2]) / (dyn.t[2:] - dyn.t[:-2])
        P = dyn.power.sum(axis=1)[1:-1]
        errs.append(np.abs(P - dE).max() / np.abs(P).max())
    assert errs[-1] < 1e-4
    # Second order: halving dt divides the error by 4 (achieves 3.9998 and 3.99993).
    assert abs(errs[0] / errs[1] - 4.0) < 0.02 and abs(errs[1] / errs[2] - 4.0) < 0.02



def test_work_is_integral_of_power(robot, thesis_run):
    _, _, dyn = thesis_run
    # Total actuator work over the run equals the change of mechanical energy (no losses).
    dE = dyn.energy[-1] - dyn.energy[0]
    # Achieves 5.3e-8 of the peak power × duration.
    assert abs(dyn.work[-1].sum() - dE) < 1e-5 * np.abs(dyn.power).sum(1).max() * dyn.t[-1]


def test_forward_dynamics_round_trip(robot, thesis_run):
    _, ik, dyn = thesis_run
    pin.initConstraintDynamics(robot.model, robot.data, robot.constraint_models,
                               robot.constraint_datas)
    for k in (0, 333, 777):
        a = forward_dynamics(robot, ik.q[k], ik.v[k], dyn.tau[k])
        assert np.abs(a - ik.a[k]).max() <= 2e-10  # achieves 1.5e-12
        # Pinocchio's own constraint forces equal our closure forces.
        # Achieves 8.9e-16 N.
        assert np.allclose(robot.data.lambda_c, dyn.closure_forces[k].ravel(), rtol=0, atol=1e-13)


def test_replay_reproduces_trajectory(robot):
    """Open-loop replay of the inverse-dynamics torques (RK4, 1 ms) stays on the curve."""
    home = robot.params.home_pose

    def curve(t):
        return thesis_curve(t, 20.0, home)

    ik0 = pp.inverse_kinematics(robot, *curve(np.array([0.0])), np.array([0.0]))
    sim = replay_open_loop(robot, trajectory_torques(robot, curve, ik0.q[0]), ik0.q[0], ik0.v[0],
                   duration=0.5, dt=1e-3)
    ref = curve(sim.t)[0]
    drift = max(np.linalg.norm(tool_pose(robot, q).translation - ref[k, :3])
                for k, q in enumerate(sim.q))
    assert drift <= 5e-9  # achieves 2.7e-11 m
    assert sim.closure_residual.max() <= 1e-9


def test_static_torques_are_virtual_work_gradient(robot):
    """At rest, τ = ∂U/∂θ_act along the closed-loop manifold (finite differences of U)."""
    q0 = robot.home()
    act = q0[robot.actuated_v]
    tau, _, _ = inverse_dynamics_sample(robot, q0, np.zeros(12), np.zeros(12))
    h = 1e-6
    grad = np.empty(6)
    for j in range(6):
        U = []
        for s in (1, -1):
            a = act.copy()
            a[j] += s * h
            q = solve_closure(robot, a, q_guess=q0)
            U.append(pin.computePotentialEnergy(robot.model, robot.data, q))
        grad[j] = (U[0] - U[1]) / (2 * h)
    assert np.abs(tau - grad).max() <= 5e-8 * np.abs(grad).max()  # achieves 2e-10 × peak
    assert np.abs(grad).max() > 0.1


def test_actuated_viscous_friction_adds_exactly(robot, thesis_run):
    """Friction on the actuated joints only adds c·q̇ to their torques; closure forces stay."""
    _, ik, dyn = thesis_run
    c = np.zeros(12)
    c[robot.actuated_v] = 0.05
    lossy = inverse_dynamics(robot, ik, JointLosses(viscous=c))
    # Achieves 3.3e-16 N·m.
    assert np.allclose(lossy.tau - dyn.tau, 0.05 * dyn.actuator_velocity, rtol=0, atol=5e-14)

    assert np.allclose(lossy.closure_forces, dyn.closure_forces, rtol=0, atol=1e-13)  # achieves 0


def test_closure_forces_balance_link(robot, thesis_run):
    """Newton–Euler on link_i alone, independent of the 12 × 12 solve: the U joint transmits
    no moment about its two axes, so about those axes the closure force's moment must equal
    the moment link_i needs (inertial wrench minus gravity)."""
    _, ik, dyn = thesis_run
    model, data = robot.model, robot.data
    for k in (100, 600):
        pin.forwardKinematics(model, data, ik.q[k])  # rnea does not update data.oMi
        pin.rnea(model, data, ik.q[k], ik.v[k], ik.a[k])  # fills data.v and data.a_gf
        for i in (1, 2):
            j = robot.joint_id(f"theta76_{i}")
            Y, v = model.inertias[j], data.v[j]
            needed = (Y * data.a_gf[j] + v.cross(Y * v)).angular  # about the joint, link axes
            lam = data.oMi[j].rotation.T @ dyn.closure_forces[k, i - 1]
            p = model.frames[robot.frame_id(f"closure{i}_A")].placement.translation
            moment = np.cross(p, lam)
            th76 = ik.q[k, robot.idx_q(f"theta76_{i}")]
            axes = (np.array([0.0, 0.0, 1.0]),  # theta76 axis
                    np.array([np.sin(th76), np.cos(th76), 0.0]))  # theta65 axis, link axes
            for ax in axes:
                assert abs(needed @ ax - moment @ ax) < 1e-13  # achieves 2.9e-16
            assert np.abs(needed).max() > 1e-3


def test_three_actuator_formula_is_ill_posed(robot, thesis_run):
    traj, _, _ = thesis_run
    out = lagrange.three_actuator_analysis(robot.params, traj.poses[::50], traj.d_poses[::50],
                                           traj.dd_poses[::50])
    # With only the base actuators the wrist part of Q cannot be produced.
    assert np.max(out["rel_residual"]) > 1e-3


def test_three_way_agreement_with_modified_parameters(tmp_path):
    """Twisted U joints (β54 ≠ 0), another attachment angle, longer arm, off-axis CoG: the
    batched and per-sample IK, the thesis' Euler–Lagrange torques and MuJoCo still agree."""
    from pollard_pin.kinematics.ik import inverse_kinematics_batch, inverse_kinematics_newton
    from pollard_pin.model.build import generate

    params = pp.load_params(overrides={
        "leg1.beta54": 10.0, "leg2.beta54": -5.0, "leg1.beta1413": 260.0, "chain0.x32": 0.34,
        "bodies.platform.com": [0.2, 0.01, -0.005], "bodies.gun.mass": 0.05})
    robot = pp.load(params)
    traj = smooth_random_trajectory(3, samples=201, home_pose=params.home_pose)
    args = (traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    ik, ref = inverse_kinematics_batch(robot, *args), inverse_kinematics_newton(robot, *args)
    assert np.abs(ik.q - ref.q).max() <= 1e-12 and np.abs(ik.a - ref.a).max() <= 1e-11
    dyn = inverse_dynamics(robot, ik)
    peak = np.abs(dyn.tau).max()
    thesis = lagrange.inverse_dynamics(params, traj.poses, traj.d_poses, traj.dd_poses)["tau"]
    assert np.abs(dyn.tau - thesis).max() <= 1e-12 * peak  # achieves 3.2e-15 × peak
    pytest.importorskip("mujoco")  # the optional peer engine
    from pollard_pin.crosscheck import mujoco as peer
    urdf = tmp_path / "modified.urdf"
    urdf_text, srdf_text = generate(params)
    urdf.write_text(urdf_text)
    urdf.with_suffix(".srdf").write_text(srdf_text)
    mj = peer.inverse_dynamics_mujoco(ik.q, ik.v, ik.a, urdf_path=urdf)
    # MuJoCo achieves 1.4e-15 of the peak torque and of the peak closure force.
    assert np.abs(mj["tau"] - dyn.tau).max() <= 2e-13 * peak
    assert np.abs(mj["closure_forces"] - dyn.closure_forces).max() <= \
        2e-13 * np.abs(dyn.closure_forces).max()



@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")
def test_batched_rnea_in_a_child_forked_after_the_parent_ran_it(robot):
    """A forked child (the sweep's process pool) gets the parent's torques bit for bit, and
    does not hang in libgomp: the old code's child waited forever once the parent had run
    the OpenMP team."""
    import time

    from pollard_pin.dynamics.inverse import RNEA_TEAM_SAMPLES, batched_rnea

    rng = np.random.default_rng(7)
    Q, V, A = (rng.normal(size=(RNEA_TEAM_SAMPLES, robot.model.nv)) for _ in range(3))
    ref = batched_rnea(robot.model, Q, V, A)  # the parent starts its OpenMP team
    pid = os.fork()
    if pid == 0:  # child: exit status 0 only when the torques are identical
        os._exit(0 if np.array_equal(batched_rnea(robot.model, Q, V, A), ref) else 1)
    deadline = time.monotonic() + 60.0
    while time.monotonic() < deadline:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        time.sleep(0.05)
    else:
        os.kill(pid, 9)
        os.waitpid(pid, 0)
        pytest.fail("the forked child hung in the batched RNEA (OpenMP after fork)")
    assert os.waitstatus_to_exitcode(status) == 0


def test_reduced_inverse_dynamics_is_m_red_u_plus_h_red(robot):
    """One RNEA at a = N·u + a₀, projected by Nᵀ, is M_red·u + h_red (seen 7e-16 N·m), and
    it is the closed-loop inverse dynamics (§13: the actuated torques of the [Sᵀ Jcᵀ] split of
    the tree torques at that a, seen 1e-15), losses and model armature included."""
    from pollard_pin.dynamics.inverse import reduced_dynamics, reduced_inverse_dynamics
    from pollard_pin.kinematics.ik import inverse_kinematics

    traj = thesis_trajectory(samples=21)
    ik = inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    rng = np.random.default_rng(5)
    losses = JointLosses(viscous=0.3, coulomb=0.1, armature=0.02)
    for k in (0, 7, 13):
        q, v, u = ik.q[k], ik.v[k], rng.normal(size=6)
        for known in (None, losses):
            M, h = reduced_dynamics(robot, q, v, known)
            tau = reduced_inverse_dynamics(robot, q, v, u, known)
            np.testing.assert_allclose(tau, M @ u + h, rtol=0, atol=1e-13)
    # at the IK's own state and acceleration: the §13 inverse dynamics
    ia = robot.actuated_v
    for k in (3, 11):
        tau = reduced_inverse_dynamics(robot, ik.q[k], ik.v[k], ik.a[k, ia])
        want = inverse_dynamics_sample(robot, ik.q[k], ik.v[k], ik.a[k])[0]
        np.testing.assert_allclose(tau, want, rtol=0, atol=1e-12)


def test_inverse_dynamics_refuses_what_is_not_its_arguments(robot):
    """None for the robot, a string for the IK result, a dict for the losses: one InputError
    line naming the argument, not an AttributeError from inside."""
    ik = pp.inverse_kinematics(robot, [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]])
    for args, says in (((None, ik), "^robot = None: expected a Robot"),
                       ((robot, "x"), "^ik = 'x': expected an IKResult"),
                       ((robot, ik, {}), "^losses = {}: expected a JointLosses")):
        with pytest.raises(pp.InputError, match=says):
            inverse_dynamics(*args)
