"""``pollard-pin run`` (cli/run.py): its CSV against the pipeline and the IK column by
column, CSV trajectories with and without derivative columns, Parquet, ``--loads``, and
failures that write nothing."""
import json
import warnings

import numpy as np
import pytest
from ik_runs import solve, wrap
from poses import wrist_singular_pose  # tests/poses.py

import pollard_pin as pp
from pollard_pin.cli import main
from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv, to_csv
from pollard_pin.names import SPHERICAL
from pollard_pin.paths.curves import smooth_random_trajectory, thesis_trajectory
from pollard_pin.paths.trajectory import Trajectory
from pollard_pin.run import run_pipeline

TASK = ("x", "y", "z", "psi", "theta", "phi")
HEADER = "t,x,y,z,psi,theta,phi"
ROUND_OFF = 1e-13  # × max(1, column peak): a streamed run against the whole solve


def write_poses_csv(path, t, poses):
    np.savetxt(path, np.column_stack([t, poses]), delimiter=",", header=HEADER, comments="",
               fmt="%.17g")
    return path


def read_out(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return dict(zip(header, data.T)), header


def _expected_columns(robot):
    tree = list(robot.joint_names)
    assert tree[0] == "theta21" and tree[-1] == "theta76_2"
    sph = [f"{a}_{i}" for i in (1, 2) for a in ("theta98", "theta109", "theta1110")]
    return (["t", *TASK, *tree, *sph], [f"d_{n}" for n in tree], [f"dd_{n}" for n in tree],
            ["wrist_margin", "sigma_parallel", "sigma_serial"])


def _check_run_output(robot, out, traj):
    cols, header = read_out(out)
    first, d, dd, diag = _expected_columns(robot)
    assert header[:len(first)] == first
    for name in d + dd + diag:
        assert name in cols, name
    assert len(cols["t"]) == len(traj)
    ik = solve(robot, traj)
    assert np.array_equal(cols["t"], traj.t)
    for i, n in enumerate(TASK):
        assert np.array_equal(cols[n], traj.poses[:, i])
    # The file round-trips the floats, so the columns are the IK's own to round-off (achieve 0).
    def same(col, want, angle=False):
        err = wrap(col - want) if angle else col - want
        return np.abs(err).max() <= 1e-14 * max(1.0, np.abs(want).max())

    for i, n in enumerate(robot.joint_names):
        assert same(cols[n], ik.q[:, i], angle=True), n
        assert same(cols[f"d_{n}"], ik.v[:, i]), n
        assert same(cols[f"dd_{n}"], ik.a[:, i]), n
    for i, n in enumerate(SPHERICAL):
        assert same(cols[n], ik.spherical[:, i], angle=True), n
        assert same(cols[f"d_{n}"], ik.d_spherical[:, i]), n

    for n in diag:
        assert np.allclose(cols[n], getattr(ik, n), rtol=1e-14, atol=0), n
    # Exactly what the pipeline computes (%.17g round-trips doubles).
    ref = run_pipeline(robot, traj).columns()
    assert list(ref) == header
    for n in header:
        assert np.array_equal(cols[n], ref[n]), n
    return cols


def test_cli_run_thesis_trajectory(robot, tmp_path, capsys):
    out = tmp_path / "thesis.csv"
    rc = main(["run", "--samples", "201", "--out", str(out), "--quiet"])
    assert rc == 0
    assert f"wrote {out} (201 rows)" in capsys.readouterr().err
    traj = thesis_trajectory(samples=201, home_pose=robot.params.home_pose)
    _check_run_output(robot, out, traj)
    # no temp leftovers
    assert sorted(p.name for p in tmp_path.iterdir()) == ["thesis.csv", "thesis.units.json"]


def test_cli_run_csv_trajectory(robot, tmp_path, capsys):
    src = tmp_path / "traj.csv"
    traj = smooth_random_trajectory(5, samples=151)
    to_csv(traj, src)
    out = tmp_path / "run.csv"
    assert main(["run", "--trajectory", str(src), "--out", str(out), "--quiet"]) == 0
    _check_run_output(robot, out, from_csv(src))
    capsys.readouterr()
    # Without derivative columns the run still works and says where the derivatives came from.
    bare = write_poses_csv(tmp_path / "bare.csv", traj.t, traj.poses)
    out2 = tmp_path / "run2.csv"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the CLI says it once, as a note, not as a warning
        assert main(["run", "--trajectory", str(bare), "--out", str(out2), "--quiet"]) == 0
    err = capsys.readouterr().err
    # Notes come after the work (an error would be the only line), once.
    notes = [ln for ln in err.splitlines() if ln.startswith("note: ")]
    assert err.count("spline") == 1 and notes[0].startswith(f"note: {bare}: no d_*/dd_*"), err
    with pytest.warns(UserWarning):
        _check_run_output(robot, out2, from_csv(bare))


@pytest.mark.parametrize("kind", ["unreachable", "malformed", "singular"])
def test_cli_run_failure_writes_nothing(robot, tmp_path, capsys, kind):
    traj = smooth_random_trajectory(5, samples=101)
    poses = traj.poses.copy()
    d, dd = traj.d_poses, traj.dd_poses
    if kind == "unreachable":
        poses[60:, 0] += 1.0
    elif kind == "singular":
        poses[:] = wrist_singular_pose(robot.params)
        d, dd = np.zeros_like(d), np.zeros_like(dd)  # still: rates that match the poses
    src = tmp_path / "in.csv"
    to_csv(Trajectory(traj.t, poses, d, dd), src)
    if kind == "unreachable":  # a jump has no rates: poses only (from_csv checks given ones)
        lines = src.read_text().splitlines()
        src.write_text("".join(",".join(r.split(",")[:7]) + "\n" for r in lines
                               if not r.startswith("#")))
    if kind == "malformed":
        lines = src.read_text().splitlines()
        lines[40] = lines[40].replace(",", ",abc", 1)
        src.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out.csv"
    rc = main(["run", "--trajectory", str(src), "--out", str(out), "--quiet"])
    assert rc != 0
    assert not out.exists()
    # no temp file either
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv", "in.units.json"]
    err = capsys.readouterr().err
    assert "error" in err and "nothing written" in err
    if kind == "unreachable":
        assert "sample 60" in err and "chain 0" in err
    elif kind == "malformed":
        assert "row 41" in err
    else:
        assert "wrist" in err and "sample 0" in err


def test_cli_run_parquet_and_times(tmp_path, capsys):
    from pollard_pin.cli import main

    out = tmp_path / "r.parquet"
    assert main(["run", "--samples", "301", "--out", str(out), "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "solved and written in " in text and "writing " in text and "µs/sample" in text
    got = read_result(out)
    assert len(got) == 301 and got.metadata["trajectory"]["samples"] == 301
    assert got.metadata["parameters"]["chain0"]["x32"] == 0.33
    ref = pp.run_pipeline(pp.load(), thesis_trajectory(samples=301)).columns()
    for name, col in ref.items():
        assert np.abs(got[name] - col).max() <= ROUND_OFF * max(1.0, np.abs(col).max()), name


def test_run_loads_writes_the_columns_and_units(tmp_path, capsys):
    out = tmp_path / "run.csv"
    assert main(["run", "--samples", "41", "--loads", "--quiet", "--out", str(out)]) == 0
    header = out.read_text().splitlines()[0].split(",")
    assert len(header) == 85 + 72 and "M_theta1817_z" in header
    units = json.loads((tmp_path / "run.units.json").read_text())["units"]
    assert units["F_theta21_x"] == "N" and units["M_theta76_2_y"] == "N·m"


def test_run_loads_bad_input_is_one_line_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "run.csv"
    code = main(["run", "--loads", "--samples", "41", "--quiet", "--set", "chain0.x32=-1",
                 "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "x32" in err
    assert not out.exists()
