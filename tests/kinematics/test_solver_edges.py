"""Edge cases of the kinematics solvers, each checked against independent numbers.

1. Singular linear systems (a pose exactly on a leg's reach boundary, singular stacks,
   spherical-joint gimbal, the closure-force split, loop closure) raise SingularityError with
   sample, time, chain and σ — never numpy's LinAlgError.
2. Margins of 0 still reject exactly or numerically singular samples (the numerical floors of
   docs/model.md §12); invalid margins are rejected up front.
3. One round-off tolerance at every arccos/arcsin boundary of the closed form (docs/model.md §7):
   poses within round-off of the reach limit are on it; messages never say "short by 0 mm".
4. Non-finite or absurd inputs, empty arrays and bad time steps are named.
5. Any sampling density gives the dense solution; a real crossing of an assembly-mode boundary
   is a BranchFlipError.
"""
import dataclasses
import math
import re

import numpy as np
import pinocchio as pin
import pytest
from poses import path_to_wrist_singularity, wrist_singular_pose  # tests/poses.py

import pollard_pin as pp
from pollard_pin.analytic import closed_form as T
from pollard_pin.analytic import jet as J
from pollard_pin.analytic import taskspace as ts
from pollard_pin.crosscheck import euler_lagrange as lagrange
from pollard_pin.dynamics.inverse import inverse_dynamics, split_tree_torques
from pollard_pin.errors import InputError
from pollard_pin.kinematics import closure
from pollard_pin.kinematics.errors import (
    BranchFlipError,
    ClosureError,
    ClosureSingularError,
    KinematicsError,
    KinematicsInputError,
    SingularityError,
    UnreachablePoseError,
)
from pollard_pin.kinematics.ik_common import zyz, zyz_rates
from pollard_pin.kinematics.ik_newton import MIN_SUBSTEP
from pollard_pin.kinematics.margins import MarginError, Margins
from pollard_pin.kinematics.singularity import (
    BRANCH_SIGNS,
    SERIAL_FLOOR,
    SIGMA_FLOOR,
    actuator_velocity_map,
    branch_quantities,
    check_margins,
    solve_stack,
)
from pollard_pin.model import constraint_jacobian
from pollard_pin.paths.curves import thesis_trajectory
from pollard_pin.paths.trajectory import Trajectory

# A pose exactly on leg 2's reach boundary (θ76_2 = 0), a reported case.
EDGE = np.array([0.5479217373830817, -0.14140430553739233, 0.2619590809778902,
                 0.1515515281768794, 0.34846838034929445, 0.04014162356854648])
METHODS = ("batch", "newton")
# The suite's closed-form agreement tolerances (tests/kinematics/test_ik.py; here the solvers
# achieve 3.6e-15 rad, 6.6e-15 rad/s, 2.2e-13 rad/s²).
POS_TOL, VEL_TOL, ACC_TOL = 5e-13, 5e-12, 5e-11
EPS = np.finfo(float).eps
ZERO_MARGINS = Margins(wrist=0.0, singularity=0.0)  # the numerical floors alone


def ik(robot, poses, d=None, dd=None, t=None, method="batch", **kw):
    options = {k: kw.pop(k) for k in ("margins", "tol", "max_iter", "chunk") if k in kw}
    return pp.inverse_kinematics(robot, poses, d, dd, t,
                                 options=pp.IkOptions(method=method, **options), **kw)


def wrap(a):
    return np.pi - np.mod(np.pi - np.asarray(a), 2.0 * np.pi)


def platform(p, pose):
    """Independent of the package's closed form: platform rotation and elbow E of chain 0 from
    plain circle geometry (its own arccos on the configured branch)."""
    x, y, z, psi, th, phi = pose
    R = J.Rx(th) @ J.Ry(psi) @ J.Rz(phi)
    L = p.x65 + p.x1514
    P15 = np.array([x, y, z]) - p.x1918 * R[:, 0]
    d = P15 - np.array([0.0, 0.0, p.z10])
    # Elbow E(t) = (x32 cos t, 0, z10 − x32 sin t) at distance L from P15.
    A, B = -2 * p.x32 * d[0], 2 * p.x32 * d[2]
    C = d @ d + p.x32 ** 2 - L ** 2
    t21 = math.atan2(B, A) + p.branches[0] * math.acos(-C / math.hypot(A, B))
    E = np.array([p.x32 * math.cos(t21), 0.0, p.z10 - p.x32 * math.sin(t21)])
    u = (P15 - E) / L
    return J.Ry(math.atan2(-u[2], u[0])) @ J.Rz(math.asin(u[1])), E


def leg_geometry(p, pose, i):
    """(−C/R, in-plane distance ρ, height) of leg i's attachment point relative to its elbow
    circle, from plain circle geometry (independent of the package's closed form)."""
    Rp, E = platform(p, pose)
    leg = p.legs[i]
    w = E + Rp @ p.attachment(i) - np.array([0.0, leg.side * leg.y10, -leg.z32])
    rho = math.hypot(w[0], w[1])
    ratio = -(w @ w + leg.x43 ** 2 - leg.x87 ** 2) / (2 * leg.x43 * rho)
    return ratio, rho, w[2]


# --- 1. singular linear systems --------------------------------------------------------------

def test_edge_pose_is_exactly_on_leg_2_reach_boundary(robot):
    ratio, _, _ = leg_geometry(robot.params, EDGE, 1)
    assert abs(abs(ratio) - 1.0) <= 1e-14
    q = T.position_ik(robot.params, EDGE)
    assert q[0, T.JOINTS.index("theta76_2")] == 0.0  # on the boundary: the branch term is 0


def test_closed_form_rates_on_the_boundary_are_a_named_singularity(robot):
    # The angles exist on the boundary, their rates do not (arccos' at ±1): say so.
    for call in (lambda: T.inverse_kinematics(robot.params, EDGE, np.full(6, 0.01),
                                              np.zeros(6)),
                 lambda: T.actuation_jacobian(robot.params, EDGE)):
        with pytest.raises(T.SingularPoseError) as ei:
            call()
        e = ei.value
        assert (e.kind, e.chain, e.sample, e.joint) == ("singular", "leg 2", 0, "theta21_2")
        assert "not finite" in str(e) and isinstance(e, T.UnreachableError)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("margins", [None, ZERO_MARGINS])
def test_pose_on_reach_boundary_raises_singularity_error(robot, method, margins):
    # Used to raise numpy's LinAlgError ("Singular matrix") from the stacked solve and Newton.
    with pytest.raises(SingularityError) as ei:
        ik(robot, EDGE[None], method=method, margins=margins)
    e = ei.value
    assert (e.sample, e.time, e.chain) == (0, 0.0, "serial")
    assert e.sigma < SERIAL_FLOOR and "serial" in str(e) and "sample 0" in str(e)


@pytest.mark.parametrize("method", METHODS)
def test_singular_sample_inside_a_trajectory_is_named(robot, method):
    home = np.asarray(robot.params.home_pose, dtype=float)
    s = np.array([0.0, 0.25, 0.5, np.nan, 0.5, 0.25])
    poses = home + np.outer(s, EDGE - home)
    poses[3] = EDGE
    t = 0.5 * np.arange(6)
    with pytest.raises(SingularityError) as ei:
        ik(robot, poses, t=t, method=method, margins=ZERO_MARGINS)
    e = ei.value
    assert (e.sample, e.time, e.chain) == (3, 1.5, "serial")
    assert "sample 3 (t = 1.5 s)" in str(e) and "round-off" in str(e)
    # Without the boundary sample, the same samples solve (the stack is not poisoned).
    keep = [0, 1, 2, 4, 5]
    r = ik(robot, poses[keep], t=t[keep], method=method, margins=Margins(singularity=0.0))
    assert np.isfinite(r.v).all() and np.isfinite(r.a).all()


def test_solve_stack_isolates_singular_members():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(5, 4, 4))
    A[2, :, 3] = A[2, :, 0]  # two equal columns: exactly singular
    B = rng.normal(size=(5, 4, 2))
    with pytest.raises(np.linalg.LinAlgError):
        np.linalg.solve(A, B)
    X, bad = solve_stack(A, B)
    assert bad.tolist() == [False, False, True, False, False]
    assert np.isnan(X[2]).all()
    for k in (0, 1, 3, 4):
        assert np.abs(X[k] - np.linalg.solve(A[k], B[k])).max() <= 1e-14  # achieves 0


def test_actuator_velocity_map_names_the_singular_sample(robot):
    Jc = np.stack([constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                                          robot.constraint_datas, robot.q_reference)] * 4)
    p = robot.passive_v
    Jc[2][:, p[1]] = Jc[2][:, p[0]]  # two passive columns equal: Jc_p singular
    with pytest.raises(SingularityError) as ei:
        actuator_velocity_map(Jc, robot.actuated_v, p, t=[0.0, 0.1, 0.2, 0.3])
    e = ei.value
    assert (e.sample, e.time, e.chain) == (2, 0.2, "parallel")
    assert e.sigma == pytest.approx(np.linalg.svd(Jc[2][:, p], compute_uv=False)[-1], abs=1e-15)
    # Regular samples: N maps actuator rates onto closed-loop velocities (Jc N = 0).
    N = actuator_velocity_map(Jc[0], robot.actuated_v, p)
    assert np.abs(Jc[0] @ N).max() <= 1e-14  # achieves 4.3e-17


def test_split_tree_torques_names_the_singular_sample(robot):
    Jc0 = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                                 robot.constraint_datas, robot.q_reference)
    Jc = np.stack([Jc0] * 3)
    p = robot.passive_v
    Jc[1][:, p[4]] = 0.0  # a passive joint the closures do not see
    tree = np.ones((3, robot.model.nv))
    with pytest.raises(SingularityError) as ei:
        split_tree_torques(robot, Jc, tree, t=np.array([0.0, 0.5, 1.0]))
    e = ei.value
    assert (e.sample, e.time, e.chain) == (1, 0.5, "parallel")
    assert e.sigma == pytest.approx(0.0, abs=1e-15)  # exactly singular: σ is round-off (5e-18)
    tau, lam = split_tree_torques(robot, Jc[[0, 2]], tree[[0, 2]])
    # Independent: Sᵀτ + Jcᵀλ reproduces the tree torques.
    S = np.zeros((6, robot.model.nv))
    S[np.arange(6), robot.actuated_v] = 1.0
    assert np.abs(tau[0] @ S + lam[0] @ Jc0 - tree[0]).max() <= 1e-13  # achieves 4.4e-16


def test_inverse_dynamics_refuses_a_numerically_singular_closure_split(robot):
    traj = thesis_trajectory(samples=11)
    r = ik(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    bad = dataclasses.replace(r, sigma_parallel=r.sigma_parallel.copy())
    bad.sigma_parallel[7] = 0.5 * SIGMA_FLOOR * r.sigma_parallel_max[7]
    with pytest.raises(SingularityError) as ei:
        inverse_dynamics(robot, bad)
    assert (ei.value.sample, ei.value.time, ei.value.chain) == (7, traj.t[7], "parallel")
    assert np.isfinite(inverse_dynamics(robot, r).tau).all()


def test_spherical_gimbal_is_a_named_singularity(robot):
    # ZYZ rates: Rz(−a) w = (ċ sin b, ḃ, ȧ + ċ cos b); independent check by finite
    # differences of the ZYZ angles of M(t) = M0 exp(t ŵ_body).
    ang = np.array([0.3, 1.1, -0.7])
    Rz = lambda a: J.Rz(a)  # noqa: E731
    M0 = Rz(ang[0]) @ J.Ry(ang[1]) @ Rz(ang[2])
    w = np.array([0.2, -0.4, 0.9])
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    h = 1e-6
    expm = lambda t: np.eye(3) + t * W + 0.5 * t * t * W @ W + t ** 3 / 6 * W @ W @ W  # noqa
    fd = (zyz(expm(h) @ M0) - zyz(expm(-h) @ M0)) / (2 * h)
    assert np.abs(zyz_rates(ang, w) - fd).max() <= 1e-8
    assert np.abs(zyz_rates(ang[None], w[None])[0] - fd).max() <= 1e-8
    assert not np.isfinite(zyz_rates(np.array([0.3, 0.0, 0.1]), w)).all()
    # Along a result, a gimbal-locked cut joint (θ109_2 = 0) is rejected with its name.
    traj = thesis_trajectory(samples=11)
    r = ik(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)
    sph = r.spherical.copy()
    sph[4, 4] = 0.0
    with pytest.raises(SingularityError) as ei:
        check_margins(robot, dataclasses.replace(r, spherical=sph), ZERO_MARGINS)
    assert (ei.value.sample, ei.value.chain) == (4, "spherical joint 2")
    assert "θ109_2" in str(ei.value)


def test_closure_on_a_parallel_singularity_is_a_singularity_error(robot, monkeypatch):
    # No parallel singularity lies near home; pretend Jc_p is singular at the solution to
    # check the wiring: the error is both a ClosureError and a SingularityError, with σ.
    act = robot.q_reference[robot.actuated_v]
    q = closure.solve_closure(robot, act)
    calls = []

    def fake(A):  # regular at the first solution, singular from the second on
        calls.append(1)
        return (0.3, 0.6) if len(calls) == 1 else (1e-17, 0.6)

    monkeypatch.setattr(closure, "sigma_range", fake)
    with pytest.raises(ClosureSingularError, match=r"^sample 1: .*parallel singularity"):
        closure.forward_kinematics(robot, np.array([act, act]), q_guess=q)
    with pytest.raises(ClosureSingularError) as ei:
        closure.solve_closure(robot, act, q_guess=q)
    e = ei.value
    assert isinstance(e, ClosureError) and isinstance(e, SingularityError)
    assert (e.chain, e.sigma) == ("parallel", 1e-17) and "parallel singularity" in str(e)
    with pytest.raises(ValueError, match="q_guess"):
        closure.solve_closure(robot, act, q_guess=np.full(robot.model.nq, np.nan))


# --- 2. margins of 0 and the numerical floors --------------------------------------------------

def _stop_at_edge(robot, n=201, duration=2.0):
    """Smooth rest-to-rest motion from home that ends exactly on leg 2's reach boundary."""
    home = np.asarray(robot.params.home_pose, dtype=float)
    tau = np.linspace(0.0, 1.0, n)
    s, ds, dds = 3 * tau ** 2 - 2 * tau ** 3, (6 * tau - 6 * tau ** 2) / duration, \
        (6 - 12 * tau) / duration ** 2
    D = EDGE - home
    poses = home + np.outer(s, D)
    poses[-1] = EDGE
    return Trajectory(tau * duration, poses, np.outer(ds, D), np.outer(dds, D), name="edge")


@pytest.mark.parametrize("method", METHODS)
def test_margin_zero_still_rejects_the_exact_reach_limit(robot, method):
    # Used to succeed with torques of 8.5e4 N·m (Newton) or 2.5e13 N·m (batch) at the last
    # sample, where σ_serial is round-off.
    traj = _stop_at_edge(robot)
    with pytest.raises(SingularityError) as ei:
        pp.run_pipeline(robot, traj, method=method, margins=ZERO_MARGINS)
    e = ei.value
    assert (e.sample, e.chain) == (200, "serial") and e.time == traj.t[200]
    assert "numerical floor" in str(e) and "round-off" in str(e)
    assert e.sigma < SERIAL_FLOOR * 2.0 and e.amount > 0
    # One sample earlier the motion is regular: finite, modest torques.
    short = Trajectory(traj.t[:200], traj.poses[:200], traj.d_poses[:200],
                       traj.dd_poses[:200], name="edge")
    res = pp.run_pipeline(robot, short, method=method, margins=ZERO_MARGINS)
    assert np.isfinite(res.dynamics.tau).all() and np.abs(res.dynamics.tau).max() < 10.0
    # Independent σ_serial at the last kept sample: SVD of J_tool N from Pinocchio.
    Jc = constraint_jacobian(robot.model, robot.data, robot.constraint_models,
                                robot.constraint_datas, res.ik.q[-1])
    N = actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)
    pin.computeJointJacobians(robot.model, robot.data, res.ik.q[-1])
    pin.updateFramePlacements(robot.model, robot.data)
    Jt = pin.getFrameJacobian(robot.model, robot.data, robot.tip_frame,
                              pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    s = np.linalg.svd(Jt @ N, compute_uv=False)
    assert abs(s[-1] - res.ik.sigma_serial[-1]) <= 1e-14 * s[0]  # achieves 1.8e-17 s[0]
    assert s[-1] > SERIAL_FLOOR * s[0]


@pytest.mark.parametrize("method", METHODS)
def test_wrist_within_round_off_of_singular_is_rejected_with_margin_zero(robot, method):
    sing = wrist_singular_pose(robot.params)
    for delta, singular in ((2e-8, True), (1e-3, False)):
        pose = sing.copy()
        pose[5] += delta  # φ: turns the tool axis off the platform arm by ≈ delta
        # Independent θ1716: angle between the tool axis and the platform arm.
        a, b = platform(robot.params, pose)[0][:, 0], ts.rotation(pose)[:, 0]
        angle = math.atan2(np.linalg.norm(np.cross(a, b)), a @ b)
        assert angle == pytest.approx(delta, rel=0.2)
        if singular:  # 1 − cos θ1716 ≈ 2.5e-16: within round-off (16 ε) of 1, so θ1716 is 0
            assert 1.0 - math.cos(angle) <= 16 * EPS
            with pytest.raises(T.WristSingularError):
                T.position_ik(robot.params, pose)
            with pytest.raises(SingularityError) as ei:
                ik(robot, pose[None], method=method, margins=ZERO_MARGINS)
            assert ei.value.chain == "wrist" and "round-off" in str(ei.value)
        else:
            q = T.position_ik(robot.params, pose)
            assert q[0, T.JOINTS.index("theta1716")] == pytest.approx(angle, rel=1e-9)
            r = ik(robot, pose[None], method=method, margins=ZERO_MARGINS)
            assert r.wrist_margin[0] == pytest.approx(math.sin(angle), rel=1e-13)  # achieves 2e-16



@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("value", [0.0, math.nan, -1.0, "1e-12"])
def test_invalid_tolerance_is_rejected_up_front(robot, method, value):
    traj = thesis_trajectory(samples=5)
    with pytest.raises(KinematicsInputError) as ei:
        ik(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t, method=method, tol=value)
    e = ei.value
    assert isinstance(e, ValueError) and isinstance(e, InputError)  # the rule: bad input
    assert not isinstance(e, KinematicsError)  # nothing was solved (pollard_pin/errors.py)
    assert e.chain == "tol" and str(e).startswith(f"tol = {value!r}: ")


@pytest.mark.parametrize("method", METHODS)
def test_margins_other_than_a_margins_value_are_refused(robot, method):
    # The margins travel as one validated value (Margins), not as loose numbers.
    traj = thesis_trajectory(samples=5)
    with pytest.raises(MarginError) as ei:
        ik(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t, method=method, margins=0.05)
    assert isinstance(ei.value, InputError)
    assert "Margins(" in str(ei.value) and "\n" not in str(ei.value)
    for loose in ("wrist_margin", "singularity_margin"):  # no such option
        with pytest.raises(TypeError, match=loose):
            pp.IkOptions(method=method, **{loose: 0.05})


@pytest.mark.parametrize("value", [-0.1, math.nan, 2.0])
def test_closed_form_rejects_invalid_wrist_margin(robot, value):
    with pytest.raises(ValueError, match="wrist_margin"):
        T.position_ik(robot.params, robot.params.home_pose, wrist_margin=value)


# --- 3. round-off at the arccos/arcsin boundaries ------------------------------------------

def _outward(robot):
    """Unit pose direction leaving leg 2's reach through EDGE (−∇|ratio|, independent)."""
    h = 1e-6
    g = np.array([(abs(leg_geometry(robot.params, EDGE + h * e, 1)[0])
                   - abs(leg_geometry(robot.params, EDGE - h * e, 1)[0])) / (2 * h)
                  for e in np.eye(6)])
    return g / np.linalg.norm(g)


def _last_solvable(params, direction):
    """Adjacent floats (s_in, s_out): EDGE + s·direction solves at s_in, not at s_out."""
    def ok(s):
        try:
            T.position_ik(params, EDGE + s * direction)
            return True
        except T.UnreachableError:
            return False
    lo, hi = -1e-9, 1e-9
    assert ok(lo) and not ok(hi)
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return lo, hi
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)


def test_reach_limit_is_one_round_off_tolerance_wide(robot):
    out = _outward(robot)
    s_in, s_out = _last_solvable(robot.params, out)
    # Beyond the limit by a round-off-sized distance: the tolerance is a few ulps of ~1 m.
    assert 0.0 < s_out < 1e-13
    q = T.position_ik(robot.params, EDGE + s_in * out)
    # within tolerance: on the boundary, θ76_2 = 0 to round-off (achieves 6.4e-17; the closed
    # form's angles are no longer rounded through a 2π wrap, which made it exactly 0)
    assert abs(q[0, T.JOINTS.index("theta76_2")]) <= 1e-14
    ratio = abs(leg_geometry(robot.params, EDGE + s_out * out, 1)[0])
    assert 1.0 - 1e-14 <= ratio <= 1.0 + 1e-13  # independent: at the boundary to round-off
    with pytest.raises(T.UnreachableError) as ei:
        T.position_ik(robot.params, EDGE + s_out * out)
    e = ei.value
    assert e.chain == "leg 2" and 0.0 < e.shortfall < 1e-13
    msg = str(e)
    m = re.search(r"short by ([^ ]+) mm", msg)
    assert m and float(m.group(1)) > 0.0, msg
    assert "|−C/R| = 1 + " in msg  # not a bare "1"
    # Inside the tolerance the pipeline sees the singular boundary, beyond it the shortfall.
    with pytest.raises(SingularityError):
        ik(robot, (EDGE + s_in * out)[None], margins=ZERO_MARGINS)
    with pytest.raises(UnreachablePoseError) as ei:
        ik(robot, (EDGE + s_out * out)[None])
    assert ei.value.chain == "leg 2" and ei.value.amount > 0.0


# Within round-off of EDGE; the old closed form refused them "(short by 0 mm)".
ROUND_OFF_EDGES = np.array([
    [0.5479217373830818, -0.14140430553739222, 0.2619590809778903, 0.15155152817687945,
     0.3484683803492945, 0.040141623568546454],
    [0.5479217373830818, -0.14140430553739258, 0.26195908097789017, 0.15155152817687942,
     0.34846838034929406, 0.04014162356854652]])


@pytest.mark.parametrize("pose", ROUND_OFF_EDGES)
def test_pose_within_round_off_of_the_limit_is_on_it(robot, pose):
    assert abs(abs(leg_geometry(robot.params, pose, 1)[0]) - 1.0) <= 1e-14  # independent
    q = T.position_ik(robot.params, pose)
    assert abs(q[0, T.JOINTS.index("theta76_2")]) <= 1e-15
    with pytest.raises(SingularityError) as ei:
        ik(robot, pose[None], margins=ZERO_MARGINS)
    assert ei.value.chain == "serial"


def test_shortfall_messages_are_positive_near_the_limit(robot):
    out, rng = _outward(robot), np.random.default_rng(3)
    for _ in range(8):
        d = out + 0.3 * rng.normal(size=6)
        d /= np.linalg.norm(d)
        s_in, s_out = _last_solvable(robot.params, d)
        for s in s_out * np.array([1.0, 1.5, 3.0, 10.0, 1e3, 1e6, 1e9]):
            with pytest.raises(T.UnreachableError) as ei:
                T.position_ik(robot.params, EDGE + s * d)
            msg = str(ei.value)
            m = re.search(r"\((?:short|target too close) by ([^ ]+) mm\)", msg)
            assert m and float(m.group(1)) > 0.0, msg
            assert ei.value.shortfall > 0.0


@pytest.mark.parametrize("step", [1e-9, 1e-6, 1e-3])
def test_shortfall_matches_independent_distance(robot, step):
    out = _outward(robot)
    pose = EDGE + step * out
    _, rho, h = leg_geometry(robot.params, pose, 1)
    leg = robot.params.legs[1]
    ref = math.hypot(rho - leg.x43, h) - leg.x87  # nearest point of the elbow circle
    with pytest.raises(T.UnreachableError) as ei:
        T.position_ik(robot.params, pose)
    # Round-off of metre-sized lengths: achieves 2.2e-17 m at every step.
    assert ref > 0.0 and ei.value.shortfall == pytest.approx(ref, rel=0, abs=5e-15)



def test_one_tolerance_at_every_unit_boundary():
    tol = T.ROUNDOFF
    assert tol == 16 * EPS
    vals = np.array([1.0 + 15 * EPS, -1.0 - 15 * EPS, 1.0 - 15 * EPS, 0.5, 1.0 + 17 * EPS])
    c, beyond = T._unit(vals)
    assert c.tolist()[:4] == [1.0, -1.0, 1.0, 0.5] and beyond.tolist() == [False] * 4 + [True]
    c, beyond = T._unit(np.array([1.0 + 30 * EPS]), scale=2.0)  # tolerance grows with scale
    assert c[0] == 1.0 and not beyond[0]


# --- 4. inputs -------------------------------------------------------------------------------

@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("which, k, c, bad, name", [
    ("poses", 3, 0, 1e300, "x"), ("poses", 2, 5, -2e6, "phi"),
    ("d_poses", 4, 3, np.nan, "d_psi"), ("dd_poses", 1, 4, np.inf, "dd_theta")])
def test_bad_input_names_column_sample_and_value(robot, method, which, k, c, bad, name):
    traj = thesis_trajectory(samples=6)
    arrays = {n: getattr(traj, n).copy() for n in ("poses", "d_poses", "dd_poses")}
    arrays[which][k, c] = bad
    with pytest.raises(KinematicsInputError) as ei:
        ik(robot, arrays["poses"], arrays["d_poses"], arrays["dd_poses"], traj.t,
           method=method)
    e = ei.value
    assert (e.sample, e.time, e.chain) == (k, traj.t[k], name)
    assert f"{name} = " in str(e) and f"sample {k}" in str(e)
    if np.isfinite(bad):
        assert "absurd" in str(e) and "1e+06" in str(e)
    else:
        assert "not a finite number" in str(e)
    if which == "poses":  # the closed form's own entry point names it too
        with pytest.raises(ValueError, match=rf"^sample {k}: {name} = "):
            T.position_ik(robot.params, arrays["poses"])


@pytest.mark.parametrize("method", METHODS)
def test_empty_pose_array_is_a_clear_error(robot, method):
    with pytest.raises(KinematicsInputError, match="empty"):
        ik(robot, np.empty((0, 6)), method=method)
    with pytest.raises(ValueError, match="empty"):
        T.position_ik(robot.params, np.empty((0, 6)))


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("dt, k, what", [(0.0, 3, "not increasing"),
                                         (-0.5, 2, "not increasing"),
                                         (1e-300, 1, "time step too small")])
def test_bad_time_steps_name_the_sample(robot, method, dt, k, what):
    traj = thesis_trajectory(samples=6)
    t = traj.t.copy()
    t[k:] += dt - (t[k] - t[k - 1])
    if dt == 1e-300:  # the reported case: samples 1e-300 s apart
        t = np.arange(6) * dt
    dd = traj.dd_poses.copy()
    dd[k] = np.nan  # what a spline through such times gives; the cause is the time step
    with pytest.raises(KinematicsInputError) as ei:
        ik(robot, traj.poses, traj.d_poses, dd, t, method=method)
    e = ei.value
    assert e.sample == k and e.chain == "t" and what in str(e) and f"sample {k}" in str(e)


def test_non_finite_time_is_named(robot):
    traj = thesis_trajectory(samples=6)
    t = traj.t.copy()
    t[2] = np.nan
    with pytest.raises(KinematicsInputError, match=r"^sample 2: time t = nan"):
        ik(robot, traj.poses, traj.d_poses, traj.dd_poses, t)


# --- 5. sampling density and real branch flips -----------------------------------------------

@pytest.fixture(scope="module")
def dense(robot):
    traj = thesis_trajectory(samples=2001)
    return traj, ik(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("n", [2, 3, 50, 101])
def test_any_sampling_gives_the_dense_solution(robot, dense, method, n):
    traj, ref = dense
    # The dense trajectory's own samples, n of them (uneven spacing for n = 50): same inputs.
    idx = np.unique(np.linspace(0, len(traj.t) - 1, n).round().astype(int))
    r = ik(robot, traj.poses[idx], traj.d_poses[idx], traj.dd_poses[idx], traj.t[idx],
           method=method)
    for f in ("q", "v", "a", "spherical", "d_spherical"):
        assert np.abs(getattr(r, f) - getattr(ref, f)[idx]).max() <= 1e-12, f
    # thesis_trajectory(samples=n) itself (times from its own linspace) at shared times.
    sp = thesis_trajectory(samples=n)
    r = ik(robot, sp.poses, sp.d_poses, sp.dd_poses, sp.t, method=method)
    i_s, i_d = np.nonzero(np.isclose(sp.t[:, None], traj.t[None, :], rtol=0, atol=1e-12))
    assert len(i_s) >= 2
    for f in ("q", "v", "a"):
        assert np.abs(getattr(r, f)[i_s] - getattr(ref, f)[i_d]).max() <= 1e-12, f
    # Independent: the closed form with exact jet derivatives at every sparse sample.
    q, qd, qdd = T.inverse_kinematics(robot.params, sp.poses, sp.d_poses, sp.dd_poses)
    tree = [T.JOINTS.index(j) for j in robot.joint_names]
    assert np.abs(wrap(r.q - q[:, tree])).max() <= POS_TOL
    assert np.abs(r.v - qd[:, tree]).max() <= VEL_TOL
    assert np.abs(r.a - qdd[:, tree]).max() <= ACC_TOL


def test_run_with_few_samples_works(robot):
    # `pollard-pin run --samples 50` failed with "joint theta76_2 jumped … branch flip".
    for n in (3, 50, 100):
        traj = thesis_trajectory(samples=n)
        res = pp.run_pipeline(robot, traj)
        assert len(res.ik) == n
        # And right: the thesis' Euler–Lagrange torques, independent of Pinocchio.
        ref = lagrange.inverse_dynamics(robot.params, traj.poses, traj.d_poses,
                                        traj.dd_poses)["tau"]
        assert np.abs(res.dynamics.tau - ref).max() <= 2e-13 * np.abs(ref).max()  # 1.6e-15




def test_branch_quantities_follow_the_configured_signs(robot):
    # Independent of the IK: for every choice of branches, the closed form's configuration has
    # the signs (b0, +, +, b1, +, b2, +), and with β54 = 0 the leg quantity is sin θ76_i.
    traj = thesis_trajectory(samples=201)
    tree = [T.JOINTS.index(j) for j in robot.joint_names]
    assert [leg.beta54 for leg in robot.params.legs] == [0.0, 0.0]
    for branches in ((1, 1, -1), (1, 1, 1), (1, -1, -1)):
        p = dataclasses.replace(robot.params, branches=branches)
        q = T.position_ik(p, traj.poses)[:, tree]
        v = branch_quantities(robot, q)
        want = np.array([branches[0], 1, 1, branches[1], 1, branches[2], 1])
        assert (np.sign(v) == want).all(), branches
        for i, col in ((1, 3), (2, 5)):
            assert np.abs(v[:, col] - np.sin(q[:, robot.idx_q(f"theta76_{i}")])).max() <= 1e-15
    assert len(BRANCH_SIGNS) == 7


def test_sign_change_between_samples_is_a_branch_flip(robot):
    traj = thesis_trajectory(samples=5)
    r = ik(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t, margins=Margins(singularity=0.0))
    other = dataclasses.replace(robot.params, branches=(1, 1, 1))  # leg 2 assembled the other way
    tree = [T.JOINTS.index(j) for j in robot.joint_names]
    q = r.q.copy()
    q[3:] = T.position_ik(other, traj.poses[3:])[:, tree]
    with pytest.raises(BranchFlipError) as ei:
        check_margins(robot, dataclasses.replace(r, q=q), ZERO_MARGINS)
    e = ei.value
    assert (e.sample, e.chain, e.time) == (3, "leg 2", traj.t[3])
    assert "between samples 2 and 3" in str(e) and "leg 2's reach boundary" in str(e)


def test_newton_keeps_the_branch_of_its_start(robot):
    # Started on leg 2's other branch, Newton stays there at any sampling: it equals the
    # closed form with that branch sign (independent), sparse or dense.
    other = dataclasses.replace(robot.params, branches=(1, 1, 1))
    tree = [T.JOINTS.index(j) for j in robot.joint_names]
    for n in (3, 201):
        traj = thesis_trajectory(samples=n)
        ref = T.position_ik(other, traj.poses)[:, tree]
        r = pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t,
                                  q_start=ref[0],
                                  options=pp.IkOptions(margins=Margins(singularity=0.0)))
        assert np.abs(wrap(r.q - ref)).max() <= POS_TOL


def test_motion_through_the_wrist_singularity_is_a_branch_flip(robot):
    # A straight pose path through θ1716 = 0 (margins 0, no sample on it): followed by
    # continuation, sin θ1716 changes sign — a real change of assembly mode.
    n, dur = 40, 3.9
    t, poses, d = path_to_wrist_singularity(robot.params, 1.9, n, dur)
    t_cross = dur / 1.9  # s = 1
    k = int(np.searchsorted(t, t_cross))
    assert t[k - 1] < t_cross < t[k]
    with pytest.raises(BranchFlipError) as ei:
        ik(robot, poses, d, np.zeros_like(poses), t, method="newton", margins=ZERO_MARGINS)
    e = ei.value
    assert (e.sample, e.chain, e.time) == (k, "wrist", t[k])
    assert "sin θ1716 changed sign" in str(e) and f"between samples {k - 1} and {k}" in str(e)
    near = float(re.search(r"near t = ([0-9.e+-]+) s", str(e)).group(1))
    assert abs(near - t_cross) <= 2 * MIN_SUBSTEP * (t[k] - t[k - 1])
    # The batch holds the configured assembly mode (sin θ1716 ≥ 0) at every sample instead.
    r = ik(robot, poses, d, np.zeros_like(poses), t, margins=ZERO_MARGINS)
    assert (np.sin(r.q[:, robot.idx_q("theta1716")]) > 0).all()
