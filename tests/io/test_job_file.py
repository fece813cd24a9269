"""A paint job written as TOML reads back equal (load_job), its paths relative to the
written file's folder."""
import shutil
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest

from pollard_pin.errors import InputError
from pollard_pin.io.job_file import job_toml, toml_string, write_job
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.job import load_job
from pollard_pin.painting.line.conveyor import Line

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("edit", [
    dict(),
    dict(position=(0.1234567, -0.25, 1e-7), rotation=(10.0, -90.0, 33.3), units="in"),
    dict(scale=0.02, line=Line(0.03, (0.0, 1.0, 0.0)), coats=2, spacing=0.012,
         direction="vertical"),
])
def test_round_trip(tmp_path, edit):
    job = replace(load_job(ROOT / "examples" / "parts" / "curved_panel.toml"), **edit)
    (tmp_path / "deep" / "er").mkdir(parents=True)
    out = write_job(job, tmp_path / "deep" / "er" / "job.toml", "a header\nof two lines")
    back = load_job(out)
    text = out.read_text()
    assert text.startswith("# a header\n# of two lines\n")
    assert 'mesh = "../../' in text  # relative to the written file's folder
    assert Path(back.mesh).samefile(job.mesh)
    for k in ("position", "rotation", "facing", "max_angle", "standoff", "sigma", "flow",
              "thickness", "coats", "spacing", "direction", "line", "scale"):
        assert getattr(back, k) == getattr(job, k), k
    assert back.unit == job.unit


def test_values_have_a_toml_form():
    job = load_job(ROOT / "examples" / "parts" / "curved_panel.toml")
    with pytest.raises(ValueError, match="no TOML form"):
        job_toml(replace(job, max_angle=float("nan")), Path("."))
    with pytest.raises(InputError, match="no TOML form"):
        job_toml(replace(job, max_angle=float("inf")), Path("."))
    with pytest.raises(InputError, match="lone surrogate"):
        toml_string("a\udcffb.stl")


# every character TOML's basic strings escape, other control characters, non-ASCII text
HOSTILE = ["new\nline", 'say "hi"', "back\\slash", "tab\there", "ünï cödé ∂ 部品", "bell\x07",
           "nul\x00del\x7f", "cr\rff\fbs\b", '\\"\n\'\'\'"""', "\\u0041 not an escape", "\x1b[31m"]


@pytest.mark.parametrize("s", HOSTILE)
def test_strings_read_back_as_themselves(s):
    assert tomllib.loads(f"k = {toml_string(s)}\n")["k"] == s


@pytest.mark.parametrize("name", [s for s in HOSTILE if "\x00" not in s])  # no NUL in a path
def test_hostile_mesh_paths_round_trip(tmp_path, name):
    """A mesh whose file name holds a newline, a quote, a backslash, a tab, non-ASCII or a
    control character: the written job is TOML and names the same file."""
    mesh = tmp_path / "m" / (name.replace("/", "_") + ".stl")
    mesh.parent.mkdir()
    shutil.copy(ROOT / "examples" / "parts" / "curved_panel.stl", mesh)
    job = replace(load_job(ROOT / "examples" / "parts" / "curved_panel.toml"), mesh=str(mesh))
    out = write_job(job, tmp_path / "job.toml")
    assert tomllib.loads(out.read_text())["part"]["mesh"] == "m/" + mesh.name
    assert Path(load_job(out).mesh).samefile(mesh)


def test_a_cell_job_keeps_its_robots(tmp_path):
    """A part job with [[robot]] tables (a cell) is written with them: load_job reads back the
    same robots."""
    robots = (CellRobot("low", (0.0, 0.0, 0.0)),
              CellRobot("high", (0.0, 0.75, 0.17), (0.0, 0.0, 5.5)))
    job = replace(load_job(ROOT / "examples" / "parts" / "curved_panel.toml"),
                  line=Line(0.02, (0.0, 1.0, 0.0)), robots=robots)
    out = write_job(job, tmp_path / "cell.toml")
    back = load_job(out)
    assert back.robots == robots and back.line == job.line
    assert out.read_text().count("[[robot]]") == 2
