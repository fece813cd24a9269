"""Task-space conventions (analytic/taskspace.py) checked numerically: the rotation is
Rx(θ)·Ry(ψ)·Rz(φ) of elementary rotations written out (tests/rotations.py), the Euler angles
round-trip, the twist is Ṙ·Rᵀ of finite differences of R(t) and its derivative that of the
twist."""

import numpy as np
from rotations import Rx, Ry, Rz

from pollard_pin.analytic import taskspace as ts


def wrap(a):
    """Angles into (−π, π]."""
    return np.pi - np.mod(np.pi - np.asarray(a), 2.0 * np.pi)


def vee(W):
    return np.array([W[2, 1], W[0, 2], W[1, 0]])


def test_rotation_is_rx_theta_ry_psi_rz_phi():
    rng = np.random.default_rng(5)
    poses = np.column_stack([rng.normal(size=(50, 3)), rng.uniform(-np.pi, np.pi, (50, 3))])
    R = ts.rotation(poses)
    assert R.shape == (50, 3, 3)
    for p, Rk in zip(poses, R):
        psi, th, phi = p[3:]
        assert np.abs(Rk - Rx(th) @ Ry(psi) @ Rz(phi)).max() <= 1e-15
    # Batched leading dimensions.
    assert np.array_equal(ts.rotation(poses.reshape(5, 10, 6)), R.reshape(5, 10, 3, 3))
    # se3_from_pose / pose_from_se3.
    M = ts.se3_from_pose(poses[0])
    assert np.abs(M.rotation - R[0]).max() <= 1e-15 and np.allclose(M.translation, poses[0, :3])


def test_angles_from_rotation_round_trip():
    rng = np.random.default_rng(6)
    n = 200
    ang = np.column_stack([rng.uniform(-np.pi / 2 + 1e-3, np.pi / 2 - 1e-3, n),
                           rng.uniform(-np.pi, np.pi, n), rng.uniform(-np.pi, np.pi, n)])
    poses = np.column_stack([np.zeros((n, 3)), ang])
    back = ts.angles_from_rotation(ts.rotation(poses))
    assert np.abs(wrap(back - ang)).max() <= 1e-14  # achieves 0
    assert np.all(np.abs(back[:, 0]) <= np.pi / 2)
    # Arbitrary rotations (QR of random matrices, det +1): R → angles → R.
    Q = np.linalg.qr(rng.normal(size=(n, 3, 3)))[0]
    Q *= np.sign(np.linalg.det(Q))[:, None, None]
    R2 = ts.rotation(np.column_stack([np.zeros((n, 3)), ts.angles_from_rotation(Q)]))
    assert np.abs(R2 - Q).max() <= 5e-13  # achieves 2.1e-15
    # pose_from_se3 inverts se3_from_pose.
    p = np.concatenate([[0.1, -0.2, 0.3], ang[0]])
    assert np.abs(wrap(ts.pose_from_se3(ts.se3_from_pose(p)) - p)).max() <= 1e-14  # achieves 0


def _pose_curve(t):
    """A smooth pose curve with large angles, and its exact first/second derivatives."""
    a = np.array([0.1, -0.2, 0.05, 0.6, -0.9, 1.3])
    w = np.array([1.1, 0.7, 1.9, 1.3, 0.8, 1.7])
    c = np.array([0.5, 0.0, 0.2, 0.3, 0.4, -0.5])
    t = np.atleast_1d(t)[:, None]
    return c + a * np.sin(w * t + c), a * w * np.cos(w * t + c), -a * w**2 * np.sin(w * t + c)


def test_twist_is_rdot_rt_and_twist_dot_its_derivative():
    h = 1e-5
    t = np.linspace(0.0, 5.0, 23)
    p, pd, pdd = _pose_curve(t)
    tw, twd = ts.twist(p, pd), ts.twist_dot(p, pd, pdd)
    Rp, Rm, R = (ts.rotation(_pose_curve(t + s)[0]) for s in (h, -h, 0.0))
    omegas = []
    for k in range(len(t)):
        W = (Rp[k] - Rm[k]) / (2 * h) @ R[k].T  # ω̂ = Ṙ Rᵀ
        assert np.abs(W + W.T).max() <= 1e-8  # skew
        omegas.append(vee(W))
    omegas = np.array(omegas)
    assert np.abs(omegas).max() > 0.5
    assert np.abs(tw[:, 3:] - omegas).max() <= 1e-8
    assert np.array_equal(tw[:, :3], pd[:, :3])
    # ω̇ and the point acceleration by central differences of the twist along the curve.
    twp, twm = (ts.twist(*_pose_curve(t + s)[:2]) for s in (h, -h))
    assert np.abs(twd - (twp - twm) / (2 * h)).max() <= 5e-8  # achieves 3.5e-10
    assert np.array_equal(twd[:, :3], pdd[:, :3])
    # euler_rates inverts twist.
    assert np.abs(ts.euler_rates(p, tw) - pd).max() <= 1e-13  # achieves 4.4e-16


def test_rate_matrix_dot_matches_finite_difference():
    h = 1e-6
    t = np.linspace(0.0, 3.0, 11)
    p, pd, _ = _pose_curve(t)
    fd = (ts.rate_matrix(_pose_curve(t + h)[0]) - ts.rate_matrix(_pose_curve(t - h)[0])) / (2 * h)
    assert np.abs(ts.rate_matrix_dot(p, pd) - fd).max() <= 1e-8
