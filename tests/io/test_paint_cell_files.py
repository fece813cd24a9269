"""What `pollard-pin paint` writes for a cell (io/paint_cell_files.py, docs/model.md §26): a
folder per robot whose path.csv passes `run` and `size`, one film of all robots on the panel
at t = 0 (its seam within the target), paint.json's line, robots and clearance, and a
colliding layout refused in one line with nothing written."""
import json
from pathlib import Path

import numpy as np
import pytest
from cell_jobs import panel_cell
from cli_run import run_and_size, run_cli

from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv

ROOT = Path(__file__).resolve().parents[2]
ACT = ROOT / "examples" / "actuators.toml"


def job_text(tables: dict) -> str:
    """The job tables as a TOML file's text."""

    def value(v):
        if isinstance(v, str):
            return f'"{v}"'
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)

    out = []
    for name, table in tables.items():
        for t in table if isinstance(table, list) else [table]:
            out.append(f"[[{name}]]" if isinstance(table, list) else f"[{name}]")
            out += [f"{k} = {value(v)}" for k, v in t.items()]
    return "\n".join(out) + "\n"


@pytest.fixture(scope="module")
def painted(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cell")
    job = folder / "cell.toml"
    job.write_text(job_text(panel_cell()))
    from pollard_pin.cli import main

    assert main(["paint", "--job", str(job), "--out", str(folder / "out")]) == 0
    return folder / "out"


def test_a_folder_per_robot_and_one_film(painted):
    assert {p.name for p in painted.iterdir()} >= {"low", "high", "thickness.csv",
                                                    "paint.json", "film.ply",
                                                    "thickness.png"}
    assert not (painted / "path.csv").exists()
    rep = json.loads((painted / "paint.json").read_text())
    assert [r["name"] for r in rep["robots"]] == ["low", "high"]
    line = rep["line"]
    cycle = max(r["cycle"] for r in rep["robots"])
    assert line["cycle"] == cycle and line["parts_per_hour"] == pytest.approx(3600 / cycle)
    assert line["min_pitch"] == pytest.approx(line["speed"] * cycle, rel=1e-12)
    assert rep["clearance"]["pair"] == ["low", "high"]
    assert rep["clearance"]["between_robots_m"] > 0.01
    table = read_result(painted / "thickness.csv")
    th = table.columns["thickness"] / rep["target"]
    assert np.abs(th - 1).max() <= 0.05  # seen ±0.5 %
    (seam,) = rep["split"]["seams"]
    assert rep["seams"][0]["at"] == seam
    # the seam's band within ±1 % (seen 0.995-1.005: the ripple along the travel)
    assert 0.99 <= rep["seams"][0]["min"] <= rep["seams"][0]["max"] <= 1.01


def test_each_robots_path_passes_run_and_size(painted, capsys, tmp_path):
    rep = json.loads((painted / "paint.json").read_text())
    for r in rep["robots"]:
        path = painted / r["name"] / "path.csv"
        tr = from_csv(path)
        assert tr.t[-1] == pytest.approx(r["path_time"], rel=1e-12)
        assert run_and_size(path, ACT, capsys, tmp_path)["given_within_ratings"]
        meta = json.loads((painted / r["name"] / "path.units.json").read_text())
        assert meta["metadata"]["robot"]["base"] == r["base"]


def test_a_colliding_layout_is_one_line_and_writes_nothing(tmp_path, capsys):
    tables = panel_cell([{"name": "low", "base": [0.0, 0.0, 0.0]},
                         {"name": "high", "base": [0.0, 0.25, 0.17]}])
    job = tmp_path / "cell.toml"
    job.write_text(job_text(tables))
    code, out, err = run_cli(["paint", "--job", job, "--out", tmp_path / "out"], capsys)
    assert code == 2, err
    assert len(err.strip().splitlines()) == 1
    assert "'low'" in err and "'high'" in err
    assert not (tmp_path / "out").exists()
