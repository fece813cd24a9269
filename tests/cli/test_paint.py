"""`pollard-pin paint` end to end: plan → files → run → size → film, the viewer overlay, and
one line with exit status 2 (nothing written) for each bad input."""
import json
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli

from pollard_pin.cli import main
from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv

ROOT = Path(__file__).resolve().parents[2]
JOB = ROOT / "examples" / "paint.toml"
ACT = ROOT / "examples" / "actuators.toml"




@pytest.fixture(scope="module")
def painted(tmp_path_factory):
    out = tmp_path_factory.mktemp("paint") / "out"
    assert main(["paint", "--job", str(JOB), "--out", str(out)]) == 0
    return out


def test_outputs(painted):
    names = {p.name for p in painted.iterdir()}
    assert {"path.csv", "thickness.csv", "paint.json", "thickness.png"} <= names
    rep = json.loads((painted / "paint.json").read_text())
    for key in ("job", "thickness", "cycle_time", "passes", "spacing", "speed", "coats",
                "motors"):
        assert key in rep
    assert set(rep["thickness"]) >= {"mean", "min", "max", "std", "uniformity",
                                     "within_10pct"}
    assert rep["job"]["gun"] == {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7}
    table = read_result(painted / "thickness.csv")
    assert list(table.columns) == ["x", "y", "z", "u", "v", "thickness"]
    assert table.units["thickness"] == "m" and table.units["u"] == "m"
    assert len(table) == rep["grid"]["nu"] * rep["grid"]["nv"]
    assert table["thickness"].min() == rep["thickness"]["min"]
    # the world points lie on the panel: x = 0.70 for the example's normal (−1, 0, 0)
    assert np.abs(table["x"] - 0.70).max() < 1e-15
    png = (painted / "thickness.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_plan_run_size_film(painted, capsys, tmp_path):
    """The written path: run solves it, size confirms every motor within its ratings, and
    the film map stays within ±2 % of the target."""
    traj = from_csv(painted / "path.csv")
    assert traj.derivatives == "file columns"
    code, out, err = run_cli(["run", "--trajectory", painted / "path.csv", "--out",
                           tmp_path / "run.csv", "--quiet"], capsys)
    assert code == 0, err
    code, out, err = run_cli(["size", "--trajectory", painted / "path.csv", "--actuators", ACT,
                           "--format", "json", "--quiet"], capsys)
    assert code == 0, err
    sized = json.loads(out)
    assert sized["given_within_ratings"] is True
    rep = json.loads((painted / "paint.json").read_text())
    for name, m in rep["motors"].items():
        given = sized["actuators"][name]
        assert given["peak_motor_torque_ratio"] <= 1.0 and given["peak_motor_speed_ratio"] <= 1
        # the planner's own check (4× denser samples) sees at least what size sees
        assert m["peak_torque"] >= given["peak_motor_torque_ratio"] - 1e-12, name
        assert m["peak_torque"] <= 1.0 and m["speed"] <= 1.0, name
    th = read_result(painted / "thickness.csv")["thickness"]
    assert np.abs(th / rep["target"] - 1).max() <= 0.02


def test_summary_lines(tmp_path, capsys):
    code, out, err = run_cli(["paint", "--job", JOB, "--out", tmp_path / "p", "--format",
                           "parquet", "--resolution", "0.005"], capsys)
    assert code == 0, err
    lines = out.strip().splitlines()
    assert lines[0].startswith("passes 9 (horizontal)")
    assert "lower bound" in lines[1] and "film" in lines[2] and "theta21_1" in lines[3]
    t = read_result(tmp_path / "p" / "thickness.parquet")
    assert np.diff(np.unique(t["u"])).max() <= 0.005 * (1 + 1e-12)


def test_view_paint_overlay(painted, tmp_path, capsys):
    from pollard_pin.viz import viewer

    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", painted, "--html", html, "--fps", "5"], capsys)
    assert code == 0, err
    cmds = viewer.page_commands(html.read_text())
    paint = [c for c in cmds if c.get("type") == "set_object"
             and c["path"].endswith(f"{viewer.ROOT}/paint")]
    assert len(paint) == 1
    rep = json.loads((painted / "paint.json").read_text())
    attrs = paint[0]["object"]["geometries"][0]["data"]["attributes"]
    assert "color" in attrs
    n = rep["grid"]["nu"] * rep["grid"]["nv"]
    pos = attrs["position"]["array"]
    pos = np.frombuffer(getattr(pos, "data", pos), dtype=np.float32)
    assert pos.size == 3 * n


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace("width = 0.26", "widht = 0.26"), "did you mean 'width'"),
    (lambda t: t.replace("sigma = 0.010", "sigma = nan"), "must be a finite number"),
    (lambda t: t.replace("flow = 1.5e-7", "flow = -1.5e-7"), "must be > 0"),
    (lambda t: t.replace("normal = [-1.0, 0.0, 0.0]", "normal = [0.0, 0.0, 0.0]"),
     "zero length"),
    (lambda t: t.replace("height = 0.12 ", "").replace("height = 0.12", ""), "is missing"),
    (lambda t: t.replace("width = 0.26", "width = 0.6"), "the largest panel that fits"),
    (lambda t: t.replace("thickness = 25e-6", "thickness = 3e-6"),
     "thinnest film per coat"),
])
def test_bad_jobs_are_one_line_and_write_nothing(tmp_path, capsys, edit, words):
    job = tmp_path / "job.toml"
    job.write_text(edit(JOB.read_text()))
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin paint: error: ")
    assert words in lines[0]
    assert not out.exists()


def test_bad_options(tmp_path, capsys):
    code, _, err = run_cli(["paint", "--job", JOB, "--out", tmp_path / "o", "--resolution",
                         "1e-6"], capsys)
    assert code == 2 and "coarser resolution" in err and not (tmp_path / "o").exists()
    code, _, err = run_cli(["paint", "--job", tmp_path / "none.toml", "--out", tmp_path / "o"],
                        capsys)
    assert code == 2 and "does not exist" in err
    code, _, err = run_cli(["view", "--paint", tmp_path, "--html", tmp_path / "v.html"], capsys)
    assert code == 2 and "not a paint output folder" in err


def test_default_actuators_are_the_example_ratings():
    """The package default (models/actuators.toml) is a copy of examples/actuators.toml."""
    from pollard_pin.model.paths import models_dir

    assert (models_dir() / "actuators.toml").read_bytes() == ACT.read_bytes()
