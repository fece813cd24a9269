"""`pollard-pin paint --robots N|auto` (docs/model.md §26.5): bad counts and jobs refused in
one line with nothing written; a proposal written as DIR/robots.toml beside the outputs,
read back as the robots planned; a search that finds no cell refused naming each count."""
import re
import tomllib
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import pytest
from cli_run import run_cli

from pollard_pin.painting.cell.robots import robots_from_tables

ROOT = Path(__file__).resolve().parents[2]
LINE = ROOT / "examples" / "line.toml"


@pytest.mark.parametrize("value, shown", [
    ("0", "0"), ("1000000", "1000000"), ("17", "17"), ("-1", "-1"), ("two", "two"),
    ("1e3", "1e3"), ("", ""),
    ("9" * 40, "9" * 23 + "…")])  # was cut to 20 nines without a mark: another number
def test_bad_counts_are_one_line(tmp_path, capsys, value, shown):
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", LINE, "--out", out, f"--robots={value}"], capsys)
    assert code == 2 and err.count("\n") == 1, err
    assert f"--robots {shown}: expected 1..16 or auto" in err and not out.exists()


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


@pytest.mark.parametrize("flags, words", [
    (["--edge-room", "0.02"], "--edge-room: only a proposed cell (--robots N|auto)"),
    (["--end-pitch", "-5"], "--end-pitch: only a proposed cell (--robots N|auto)"),
    # the options' refusals name the flag the user typed, not the field it set
    (["--robots", "2", "--edge-room", "0.6"], "error: --edge-room 0.6: expected a length in "
     "[0, 0.5] m"),
    (["--seams", "0.2,0.1"], "error: --seams (0.2, 0.1): must increase"),
    (["--seam-run", "1e300"], "error: --seam-run 1e+300: must be at most 10"),
    (["--strokes", "along", "--step-from", "trailing"], "error: --step-from 'trailing': "
     "strokes along the travel step across it"),
    # a cell's knob on the line job of one robot: refused, not silently dropped
    (["--smoothing", "0.05", "--seam-run", "0"], "PlannerPolicy.seam_run, smoothing: a "
     "cell's (a job with [[robot]] tables, or --robots); the line panel job has one robot"),
])
def test_a_cells_levers_out_of_place_are_one_line(tmp_path, capsys, flags, words):
    """The layout's room at the free edges and its top robot's pitch need a proposal; a room
    or seams out of range are refused before any planning, nothing written (docs/model.md
    §26.5)."""
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", LINE, "--out", out, *flags], capsys)
    assert code == 2 and err.count("\n") == 1 and words in err, err
    assert not out.exists()


def test_the_proposal_is_written_beside_the_outputs(tmp_path, capsys, monkeypatch):
    import pollard_pin.painting.api as api

    real, planned = api.paint_job, []

    def paint_job(robot, job, actuators=None, options=None):
        # the proposal recorded, the job planned by one robot: the cell's own planning is
        # tested in tests/painting/cell/test_plan.py, and takes a minute
        planned.append(job.robots)
        return real(robot, replace(job, robots=()), actuators, options)

    monkeypatch.setattr(api, "paint_job", paint_job)
    out = tmp_path / "out"
    # compliance not asserted here (tests/painting/checks/test_compliance.py checks it)
    code, _, err = run_cli(["paint", "--job", LINE, "--out", out, "--robots", "1",
                            "--resolution", "0.005", "--no-compliance"], capsys)
    assert code == 0, err
    text = (out / "robots.toml").read_text()
    robots = robots_from_tables("robots.toml", tomllib.loads(text)["robot"])
    assert [robots] == planned and len(robots) == 1
    assert (out / "paint.json").exists() and "proposed 1 robot(s): robot1 at" in err


def test_a_search_that_finds_no_cell_names_each_count_and_its_cause(tmp_path, capsys,
                                                                      monkeypatch):
    """--robots auto with no count painting: one line naming each count tried and why
    (docs/model.md §26.5), exit 2, nothing written."""
    import pollard_pin.painting.api as api
    from pollard_pin.painting.errors import PlanError
    from pollard_pin.painting.layout import seat

    def paint_job(robot, job, actuators=None, options=None):
        n = len(job.robots)
        raise PlanError(f"robot 'robot{n}': no place on the line keeps its first ramp in reach"
                        if n < 3 else "no line speed paints the part: too slow at 0.02 m/s "
                        "(a motor at 131 % of its rating), too fast at 0.03 m/s (a motor at "
                        "126 % of its rating); binding: slow (motors), fast (motors)")

    monkeypatch.setattr(api, "paint_job", paint_job)
    # no robot planned alone either (the seating, tests/painting/layout/test_seat.py)
    monkeypatch.setattr(seat, "seat_ends", lambda robot, job, *args: (job.robots, None))
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", LINE, "--out", out, "--robots", "auto"], capsys)
    assert code == 2 and err.count("\n") == 1 and not out.exists(), err
    # the job's folders and the outputs' name as long as the line allows
    said = re.sub(r" \(nothing written[^()]*\)\n$", "", err.replace(f"{LINE.parent}/", ""))
    assert said == ("pollard-pin paint: error: line.toml: no cell of 1–4 robots paints the part "
                    "at 0.03 m/s: 1 first ramp out of reach; 2 first ramp out of reach; 3 motor "
                    "131 % at any speed; 4 motor 131 % at any speed"), err


def test_seated_seams_are_said_in_the_proposal(tmp_path, capsys):
    """A proposal planned with seams of its own (seated, docs/model.md §26.5) says them in
    robots.toml's header, as the --seams that plans the same cell; the tables read back."""
    from pollard_pin.cli.paint_robots import write_layout
    from pollard_pin.painting.cell.robots import CellRobot

    cell = (CellRobot("robot1"), CellRobot("robot2", (0.0, 0.77, 0.2)))
    job = SimpleNamespace(source="door.toml")
    write_layout(cell, tmp_path, 2, job, (0.2950001,))
    text = (tmp_path / "robots.toml").read_text()
    assert "# planned with its seams at 0.295 m: plan them again with --seams 0.295\n" in text
    assert robots_from_tables("robots.toml", tomllib.loads(text)["robot"]) == cell
    (tmp_path / "split").mkdir()
    write_layout(cell, tmp_path / "split", 2, job)  # the split's own seams: none said
    assert "--seams" not in (tmp_path / "split" / "robots.toml").read_text()


def test_the_levers_auto_found_are_said(tmp_path, capsys):
    """A cell --robots auto found with the levers (paint.json's ``levers``, docs/model.md
    §26.5) says them on standard error and in robots.toml's header, with the plain refusal
    and the planner's flags that plan the tables again (the room and pitch are in them)."""
    from pollard_pin.cli.paint_robots import write_layout
    from pollard_pin.painting.cell.robots import CellRobot

    cell = (CellRobot("robot1"), CellRobot("robot2", (0.0, 0.77, 0.2), (0.0, -5.0, 0.0)))
    levers = {"seam_run": 0.005, "smoothing": 0.06, "edge_room": 0.022, "end_pitch": -5.0,
              "plain": "no cell of 1–2 robots paints the part at 0.024 m/s: 2 motor 106 %"}
    write_layout(cell, tmp_path, "auto", SimpleNamespace(source="door.toml"), (0.295,),
                 levers)
    text = (tmp_path / "robots.toml").read_text()
    flags = "--seam-run 0.005 --smoothing 0.06 --edge-room 0.022 --end-pitch -5"
    assert (f"# found with {flags} (the plain proposal refused: no cell of 1–2 robots paints "
            "the part at 0.024 m/s: 2 motor 106 %): plan them again with --seam-run 0.005 "
            "--smoothing 0.06\n") in text, text
    assert robots_from_tables("robots.toml", tomllib.loads(text)["robot"]) == cell
    err = capsys.readouterr().err
    assert f"--robots auto: the plain proposal refused, found with {flags}\n" in err, err
