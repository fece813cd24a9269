"""The constant-s̈ parametrisation (pollard_pin.paths.const_accel) against toppra's own
ParametrizeConstAccel on the identity path p(s) = s, and the retimed curve against a known
curve evaluated at that s(t) and finite differences."""
import numpy as np
import toppra

from pollard_pin.paths import const_accel as CA

GRID = np.array([0.0, 0.1, 0.25, 0.3, 0.55, 0.8, 1.0])
S_DOT = np.array([0.0, 0.7, 1.3, 1.2, 0.4, 0.9, 0.0])  # rest to rest


def _peer():
    identity = toppra.SplineInterpolator([0.0, 1.0], [[0.0], [1.0]])  # p(s) = s
    return toppra.parametrizer.ParametrizeConstAccel(identity, GRID, S_DOT)


def _times():
    return np.concatenate([[0.0], np.cumsum(CA.interval_durations(GRID, S_DOT))])


def test_times_and_state_match_toppra():
    """Sample times, and (s, ṡ, s̈) at any time, as toppra's replay (seen 1e-16)."""
    peer = _peer()
    t = _times()
    assert t[-1] == peer.duration
    times = np.linspace(0.0, t[-1], 777)
    s, sd, sdd = CA.at_time(t, GRID, S_DOT, times)
    np.testing.assert_allclose(s, peer(times)[:, 0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(sd, peer(times, 1)[:, 0], rtol=0, atol=1e-14)
    inner = np.min(np.abs(times[:, None] - t), axis=1) > 1e-9  # s̈ jumps at the samples
    np.testing.assert_allclose(sdd[inner], peer(times[inner], 2)[:, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(CA.interval_acceleration(GRID, S_DOT),
                               np.diff(S_DOT**2) / (2 * np.diff(GRID)), rtol=1e-15)


def test_at_path_inverts_at_time_and_rate_squared():
    """t(s) is the inverse of s(t); ṡ² at fractions θ of each interval is ṡ_i² + 2θΔs·s̈_i
    (seen 1e-16)."""
    t = _times()
    theta = np.linspace(0.0, 1.0, 9)
    s = (GRID[:-1, None] + theta * np.diff(GRID)[:, None]).ravel()
    t_s, sd, u = CA.at_path(t, GRID, S_DOT, s)
    back, sd_back, _ = CA.at_time(t, GRID, S_DOT, t_s)
    np.testing.assert_allclose(back, s, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sd, sd_back, rtol=0, atol=1e-9)
    np.testing.assert_allclose(CA.rate_squared(GRID, S_DOT, theta).ravel(), sd**2,
                               rtol=0, atol=1e-12)


class _Cubic:
    """A known base curve p(t) = c0 + c1 t + c2 t² + c3 t³ on t ∈ [2, 5] (T = 3)."""

    c = np.random.default_rng(3).normal(size=(4, 6))

    def __call__(self, t):
        t = np.asarray(t, dtype=float)[:, None]
        c = self.c
        return (c[0] + c[1] * t + c[2] * t**2 + c[3] * t**3, c[1] + 2 * c[2] * t
                + 3 * c[3] * t**2, 2 * c[2] + 6 * c[3] * t)


def test_retimed_curve_is_the_base_at_s_of_t():
    """Poses are the base curve at t0 + s(t)·T with toppra's s(t); rates and accelerations
    are their time derivatives (central differences inside the intervals, seen 1e-7)."""
    base, t0, T = _Cubic(), 2.0, 3.0
    timing = type("Timing", (), {"t": _times(), "s": GRID, "s_dot": S_DOT})()
    curve = CA.RetimedCurve(base, t0, T, timing)
    times = np.linspace(0.0, timing.t[-1], 501)[1:-1]
    times = times[np.min(np.abs(times[:, None] - timing.t), axis=1) > 1e-3]
    s = _peer()(times)[:, 0]
    poses, rates, acc = curve(times)
    np.testing.assert_allclose(poses, base(t0 + s * T)[0], rtol=0, atol=1e-12)
    h = 1e-5
    lo, hi = curve(times - h), curve(times + h)
    np.testing.assert_allclose(rates, (hi[0] - lo[0]) / (2 * h), rtol=0, atol=1e-5)
    np.testing.assert_allclose(acc, (hi[1] - lo[1]) / (2 * h), rtol=0, atol=1e-4)
