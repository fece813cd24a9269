"""``pollard-pin report`` (cli/report.py): the file it writes is what it prints, JSON or
Markdown, a simulation table adds its section, and bad input is one line with nothing written.
(The report's numbers: tests/viz/test_report.py.)"""
import json

from cli_run import run_cli

SHORT = ["--samples", "41", "--quiet", "--no-cross-check"]


def test_out_is_what_it_prints(tmp_path, capsys):
    code, md, _ = run_cli(["report", *SHORT], capsys)
    assert code == 0 and md.startswith("# Actuator sizing report")
    out = tmp_path / "r.md"
    code, printed, err = run_cli(["report", *SHORT, "--out", out], capsys)
    assert code == 0 and printed == "" and f"wrote {out}" in err
    assert out.read_text() == md
    code, js, _ = run_cli(["report", *SHORT, "--format", "json"], capsys)
    assert json.loads(js)["trajectory"]["samples"] == 41


def test_json_is_the_librarys_report(robot, capsys):
    from pollard_pin.paths.curves import thesis_trajectory
    from pollard_pin.run import run_pipeline
    from pollard_pin.viz.report import report, to_json

    code, js, _ = run_cli(["report", *SHORT, "--format", "json"], capsys)
    rep = report(robot, run_pipeline(robot, thesis_trajectory(samples=41)), cross_check=False)
    assert code == 0 and json.loads(js) == json.loads(to_json(rep))


def test_not_a_simulation_table_is_one_line_and_writes_nothing(tmp_path, capsys):
    table = tmp_path / "run.csv"
    assert run_cli(["run", "--samples", "41", "--quiet", "--out", table], capsys)[0] == 0
    out = tmp_path / "r.md"
    code, _, err = run_cli(["report", *SHORT, "--simulation", table, "--out", out], capsys)
    assert code == 2 and "not a simulation table" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()
