"""``pollard-pin stiffness`` (cli/stiffness.py, docs/model.md §27): its table is the library's
result with units, a wrench moves the tip by C·W, it names the worst samples, and bad input is
one line, exit 2, nothing written. (The numbers: tests/dynamics/test_stiffness.py.)"""
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli

import pollard_pin as pp
from pollard_pin.dynamics.drives.stiffness import closed_loop_maps
from pollard_pin.io.table import read_result

ROOT = Path(__file__).resolve().parents[2]
ACT = ROOT / "examples" / "actuators.toml"
FIG8 = ROOT / "examples" / "figure8.csv"
SHORT = ["--samples", "41", "--quiet"]


def test_table_is_the_library_result(robot, tmp_path, capsys):
    out = tmp_path / "s.csv"
    code, text, err = run_cli(["stiffness", *SHORT, "--actuators", ACT, "--out", out], capsys)
    assert code == 0, err
    table = read_result(out)
    act = pp.load_actuators(ACT)
    traj = pp.thesis_trajectory(samples=41, home_pose=robot.params.home_pose)
    whole = pp.stiffness(robot, traj, act)
    assert list(table.columns) == list(whole.columns())
    for name, col in whole.columns().items():
        assert np.abs(table[name] - col).max() <= 1e-12 * np.abs(col).max(), name
    assert table.units["dx"] == "m" and table.units["f3"] == "Hz"
    assert table.metadata["command"] == "stiffness"
    assert table.metadata["actuators"]["stiffness"]["theta21"] == 3000.0
    k = int(np.argmin(table["kmin"]))
    assert f"sample {k} " in [line for line in text.splitlines() if "kmin" in line][0]


def test_a_wrench_adds_its_compliance(robot, tmp_path, capsys):
    """d(W) − d(0) = J K⁻¹ Jᵀ W on figure8.csv, J from the closed-loop maps (achieved 1e-16 m,
    tolerance 1e-12 m)."""
    paths = [tmp_path / "a.parquet", tmp_path / "b.parquet"]
    W = np.array([-5.0, 2.0, 3.0, 0.05, 0.0, -0.1])
    assert run_cli(["stiffness", "--trajectory", FIG8, "--actuators", ACT, "--quiet",
                    "--out", paths[0]], capsys)[0] == 0
    code, _, err = run_cli(["stiffness", "--trajectory", FIG8, "--actuators", ACT, "--quiet",
                            f"--wrench={','.join(map(str, W))}", "--out", paths[1]], capsys)
    assert code == 0, err
    a, b = (read_result(p) for p in paths)
    names = ("dx", "dy", "dz", "rx", "ry", "rz")
    diff = np.stack([b[n] - a[n] for n in names], axis=1)
    traj = pp.from_csv(FIG8)
    J = closed_loop_maps(robot, pp.inverse_kinematics(robot, traj.poses).q).J
    k = pp.load_actuators(ACT).stiffness()
    expect = np.einsum("nij,j,nkj,k->ni", J, 1 / k, J, W)
    assert np.abs(diff - expect).max() < 1e-12
    assert b.metadata["options"]["wrench"] == W.tolist()


def _bare(tmp_path, key_line):
    text = ACT.read_text().replace(key_line, "", 1)
    path = tmp_path / "act.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("case, says", [
    ("missing", "'theta21.stiffness' is missing"),
    ("zero", "theta1615.stiffness"),
    ("wrench5", "--wrench: expected six numbers"),
    ("wrench_nan", "--wrench: MX"),
    ("reach", "sample 3"),
])
def test_bad_input_is_one_line_and_nothing_written(tmp_path, capsys, case, says):
    out = tmp_path / "s.csv"
    act, extra, traj = ACT, [], SHORT
    if case == "missing":
        act = _bare(tmp_path, "stiffness = 3000.0\n")
    elif case == "zero":
        text = ACT.read_text()
        cut = text.index("[theta1615]")
        act = tmp_path / "act.toml"
        act.write_text(text[:cut] + text[cut:].replace("stiffness = 300.0", "stiffness = 0",
                                                         1))
    elif case == "wrench5":
        extra = ["--wrench=1,2,3,4,5"]
    elif case == "wrench_nan":
        extra = ["--wrench=0,0,0,nan,0,0"]
    else:
        lines = (ROOT / "examples" / "figure8_poses.csv").read_text().splitlines()
        cols = lines[0].split(",")
        row = lines[4].split(",")
        row[cols.index("x")] = "3.0"
        lines[4] = ",".join(row)
        traj = ["--trajectory", tmp_path / "far.csv", "--quiet"]
        (tmp_path / "far.csv").write_text("\n".join(lines[:12]) + "\n")
    code, _, err = run_cli(["stiffness", *traj, "--actuators", act, *extra, "--out", out],
                           capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, err
    assert says in lines[0] and lines[0].startswith("pollard-pin stiffness: error"), lines[0]
    assert not out.exists() and not (tmp_path / "s.units.json").exists()


@pytest.mark.parametrize("wrench, stiffness, turn", [
    ("1e6,0,0,0,0,0", None, "81.8 rad"), ("1e4,0,0,0,0,0", None, "0.818 rad"),
    ("0,0,0,1e5,0,0", None, "333 rad"), ("0,0,0,0,0,0", "1.0", "0.491 rad"),
    ("0,0,0,0,0,0", "0.001", " rad"), ("0,0,0,0,0,0", "1e-300",
                                                       "act.toml: 'theta21.stiffness' = 1e-300: "
                                                       "must be between 0.001 and 1e+09"),
])
def test_beyond_the_linear_model_is_one_line(tmp_path, capsys, wrench, stiffness, turn):
    """A load or drives far outside the linear model (docs/model.md §27.2: a drive turned by
    more than 3 mrad, the model's error ≈ 1 % there) is refused in one line naming the sample,
    the turn and the bound; nothing written (it used to print 40.9 m, 0.87 m, 22.7 m,
    0.21 m, 2e299 m)."""
    act = ACT
    if stiffness is not None:
        act = tmp_path / "act.toml"
        text = ACT.read_text().replace("stiffness = 3000.0", f"stiffness = {stiffness}")
        act.write_text(text.replace("stiffness = 300.0", f"stiffness = {stiffness}"))
    out = tmp_path / "s.csv"
    code, _, err = run_cli(["stiffness", *SHORT, "--actuators", act, f"--wrench={wrench}",
                            "--out", out], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, err
    assert len(lines[0].split(" (nothing written to ")[0]) <= 250, lines[0]
    assert turn in lines[0], lines[0]
    if stiffness != "1e-300":  # that one is out of the stiffnesses' range: a unit slip
        assert "sample 0 (t = 0 s): a drive turns by" in lines[0], lines[0]
        assert "beyond the linear model's 0.003 rad" in lines[0]
    assert not out.exists() and not list(tmp_path.glob("s.*"))
