"""Small dense linear algebra of pollard_pin.kinematics.singularity on one matrix (a control
tick's): LAPACK called directly, against numpy."""
import numpy as np
import pytest

from pollard_pin.kinematics.singularity import (
    actuator_velocity_map,
    sigma_range,
    solve_small,
    solve_stack,
)


def test_solve_small_is_numpys_solve_and_fails_as_it_does():
    rng = np.random.default_rng(1)
    A = rng.normal(size=(6, 6))
    for B in (rng.normal(size=6), rng.normal(size=(6, 7))):
        np.testing.assert_allclose(solve_small(A, B), np.linalg.solve(A, B), rtol=1e-13,
                                   atol=1e-13)  # seen: the same bits
    A[:, 2] = 0.0
    with pytest.raises(np.linalg.LinAlgError):
        solve_small(A, B)


def test_one_matrix_sigma_range_is_the_svds():
    """One matrix goes to LAPACK's SVD directly: numpy's values (seen: the same bits)."""
    rng = np.random.default_rng(2)
    for last in (0.5, 1e-6):
        A = rng.normal(size=(6, 6)) @ np.diag([1, 1, 1, 1, 1, last])
        s = np.linalg.svd(A, compute_uv=False)
        smin, smax = sigma_range(A)
        assert smin == pytest.approx(s[-1], rel=1e-12)
        assert smax == pytest.approx(s[0], rel=1e-13)
    assert all(np.isnan(x) for x in sigma_range(np.full((6, 6), np.nan)))


def test_a_stacks_non_finite_matrices_are_nan_and_only_they():
    """sigma_range of a stack: its finite-sum fast path agrees with looking at each matrix
    — a NaN, a +inf and a −inf matrix give NaN, their neighbours and a finite stack whose
    sum overflows (every matrix looked at then) their own values, bit for bit those of each
    matrix in a finite stack (against the SVD)."""
    rng = np.random.default_rng(6)
    A = rng.normal(size=(9, 6, 6))
    alone = [sigma_range(A[k:k + 1]) for k in range(9)]
    bad = A.copy()
    bad[2, 1, 3], bad[5, 0, 0], bad[7, 4, 2] = np.nan, np.inf, -np.inf
    huge = A.copy()
    huge[:, 0, 0] = 1e308  # finite entries, an infinite sum
    for stack, nan in ((A, ()), (bad, (2, 5, 7)), (huge, ())):
        smin, smax = sigma_range(stack)
        for k in range(9):
            if k in nan:
                assert np.isnan(smin[k]) and np.isnan(smax[k])
            elif stack is huge:
                s = np.linalg.svd(huge[k], compute_uv=False)
                assert smax[k] == pytest.approx(s[0], rel=1e-12)
            else:
                assert smin[k] == alone[k][0][0] and smax[k] == alone[k][1][0]
        s = np.linalg.svd(A, compute_uv=False)
    np.testing.assert_allclose(sigma_range(A)[1], s[:, 0], rtol=1e-12)


def test_finite_rows_is_each_arrays_rows_looked_at():
    """finite_rows (the IK's and check_margins' one test) against each array's rows tested
    entry by entry: a NaN, a +inf, a −inf in different arrays and rows, and finite entries
    whose sum overflows (every row finite)."""
    from types import SimpleNamespace

    from pollard_pin.kinematics.singularity import finite_rows

    rng = np.random.default_rng(7)
    arrays = {k: rng.normal(size=(6, w)) for k, w in (("q", 12), ("v", 12), ("a", 12),
                                                       ("spherical", 6), ("d_spherical", 6))}
    arrays["v"][1, 3], arrays["spherical"][4, 0], arrays["a"][1, 0] = np.nan, np.inf, -np.inf
    arrays["q"][:, 0] = 1e308  # an infinite sum of finite entries
    r = SimpleNamespace(**arrays)
    want = np.logical_and.reduce([np.isfinite(x).all(axis=1) for x in arrays.values()])
    assert want.tolist() == [True, False, True, True, False, True]
    assert finite_rows(r).tolist() == want.tolist()
    clean = SimpleNamespace(**{k: np.nan_to_num(x, posinf=0, neginf=0)
                               for k, x in arrays.items()})
    assert finite_rows(clean).all()


def test_velocity_map_of_one_matrix_is_the_stacks():
    """The single-matrix path (one dgesv) gives the stacked path's N; a singular Jc_p still
    raises."""
    rng = np.random.default_rng(3)
    Jc = rng.normal(size=(6, 12))
    ia, ip = np.array([0, 6, 9, 3, 4, 5]), np.array([1, 2, 7, 8, 10, 11])
    N = actuator_velocity_map(Jc, ia, ip)
    stacked = actuator_velocity_map(Jc[None], ia, ip)[0]
    np.testing.assert_allclose(N, stacked, rtol=0, atol=1e-12)
    np.testing.assert_allclose(N[ip], -solve_stack(Jc[:, ip], Jc[:, ia])[0], rtol=0,
                               atol=1e-12)
    np.testing.assert_array_equal(N[ia], np.eye(6))
    np.testing.assert_allclose(Jc @ N, 0.0, atol=1e-12)
    Jc[:, ip[0]] = 0.0
    with pytest.raises(Exception, match="singular"):
        actuator_velocity_map(Jc, ia, ip)
