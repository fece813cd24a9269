"""pollard-pin design (cli/design.py): the study file's refusals before any work (one line,
exit 2, nothing written), the options, the help."""
import os

import pytest
from cli_run import run_cli, tree_state

from pollard_pin.cli import build_parser


def _refused(argv, says, capsys, folder):
    before = tree_state(folder)
    code, out, err = run_cli(argv, capsys)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and out == "" and len(lines) == 1, err
    assert lines[0].startswith("pollard-pin design: error: ") and says in lines[0], lines[0]
    assert tree_state(folder) == before


def _argv(tmp_path, *more):
    (tmp_path / "job.toml").write_text("")  # never read: the study file is refused first
    (tmp_path / "space.toml").write_text("")
    return ["design", "--job", tmp_path / "job.toml", "--space", tmp_path / "space.toml",
            "--out", tmp_path / "out", "--quiet", *more]


@pytest.mark.parametrize("make, says, resume", [
    (lambda p: os.mkfifo(p), "not a regular file (a FIFO", True),
    (lambda p: p.write_text("trial,value\n"), "not a study database (not a SQLite file)", True),
    (lambda p: p.write_bytes(b"SQLite format 3\x00" + b"\x00" * 200), "damaged study", True),
    (lambda p: p.mkdir(), "is a folder", True),
    (None, "no study to resume", True),
])
def test_a_study_file_that_cannot_be_used_is_one_line(tmp_path, capsys, make, says, resume):
    (tmp_path / "out").mkdir()
    if make is not None:
        make(tmp_path / "out" / "study.db")
    _refused(_argv(tmp_path, *(["--resume"] if resume else [])), says, capsys, tmp_path)


def test_a_held_study_needs_resume(tmp_path, capsys):
    import design_stub as stub
    from design_runs import run_stub

    (tmp_path / "out").mkdir()
    run_stub(tmp_path / "out" / "study.db", 2)
    assert stub  # the stand-in's study: a real one, not to be started over
    _refused(_argv(tmp_path), "holds a study already: use --resume", capsys, tmp_path)


@pytest.mark.parametrize("flag, value, says", [
    ("--trials", "0", "must be between 1 and"), ("--pick", "0", "must be >= 1"),
    ("--workers", "x", "not an integer"), ("--dask", " ", "an empty address"),
    ("--population", "1", "must be between 2 and")])
def test_bad_options_are_one_line(tmp_path, capsys, flag, value, says):
    _refused(_argv(tmp_path, flag, value), says, capsys, tmp_path)


def test_the_help_names_the_rule_and_the_outputs():
    p = build_parser()._subparsers._group_actions[0].choices["design"]
    text = " ".join(p.format_help().split())
    for part in ("--resume", "--dask ADDRESS", "--pick N", "front.csv", "trials.parquet",
                 "study.db", "within motor use 0.9 the fewest robots"):
        assert part in text, part
