"""The compiled kernels (pollard_pin/kinematics/kernels.py) and Pinocchio's batched RNEA against
independent references: LAPACK's eigvalsh and inverse, and Pinocchio's per-sample rnea."""
import numpy as np
import pinocchio as pin
import pytest

import pollard_pin as pp
from pollard_pin.dynamics.inverse import batched_rnea
from pollard_pin.kinematics.ik_batch import kinematic_inverse, layout, point_rows
from pollard_pin.kinematics.kernels import block_inverse, gram_extremes

RNG = np.random.default_rng(20261123)


def _graded(n, rng, k=6):
    """Matrices U diag(s) Vᵀ with singular values over 15 decades, repeated and zero ones."""
    out = []
    for _ in range(n):
        U, _ = np.linalg.qr(rng.standard_normal((k, k)))
        V, _ = np.linalg.qr(rng.standard_normal((k, k)))
        s = np.exp(rng.uniform(-12.0, 3.0, k))
        if rng.random() < 0.3:
            s[:3] = s[0]  # a triple singular value: Laguerre's slow (linear) case
        if rng.random() < 0.2:
            s[-1] = 0.0
        out.append(U @ np.diag(s) @ V.T)
    return np.array(out)


STACKS = {
    "gaussian 6x6": RNG.standard_normal((500, 6, 6)),
    "gaussian 7x5": RNG.standard_normal((100, 7, 5)),
    "graded": _graded(300, RNG),
    "special": np.array([np.eye(6), np.zeros((6, 6)), np.diag([1, 1, 1, 1e-6, 1e-6, 1.0]),
                         1e-200 * np.eye(6), 1e150 * RNG.standard_normal((6, 6)),
                         np.ones((6, 6))]),
}


@pytest.mark.parametrize("name", STACKS)
def test_gram_extremes_match_lapack(name):
    A = STACKS[name]
    lo, hi = gram_extremes(np.ascontiguousarray(A))
    ev = np.linalg.eigvalsh(np.swapaxes(A, 1, 2) @ A)
    scale = np.maximum(ev[:, -1], np.finfo(float).tiny)
    # Both backward stable, errors O(k ε λ_max) (forming AᵀA alone rounds by m ε λ_max; LAPACK
    # and the squared SVD differ by up to 12 ε here): 4 k ε.
    tol = 4 * A.shape[-1] * np.finfo(float).eps * scale
    assert np.all(np.abs(lo - ev[:, 0]) <= tol)
    assert np.all(np.abs(hi - ev[:, -1]) <= tol)


def test_gram_extremes_on_the_robot(robot, ik_traj):
    """The two maps whose σ the IK reports (docs/model.md §12), along the thesis trajectory."""
    Jc = ik_traj.constraint_jacobian[..., robot.passive_v]
    lo, hi = gram_extremes(np.ascontiguousarray(Jc))
    s = np.linalg.svd(Jc, compute_uv=False)
    assert np.abs(np.sqrt(lo) - s[:, -1]).max() <= 1e-12 * s[:, 0].max()
    assert np.abs(np.sqrt(hi) - s[:, 0]).max() <= 1e-14 * s[:, 0].max()


def _robot_K(robot, q):
    lay = layout(robot)
    R, o = lay.tree.placements(q)
    return point_rows(lay, R, o, robot.model.nv)[0], lay


def test_block_inverse_equals_lapack(robot, ik_traj):
    K, lay = _robot_K(robot, ik_traj.q)
    assert lay.blocks is not None
    top, bottom, first, second = lay.blocks
    assert np.all(K[:, bottom][:, :, second] == 0.0)  # the structure the kernel relies on
    Ki = kinematic_inverse(K, lay)
    ref = np.linalg.inv(K)
    assert np.abs(Ki - ref).max() <= 1e-13 * np.abs(ref).max()
    assert np.abs(Ki @ K - np.eye(12)).max() <= 1e-12


def test_block_inverse_random_and_singular():
    K = RNG.standard_normal((50, 8, 8))
    top, bottom, first, second = np.arange(4), np.arange(4, 8), np.array([0, 2, 4, 6]), \
        np.array([1, 3, 5, 7])
    K[:, 4:, 1::2] = 0.0
    K[7, :4, 3] = 0.0  # X has a zero column: exactly singular
    K[9, 5, [0, 2, 4, 6]] = 0.0  # T has a zero row
    Ki = block_inverse(K, top, bottom, first, second)
    bad = ~np.isfinite(Ki).all(axis=(1, 2))
    assert np.flatnonzero(bad).tolist() == [7, 9]
    ok = ~bad
    ref = np.linalg.inv(K[ok])
    assert np.abs(Ki[ok] - ref).max() <= 1e-11 * np.abs(ref).max()


def test_batched_rnea_equals_pinocchio(robot):
    """On one thread (a short stack) and on RNEA_THREADS (PARALLEL_SAMPLES or more): the same
    torques, bit for bit."""
    from pollard_pin.dynamics.inverse import PARALLEL_SAMPLES

    model, data = robot.model, robot.data
    n = 37
    Q, V, A = (RNG.uniform(-2, 2, (PARALLEL_SAMPLES, model.nv)) for _ in range(3))
    tau = batched_rnea(model, Q[:n], V[:n], A[:n])
    ref = np.array([pin.rnea(model, data, Q[k], V[k], A[k]) for k in range(n)])
    assert np.abs(tau - ref).max() <= 1e-12 * np.abs(ref).max()
    assert batched_rnea(model, Q[:0], V[:0], A[:0]).shape == (0, model.nv)
    np.testing.assert_array_equal(batched_rnea(model, Q, V, A)[:n], tau)


@pytest.fixture(scope="module")
def ik_traj(robot):
    traj = pp.thesis_trajectory(samples=401)
    return pp.inverse_kinematics(robot, traj.poses, traj.d_poses, traj.dd_poses, traj.t)


def test_kernels_take_any_layout_and_refuse_bad_indices():
    """The C loops get C-contiguous float64 whatever is passed (a strided view, integers)
    and check every index before reading memory: a bad one is a ValueError naming it."""
    A = RNG.standard_normal((20, 6, 6))
    view = np.asfortranarray(A)[::-1][::-1]  # the same values, Fortran-ordered, strided
    assert not view.flags.c_contiguous
    assert all(np.array_equal(a, b) for a, b in zip(gram_extremes(view), gram_extremes(A)))
    assert np.array_equal(gram_extremes((100 * A).astype(np.int32))[1],
                          gram_extremes(np.trunc(100 * A))[1])
    half = np.arange(3)
    with pytest.raises(ValueError, match=r"kernels: second\[2\] = 6 is outside \[0, 6\)"):
        block_inverse(A, half, half + 3, half, np.array([3, 4, 6]))


def test_rk4_step_is_numpys_rk4_to_the_bit():
    """kernels.rk4_step: the stages' arithmetic compiled, each operation numpy's in the same
    order (no FMA), so the step equals the numpy expression exactly; errors of the stage
    function come through."""
    from pollard_pin.kinematics.kernels import rk4_step

    rng = np.random.default_rng(7)
    W = rng.normal(size=(12, 12))

    def f(q, v):  # any nonlinear field
        return np.sin(W @ q) - 0.3 * v * np.abs(v)

    q, v = rng.normal(size=12), rng.normal(size=12)
    for h in (1e-3, 0.1, 1.0 / 3.0):
        a1 = f(q, v)
        v2 = v + 0.5 * h * a1
        a2 = f(q + 0.5 * h * v, v2)
        v3 = v + 0.5 * h * a2
        a3 = f(q + 0.5 * h * v2, v3)
        v4 = v + h * a3
        a4 = f(q + h * v3, v4)
        want = (q + h / 6.0 * (v + 2 * v2 + 2 * v3 + v4),
                v + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4))
        got = rk4_step(f, q, v, a1, h, np.empty(12), np.empty(12))
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])

    def fails(q, v):
        raise ZeroDivisionError("stage failed")

    with pytest.raises(ZeroDivisionError, match="stage failed"):
        rk4_step(fails, q, v, v, 1e-3, np.empty(12), np.empty(12))
    with pytest.raises(ValueError, match="returned no 12 float64 values"):
        rk4_step(lambda q, v: q[:6], q, v, v, 1e-3, np.empty(12), np.empty(12))
    for wrong in (np.float32, np.int64):  # 96 bytes each, not float64
        with pytest.raises(ValueError, match="returned no 12 float64 values"):
            rk4_step(lambda q, v, w=wrong: np.zeros(96 // np.dtype(w).itemsize, w), q, v, v,
                     1e-3, np.empty(12), np.empty(12))
