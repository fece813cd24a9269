"""from_csv checks the derivative columns it is given against the positions, and refuses angle
wraps (docs: README, trajectory format)."""
import math
from pathlib import Path

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.io.trajectory import DERIVATIVE_TOLERANCE, from_csv, to_csv
from pollard_pin.paths import smooth_random_trajectory
from pollard_pin.paths.trajectory import Trajectory, TrajectoryError

FIGURE8 = Path(__file__).resolve().parents[2] / "examples" / "figure8.csv"


def _write(path, traj: Trajectory, columns=("", "d_", "dd_")):
    names = ["t"] + [p + n for p in columns for n in ("x", "y", "z", "psi", "theta", "phi")]
    arrays = {"": traj.poses, "d_": traj.d_poses, "dd_": traj.dd_poses}
    data = np.column_stack([traj.t] + [arrays[p] for p in columns])
    path.write_text(",".join(names) + "\n"
                    + "".join(",".join(repr(float(v)) for v in row) + "\n" for row in data))
    return path


def _rms_rel(a, b):  # an independent number: RMS of the column difference over the column's
    return np.sqrt(np.mean((a - b) ** 2)) / np.sqrt(np.mean(b ** 2))


@pytest.fixture(scope="module")
def figure8():
    return from_csv(FIGURE8)


def test_rates_in_degrees_are_refused(tmp_path, figure8):
    d, dd = figure8.d_poses.copy(), figure8.dd_poses.copy()
    d[:, 3], dd[:, 3] = np.degrees(d[:, 3]), np.degrees(dd[:, 3])
    bad = _write(tmp_path / "deg.csv", Trajectory(figure8.t, figure8.poses, d, dd))
    with pytest.raises(TrajectoryError, match=r"column d_psi disagrees with the positions by "
                                              r"5\d\.\d× .*expected rad/s"):
        from_csv(bad)
    # dd alone in degrees is caught by the rates it should integrate to
    bad = _write(tmp_path / "deg2.csv",
                 Trajectory(figure8.t, figure8.poses, figure8.d_poses, dd))
    with pytest.raises(TrajectoryError, match=r"column dd_psi disagrees with the d_\* rates"):
        from_csv(bad)


def test_zero_derivatives_are_refused(tmp_path, figure8):
    zero = np.zeros_like(figure8.d_poses)
    bad = _write(tmp_path / "zero.csv", Trajectory(figure8.t, figure8.poses, zero, zero))
    with pytest.raises(TrajectoryError, match=r"column d_y disagrees with the positions by 1×"):
        from_csv(bad)
    bad = _write(tmp_path / "zero_dd.csv",
                 Trajectory(figure8.t, figure8.poses, figure8.d_poses, zero))
    with pytest.raises(TrajectoryError, match="column dd_y is all zero while its rate changes"):
        from_csv(bad)
    bad = _write(tmp_path / "zero_d.csv", Trajectory(figure8.t, figure8.poses, zero, zero),
                 columns=("", "d_"))  # d_* alone: checked with the spline's accelerations
    with pytest.raises(TrajectoryError, match="column d_y disagrees"), pytest.warns(UserWarning):
        from_csv(bad)


@pytest.mark.parametrize("samples", [41, 401])
def test_exact_derivatives_pass(tmp_path, samples):
    """Exact derivatives of a smooth curve pass, even sparsely sampled; the achieved mismatch
    is far below the tolerance. Reference: the analytic rates vs central differences."""
    traj = smooth_random_trajectory(samples=samples)
    got = from_csv(_write(tmp_path / "exact.csv", traj))
    assert np.array_equal(got.d_poses, traj.d_poses)
    fd = np.gradient(traj.poses, traj.t, axis=0)[1:-1]
    assert _rms_rel(fd, traj.d_poses[1:-1]) < DERIVATIVE_TOLERANCE / 10  # 1.6e-3 at 41


def test_retimed_and_thesis_files_pass(tmp_path, figure8_sized):
    """The files the package writes itself (exact thesis derivatives, a TOPP-RA retiming with
    its piecewise-constant s̈) are accepted (figure8.csv's sizing: the session's,
    tests/examples_planned.py)."""
    from pollard_pin.io.retime import retimed_trajectory

    to_csv(pp.thesis_trajectory(samples=201), tmp_path / "thesis.csv")
    assert from_csv(tmp_path / "thesis.csv").derivatives == "file columns"
    traj, sized = figure8_sized
    to_csv(retimed_trajectory(traj, sized.timing), tmp_path / "retimed.csv")
    assert from_csv(tmp_path / "retimed.csv").derivatives == "file columns"


def test_angle_wrap_is_refused(tmp_path, figure8):
    poses = figure8.poses.copy()
    poses[:, 5] = 3.0 + 0.2 * np.sin(np.linspace(0.0, 6.0, len(poses)))
    wrapped = (poses[:, 5] + math.pi) % (2 * math.pi) - math.pi
    assert np.abs(np.diff(wrapped)).max() > 6  # the file really holds a wrap
    poses[:, 5] = wrapped
    bad = _write(tmp_path / "wrap.csv", Trajectory(figure8.t, poses, poses, poses),
                 columns=("",))
    first = int(np.argmax(np.abs(np.diff(wrapped)) > math.pi))
    with pytest.raises(TrajectoryError, match=rf"row {first + 3}, column 'phi': jumps by "
                                              r"-6\.2\d rad .*angle wrap"):
        from_csv(bad)
    # unwrapped, the same motion is accepted (and spins at its true, small rate)
    poses[:, 5] = np.unwrap(wrapped)
    with pytest.warns(UserWarning, match="quintic interpolating spline"):
        ok = from_csv(_write(tmp_path / "unwrapped.csv",
                             Trajectory(figure8.t, poses, poses, poses), columns=("",)))
    assert np.abs(ok.d_poses[:, 5]).max() < 1.0  # 0.2·6/6 s ≈ 0.2 rad/s, vs 460 wrapped


def test_the_spray_column_is_read_with_the_samples_and_written_back(tmp_path, figure8):
    """A paint program's trigger (``spray``) comes with its rows, each value exact, and goes
    back out with them; a file without one has none."""
    spray = np.where(np.arange(len(figure8)) % 7 < 3, 0.0, 1.0)
    spray[5] = 0.25
    to_csv(figure8, tmp_path / "p.csv", spray=spray)
    got = from_csv(tmp_path / "p.csv")
    assert np.array_equal(got.spray, spray) and np.array_equal(got.poses, figure8.poses)
    to_csv(got, tmp_path / "q.csv")  # its own spray, unless told otherwise
    assert (tmp_path / "q.csv").read_text() == (tmp_path / "p.csv").read_text()
    assert figure8.spray is None


def test_carried_metadata_is_the_robots_entries_checked(tmp_path):
    """carried_metadata: the sidecar's frame, robot and gravity_base (checked: booleans and
    a gravity off by more than 10 % are one line), nothing else; none without a sidecar."""
    import json

    import pollard_pin as pp
    from pollard_pin.errors import InputError
    from pollard_pin.io.trajectory import carried_metadata

    path = tmp_path / "p.csv"
    pp.to_csv(pp.thesis_trajectory(samples=5), path)
    side = path.with_name("p.units.json")
    base = json.loads(side.read_text())
    assert carried_metadata(path) == {}
    base["metadata"].update(frame="f", robot={"name": "a"}, gravity_base=[0, 0, 9.81])
    side.write_text(json.dumps(base))
    assert carried_metadata(path) == {"frame": "f", "robot": {"name": "a"},
                                      "gravity_base": [0.0, 0.0, 9.81]}
    base["metadata"]["gravity_base"] = [True, 0, -9.81]
    side.write_text(json.dumps(base))
    with pytest.raises(InputError, match="gravity_base.*not booleans"):
        carried_metadata(path)
    assert carried_metadata(tmp_path / "none.csv") == {}


@pytest.mark.parametrize("path", [3, None, ""])
def test_from_csv_refuses_what_names_no_file(path):
    with pytest.raises(TrajectoryError, match="^path = .*: (expected a file path|an empty path)"):
        from_csv(path)


def test_to_csv_refuses_what_is_not_a_trajectory(tmp_path):
    with pytest.raises(TrajectoryError, match="^traj = 'x': expected a Trajectory, got str$"):
        to_csv("x", tmp_path / "x.csv")
    assert list(tmp_path.iterdir()) == []


def test_to_csv_refuses_a_spray_from_csv_cannot_read(tmp_path):
    traj = pp.thesis_trajectory(samples=5)
    with pytest.raises(TrajectoryError, match=r"spray\[1\] = 2 is outside \[0, 1\]"):
        to_csv(traj, tmp_path / "x.csv", spray=[0.0, 2.0, 1.0, 1.0, 0.0])
    assert list(tmp_path.iterdir()) == []
    to_csv(traj, tmp_path / "ok.csv", spray=[0.0, 0.5, 1.0, 1.0, 0.0])
    assert from_csv(tmp_path / "ok.csv").spray.tolist() == [0.0, 0.5, 1.0, 1.0, 0.0]


@pytest.mark.parametrize("text, says", [
    # the header's field over the csv module's limit, on line 1 (it was said to be line 2)
    ("t," + "x" * 200_000 + "\n0,1\n", "line 1: not CSV (field larger than field limit"),
    ("t,x\n0,\"" + "y" * 200_000 + "\"\n", "line 2: not CSV (field larger than field limit"),
    # the column given twice named, with where (it was the whole header, cut)
    ("t,x,y,z,psi,theta,phi,y\n0,0.5,0,0.1,0,0,0,0\n", "duplicate column 'y' (columns 3 and 8)"),
])
def test_malformed_csv_names_the_line_and_the_column(tmp_path, text, says):
    bad = tmp_path / "bad.csv"
    bad.write_text(text)
    with pytest.raises(TrajectoryError) as info:
        from_csv(bad)
    assert says in str(info.value) and "\n" not in str(info.value), str(info.value)
