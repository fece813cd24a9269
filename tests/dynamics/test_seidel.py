"""TOPP-RA with lean per-stage loops (dynamics/seidel.py): the same parameterisations as
toppra's own TOPPRA, to the bit, on toppra's own kind of problem (joint velocity and
acceleration limits along a spline), solvable or not; and the one-line hint without toppra."""
import sys

import numpy as np
import pytest
import toppra
import toppra.algorithm
import toppra.constraint

from pollard_pin.dynamics.seidel import lean_toppra, load_toppra


def _problem(accel):
    """Toppra's textbook instance: a random-looking 6-joint spline, 301 grid points, unevenly
    spaced (each interval its own length)."""
    rng = np.random.default_rng(7)
    way = np.cumsum(rng.normal(size=(9, 6)), axis=0)
    path = toppra.SplineInterpolator(np.linspace(0, 1, 9), way)
    vlim = np.column_stack([-np.full(6, 2.0), np.full(6, 2.0)])
    alim = np.column_stack([-np.full(6, accel), np.full(6, accel)])
    constraints = [toppra.constraint.JointVelocityConstraint(vlim),
                   toppra.constraint.JointAccelerationConstraint(alim)]
    return constraints, path, np.linspace(0, 1, 301) ** 1.5


@pytest.mark.parametrize("ends", [(0.0, 0.0), (0.0, 0.05), (0.06, 0.0)])
def test_the_same_parameterisation_as_toppra(ends):
    constraints, path, grid = _problem(accel=5.0)
    got, want = (algo(constraints, path, gridpoints=grid, solver_wrapper="seidel")
                 .compute_parameterization(*ends, return_data=True)
                 for algo in (lean_toppra(), toppra.algorithm.TOPPRA))
    assert got[1] is not None and np.all(np.isfinite(got[1]))
    for g, w in zip(got, want):
        np.testing.assert_array_equal(g, w)


def test_an_unreachable_end_fails_as_toppra_does():
    """An end rate no acceleration can reach from rest: no parameterisation, the same
    controllable sets."""
    constraints, path, grid = _problem(accel=5.0)
    got, want = (algo(constraints, path, gridpoints=grid, solver_wrapper="seidel")
                 .compute_parameterization(0.0, 50.0, return_data=True)
                 for algo in (lean_toppra(), toppra.algorithm.TOPPRA))
    assert got[1] is None and want[1] is None
    np.testing.assert_array_equal(got[3], want[3])


def test_toppra_missing_is_one_line(monkeypatch):
    monkeypatch.setitem(sys.modules, "toppra", None)
    with pytest.raises(ImportError, match=r"pip install 'toppra>=0.6.10,<0.7'") as err:
        load_toppra()
    assert "\n" not in str(err.value)
