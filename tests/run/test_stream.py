"""The streaming run (run/stream.py): window by window it writes the rows of the
whole-trajectory solve (to round-off: numpy's vectorised sin/cos may round the last bit
differently at other array offsets), CSV or Parquet, with units and metadata; errors count
samples from the trajectory's start; a failure leaves an existing output untouched."""
import json
import re

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.io.table import read_result, units_path
from pollard_pin.kinematics.errors import SingularityError
from pollard_pin.paths.curves import ThesisTrajectory, thesis_trajectory
from pollard_pin.paths.trajectory import Trajectory
from pollard_pin.run import StreamOptions, stream_run, write_run_table

# A pose exactly on leg 2's reach boundary (tests/kinematics/test_solver_edges.py): singular.
ROUND_OFF = 1e-13  # × max(1, column peak)
EDGE = np.array([0.5479217373830817, -0.14140430553739233, 0.2619590809778902,
                 0.1515515281768794, 0.34846838034929445, 0.04014162356854648])


def _whole(robot, path, samples):
    write_run_table(pp.run_pipeline(robot, thesis_trajectory(samples=samples)), path)
    return read_result(path)


@pytest.fixture(scope="module")
def whole(robot, tmp_path_factory):
    return _whole(robot, tmp_path_factory.mktemp("whole") / "whole.csv", 1201)


@pytest.mark.parametrize("chunk, workers", [(2, 1), (97, 1), (500, 1), (1201, 1), (5000, 1),
                                            (97, 3), (500, 2)])
def test_windows_give_the_whole_solve(robot, whole, tmp_path, chunk, workers):
    # 2-sample windows on 121 samples, not 1201 (600 windows' overhead, ~5 s): as many kinds
    # of window edges, a tenth of them
    n = 121 if chunk == 2 else 1201
    ref = _whole(robot, tmp_path / "whole.csv", n) if n != 1201 else whole
    path = tmp_path / "s.csv"
    stats = stream_run(robot, ThesisTrajectory(samples=n), path,
                       StreamOptions(chunk=chunk, workers=workers))
    got = read_result(path)
    assert list(got.columns) == list(ref.columns) and len(got) == n == stats.samples
    _same(got, ref)


def _same(got, ref):
    for name, col in ref.columns.items():  # work carried across windows too
        scale = max(1.0, np.abs(col).max())
        assert np.abs(got[name] - col).max() <= ROUND_OFF * scale, name


def test_parquet_round_trip_units_and_metadata(robot, whole, tmp_path):
    path = tmp_path / "s.parquet"
    meta = {"trajectory": {"name": "thesis", "samples": 1201}, "pollard_pin": pp.__version__}
    stream_run(robot, ThesisTrajectory(samples=1201), path, StreamOptions(chunk=300),
               metadata=meta)
    got = read_result(path)
    _same(got, whole)
    assert got.metadata == meta
    assert got.units["tau_theta21"] == "N·m" and got.units["d_theta43"] == "rad/s"
    assert got.units["x"] == "m" and got.units["f1_z"] == "N"
    assert not units_path(path).exists()  # Parquet carries its own units


def test_csv_sidecar_names_every_column(robot, tmp_path):
    path = tmp_path / "s.csv"
    stream_run(robot, ThesisTrajectory(samples=50), path, metadata={"k": 1})
    side = json.loads(units_path(path).read_text(encoding="utf-8"))
    header = path.read_text().splitlines()[0].split(",")
    assert list(side["units"]) == header and side["metadata"] == {"k": 1}
    assert all(side["units"].values())


def _with_singular_sample(k, n=1201):
    traj = thesis_trajectory(samples=n)
    poses, d, dd = traj.poses.copy(), traj.d_poses.copy(), traj.dd_poses.copy()
    poses[k], d[k], dd[k] = EDGE, 0.0, 0.0
    return Trajectory(traj.t, poses, d, dd, name="edge")


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize("k", [0, 299, 300, 301, 1000, 1200])
def test_errors_count_samples_from_the_start(robot, tmp_path, k, workers):
    traj = _with_singular_sample(k)
    with pytest.raises(SingularityError) as whole:
        pp.run_pipeline(robot, traj)
    path = tmp_path / "s.csv"
    path.write_text("keep me\n")
    with pytest.raises(SingularityError) as streamed:
        stream_run(robot, traj, path, StreamOptions(chunk=300, workers=workers))
    assert whole.value.sample == streamed.value.sample == k
    assert whole.value.chain == streamed.value.chain
    # the same message; σ at round-off level (≈ 1e-17) need not have the same bits
    number = re.compile(r"\d\.\d+e-1\d")
    assert number.sub("σ", str(streamed.value)) == number.sub("σ", str(whole.value))
    assert streamed.value.time == whole.value.time == traj.t[k]
    assert path.read_text() == "keep me\n"  # untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.csv"]


def test_memory_is_one_window(robot, tmp_path, monkeypatch):
    # Bounded memory: the pipeline never sees more than one window, and the lazy thesis
    # trajectory never builds the whole time grid.
    import pollard_pin.run.stream as results

    seen = []
    real = results.run_pipeline
    monkeypatch.setattr(results, "run_pipeline",
                        lambda robot, traj, **kw: seen.append(len(traj)) or real(robot, traj, **kw))
    traj = ThesisTrajectory(samples=5001)
    stats = stream_run(robot, traj, tmp_path / "s.parquet", StreamOptions(chunk=1000))
    assert stats.samples == 5001 and max(seen) == 1000 and sum(seen) == 5001 + len(seen) - 1
    assert not hasattr(traj, "t")


def test_first_error_in_order_with_threads(robot, tmp_path):
    # Two bad samples in different windows: the earlier one is reported, whichever thread
    # finished first.
    traj = _with_singular_sample(1100)
    poses = traj.poses.copy()
    poses[400] = EDGE
    traj = Trajectory(traj.t, poses, traj.d_poses, traj.dd_poses, name="edge")
    with pytest.raises(SingularityError) as ei:
        stream_run(robot, traj, tmp_path / "s.csv", StreamOptions(chunk=300, workers=3))
    assert ei.value.sample == 400


def test_worker_robots_do_not_share_pinocchio_data(robot):
    from pollard_pin.run.stream import worker_robot

    other = worker_robot(robot)
    assert other.model is robot.model and other.data is not robot.data
    assert all(a is not b for a, b in zip(other.constraint_datas, robot.constraint_datas))


def test_unwritable_sidecar_leaves_the_table_untouched(robot, tmp_path):
    # the sidecar was checked only after the CSV had replaced the old one
    from pollard_pin.io.atomic import OutputError

    out = tmp_path / "r.csv"
    out.write_text("precious\n")
    units_path(out).mkdir()
    with pytest.raises(OutputError, match=r"r\.units\.json: is a folder"):
        stream_run(robot, ThesisTrajectory(samples=11), out)
    assert out.read_text() == "precious\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.csv", "r.units.json"]


def test_cli_window_size_is_the_streaming_window():
    # the CLI keeps its own copy (importing pollard_pin.run would slow --help): they must agree.
    from pollard_pin.cli.run import STREAM_WINDOW
    from pollard_pin.run import stream as results

    assert STREAM_WINDOW == results.STREAM_CHUNK


@pytest.mark.parametrize("kw, says", [({"chunk": 1}, "chunk must be an integer >= 2, got 1"),
                                      ({"chunk": 2.0}, "chunk must be an integer >= 2"),
                                      ({"workers": 0}, "workers must be an integer >= 1"),
                                      # shown short, not in 401 digits
                                      ({"chunk": -10**400}, r"got -1e\+400 \(a 401-digit"),
                                      ({"workers": -10**400}, r"got -1e\+400 \(a 401-digit")],
                         ids=["chunk 1", "chunk 2.0", "workers 0", "chunk huge", "workers huge"])
def test_stream_options_refuse_bad_values_before_any_work(kw, says):
    from pollard_pin.errors import InputError

    with pytest.raises(InputError, match=says):
        StreamOptions(**kw)


def test_stream_run_refuses_wrong_arguments_before_writing(robot, tmp_path):
    """A dict for the options, a string for the trajectory, None for the robot: one
    InputError line (not an AttributeError from inside), and no file written."""
    traj = thesis_trajectory(samples=11)
    out = tmp_path / "run.csv"
    for args, says in (((robot, traj, out, {}), "^stream = {}: expected StreamOptions"),
                       ((robot, "x", out), "^traj = 'x': expected a Trajectory"),
                       ((None, traj, out), "^robot = None: expected a Robot")):
        with pytest.raises(pp.InputError, match=says):
            stream_run(*args)
    for kw, says in (({"progress": "x"}, "^progress = 'x': expected a function or None"),
                     ({"metadata": "x"}, "^metadata = 'x': expected a dict or None")):
        with pytest.raises(pp.InputError, match=says):
            stream_run(robot, traj, out, **kw)
    assert list(tmp_path.iterdir()) == []
