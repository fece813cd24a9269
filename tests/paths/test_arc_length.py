"""The arc-length re-parameterisation (paths/arc_length.py) against closed forms: a straight
line timed unevenly is σ linear in the distance at unit scaled speed, and the same path
sampled or timed otherwise gives the same curve; stops are refused."""
import numpy as np
import pytest

from pollard_pin.paths.arc_length import arc_length_path


def _line(t):
    """A straight segment in x (0.2 m) with a fixed roll change (0.5 rad), timed by the smooth
    step s(t) = 3t² − 2t³ on [0, 1]: at rest at both ends, never inside."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    s, ds, dds = 3 * t**2 - 2 * t**3, 6 * t - 6 * t**2, 6 - 12 * t
    d = np.array([0.2, 0.0, 0.0, 0.5, 0.0, 0.0])
    home = np.array([0.55, 0.0, 0.16, 0.0, 0.0, 0.0])
    return home + s[:, None] * d, ds[:, None] * d, dds[:, None] * d


def test_a_straight_path_is_parameterised_by_its_scaled_distance():
    """Scaled by their ranges (0.2 m, 0.5 rad) both moving coordinates run 0 → 1, so the
    length is √2 (achieved 2.4e-15, asserted 1e-13), the path at σ is home + (σ/√2)·d
    (1.5e-15, asserted 1e-13) at unit scaled speed (3.6e-9, asserted 4e-7), and the grid,
    curvature-weighted, is even in σ (2.3e-8, asserted 3e-6). The spline's second derivative
    is not checked: through 6,400 knots it carries round-off of order 1e-2 per unit σ², which
    √(1 + κ) barely feels."""
    arc = arc_length_path(_line, np.linspace(0.0, 1.0, 11))
    assert abs(arc.length - np.sqrt(2.0)) < 1e-13
    sigma = np.linspace(0.0, arc.length, 37)
    p, dp, _ = arc(sigma)
    want, _, _ = _line(np.zeros(1))
    d = np.array([0.2, 0.0, 0.0, 0.5, 0.0, 0.0])
    np.testing.assert_allclose(p, want + (sigma / np.sqrt(2.0))[:, None] * d, atol=1e-13)
    np.testing.assert_allclose(np.linalg.norm(dp / arc.scale, axis=1), 1.0, atol=4e-7)
    np.testing.assert_allclose(arc.grid(21), np.linspace(0.0, 1.0, 21), atol=3e-6)


def test_the_same_path_whatever_the_samples():
    """11 or 301 samples of the same timed path: the same arc-length curve (achieved 2.6e-15
    m and rad, asserted 1e-13)."""
    a, b = (arc_length_path(_line, np.linspace(0.0, 1.0, n)) for n in (11, 301))
    sigma = np.linspace(0.0, a.length, 50)
    np.testing.assert_allclose(a(sigma)[0], b(sigma)[0], atol=1e-13)


def test_a_path_that_stops_inside_or_stands_still_has_no_arc_length():
    def back_and_forth(t):  # x = sin(2πt)·0.1: stops at t = 1/4 and 3/4 and turns back
        t = np.atleast_1d(np.asarray(t, dtype=float))
        p = np.zeros((len(t), 6))
        v, a = np.zeros_like(p), np.zeros_like(p)
        w = 2 * np.pi
        p[:, 0], v[:, 0], a[:, 0] = 0.1 * np.sin(w * t), 0.1 * w * np.cos(w * t), \
            -0.1 * w * w * np.sin(w * t)
        return p, v, a

    def still(t):
        z = np.zeros((len(np.atleast_1d(t)), 6))
        return z, z, z

    t = np.linspace(0.0, 1.0, 41)
    assert arc_length_path(back_and_forth, t) is None
    assert arc_length_path(still, t) is None


def test_a_densely_sampled_rest_end_is_no_stop_inside():
    """10⁵ samples of the smooth-step line: the knots next to its rest ends move 1e-10 of its
    top speed (below STOP) and are no stop; their chords, 1e-11 long, are thinned so that the
    spline through them stays the line (achieved 1.5e-14 on the length, 9e-15 on the poses;
    asserted 1e-12). A path that stops inside is still refused (above)."""
    arc = arc_length_path(_line, np.linspace(0.0, 1.0, 100_001))
    assert arc is not None and abs(arc.length - np.sqrt(2.0)) < 1e-12
    sigma = np.linspace(0.0, arc.length, 37)
    want, _, _ = _line(np.zeros(1))
    d = np.array([0.2, 0.0, 0.0, 0.5, 0.0, 0.0])
    np.testing.assert_allclose(arc(sigma)[0], want + (sigma / np.sqrt(2.0))[:, None] * d,
                               atol=1e-12)


def test_a_moving_path_is_the_curve_itself_at_its_arc_length():
    """A path moving at both ends (a circle arc in y-z, at speed varying 1 : 3) is the curve
    at u(σ): on the circle to round-off, at unit scaled speed (achieved 2.6e-12, asserted
    3e-10), its length the circle's (2e-16 relative, asserted 1e-13)."""
    def arc_curve(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        a, da, dda = t + t**2, 1 + 2 * t, 2 + 0 * t  # angle along the arc, 0 → 2 rad
        p, v, acc = (np.zeros((len(t), 6)) for _ in range(3))
        p[:, 1], p[:, 2] = 0.1 * np.cos(a), 0.1 * np.sin(a)
        v[:, 1], v[:, 2] = -0.1 * np.sin(a) * da, 0.1 * np.cos(a) * da
        acc[:, 1] = -0.1 * np.cos(a) * da**2 - 0.1 * np.sin(a) * dda
        acc[:, 2] = -0.1 * np.sin(a) * da**2 + 0.1 * np.cos(a) * dda
        return p, v, acc

    arc = arc_length_path(arc_curve, np.linspace(0.0, 1.0, 11))
    scale = arc.scale[1]  # the largest range of y, z
    assert arc.length == pytest.approx(0.1 * 2.0 / scale, rel=1e-13)
    p, dp, _ = arc(np.linspace(0.0, arc.length, 101))
    np.testing.assert_allclose(np.hypot(p[:, 1], p[:, 2]), 0.1, atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(dp / arc.scale, axis=1), 1.0, atol=3e-10)
