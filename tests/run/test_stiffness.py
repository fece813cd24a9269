"""Stiffness along a trajectory (run/stiffness.py, docs/model.md §27): the streamed table is the
whole result cut into windows (same bits), the worst samples are those of the whole arrays, the
table reads back with its units, and an unreachable pose is named by its sample."""
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from refusals import WRONG, refused

import pollard_pin as pp
from pollard_pin.dynamics import ActuatorError
from pollard_pin.dynamics.drives.stiffness import DEFLECTION, FREQUENCIES, UNITS, StiffnessOptions
from pollard_pin.io.table import read_result
from pollard_pin.kinematics.errors import UnreachablePoseError
from pollard_pin.run import StreamOptions
from pollard_pin.run.stiffness import StiffnessStats, stiffness, stream_stiffness

ROOT = Path(__file__).resolve().parents[2]
K = np.array([3000.0, 3000.0, 3000.0, 300.0, 300.0, 300.0])


@pytest.fixture(scope="module")
def traj(robot):
    return pp.thesis_trajectory(samples=301, home_pose=robot.params.home_pose)


def test_streamed_windows_give_the_whole_result(robot, traj, tmp_path):
    """Windows of 64 samples (overlap included) write the same rows as one solve (the IK to
    the bit; the batched LAPACK calls round with the batch: achieved 7e-15 relative,
    tolerance 1e-12); the worst samples are the table's extremes."""
    options = StiffnessOptions((1.0, -2.0, 0.5, 0.0, 0.01, 0.0))
    whole = stiffness(robot, traj, K, options)
    path = tmp_path / "s.parquet"
    stats = stream_stiffness(robot, traj, K, path, options, StreamOptions(chunk=64))
    table = read_result(path)
    for name, col in whole.columns().items():
        assert np.abs(table[name] - col).max() <= 1e-12 * np.abs(col).max(), name
        assert table.units[name] == UNITS[name]
    assert stats.samples == len(traj) == len(whole)
    for name in DEFLECTION:
        k = int(np.argmax(np.abs(table[name])))
        assert stats.worst[name][:2] == (table[name][k], k)
    for name in (*FREQUENCIES, "kmin"):
        k = int(np.argmin(table[name]))
        assert stats.worst[name] == (table[name][k], k, table["t"][k])
    assert "kmin" in stats.summary() and "µm" in stats.summary()


def test_write_is_the_command_table(robot, traj, tmp_path):
    result = stiffness(robot, traj.window(0, 20), K)
    result.write(tmp_path / "s.csv")
    table = read_result(tmp_path / "s.csv")
    assert list(table.columns) == list(result.columns())
    assert np.array_equal(table["f1"], result.frequencies[:, 0])
    assert table.units["kmin"] == "N/m" and table.units["dz"] == "m"


def test_actuators_without_stiffness_are_named(robot, traj):
    act = pp.load_actuators(ROOT / "examples" / "actuators.toml")
    bare = replace(act, units=(replace(act.units[0], stiffness=None), *act.units[1:]))
    with pytest.raises(ActuatorError, match=r"'theta21\.stiffness' is missing"):
        stiffness(robot, traj, bare)
    assert np.array_equal(stiffness(robot, traj.window(0, 5), act).kmin,
                          stiffness(robot, traj.window(0, 5), act.stiffness()).kmin)


def test_a_pose_out_of_reach_is_named_by_its_sample(robot, traj, tmp_path):
    poses = traj.poses.copy()
    poses[200, 0] = 2.0  # far beyond the reach
    bad = pp.Trajectory(traj.t, poses, traj.d_poses, traj.dd_poses, "bad")
    with pytest.raises(UnreachablePoseError, match="sample 200"):
        stream_stiffness(robot, bad, K, tmp_path / "s.csv", stream=StreamOptions(chunk=64))
    assert not (tmp_path / "s.csv").exists()


def test_stats_start_empty():
    stats = StiffnessStats()
    assert stats.samples == 0 and stats.worst == {}


@pytest.mark.parametrize("arg, wrong", [
    *(("robot", w) for w in WRONG), *(("traj", w) for w in WRONG),
    *(("options", w) for w in WRONG if w is not None),
    *(("margins", w) for w in WRONG if w is not None)], ids=repr)
def test_a_wrong_argument_is_one_line(robot, arg, wrong):
    """stiffness' robot, traj, options and margins: one line naming the argument, nothing
    solved."""
    args = {"robot": robot, "traj": pp.thesis_trajectory(), "options": None, "margins": None,
            arg: wrong}
    refused(lambda: stiffness(args["robot"], args["traj"], K, args["options"],
                              margins=args["margins"]), arg)
