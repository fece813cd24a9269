"""The analytic curves (pollard_pin.paths.curves): exact derivatives against finite
differences, the thesis curve's end points (docs/model.md §9)."""
import numpy as np
import pytest

from pollard_pin.paths.curves import (
    ThesisTrajectory,
    sinusoid_curve,
    thesis_curve,
    thesis_trajectory,
)


@pytest.mark.parametrize("curve", [thesis_curve, sinusoid_curve])
def test_rates_and_accelerations_are_the_derivatives(curve):
    """Central differences, h = 1e-4 s (seen 5e-8 relative to the largest value)."""
    t, h = np.linspace(0.3, 19.7, 301), 1e-4
    lo, mid, hi = curve(t - h), curve(t), curve(t + h)
    for k in (1, 2):
        fd = (hi[k - 1] - lo[k - 1]) / (2 * h)
        np.testing.assert_allclose(mid[k], fd, rtol=0, atol=5e-6 * np.abs(mid[k]).max())


def test_thesis_curve_ends_and_lazy_windows():
    """u runs from −60π to 60π mm: x = −0.001u² mm off home at both ends, y = ±60π mm; the
    lazy trajectory's windows are the slices of the eager one, bit for bit."""
    poses, _, _ = thesis_curve([0.0, 20.0])
    u = 60 * np.pi
    np.testing.assert_allclose(poses[:, 0], 0.55 - 0.001 * u**2 * 1e-3, rtol=0, atol=1e-15)
    np.testing.assert_allclose(poses[:, 1], [-u * 1e-3, u * 1e-3], rtol=0, atol=1e-15)
    eager, lazy = thesis_trajectory(samples=101), ThesisTrajectory(samples=101)
    for start, w in lazy.windows(30):
        np.testing.assert_array_equal(w.t, eager.t[start:start + 30])
        np.testing.assert_array_equal(w.dd_poses, eager.dd_poses[start:start + 30])
