"""The whole-trajectory run (run/pipeline.py): its columns are the solvers' arrays under their
names, the dynamics and joint loads come only when asked, and the table reads back bit for
bit."""
import re

import numpy as np
import pytest

from pollard_pin.errors import InputError
from pollard_pin.io.table import read_result
from pollard_pin.names import SPHERICAL
from pollard_pin.paths.curves import thesis_trajectory
from pollard_pin.run import run_pipeline, write_run_table


@pytest.fixture(scope="module")
def result(robot):
    return run_pipeline(robot, thesis_trajectory(samples=61))


def test_columns_are_the_solvers_arrays(robot, result):
    cols, ik = result.columns(), result.ik
    assert cols["t"] is ik.t
    for i, n in enumerate(ik.joint_names):
        assert np.array_equal(cols[n], ik.q[:, i]) and np.array_equal(cols[f"d_{n}"], ik.v[:, i])
        assert np.array_equal(cols[f"dd_{n}"], ik.a[:, i])
    for i, n in enumerate(SPHERICAL):
        assert np.array_equal(cols[n], ik.spherical[:, i])
    for i, n in enumerate(robot.actuated):
        assert np.array_equal(cols[f"tau_{n}"], result.dynamics.tau[:, i])
    assert all(len(c) == 61 for c in cols.values())


def test_dynamics_and_loads_only_when_asked(robot):
    traj = thesis_trajectory(samples=11)
    bare = run_pipeline(robot, traj, dynamics=False)
    assert bare.dynamics is None and bare.loads is None
    assert not any(c.startswith(("tau_", "F_")) for c in bare.columns())
    loaded = run_pipeline(robot, traj, dynamics=False, loads=True)  # loads need the dynamics
    assert loaded.dynamics is not None and loaded.loads is not None
    assert any(c.startswith("F_") for c in loaded.columns())


@pytest.mark.parametrize("name", ["r.csv", "r.parquet"])
def test_table_reads_back_bit_for_bit(result, tmp_path, name):
    path = tmp_path / name
    write_run_table(result, path, {"k": 1})
    back = read_result(path)
    cols = result.columns()
    assert list(back.columns) == list(cols) and back.metadata == {"k": 1}
    for n, col in cols.items():
        assert np.array_equal(back[n], col), n


@pytest.mark.parametrize("traj", [None, "examples/figure8.csv", [[0.0] * 6]])
def test_a_trajectory_that_is_not_one_is_one_line(robot, traj):
    with pytest.raises(InputError, match="not a Trajectory"):
        run_pipeline(robot, traj)


def test_write_run_table_refuses_what_is_not_a_result(tmp_path):
    with pytest.raises(InputError, match="^result = 'x': expected a RunResult"):
        write_run_table("x", tmp_path / "run.csv")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("flag", ["dynamics", "loads", "joint_limits"])
@pytest.mark.parametrize("value", ["no", 0, None])
def test_a_flag_must_be_a_real_bool(robot, flag, value):
    """"no" is truthy: the old code solved the dynamics (or skipped the joint limits' check
    on 0) as if True (or False) were meant; refused before any sample is solved."""
    calls = []
    with pytest.raises(InputError, match=rf"^{flag} = {re.escape(repr(value))}: expected True "
                                         rf"or False, got {type(value).__name__}$"):
        run_pipeline(robot, thesis_trajectory(samples=11), progress=lambda *a: calls.append(a),
                     **{flag: value})
    assert calls == []
