"""PaintResult (painting/result.py): write writes what the result holds (tables read back
against its arrays) and what the CLI writes; summary_lines are the lines the CLI prints."""
import json
from pathlib import Path

import numpy as np
import pytest

import pollard_pin as pp
from pollard_pin.errors import InputError
from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv
from pollard_pin.painting.kinds.panel import summary_lines
from pollard_pin.painting.summary import clearance_line, compliance_line


@pytest.fixture(scope="module")
def result(robot, job, act) :
    return pp.paint(robot, job, act)


@pytest.mark.parametrize("fmt", ["csv", "parquet"])
def test_write_holds_the_result(result, tmp_path, fmt):
    """The table, path.csv and paint.json read back: the film's points and thickness, the
    plan's path, the report (CSV's shortest round-trip floats: equal; asserted 1e-15
    relative), film.ply's colour range in paint.json; a stale table of the other format
    removed."""
    other = "parquet" if fmt == "csv" else "csv"
    (tmp_path / f"thickness.{other}").write_text("stale")
    name = result.write(tmp_path, fmt)
    assert name == tmp_path / f"thickness.{fmt}" and not (tmp_path / f"thickness.{other}").exists()
    table = read_result(name)
    flat = result.film.points.reshape(-1, 3)
    for k, col in enumerate("xyz"):
        np.testing.assert_allclose(table[col], flat[:, k], rtol=1e-15, atol=0)
    np.testing.assert_allclose(table["thickness"], result.film.thickness, rtol=1e-15, atol=0)
    path = from_csv(tmp_path / "path.csv")
    np.testing.assert_allclose(path.poses, result.plan.trajectory.poses, rtol=1e-15, atol=0)
    rep = json.loads((tmp_path / "paint.json").read_text(encoding="utf-8"))
    assert rep["thickness"] == result.report.thickness and rep["grid"]["nu"] == len(
        result.film.grid[0])
    target = result.job.thickness
    assert rep["film_ply"]["range"] == [target * 0.9, target * 1.1]
    assert list(rep)[-1] == "pollard_pin"
    assert {p.name for p in tmp_path.iterdir()} >= {"path.csv", "film.ply", "paint.json",
                                                  "thickness.png", name.name}


def test_write_refuses_a_format_and_writes_nothing(result, tmp_path):
    out = tmp_path / "out"
    with pytest.raises(InputError, match="format 'xlsx'"):
        result.write(out, "xlsx")
    assert not out.exists()


def test_write_is_what_the_cli_writes(result, tmp_path):
    """pollard-pin paint on the same job and motors: the same files, byte for byte, and the
    same paint.json but for the timings."""
    from pollard_pin.cli import main

    job = Path(result.job.source)
    assert main(["paint", "--job", str(job), "--out", str(tmp_path / "cli"),
                 "--actuators", str(job.parent / "actuators.toml")]) == 0
    result.write(tmp_path / "api")
    for name in ("path.csv", "path.units.json", "thickness.csv", "thickness.units.json",
                 "film.ply", "thickness.png"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "api" / name).read_bytes()
    cli, api = (json.loads((tmp_path / d / "paint.json").read_text(encoding="utf-8"))
                for d in ("cli", "api"))
    assert cli.pop("timings").keys() == api.pop("timings").keys()
    assert cli == api


def test_summary_lines_are_the_kinds_then_clearance_and_compliance(result):
    """A still panel: its kind's five lines, the gun body's clearance, the compliance; no
    folder per robot."""
    rep = result.report.data
    assert result.summary_lines() == [*summary_lines(rep, result.actuators.names),
                                      clearance_line(rep), compliance_line(rep["compliance"])]
    assert result.robot_folders == () and result.painter.name == result.kind == "panel"
