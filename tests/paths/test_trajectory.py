"""The trajectory type and its curve (pollard_pin.paths.trajectory)."""
import pickle
from dataclasses import replace

import numpy as np
import pytest

from pollard_pin.paths.curves import thesis_curve, thesis_trajectory
from pollard_pin.paths.splines import QuinticHermite
from pollard_pin.paths.trajectory import Trajectory, TrajectoryError, trajectory_curve


def test_shapes_are_checked_and_windows_are_views():
    t = np.linspace(0.0, 1.0, 5)
    with pytest.raises(TrajectoryError, match=r"d_poses has shape \(4, 6\), expected \(5, 6\)"):
        Trajectory(t, np.zeros((5, 6)), np.zeros((4, 6)), np.zeros((5, 6)))
    traj = thesis_trajectory(samples=11)
    w = traj.window(3, 7)
    assert len(w) == 4 and w.curve is traj.curve and np.shares_memory(w.poses, traj.poses)
    assert [s for s, _ in traj.windows(4)] == [0, 4, 8]
    spray = np.array([0.0, 1, 1, 0.5, 0])
    assert np.array_equal(replace(traj.window(0, 5), spray=spray).window(1, 4).spray,
                          [1, 1, 0.5])
    with pytest.raises(TrajectoryError, match=r"spray has shape \(4,\), expected \(5,\)"):
        Trajectory(t, *np.zeros((3, 5, 6)), spray=np.zeros(4))


def test_the_curve_is_the_trajectorys_own_else_the_hermite_through_its_samples():
    """The thesis trajectory's curve is the analytic curve (bit for bit); without one, the
    quintic Hermite through the samples, exact at them; either pickles."""
    traj = thesis_trajectory(samples=201)
    t = np.linspace(0.0, 20.0, 333)
    for got, want in zip(pickle.loads(pickle.dumps(trajectory_curve(traj)))(t),
                         thesis_curve(t)):
        np.testing.assert_array_equal(got, want)
    bare = replace(traj, curve=None)
    curve = pickle.loads(pickle.dumps(trajectory_curve(bare)))
    assert isinstance(curve, QuinticHermite)
    for got, want in zip(curve(traj.t), (traj.poses, traj.d_poses, traj.dd_poses)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)


@pytest.mark.parametrize("field, value, says", [
    ("poses", np.full((3, 6), 0.5 + 1j), "poses = .*got complex128 values"),  # was cast
    ("t", [0.0, 1.0, 10**400], "t = .*expected an array of real numbers"),
    ("t", np.zeros((3, 1)), r"t has shape \(3, 1\), expected \(N,\)"),
    ("d_poses", "abc", "d_poses = 'abc': expected an array of real numbers"),
], ids=["complex", "1e400", "2-D t", "str"])
def test_a_trajectory_of_what_is_not_real_numbers_is_refused(field, value, says):
    args = {"t": [0.0, 1.0, 2.0], "poses": np.zeros((3, 6)), "d_poses": np.zeros((3, 6)),
            "dd_poses": np.zeros((3, 6)), field: value}
    with pytest.raises(TrajectoryError, match="^trajectory: " + says):
        Trajectory(**args)


def test_a_trajectory_keeps_float_arrays_as_given():
    t, p = np.arange(3.0), np.zeros((3, 6))
    traj = Trajectory(t, p, p, p)
    assert traj.t is t and traj.poses is p  # no copy: a window stays a view
    assert Trajectory([0, 1, 2], p, p, p).t.dtype == np.float64


@pytest.mark.parametrize("spray, says", [
    (np.full(3, np.nan), r"spray\[0\] = nan is outside \[0, 1\]"),
    ([0.0, 1.0, 2.0], r"spray\[2\] = 2 is outside \[0, 1\]"),
    (np.full(3, 1j), "spray = .*got complex128 values"),
    ([10**400] * 3, "spray = .*expected an array of real numbers"),
], ids=["nan", "2", "complex", "1e400"])
def test_a_spray_outside_its_range_is_refused(spray, says):
    """As from_csv refuses it: to_csv must not write what from_csv cannot read."""
    p = np.zeros((3, 6))
    with pytest.raises(TrajectoryError, match="^trajectory: " + says):
        Trajectory([0.0, 1.0, 2.0], p, p, p, spray=spray)


@pytest.mark.parametrize("field, index, value, says", [
    ("poses", (4, 3), np.nan, "sample 4: psi = nan is not a finite number (poses[4, 3])"),
    ("d_poses", (2, 0), np.inf, "sample 2: d_x = inf is not a finite number (d_poses[2, 0])"),
    ("dd_poses", (9, 5), -np.inf, "sample 9: dd_phi = -inf is not a finite number "
                                  "(dd_poses[9, 5])"),
    ("t", (3,), np.nan, "sample 3: t = nan is not a finite number (t[3])"),
], ids=["nan pose", "inf rate", "-inf acceleration", "nan time"])
def test_a_value_that_is_not_finite_is_refused_naming_its_sample_and_column(field, index,
                                                                            value, says):
    """Said when the trajectory is made (the old one took it, and the IK refused it later)."""
    traj = thesis_trajectory(samples=11)
    arrays = {n: getattr(traj, n).copy() for n in ("t", "poses", "d_poses", "dd_poses")}
    arrays[field][index] = value
    arrays[field][-1] = value  # the first bad sample is named
    with pytest.raises(TrajectoryError) as e:
        Trajectory(arrays["t"], arrays["poses"], arrays["d_poses"], arrays["dd_poses"])
    assert str(e.value) == f"trajectory: {says}"
