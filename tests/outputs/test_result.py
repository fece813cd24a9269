"""PaintResult (outputs/result.py): write writes what the result holds (tables read back
against its arrays) and what the CLI writes; a painted job from painting (a layout proposal's)
becomes one that writes itself."""
import json
from pathlib import Path

import numpy as np
import pytest
from refusals import WRONG, refused

import pollard_pin as pp
from pollard_pin.errors import InputError
from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv
from pollard_pin.outputs.result import PaintResult
from pollard_pin.painting.api import paint_job
from pollard_pin.painting.result import PaintedJob

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def result(panel_result):
    """examples/paint.toml painted with examples/actuators.toml, once per session
    (tests/examples_planned.py)."""
    return panel_result


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


def test_a_painted_job_becomes_a_result_that_writes(robot, result, tmp_path):
    """paint_job's PaintedJob, made a PaintResult, holds the same objects and writes the
    same files as pp.paint's result (byte for byte, paint.json but its timings)."""
    painted = paint_job(robot, result.job, result.actuators)
    assert type(painted) is PaintedJob and not hasattr(painted, "write")
    writable = PaintResult.of(painted)
    assert isinstance(writable, PaintResult) and PaintResult.of(writable) is writable
    assert all(getattr(writable, f) is getattr(painted, f) for f in
               ("job", "kind", "plan", "film", "report", "actuators", "options", "painter"))
    writable.write(tmp_path / "a")
    result.write(tmp_path / "b")
    for name in ("path.csv", "thickness.csv", "film.ply", "thickness.png"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    ja, jb = (json.loads((tmp_path / d / "paint.json").read_text()) for d in "ab")
    assert {k: v for k, v in ja.items() if k != "timings"} == \
        {k: v for k, v in jb.items() if k != "timings"}


@pytest.mark.parametrize("folder", [v for v in WRONG if not isinstance(v, str)])
def test_write_refuses_what_is_not_a_folder(result, folder):
    """write(None), write(3), write(nan)…: one line naming the folder, nothing written."""
    refused(lambda: result.write(folder), "folder")


def test_paint_takes_an_actuator_file(robot, result):
    """pp.paint(robot, job, "actuators.toml"): the path is read as load_actuators reads it;
    anything else where the ratings go is one line naming ``actuators``."""
    job = pp.load_job(EXAMPLES / "paint.toml")
    by_path = pp.paint(robot, job, str(EXAMPLES / "actuators.toml"),
                       pp.PaintOptions(compliance=False))
    assert by_path.actuators == result.actuators
    assert by_path.report.cycle_time == result.report.cycle_time
    for wrong in (3, float("nan"), [1, 2], {"a": 1}, b"bytes", job):
        refused(lambda w=wrong: pp.paint(robot, job, w), "actuators")


@pytest.mark.parametrize("arg", ["robot", "job", "options"])
@pytest.mark.parametrize("wrong", WRONG, ids=repr)
def test_paint_refuses_a_wrong_argument(robot, arg, wrong):
    """pp.paint's and pp.fewest_robots' robot, job and options: None (but for the options,
    which may be None), the wrong types and NaN are one line naming the argument."""
    if arg == "options" and wrong is None:
        return
    args = {"robot": robot, "job": pp.load_job(EXAMPLES / "line.toml"), "options": None,
            arg: wrong}
    refused(lambda: pp.paint(args["robot"], args["job"], None, args["options"]), arg)
    refused(lambda: pp.fewest_robots(args["robot"], args["job"], None, args["options"]), arg)


@pytest.mark.parametrize("fmt", WRONG + ["xlsx"], ids=repr)
def test_write_refuses_a_format_it_does_not_write(result, tmp_path, fmt):
    refused(lambda: result.write(tmp_path / "out", fmt), "format")
    assert not (tmp_path / "out").exists()
