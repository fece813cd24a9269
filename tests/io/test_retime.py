"""A trajectory retimed along its own path (io/retime.py): with a timing whose s(t) is known in
closed form (s = (t/D)², constant s̈), the retimed samples are the path at s(t) with the chain
rule's rates, checked against central differences of the retimed curve between the samples."""
import numpy as np
import pytest

from pollard_pin.dynamics.timeopt import TimeOptimal
from pollard_pin.io.retime import retimed_trajectory
from pollard_pin.paths.curves import thesis_trajectory

D = 7.0  # s: the new duration


@pytest.fixture(scope="module")
def traj():
    return thesis_trajectory(samples=201)  # 20 s


def _timing(traj):
    s = (traj.t - traj.t[0]) / (traj.t[-1] - traj.t[0])  # the path's own grid
    t = D * np.sqrt(s)  # s = (t/D)²: ṡ = 2t/D², s̈ = 2/D² everywhere
    return TimeOptimal(s=s, t=t, s_dot=2 * t / D**2, s_ddot=np.full_like(s, 2 / D**2),
                       iterations=1)


def test_samples_are_the_path_at_the_new_times(traj):
    r = retimed_trajectory(traj, _timing(traj))
    assert r.t[-1] == pytest.approx(D) and np.array_equal(r.poses, traj.poses)
    T = traj.t[-1] - traj.t[0]
    sd = (2 * r.t / D**2)[:, None]
    assert np.abs(r.d_poses - T * traj.d_poses * sd).max() < 1e-15
    assert r.name == f"{traj.name}_time_optimal"


def test_rates_and_curve_against_central_differences(traj):
    """Between the samples the curve is the path at s(t) = (t/D)² exactly (s̈ constant); its
    central differences (h = 1e-5) give the retimed rates (achieved 4.9e-8 m/s, rad/s) and
    accelerations (achieved 4.4e-7 of their peak)."""
    r = retimed_trajectory(traj, _timing(traj))
    times = np.linspace(0.3, D - 0.3, 37)
    p, v, a = r.curve(times)
    base = traj.curve(traj.t[0] + (times / D) ** 2 * (traj.t[-1] - traj.t[0]))[0]
    assert np.abs(p - base).max() < 1e-12
    h = 1e-5
    pp_, pm = r.curve(times + h)[0], r.curve(times - h)[0]
    assert np.abs((pp_ - pm) / (2 * h) - v).max() < 5e-6
    assert np.abs((pp_ - 2 * p + pm) / h**2 - a).max() < 5e-5 * np.abs(a).max()
    # at the samples the curve is the retimed trajectory
    k = [10, 100, 150]
    cp, cv, ca = r.curve(r.t[k])
    assert np.abs(cv - r.d_poses[k]).max() < 1e-12 and np.abs(ca - r.dd_poses[k]).max() < 1e-10


def test_a_timing_of_another_length_is_refused(traj):
    tim = _timing(thesis_trajectory(samples=11))
    with pytest.raises(ValueError, match="timing has 11 samples, the trajectory 201"):
        retimed_trajectory(traj, tim)
