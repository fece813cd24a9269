"""The compiled round Gaussian rate (pollard_pin/painting/spray/kernel.py, docs/model.md §20)
against the formula evaluated by numpy pair by pair, against numpy's block formulation (the
other spots' path) and at its edges: behind the nozzle, grazing, on the axis, h → 0."""
import math

import numpy as np
import pytest

from pollard_pin.painting.spray.deposition import Gun, sources
from pollard_pin.painting.spray.kernel import cone_keep, round_near, round_rate

GUN = Gun(standoff=0.15, sigma=0.010, flow=1.5e-7, apex=-0.01)
K = GUN.sigma / (GUN.standoff - GUN.apex)  # σ(h) = K·h
COEF = GUN.flow / (2.0 * math.pi)
EPS = np.finfo(float).eps


def _block(seed: int, T: int = 16, P: int = 1500, offset=(0.4, -0.3, 0.2)):
    """A block of sources about the standoff above a ±0.1 m patch, the scene ``offset`` from
    the origin (as a part's film points and tips lie from their origin): points behind some
    sources (one sprays away), on the sources' axes, beside a nozzle, with normals turned up
    to grazing and past it."""
    rng = np.random.default_rng(seed)
    o = np.asarray(offset)
    p = o + [0.0, 0.0, 0.15] + 0.02 * rng.standard_normal((T, 3))
    a = np.array([0.0, 0.0, -1.0]) + 0.2 * rng.uniform(-1, 1, (T, 3)) * [1, 1, 0]
    a /= np.linalg.norm(a, axis=1, keepdims=True)
    a[0] *= -1  # spraying away from every point: h < 0
    s = o + np.column_stack([rng.uniform(-0.1, 0.1, (P, 2)), 0.01 * rng.uniform(-1, 1, P)])
    s[:T] = p + rng.uniform(0.05, 0.3, (T, 1)) * a  # on each source's axis: ρ² ≈ 0
    s[T:2 * T] = p + 0.002 * rng.standard_normal((T, 3))  # beside a nozzle: some h ≤ 0
    s[2 * T] = p[1] - 1e-200 * a[1]  # h of 1e-200: σ(h)² underflows
    n = np.array([0.0, 0.0, 1.0]) + 1.5 * rng.uniform(-1, 1, (P, 3)) * [1, 1, 0]
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    d = s[3 * T:4 * T] - p[2]  # grazing source 2: n ⟂ d
    g = np.cross(d, rng.standard_normal((T, 3)))
    n[3 * T:4 * T] = g / np.linalg.norm(g, axis=1, keepdims=True)
    return p, a, s, n


def _pairwise(p, a, s, n):
    """(rate, height) by numpy, elementwise pair by pair (T, P): d = s − p, the dot products
    summed in their components' order, then §20's operations in the kernel's order."""
    d = s[None, :, :] - p[:, None, :]
    n = np.broadcast_to(n, s.shape)[None, :, :]
    dot = [lambda x, y=y: x[..., 0] * y[..., 0] + x[..., 1] * y[..., 1] + x[..., 2] * y[..., 2]
           for y in (a[:, None, :], n, d)]
    h, dn, d2 = (f(d) for f in dot)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        sh2 = (K * h) ** 2
        x = np.maximum(d2 - h * h, 0.0) * -0.5 / sh2
        rate = COEF / sh2 * np.exp(x) * np.maximum(-dn, 0.0) / h
    return np.where((h > 0) & (rate < np.inf), rate, 0.0), -dn, x


@pytest.mark.parametrize("per_point", [True, False])
def test_the_kernel_is_the_formula_pair_by_pair(per_point):
    """Equal to numpy's pairwise evaluation of the same operations to 1e-15 of each rate
    (achieved: bitwise where numpy's exp is the C library's; 4 ulp allow for an exp of its
    own), the heights to the ulp; zero exactly behind the nozzle, where the surface faces
    away and where σ(h)² underflows; finite everywhere."""
    p, a, s, n = _block(1)
    n = n if per_point else n[40]
    got, height = sources(GUN, p, a).rate_and_height(GUN, s, n)
    want, want_height, _ = _pairwise(p + GUN.apex * a, a, s, n)
    assert np.isfinite(got).all() and (got >= 0).all()
    assert np.all(np.abs(got - want) <= 1e-15 * want)
    assert np.all(np.abs(height - want_height) <= 2 * EPS * np.abs(want_height) + 1e-17)
    d = s[None] - (p + GUN.apex * a)[:, None]
    h = np.einsum("tpi,ti->tp", d, a)
    assert np.all(got[h <= 0] == 0) and np.all(got[height <= 0] == 0)
    assert (got > 0).sum() > 0.3 * got.size  # most pairs are sprayed


def test_the_kernel_is_numpys_block_formulation():
    """Against Sources.numpy_rate_and_height (the expansion |d|² = s·s + p·p − 2 s·p of
    matrix products, which rounds by ~eps·(|s|² + |p|²) in ρ², half a metre off the origin
    here): equal pair by pair to within 100 × (eps·(|s|² + |p|²)/σ(h)² + 4 eps) of the rate
    (achieved 0.9 of that bound: 5e-10 of the rate beside a nozzle, where σ(h) is small), the
    heights to 2e-14 m (achieved 1.8e-16 m, an ulp of the coordinates)."""
    p, a, s, n = _block(2)
    src = sources(GUN, p, a)
    got, height = src.rate_and_height(GUN, s, n)
    ref, ref_height = src.numpy_rate_and_height(GUN, s, n)
    q = src.p  # the sources (the cone's apex)
    h = np.einsum("tpi,ti->tp", s[None] - q[:, None], a)
    spread = EPS * ((s * s).sum(1)[None] + (q * q).sum(1)[:, None])
    bound = 100 * (spread / np.maximum(K * h, 1e-150) ** 2 + 4 * EPS) * ref
    assert np.all(np.abs(got - ref) <= bound)
    assert np.abs(height - ref_height).max() < 2e-14
    assert np.array_equal(got > 0, ref > 0) and (got > 0).sum() > 0.3 * got.size


def test_on_the_axis_the_rate_is_the_peak_over_the_obliquity():
    """A point on a source's axis: ρ = 0, where |d|² − h² rounds by eps·|d|² either side of
    0 (clipped), so the rate flow/(2π σ(h)²) · (−d·n)/h to 100 × eps·|d|²/(2σ(h)²) (achieved
    1.07 of that)."""
    p, a, s, n = _block(3)
    q = p + GUN.apex * a
    got = round_rate(q, a, s[:16], n[:16], K, COEF)[0].diagonal()
    d = s[:16] - q
    h, dn = (d * a).sum(1), (d * n[:16]).sum(1)
    want = COEF / (K * h) ** 2 * np.maximum(-dn, 0) / h
    tol = EPS * (d * d).sum(1) / (2 * (K * h) ** 2)
    assert (want > 0).sum() > 8 and np.all(np.abs(got - want) <= 100 * tol * want)


def test_the_kernel_checks_its_shapes_and_takes_any_layout():
    p, a, s, n = _block(4, T=4, P=30)
    rate, height = round_rate(p, a, s, n, K, COEF)
    again = round_rate(np.asfortranarray(p), a.tolist(), np.repeat(s, 2, axis=0)[::2],
                       n.T.copy().T, K, COEF)
    assert np.array_equal(rate, again[0]) and np.array_equal(height, again[1])
    with pytest.raises(ValueError, match="normals"):
        round_rate(p, a, s, n[:5], K, COEF)
    with pytest.raises(ValueError, match="axes"):
        round_rate(p, a[:3], s, n, K, COEF)


def _cone_case(seed: int, P: int = 4000, tight: bool = False):
    """A block of 16 samples and points around it: near the cone's edge (angles spread
    about it, a quarter within 1e-6 rad of it), inside, behind the nozzle, at the block's
    mean tip (r = 0, where the angle is 0/0), a hair off it, and a NaN point. ``tight``: the
    tips within 1e-9 m of each other, no apex (the spread ≈ 0: the edge the angle's own)."""
    from pollard_pin.painting.spray.deposition import Reach, spot_block
    rng = np.random.default_rng(seed)
    p, a, _, _ = _block(seed, T=16, P=80)
    a[0] *= -1  # all towards the points
    if tight:
        p = p[0] + 1e-9 * rng.standard_normal(p.shape)
    reach = Reach(Gun(GUN.standoff, GUN.sigma, GUN.flow) if tight else GUN, *spot_block(p, a))
    u = rng.standard_normal((P, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    # directions at angles about the cone's edge (widened by δa and the spread) from the
    # mean axis, beyond the nozzle's ball
    r = rng.uniform(0.1, 0.6, P)
    tilt = reach.cone + reach.da + np.arcsin(np.minimum(reach.dp / r, 1)) + rng.uniform(
        -0.3, 0.3, P) * np.where(np.arange(P) % 4, 1.0, 3e-6)
    side = u - (u @ reach.am)[:, None] * reach.am
    side /= np.linalg.norm(side, axis=1, keepdims=True)
    dirs = np.cos(tilt)[:, None] * reach.am + np.sin(tilt)[:, None] * side
    s = reach.pm + r[:, None] * dirs
    s[:50] = reach.pm - rng.uniform(0.0, 0.3, (50, 1)) * u[:50]  # all round, behind too
    s[50], s[51], s[52] = reach.pm, reach.pm + 1e-300, np.nan
    return reach, s, rng


def test_the_compiled_cone_test_is_keeps_numpy_formula():
    """Reach.keep (compiled) and Reach.numpy_keep (the formula it replaced) give the same
    verdict on every point, with no radius, one radius and a radius per point (balls), on
    points about the cone's edge, at the mean tip (kept: the angle is not finite) and NaN
    (kept); both verdicts occur near the edge; an 'everywhere' cone keeps all."""
    from pollard_pin.painting.spray.deposition import Reach, spot_block
    for seed, tight in ((5, False), (6, True)):
        reach, s, rng = _cone_case(seed, tight=tight)
        for radius in (0.0, 0.004, rng.uniform(0.0, 0.02, len(s))):
            got, want = reach.keep(s, radius), reach.numpy_keep(s, radius)
            assert np.array_equal(got, want)
            assert got[50:53].all() and 0.2 < got.mean() < 0.8
    wide = Gun(standoff=0.15, sigma=0.1, flow=1.5e-7)  # tan = 10 σ/standoff > CULL_WIDEST
    p, a, s, _ = _block(7, T=16, P=80)
    reach = Reach(wide, *spot_block(p, a))
    assert reach.everywhere and reach.keep(s).all() and reach.numpy_keep(s).all()


@pytest.mark.parametrize("per_point", [True, False])
def test_the_cull_and_rate_in_one_call_are_keep_then_the_rate(per_point):
    """Reach.rate_near (one compiled call: the held groups' points, the cone test, the rate
    of those kept) against its steps done apart: the points of the held groups, numpy_keep's
    verdicts on them and the compiled rate of the kept points, bitwise; without a cone
    (everywhere) every point of a held group."""
    from pollard_pin.painting.spray.deposition import sources
    reach, s, rng = _cone_case(8)
    s = s[53:]  # no NaN
    n = rng.standard_normal((len(s), 3)) + [0.0, 0.0, 3.0]
    n = n / np.linalg.norm(n, axis=1, keepdims=True) if per_point else n[0] / np.linalg.norm(n[0])
    group = rng.integers(0, 40, len(s))
    held = rng.uniform(size=40) < 0.7
    p, a, _, _ = _block(8, T=16, P=80)
    src = sources(GUN, p, a)
    k, rate, height = reach.rate_near(GUN, src, s, n, group, held)
    near = np.flatnonzero(held[group])
    want = near[reach.numpy_keep(s[near])]
    assert np.array_equal(k, want) and 0 < len(k) < len(near)
    r, h = src.rate_and_height(GUN, s[k], n[k] if per_point else n)
    assert np.array_equal(rate, r) and np.array_equal(height, h) and (rate > 0).any()
    k, rate, _ = round_near(src.p, src.a, s, n, group, held, None, K, COEF)
    assert np.array_equal(k, near) and np.array_equal(rate, src.rate_and_height(
        GUN, s[near], n[near] if per_point else n)[0])


def test_the_cone_test_checks_its_arguments():
    reach, s, _ = _cone_case(9, P=60)
    with pytest.raises(ValueError, match="radii"):
        cone_keep(s, reach.cone_args, np.zeros(7))
    with pytest.raises(ValueError, match="cone"):
        cone_keep(s, reach.cone_args[:9])
    with pytest.raises(ValueError, match="group"):  # a group beyond held's
        round_near(s[:2], s[:2], s, [0.0, 0.0, 1.0], np.full(len(s), 40), np.ones(40, bool),
                   reach.cone_args, K, COEF)
