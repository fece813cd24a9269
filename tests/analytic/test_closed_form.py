"""The thesis' closed form (analytic/closed_form.py) against independent numbers:
docs/model.md §9 home table, the numpy forward chain, finite differences. (Its Euler–Lagrange
dynamics: tests/crosscheck/test_euler_lagrange.py.)"""

import numpy as np
import pytest
from bare_modules import run_bare
from thesis_curves import T_PROBE, TRAJECTORIES, painting_trajectory, sinusoid_trajectory

from pollard_pin.analytic import jet as J
from pollard_pin.analytic.closed_form import (
    ACTUATED,
    ACTUATED_INDEX,
    JOINTS,
    UnreachableError,
    WristSingularError,
    actuation_jacobian,
    body_kinematics,
    closure_points,
    forward_frames,
    forward_tool_pose,
    inverse_kinematics,
    position_ik,
)
from pollard_pin.model.params import load_params

HOME_DEG = {  # docs/model.md §9, rounded to 3 decimals
    "theta21": -77.629, "theta43": 104.487, "theta54": 0.0,
    "theta1615": 90.0, "theta1716": 26.858, "theta1817": -90.0,
    "theta21_1": -26.390, "theta65_1": -92.623, "theta76_1": 46.778,
    "theta21_2": 26.390, "theta65_2": -92.623, "theta76_2": -46.778,
    "theta98_1": -33.820, "theta109_1": 116.430, "theta1110_1": 119.725,
    "theta98_2": 33.820, "theta109_2": 116.430, "theta1110_2": -119.725,
}
@pytest.fixture(scope="module")
def p():
    return load_params()


def test_home_configuration_matches_spec_table(p):
    q = position_ik(p, p.home_pose)[0]
    assert q.shape == (18,)
    got = dict(zip(JOINTS, np.degrees(q)))
    for name, want in HOME_DEG.items():
        assert abs(got[name] - want) <= 5e-4 + 1e-12, (name, got[name], want)  # 3 decimals


@pytest.mark.parametrize("traj", TRAJECTORIES)
def test_forward_chain_reproduces_pose_and_closes_loops(p, traj):
    _, x, _, _ = traj(p)
    q = position_ik(p, x)
    assert np.abs(forward_tool_pose(p, q) - x).max() <= 1e-13  # achieves 1.1e-15
    cp = closure_points(p, q)
    assert np.abs(cp[..., 0, :] - cp[..., 1, :]).max() <= 1e-13  # achieves 6.1e-16


def test_trajectory_stays_continuous_and_away_from_singularity(p):
    _, x, _, _ = painting_trajectory(p)
    q = position_ik(p, x)
    assert np.abs(np.diff(q, axis=0)).max() < 0.05  # no branch jumps or 2π wraps
    t1716 = np.degrees(q[:, JOINTS.index("theta1716")])
    # docs/model.md §9: about 15° to 47° (14.5725° and 46.9934° at 2001 samples).
    assert t1716.min() == pytest.approx(14.5725, abs=1e-4)
    assert t1716.max() == pytest.approx(46.9934, abs=1e-4)


def test_reference_selects_the_2pi_representative(p):
    q0 = position_ik(p, p.home_pose)[0]
    ref = q0 + 2 * np.pi * (np.arange(18) % 3 - 1)
    q = position_ik(p, p.home_pose, reference=ref)[0]
    assert np.allclose(q, ref, rtol=0, atol=1e-13)  # achieves 8.9e-16


@pytest.mark.parametrize("traj", TRAJECTORIES)
def test_velocities_and_accelerations_match_finite_differences(p, traj):
    h = 1e-4
    _, x, xd, xdd = traj(p, t=T_PROBE)
    q, qd, qdd = inverse_kinematics(p, x, xd, xdd)
    assert np.allclose(q, position_ik(p, x), rtol=0, atol=2e-13)  # achieves 1.3e-15
    qp = position_ik(p, traj(p, t=T_PROBE + h)[1], reference=q[0])
    qm = position_ik(p, traj(p, t=T_PROBE - h)[1], reference=q[0])
    qp, qm = (np.unwrap(np.stack([q, a]), axis=0)[1] for a in (qp, qm))
    assert np.abs((qp - qm) / (2 * h) - qd).max() <= 1e-6 * (1 + np.abs(qd).max())
    assert np.abs((qp - 2 * q + qm) / h**2 - qdd).max() <= 1e-4 * (1 + np.abs(qdd).max())


def test_body_velocities_match_finite_differences(p):
    h = 1e-5
    args = sinusoid_trajectory(p, t=T_PROBE[:3])[1:]
    bk = body_kinematics(p, *args)
    bp = body_kinematics(p, *sinusoid_trajectory(p, t=T_PROBE[:3] + h)[1:])
    bm = body_kinematics(p, *sinusoid_trajectory(p, t=T_PROBE[:3] - h)[1:])
    # Central differences achieve 1.2e-11 (v), 2.4e-11 (a), 2.5e-10 (ω), 2.6e-9 (α).
    for name, b in bk.items():
        assert np.abs((bp[name]["r"] - bm[name]["r"]) / (2 * h) - b["v"]).max() < 2e-9, name
        assert np.abs((bp[name]["v"] - bm[name]["v"]) / (2 * h) - b["a"]).max() < 5e-9, name
        W = (bp[name]["R"] - bm[name]["R"]) / (2 * h) @ np.swapaxes(b["R"], -1, -2)
        w = np.stack([W[..., 2, 1], W[..., 0, 2], W[..., 1, 0]], -1)
        assert np.abs(w - b["omega"]).max() < 1e-8, name
        al = (bp[name]["omega"] - bm[name]["omega"]) / (2 * h)
        assert np.abs(al - b["alpha"]).max() < 5e-7, name


def test_actuation_jacobian_matches_finite_differences(p):
    _, x, _, _ = sinusoid_trajectory(p, t=T_PROBE[:4])
    Jt = actuation_jacobian(p, x)
    h = 1e-6
    fd = np.empty_like(Jt)
    for j in range(6):
        e = np.zeros(6)
        e[j] = h
        ref = position_ik(p, x[:1])[0]
        diff = position_ik(p, x + e, reference=ref) - position_ik(p, x - e, reference=ref)
        fd[:, :, j] = diff[:, ACTUATED_INDEX] / (2 * h)
    assert np.abs(fd - Jt).max() <= 1e-8 * np.abs(Jt).max()  # achieves 8.2e-11 × max
    assert ACTUATED == tuple(JOINTS[k] for k in ACTUATED_INDEX)


def test_thesis_method_does_not_import_pinocchio():
    """The closed form and the Euler–Lagrange cross-check are numpy only, and so independent
    of the Pinocchio pipeline they check: with Pinocchio hidden and the package ``__init__``
    files (the root imports every layer) bypassed, both load and solve the home pose."""
    r = run_bare("import numpy as np\n"
                 "from pollard_pin.analytic.closed_form import position_ik\n"
                 "from pollard_pin.crosscheck.euler_lagrange import inverse_dynamics\n"
                 "from pollard_pin.model.params import load_params\n"
                 "q = position_ik(load_params(), [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]])\n"
                 "assert sys.modules['pinocchio'] is None and q.shape == (1, 18)\n"
                 "assert not [m for m in sys.modules if m.startswith('pinocchio.')]\n")
    assert r.returncode == 0, r.stderr


def test_the_bare_check_can_fail():
    """The same check on a module that does need Pinocchio (the model) fails."""
    r = run_bare("import pollard_pin.model.build\n")
    assert r.returncode == 1 and "ModuleNotFoundError" in r.stderr, r.stderr
    assert "pinocchio" in r.stderr.strip().splitlines()[-1]


def test_unreachable_chain0_reports_sample_and_shortfall(p):
    poses = np.tile(p.home_pose, (5, 1))
    poses[3, :3] = (1.5, 0.0, 0.05)  # wrist centre at (1.44, 0, 0.05): 1.44 − x32 − L = 0.64 m
    with pytest.raises(UnreachableError) as ei:
        position_ik(p, poses)
    e = ei.value
    assert (e.chain, e.sample, e.kind, e.too_close) == ("chain 0", 3, "unreachable", False)
    assert e.shortfall == pytest.approx(1.44 - p.x32 - p.x65 - p.x1514, abs=1e-14)  # 2.2e-16
    assert "chain 0" in str(e) and "sample 3" in str(e) and "640 mm" in str(e)


def test_unreachable_leg_reports_chain_and_distance(p):
    poses = np.tile(p.home_pose, (4, 1))
    poses[2:, 1] = 0.4  # far to +y: leg 1 (side −1) cannot follow
    with pytest.raises(UnreachableError) as ei:
        position_ik(p, poses)
    e = ei.value
    assert (e.chain, e.sample, e.count) == ("leg 1", 2, 2)
    # Independent shortfall: chain 0 by a dense scan, then distance to leg 1's elbow circle.
    P15 = poses[2, :3] - np.array([p.x1918, 0, 0])
    t = np.linspace(-np.pi, 0, 2_000_001)
    L = p.x65 + p.x1514
    E = np.stack([p.x32 * np.cos(t), 0 * t, p.z10 - p.x32 * np.sin(t)], -1)
    E = E[np.argmin(np.abs(np.linalg.norm(P15 - E, axis=1) - L))]
    u = (P15 - E) / L
    a, b = np.arctan2(-u[2], u[0]), np.arcsin(u[1])
    Aw = E + J.Ry(a) @ J.Rz(b) @ p.attachment(0)
    leg = p.legs[0]
    rho = np.hypot(Aw[0], Aw[1] - leg.side * leg.y10)
    short = np.hypot(rho - leg.x43, Aw[2] + leg.z32) - leg.x87
    # The scan's grid limits the reference: it achieves 7e-9 m.
    assert short > 0 and e.shortfall == pytest.approx(short, abs=1e-6)
    msg = str(e)
    assert "leg 1 cannot reach" in msg and "sample 2" in msg and "short by 0.627" in msg


def test_wrist_singularity_is_reported(p):
    with pytest.raises(WristSingularError) as ei:
        position_ik(p, p.home_pose, wrist_margin=0.5)  # sin 26.858° = 0.452
    e = ei.value
    assert isinstance(e, UnreachableError) and e.kind == "singular" and e.chain == "wrist"
    assert e.ratio == pytest.approx(np.sin(np.radians(26.858)), abs=1e-5)
    assert "wrist" in str(e) and "sample 0" in str(e)
    position_ik(p, p.home_pose, wrist_margin=0.4)


def test_jet_chain_rule_against_closed_form():
    t = np.linspace(0.1, 1.2, 7)
    x = J.Jet(t, np.ones_like(t), np.zeros_like(t))
    f = J.atan2(J.sin(x) * x, J.cos(x) + 2.0) + J.asin(x / 2) - J.acos(x / 3) + J.sqrt(x) / x
    g = lambda s: (np.arctan2(np.sin(s) * s, np.cos(s) + 2) + np.arcsin(s / 2)  # noqa: E731
                   - np.arccos(s / 3) + np.sqrt(s) / s)
    h = 1e-4
    assert np.allclose(f.v, g(t), rtol=0, atol=5e-14)  # achieves 4.4e-16
    assert np.allclose(f.d, (g(t + h) - g(t - h)) / (2 * h), atol=1e-7)
    assert np.allclose(f.dd, (g(t + h) - 2 * g(t) + g(t - h)) / h**2, atol=1e-5)
    R = J.Rx(x) @ J.Ry(2 * x) @ J.Rz(-x)
    Rn = lambda s: J.Rx(s) @ J.Ry(2 * s) @ J.Rz(-s)  # noqa: E731
    assert np.allclose(R.d, (Rn(t + h) - Rn(t - h)) / (2 * h), rtol=0, atol=5e-6)  # 3.2e-8

    v = R @ J.stack([x, 1.0, x * x])
    assert v.shape == (7, 3)


def test_body_frames_agree_with_forward_chain(p):
    # body_kinematics reuses the IK's rotations; they must equal docs/model.md §3 tree built anew.
    args = sinusoid_trajectory(p, t=T_PROBE)[1:]
    bk = body_kinematics(p, *args)
    f = forward_frames(p, position_ik(p, args[0]))
    for name, b in bk.items():
        R, o = f[name]
        assert np.abs(b["R"] - R).max() < 1e-14, name
        r = o + R @ np.asarray(p.body(name).com)
        assert np.abs(b["r"] - r).max() < 1e-14, name
