"""`pollard-pin paint --robots N|auto` (docs/model.md §26.5): bad counts and jobs refused in
one line with nothing written; a proposal written as DIR/robots.toml beside the outputs,
read back as the robots planned."""
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest
from cli_run import run_cli

from pollard_pin.painting.cell.robots import robots_from_tables

ROOT = Path(__file__).resolve().parents[2]
LINE = ROOT / "examples" / "line.toml"


@pytest.mark.parametrize("value", ["0", "1000000", "17", "-1", "two", "1e3", ""])
def test_bad_counts_are_one_line(tmp_path, capsys, value):
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", LINE, "--out", out, f"--robots={value}"], capsys)
    assert code == 2 and err.count("\n") == 1, err
    assert f"--robots {value}: expected 1..16 or auto" in err and not out.exists()


@pytest.mark.parametrize("extra, words", [
    ("[[robot]]\nname = 'a'\nbase = [0.0, 0.0, 0.0]\n", "places its own 1 robot(s)"),
    (None, "has no [line] table"),
])
def test_jobs_that_cannot_take_a_layout(tmp_path, capsys, extra, words):
    job = tmp_path / "job.toml"
    if extra is None:
        job.write_text((ROOT / "examples" / "paint.toml").read_text())
    else:
        job.write_text(LINE.read_text() + "\n" + extra)
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", job, "--out", out, "--robots", "2"], capsys)
    assert code == 2 and err.count("\n") == 1 and words in err, err
    assert not out.exists()


def test_the_proposal_is_written_beside_the_outputs(tmp_path, capsys, monkeypatch):
    import pollard_pin.outputs.result as result

    real, planned = result.paint_job, []

    def paint_job(robot, job, actuators=None, options=None):
        # the proposal recorded, the job planned by one robot: the cell's own planning is
        # tested in tests/painting/cell/test_plan.py, and takes a minute
        planned.append(job.robots)
        return real(robot, replace(job, robots=()), actuators, options)

    monkeypatch.setattr(result, "paint_job", paint_job)
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", LINE, "--out", out, "--robots", "1",
                            "--resolution", "0.005"], capsys)
    assert code == 0, err
    text = (out / "robots.toml").read_text()
    robots = robots_from_tables("robots.toml", tomllib.loads(text)["robot"])
    assert [robots] == planned and len(robots) == 1
    assert (out / "paint.json").exists() and "proposed 1 robot(s): robot1 at" in err
