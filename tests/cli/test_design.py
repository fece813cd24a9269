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
    import synthesis_stub as stub
    from synthesis_runs import run_stub

    (tmp_path / "out").mkdir()
    run_stub(tmp_path / "out" / "study.db", 2)
    assert stub  # the stand-in's study: a real one, not to be started over
    _refused(_argv(tmp_path), "holds a study already: use --resume", capsys, tmp_path)


@pytest.mark.parametrize("flag, value, says", [
    ("--trials", "0", "must be between 1 and"), ("--pick", "0", "must be >= 1"),
    ("--workers", "x", "not an integer"), ("--dask", " ", "an empty scheduler address"),
    ("--population", "1", "must be between 2 and"),
    # beyond numpy's seeds: was a traceback from the sampler, the study file left behind
    ("--seed", str(2**32), "must be between 0 and 4294967295")])
def test_bad_options_are_one_line(tmp_path, capsys, flag, value, says):
    _refused(_argv(tmp_path, flag, value), says, capsys, tmp_path)


def test_the_help_names_the_rule_and_the_outputs():
    p = build_parser()._subparsers._group_actions[0].choices["design"]
    text = " ".join(p.format_help().split())
    for part in ("--resume", "--dask ADDRESS", "--pick N", "front.csv", "trials.parquet",
                 "study.db", "within motor use 0.9 the fewest robots"):
        assert part in text, part


@pytest.fixture
def stand_in(monkeypatch):
    """The command over the stand-in evaluator (tests/synthesis_stub.py): its job, its space."""
    import synthesis_stub as stub

    from pollard_pin.synthesis import api

    monkeypatch.setattr(api, "default_evaluator", lambda: stub)
    monkeypatch.setattr(api, "_as_job", lambda job: stub.StubJob())
    monkeypatch.setattr(api, "_as_space", lambda space: stub.StubSpace())
    return stub


def test_a_study_writes_the_chosen_design_and_resumes(tmp_path, capsys, stand_in):
    argv = _argv(tmp_path, "--trials", "12", "--workers", "1", "--population", "4")
    code, out, err = run_cli(argv, capsys)
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0].startswith("12 evaluations, ") and lines[1].startswith("thesis robot: ")
    assert lines[2].startswith("design 1 (chosen): ")
    assert "(one per box of parts/h 1 %, motor use 0.01, kmin 10 %, moving mass 2 %)" in lines[0]
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"params.toml", "actuators.toml", "front.csv", "front.units.json",
            "trials.parquet", "front.png", "study.db"} <= names
    assert not [n for n in names if n.startswith("study.db-")]  # no -wal, no -shm left
    assert "wrote " in err and "chosen: design 1" in err
    # resumed to 16: the 12 kept, 4 more; --pick 2 writes the second row's files (of the
    # exact front: --exact-front)
    code, out, err = run_cli([*argv[:-6], "--trials", "16", "--workers", "1", "--population",
                              "4", "--resume", "--pick", "2", "--exact-front"], capsys)
    assert code == 0, err
    assert out.splitlines()[0].startswith("16 evaluations, ")
    assert "box" not in out.splitlines()[0]
    assert "chosen: design 2" in err and "design 2 (chosen): " in out


def test_a_study_that_fails_before_any_evaluation_leaves_nothing(tmp_path, capsys, stand_in,
                                                                  monkeypatch):
    # a scheduler that never answers (or a full disk) after the study file was made: the old
    # code left out/study.db behind a line that said "nothing written to out"
    from pollard_pin.errors import SolveError
    from pollard_pin.synthesis import api

    def unreachable(*args, **kwargs):
        raise SolveError("cannot connect to the Dask scheduler at 'tcp://127.0.0.1:1'")

    monkeypatch.setattr(api, "make_runner", unreachable)
    _refused(_argv(tmp_path, "--trials", "4", "--workers", "1", "--population", "4"),
             "cannot connect to the Dask scheduler at 'tcp://127.0.0.1:1' (nothing written to",
             capsys, tmp_path)
    assert not (tmp_path / "out").exists()


def test_a_study_that_fails_after_its_evaluations_says_they_are_kept(tmp_path, capsys,
                                                                     stand_in):
    argv = _argv(tmp_path, "--trials", "8", "--workers", "1", "--population", "4")
    code, out, err = run_cli([*argv, "--pick", "99"], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and out == "" and len(lines) == 1, err
    assert lines[0].startswith("pollard-pin design: error: --pick 99: the front has "), lines[0]
    assert lines[0].endswith(f"(8 finished evaluations kept in {tmp_path / 'out' / 'study.db'}"
                             ": --resume continues the study)"), lines[0]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["study.db"]
    code, out, err = run_cli([*argv, "--resume"], capsys)  # and it does
    assert code == 0 and out.startswith("8 evaluations, "), err
