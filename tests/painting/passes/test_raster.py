"""Raster geometry and its path pieces (paint/passes/raster.py, docs/model.md §21): the pass layout
against its ripple rule, the turnaround shape's boundary conditions, the pieces' exact
derivatives against finite differences and their continuity, the rest-to-rest ends."""
import numpy as np
import pytest

from pollard_pin.painting.passes.raster import (
    _turn_u,
    cross_profile,
    pass_offsets,
    raster_motion,
    raster_segments,
    ripple_spacing,
    spot_runon,
    task_motion,
)


def test_pass_layout_meets_its_tolerance():
    sigma = 0.01
    d = ripple_spacing(sigma, 0.005)
    off = pass_offsets(0.12, d, sigma, 0.01)
    y = np.linspace(-0.06, 0.06, 1201)
    assert np.abs(cross_profile(off, d, sigma, y) - 1).max() <= 0.01
    # one pass fewer breaks it
    fewer = (np.arange(len(off) - 1) - (len(off) - 2) / 2) * d
    assert np.abs(cross_profile(fewer, d, sigma, y) - 1).max() > 0.01
    # interior ripple: Poisson's 2·exp(−2π²σ²/Δ²) = 0.5 % at the chosen spacing
    many = (np.arange(41) - 20) * d
    mid = np.linspace(-d, d, 401)
    ripple = np.abs(cross_profile(many, d, sigma, mid) - 1).max()
    assert ripple == pytest.approx(0.005, rel=1e-3)


@pytest.mark.parametrize("m", [1, 2, 3])
def test_turn_shape_boundary_conditions(m):
    f = _turn_u(m)
    fd, fdd = f.deriv(), f.deriv(2)
    assert [f(0), f(1), fd(0), fd(1), fdd(0), fdd(1)] == pytest.approx([0, 0, 1, -1, 0, 0],
                                                                        abs=1e-13)


def test_exact_derivatives_rest_to_rest_and_c2(plan):
    tr = plan.trajectory
    seg = plan.segments
    h = 1e-5  # s: central differences of the path itself, inside the pieces
    t = np.clip(tr.t, h, seg.total - h)
    plus, minus = (np.array(seg.evaluate(t + s)) for s in (h, -h))
    mid = np.array(seg.evaluate(t))
    fd, fdd = (plus[:2] - minus[:2]) / (2 * h), (plus[2:4] - minus[2:4]) / (2 * h)
    # achieved 6e-8 m/s and 5e-6 m/s² (h²·jerk/6, h²·snap/6 in the 23 ms ramps)
    assert np.abs(fd - mid[2:4]).max() < 6e-6
    assert np.abs(fdd - mid[4:6]).max() < 5e-4
    speeds = np.linalg.norm(tr.d_poses[:, :3], axis=1)
    assert np.abs(speeds - np.hypot(*seg.evaluate(tr.t)[2:4])).max() < 1e-15
    assert np.abs(tr.d_poses[[0, -1]]).max() < 1e-12
    assert np.abs(tr.dd_poses[[0, -1]]).max() < 1e-12
    seg = plan.segments
    b = seg.start[1:]
    before, after = (np.array(seg.evaluate(b + s)) for s in (-1e-10, 1e-10))
    # C²: position, rate, acceleration continuous at every piece boundary
    assert np.abs(before - after).max() < 1e-6
    assert np.ptp(tr.poses[:, 3:], axis=0).max() == 0  # the gun keeps its orientation


def test_raster_motion_rests_exactly_at_its_ends(plan):
    """At t = 0 and t = total the path is at rest: rates and accelerations exactly 0, where the
    polynomials leave round-off (seen 1.7e-16 m/s); elsewhere it is task_motion's."""
    seg, frame, standoff = plan.segments, plan.frame, plan.job.standoff
    t = np.linspace(0.0, seg.total, 101)
    poses, d, dd = raster_motion(frame, standoff, seg, t)
    p, dr, ddr = task_motion(frame, standoff, *seg.evaluate(t))
    assert np.all(d[[0, -1]] == 0) and np.all(dd[[0, -1]] == 0)
    assert np.abs(dr[[0, -1]]).max() < 1e-12  # only round-off was removed
    assert np.array_equal(poses, p)
    assert np.array_equal(d[1:-1], dr[1:-1]) and np.array_equal(dd[1:-1], ddr[1:-1])


def test_segments_serpentine_over_the_offsets():
    """Two coats over three passes: passes at the offsets, then back in reverse order; each
    pass at constant speed over |U| ≤ half_length, alternating direction."""
    seg = raster_segments([-0.02, 0.0, 0.02], 0.1, 0.25, 0.3, (0.4, 0.5), coats=2)
    assert seg.kind == ("ramp",) + ("pass", "turn") * 5 + ("pass", "ramp")
    passes = [i for i, k in enumerate(seg.kind) if k == "pass"]
    mid = seg.start[passes] + seg.duration[passes] / 2
    U, V, dU, dV, _, _ = seg.evaluate(mid)
    assert V == pytest.approx([-0.02, 0.0, 0.02, 0.02, 0.0, -0.02], abs=1e-15)
    assert dU == pytest.approx([0.25, -0.25] * 3, rel=1e-12) and np.all(dV == 0)
    assert U == pytest.approx(0, abs=1e-12)
    assert seg.duration[passes] == pytest.approx(0.2 / 0.25, rel=1e-15)
    assert seg.duration[0] == 0.4 and seg.duration[-1] == 0.5


def test_the_spots_cross_profile_and_layout():
    """cross_profile of a spot: the round Gaussian's stripe gives the Gaussian form (1e-14;
    achieved 2e-16); the β spot's passes at its spacing meet the tolerance across the
    extent, edges included, and one pass fewer does not."""
    from pollard_pin.painting.spray.spots import BetaSpot, RoundGaussian

    sigma = 0.01
    d = ripple_spacing(sigma, 0.005)
    off = pass_offsets(0.12, d, sigma, 0.01)
    y = np.linspace(-0.06, 0.06, 1201)
    gauss = cross_profile(off, d, sigma, y)
    assert np.abs(cross_profile(off, d, sigma, y, RoundGaussian(sigma)) - gauss).max() < 1e-14
    beta = BetaSpot(0.03, 2.5)
    d = beta.spacing(0.005)
    off = pass_offsets(0.12, d, beta.width, 0.01, spot=beta)
    assert np.abs(cross_profile(off, d, beta.width, y, beta) - 1).max() <= 0.01
    fewer = (np.arange(len(off) - 1) - (len(off) - 2) / 2) * d
    assert np.abs(cross_profile(fewer, d, beta.width, y, beta) - 1).max() > 0.01


def test_job_spacing_follows_the_spot_across_the_passes():
    """The round Gaussian (spot None) keeps ripple_spacing exactly; the elliptic spot's
    horizontal passes cross its long axis (σ_long), vertical ones its short; the β spot's
    is its own ripple's."""
    from types import SimpleNamespace

    from pollard_pin.painting.passes.raster import job_spacing
    from pollard_pin.painting.spray.spots import BetaSpot, EllipticGaussian

    def job(spot, direction="horizontal", sigma=0.01):
        return SimpleNamespace(spot=spot, sigma=sigma, direction=direction)

    assert job_spacing(job(None)) == ripple_spacing(0.01)
    e = EllipticGaussian(0.02, 0.008)
    assert job_spacing(job(e)) == pytest.approx(ripple_spacing(0.02), rel=1e-15)
    assert job_spacing(job(e, "vertical")) == pytest.approx(ripple_spacing(0.008), rel=1e-15)
    b = BetaSpot(0.03, 2.5)
    assert job_spacing(job(b)) == b.spacing(0.005)


def test_the_run_on_stops_where_a_finite_spot_deposits_nothing():
    """The run-on past an edge is k·σ, but never past a β spot's reach R, beyond which its
    film is exactly 0 (brute force: the stripe there); the Gaussians keep k·σ bit for bit."""
    from pollard_pin.painting.spray.spots import BetaSpot, EllipticGaussian, RoundGaussian

    steep = BetaSpot(0.06, 1.5)  # σ = 26.8 mm: 4σ = 107 mm, 3σ = 80 mm, both past R
    assert spot_runon(steep.width, steep) == 0.06
    assert spot_runon(steep.width, steep, 3.0) == 0.06
    assert steep.stripe(np.linspace(0.06, 0.2, 50)).max() == 0.0
    narrow = BetaSpot(0.06, 20.0)  # 4σ = 37 mm < R
    assert spot_runon(narrow.width, narrow) == 4.0 * narrow.width
    for spot in (None, RoundGaussian(0.01), EllipticGaussian(0.02, 0.01)):
        sigma = 0.01 if spot is None else spot.width
        assert spot_runon(sigma, spot) == 4.0 * sigma
