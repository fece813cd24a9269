"""What a job kind is (painting/kinds/base.py) and the table of kinds: every shipped job is
recognised by exactly one kind; the files paint writes (a cell's path.csv per robot); a new
kind is one module and one line in the table, and pp.paint and the CLI then use it."""
from pathlib import Path

import pytest

import pollard_pin as pp
from pollard_pin.cli import main
from pollard_pin.errors import PollardError
from pollard_pin.painting import kinds
from pollard_pin.painting.kinds import panel
from pollard_pin.painting.kinds.base import JobKind, Outputs, output_files, with_speeds
from pollard_pin.painting.options import PaintOptions

ROOT = Path(__file__).resolve().parents[3]


def test_every_example_job_is_of_exactly_one_kind():
    jobs = [ROOT / "examples" / n for n in ("paint.toml", "line.toml", "line_part.toml",
                                           "cell.toml", "parts/curved_panel.toml")]
    names = []
    for path in jobs:
        job = pp.load_job(path)
        (kind,) = [k for k in kinds.KINDS.values() if k.recognises(job)]
        assert kinds.kind_of(job) is kind
        names.append(kind.name)
    assert names == ["panel", "line panel", "line part", "cell panel", "part"]
    from pollard_pin.painting.kinds import cell
    from pollard_pin.painting.kinds.base import robot_compliance

    assert [k.compliance for k in kinds.KINDS.values()] == [robot_compliance] * 4 + \
        [cell.compliance] * 2


def test_anything_else_is_one_line_naming_the_kinds():
    with pytest.raises(PollardError, match="cannot paint a dict: expected a paint job of kind "
                                           "panel, part, line panel, line part, cell panel, "
                                           "cell part"):
        kinds.kind_of({"panel": {}})


def test_the_files_paint_writes(tmp_path):
    """One path.csv, or a cell's one per robot; the other format's table is stale."""
    files, stale = output_files(tmp_path, "csv")
    assert [f.relative_to(tmp_path).as_posix() for f in files] == [
        "path.csv", "path.units.json", "thickness.csv", "thickness.units.json", "paint.json",
        "thickness.png", "film.ply"]
    assert stale == (tmp_path / "thickness.parquet",)
    cell, _ = output_files(tmp_path, "parquet", ["a", "b"])
    assert [f.relative_to(tmp_path).as_posix() for f in cell[:5]] == [
        "a/path.csv", "a/path.units.json", "b/path.csv", "b/path.units.json",
        "thickness.parquet"]
    assert Outputs().files(tmp_path, "csv", ["a"]) == (files, stale)  # one robot's folder
    assert kinds.KINDS["cell part"].outputs.files(tmp_path, "parquet", ["a", "b"])[0] == cell


# --- a new kind: one module (here an object) and one line in the table ----------------------
def quick_lines(rep: dict, names) -> list[str]:
    return [f"quick look: {rep['passes']} passes, cycle {rep['cycle_time']:.1f} s"]


# a still panel's recipe, its own lines, no compliance report, for jobs named quick.toml
QUICK = JobKind("quick", panel.paint, quick_lines, compliance=None,
                recognise=lambda job: Path(job.source).name == "quick.toml")


def test_a_new_kind_is_one_module_and_one_table_line(monkeypatch, robot, act, tmp_path,
                                                    capsys):
    monkeypatch.setattr(kinds, "KINDS", {"quick": QUICK, **kinds.KINDS})  # asked first
    job = tmp_path / "quick.toml"
    job.write_text((ROOT / "examples" / "paint.toml").read_text())
    result = pp.paint(robot, pp.load_job(job), act, PaintOptions(resolution=0.01))
    assert result.kind == "quick" and "compliance" not in result.report.data
    assert result.summary_lines()[0] == "quick look: 9 passes, cycle 10.0 s"
    assert main(["paint", "--job", str(job), "--out", str(tmp_path / "out"),
                 "--resolution", "0.01"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed == result.summary_lines() and printed[1].startswith("gun body")
    assert (tmp_path / "out" / "film.ply").is_file()


def test_speeds_only_when_asked():
    """With PaintOptions(speeds=True) the line table gains the interval's table and the
    timings its time; without, the report is untouched and nothing is searched."""
    from pollard_pin.painting.line.speeds import SpeedInterval

    found = SpeedInterval(0.02, 0.04, 0.05, "budget floor", "too fast: drifts")

    def find():
        calls.append(1)
        return found

    calls = []
    rep = {"line": {"speed": 0.03}, "timings": {"plan": 1.0}}
    with_speeds(rep, PaintOptions(), find)
    assert rep == {"line": {"speed": 0.03}, "timings": {"plan": 1.0}} and calls == []
    with_speeds(rep, PaintOptions(speeds=True), find)
    assert rep["line"]["speeds"] == found.table() and calls == [1]
    assert rep["timings"]["speeds"] >= 0
