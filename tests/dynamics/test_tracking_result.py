"""The result of a closed-loop run (docs/model.md §18): its summary's RMS errors are
time-weighted (docs/model.md §13)."""
import numpy as np
import pytest
from thesis_curves import thesis_head

from pollard_pin.dynamics.tracking import TrackingOptions, simulate_tracking
from pollard_pin.paths.trajectory import Trajectory


def test_tracking_rms_is_time_weighted(robot):
    """Uneven output samples: the summary's RMS is √(∫e² dt / T) by the trapezoid rule (a
    quadrature written out here), not the plain mean over rows."""
    traj = thesis_head(0.3)
    keep = np.r_[0:10, 10:31:5]  # 10 ms samples, then 50 ms
    uneven = Trajectory(traj.t[keep], traj.poses[keep], traj.d_poses[keep],
                        traj.dd_poses[keep], name="uneven")
    res = simulate_tracking(robot, uneven, TrackingOptions("pd"))
    t, e = res.t, res.tip_position_error
    by_hand = np.sqrt(np.sum(0.5 * (e[1:] ** 2 + e[:-1] ** 2) * np.diff(t)) / (t[-1] - t[0]))
    s = res.summary()
    assert s["rms_tip_position_error"] == pytest.approx(by_hand, rel=1e-13)
    assert abs(np.sqrt(np.mean(e**2)) / by_hand - 1) > 0.05  # rows would weigh differently
