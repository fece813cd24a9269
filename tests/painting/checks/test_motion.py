"""The planner's motion check (painting/checks/motion.py): motor utilisation at rest, the duration
bisection against a closed form, the joint-limit rule."""
import numpy as np
import pytest


def test_breakaway_counted_at_rest(robot, plan, act):
    """At the rest-to-rest ends every motor must overcome Coulomb friction in either
    direction: utilisation (|τ/N + Jm·N·q̈| + c)/peak there, not sign(0) = 0 (exact)."""
    from pollard_pin.painting.checks.motion import motion

    tr = plan.trajectory
    ends = [0, len(tr) - 1]
    m = motion(robot, act, tr.poses[ends], tr.d_poses[ends], tr.dd_poses[ends])
    ia = robot.actuated_v
    assert np.all(m.ik.v[:, ia] == 0)
    n, jm, c = (act.column(k) for k in ("gear_ratio", "rotor_inertia", "coulomb"))
    rest = m.tau / n + jm * n * m.ik.a[:, ia]
    expected = (np.abs(rest) + c) / act.column("peak_torque")
    assert m.torque_ratio == pytest.approx(expected, rel=1e-14)


def test_fastest_finds_the_smallest_feasible_durations():
    """Utilisation (c/τ)² per piece falls as τ grows: the smallest τ within ``target`` is
    c/√target. The bisection returns a feasible τ within its bracket (guess·2^k / 2^16) of it,
    each piece on its own."""
    from pollard_pin.painting.checks.motion import fastest

    c, target = np.array([0.05, 0.3, 1.7]), 0.97
    tau = fastest(lambda t: (c / t) ** 2, np.full(3, 0.1), target)
    exact = c / np.sqrt(target)
    assert np.all((c / tau) ** 2 <= target)
    assert np.all(tau >= exact) and np.all(tau - exact <= 0.1 * 2 ** 5 / 2 ** 16)
    assert tau[0] - exact[0] <= 0.1 / 2 ** 16  # feasible from the start: no doubling


def test_fastest_refuses_a_piece_no_duration_fixes():
    from pollard_pin.painting.checks.motion import fastest
    from pollard_pin.painting.errors import PlanError

    with pytest.raises(PlanError, match="the pass speed itself is too much"):
        fastest(lambda t: np.array([0.5, 1.2]) + 0 * t, np.ones(2), 0.97)


def test_fastest_halves_a_first_guess_out_of_reach():
    """A piece that runs on v·τ/2 (a ramp) leaves the workspace past τ = 0.3 s, and the motors
    need τ ≥ c/√target: a first guess of 1 s out of reach is halved (to 0.25 s) and the
    search finds the motors' shortest; without halvings, or when the motors need a piece
    longer than the reach allows, the reach error is the refusal."""
    from pollard_pin.painting.checks.motion import fastest
    from pollard_pin.painting.errors import ReachError

    def evaluate(c):
        def ev(t):
            if np.any(t > 0.3):
                raise ReachError("the ramp leaves the workspace", 0)
            return (c / t) ** 2
        return ev

    c, target = np.array([0.05, 0.2]), 0.97
    tau = fastest(evaluate(c), np.ones(2), target, halvings=4)
    exact = c / np.sqrt(target)
    assert np.all(tau >= exact) and np.all(tau - exact <= 0.25 / 2 ** 16)
    with pytest.raises(ReachError):
        fastest(evaluate(c), np.ones(2), target)
    with pytest.raises(ReachError):  # the motors need 0.41 s, the reach allows 0.3
        fastest(evaluate(np.array([0.4])), np.ones(1), target, halvings=4)


def test_reach_names_the_first_joint_beyond_its_limits(robot, plan, act, monkeypatch):
    """A joint pushed past its upper limit is named with its first sample, its angle and how
    far off (kinematics.limits, the one rule); an angle 2π off a legal one is legal."""
    import pollard_pin.painting.checks.motion as motion_module
    from pollard_pin.kinematics.limits import check_joint_limits
    from pollard_pin.painting.checks.motion import motion, reach
    from pollard_pin.painting.errors import ReachError

    tr = plan.trajectory
    pick = np.linspace(0, len(tr) - 1, 8).astype(int)
    ik = motion(robot, act, tr.poses[pick], tr.d_poses[pick], tr.dd_poses[pick]).ik
    check_joint_limits(robot, ik.q)
    check_joint_limits(robot, ik.q + 2 * np.pi)
    j = 0
    lim = robot.params.joint_limits(robot.joint_names[j])
    bad = ik.q.copy()
    bad[3:, j] = lim.upper + 0.01

    def pushed(robot_, q, t=None):  # the IK's angles, one joint pushed 0.01 rad too far
        return check_joint_limits(robot_, bad, t)

    monkeypatch.setattr(motion_module, "check_joint_limits", pushed)
    with pytest.raises(ReachError, match=rf"joint {robot.joint_names[j]} at .* by 0\.573°") as e:
        reach(robot, tr.poses[pick], tr.d_poses[pick], tr.dd_poses[pick])
    assert e.value.sample == 3


def test_a_wait_is_solved_once_with_the_same_result(robot):
    # a path that waits 40 samples at its first pose: reach solves the wait once, and its
    # IKResult, or the sample a failure names, equal the IK of every sample (brute force)
    from dataclasses import fields

    import pollard_pin as pp
    from pollard_pin.kinematics import KinematicsError
    from pollard_pin.kinematics.ik import inverse_kinematics
    from pollard_pin.painting.checks.motion import LEADING_RUN, motion, reach
    from pollard_pin.painting.errors import ReachError

    tr = pp.thesis_trajectory(samples=101)
    wait = 40
    assert wait >= LEADING_RUN
    P = np.concatenate([np.repeat(tr.poses[:1], wait, axis=0), tr.poses])
    D = np.concatenate([np.zeros((wait, 6)), tr.d_poses])
    A = np.concatenate([np.zeros((wait, 6)), tr.dd_poses])
    D[wait], A[wait] = 0.0, 0.0  # the path starts at rest
    ref = inverse_kinematics(robot, P, D, A, np.arange(len(P), dtype=float))
    got = reach(robot, P, D, A)
    for f in fields(ref):
        a, b = getattr(ref, f.name), getattr(got, f.name)
        assert (a is None and b is None) or np.array_equal(a, b), f.name
    # and motion's dynamics, the wait's solved once too, equal every sample's
    from pollard_pin.dynamics.inverse import inverse_dynamics
    from pollard_pin.dynamics.motors import load_actuators

    act = load_actuators()
    tau = inverse_dynamics(robot, ref, energies=False).tau
    mo = motion(robot, act, P, D, A)
    assert np.array_equal(mo.tau, tau) and np.array_equal(mo.ik.q, ref.q)
    assert mo.torque_ratio.max() > 0.01

    def named(P):  # the sample the brute force names
        try:
            inverse_kinematics(robot, P, D, A, np.arange(len(P), dtype=float))
        except KinematicsError as exc:
            return exc.sample

    for bad in ([0, wait], [wait + 30], [wait + 60, wait + 70]):  # the wait, later ones
        Q = P.copy()
        Q[bad[0]:bad[-1] + 1, 0] += 1.0  # out of reach
        with pytest.raises(ReachError) as e:
            reach(robot, Q, D, A)
        assert e.value.sample == named(Q) == bad[0]


def test_reach_at_rest_is_the_ik_with_zero_rates(robot):
    """reach without rates solves the poses at rest (no drifts): its positions and every
    figure but the rates are those of the IK given zero rates, to the bit, the rates zero;
    a path that fails (a sample out of reach, one past a joint limit, one under a tighter
    singularity margin) fails at the same sample with the same words."""
    import pollard_pin as pp
    from pollard_pin.kinematics.ik import inverse_kinematics
    from pollard_pin.painting.checks.motion import reach
    from pollard_pin.painting.errors import ReachError

    poses = pp.thesis_trajectory(samples=120).poses
    zero = np.zeros_like(poses)
    got, want = reach(robot, poses), inverse_kinematics(robot, poses, zero, zero)
    for f in ("q", "spherical", "sigma_parallel", "sigma_serial", "closure_residual",
              "wrist_margin", "constraint_jacobian"):
        assert getattr(got, f).tobytes() == getattr(want, f).tobytes(), f
    assert not np.abs(got.v).any() and not np.abs(got.a).any()
    far, bent = poses.copy(), poses.copy()
    far[70, 0] += 1.0
    bent[40:60, 2] -= np.linspace(0.0, 0.3, 20)
    tight = pp.Margins(singularity=0.14)  # a σ under it along the path: the margins' check
    for bad, margins in ((far, None), (bent, None), (poses, tight)):
        with pytest.raises(ReachError) as rest:
            reach(robot, bad, margins=margins)
        with pytest.raises(ReachError) as moving:
            reach(robot, bad, zero, zero, margins=margins)
        assert str(rest.value) == str(moving.value) and rest.value.sample == moving.value.sample
