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


def test_wait_then_strokes_rests_then_moves_with_consistent_derivatives():
    """The wait is at rest on the curve's start; the moving part's rates and accelerations
    are its poses' exact derivatives: central differences miss them by a truncation error
    that falls as h² (ratio 4.00 when the step halves, achieved to 1e-3; a wrong derivative
    would leave an error that does not shrink)."""
    from pollard_pin.paths.curves import wait_then_strokes

    errors = []
    for n, dt in ((4000, 2e-3), (8000, 1e-3)):  # the same 8 s
        tr = wait_then_strokes(n, dt=dt)
        still = int(0.47 * n)
        assert np.all(tr.d_poses[:still] == 0) and np.all(tr.dd_poses[:still] == 0)
        assert np.all(tr.poses[:still] == tr.poses[still])  # at rest where the strokes begin
        q, h = tr.poses[still:], dt
        dq = (q[2:] - q[:-2]) / (2 * h)
        ddq = (q[2:] - 2 * q[1:-1] + q[:-2]) / h**2
        errors.append([np.abs(dq - tr.d_poses[still + 1:-1]).max(),
                       np.abs(ddq - tr.dd_poses[still + 1:-1]).max()])
    ratio = np.array(errors[0]) / np.array(errors[1])
    np.testing.assert_allclose(ratio, 4.0, rtol=0.05)


@pytest.mark.parametrize("duration, says", [
    # 1e308 s: plot's axes overflowed (a RuntimeWarning), size's dynamics made NaN; a file's
    # times beyond 1e6 s were refused (pollard_pin.io.trajectory), the thesis curve's not
    (1e308, "duration 1e+308 s is beyond 1e+06 s (seconds, not ms?)"),
    (1.5e6, "duration 1.5e+06 s is beyond 1e+06 s"),
    (5e-324, "duration 5e-324 s is too short"),
])
def test_an_absurd_thesis_duration_is_refused(duration, says):
    from pollard_pin.paths.trajectory import TrajectoryError

    with pytest.raises(TrajectoryError) as info:
        thesis_trajectory(duration=duration, samples=11)
    assert str(info.value).startswith(says), str(info.value)
    with pytest.raises(TrajectoryError):  # the streamed one checks the same
        ThesisTrajectory(duration=duration, samples=11)
    assert len(thesis_trajectory(duration=1e6, samples=11)) == 11  # the limit itself is taken
