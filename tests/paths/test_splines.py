"""The quintic splines of pollard_pin.paths.splines against known polynomials, finite
differences and a peer engine (scipy's BPoly)."""
import numpy as np
import pytest
from scipy.interpolate import BPoly

from pollard_pin.paths.splines import QuinticHermite, QuinticSpline

RNG = np.random.default_rng(7)
COEF = RNG.normal(size=(6, 6))  # p_j(t) = Σ_k COEF[k, j] t^k: a quintic per coordinate


def _quintic(t):
    """Positions, rates and accelerations (N, 6) of the known quintic."""
    t = np.asarray(t, dtype=float)[:, None]
    k = np.arange(6)[:, None, None]
    c = COEF[:, None, :]
    pos = (c * t[None] ** k).sum(0)
    rate = (c[1:] * k[1:] * t[None] ** (k[1:] - 1)).sum(0)
    acc = (c[2:] * k[2:] * (k[2:] - 1) * t[None] ** (k[2:] - 2)).sum(0)
    return pos, rate, acc


KNOTS = np.array([0.0, 0.13, 0.4, 0.45, 0.9, 1.3, 2.0])  # uneven on purpose
TIMES = np.linspace(0.0, 2.0, 1001)


def test_hermite_reproduces_a_quintic_exactly():
    """A quintic is its own quintic Hermite interpolant: positions, rates and accelerations
    anywhere (seen 2e-12 on accelerations)."""
    curve = QuinticHermite(KNOTS, *_quintic(KNOTS))
    for got, want in zip(curve(TIMES), _quintic(TIMES)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-11)


def test_hermite_matches_bpoly_and_its_finite_differences():
    """Through arbitrary samples: the same piecewise quintic as scipy's BPoly (seen 2e-11);
    the rates and accelerations are the derivatives of the positions (central differences,
    seen 5e-7 of the largest value at h = 1e-5)."""
    p, v, a = (RNG.normal(size=(len(KNOTS), 6)) for _ in range(3))
    curve = QuinticHermite(KNOTS, p, v, a)
    peer = BPoly.from_derivatives(KNOTS, np.stack([p, v, a], axis=1))
    for order, got in enumerate(curve(TIMES)):
        np.testing.assert_allclose(got, peer(TIMES, order), rtol=0, atol=1e-9)
    h = 1e-5
    t = np.linspace(0.01, 1.99, 397)
    t = t[np.min(np.abs(t[:, None] - KNOTS), axis=1) > 2 * h]  # C² only: stay off the knots
    lo, mid, hi = curve(t - h), curve(t), curve(t + h)
    for k in (1, 2):
        np.testing.assert_allclose(mid[k], (hi[k - 1] - lo[k - 1]) / (2 * h), rtol=0,
                                   atol=1e-4 * np.abs(mid[k]).max())
    # exact at the samples, C² across them
    for got, want in zip(curve(KNOTS), (p, v, a)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
    for left, right in zip(curve(KNOTS[1:-1] - 1e-12), curve(KNOTS[1:-1])):
        np.testing.assert_allclose(left, right, rtol=0, atol=1e-6)


@pytest.mark.parametrize("n", [6, 11])
def test_interpolating_spline_reproduces_a_quintic(n):
    """The not-a-knot quintic spline through positions only reproduces a quintic, rates and
    accelerations included (seen 3e-11)."""
    knots = np.sort(np.append(RNG.uniform(0.1, 1.9, n - 2), [0.0, 2.0]))
    curve = QuinticSpline(knots, _quintic(knots)[0])
    for got, want in zip(curve(TIMES), _quintic(TIMES)):
        np.testing.assert_allclose(got, want, rtol=0, atol=3e-9)
