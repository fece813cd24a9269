"""The study (synthesis/study.py): every finished evaluation is stored as it finishes, a stopped
study resumes where it stopped and loses nothing, SIGTERM stops it within a second."""
import contextlib
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import optuna
import pytest
import synthesis_stub as stub
from synthesis_runs import run_stub

from pollard_pin.errors import InputError, SolveError
from pollard_pin.synthesis.api import design
from pollard_pin.synthesis.space import Variable
from pollard_pin.synthesis.study import (
    EVALUATION,
    DesignOptions,
    finished,
    outside_bounds,
    suggest,
)

ROOT = Path(__file__).resolve().parents[2]


def _trials(path):
    study = optuna.load_study(study_name="pollard-pin design",
                              storage=f"sqlite:///{path}")
    return study.get_trials()


def _stop_after(n):
    def report(done, total, feasible, best):
        if done >= n:
            raise KeyboardInterrupt
    return report


def test_a_stopped_study_resumes_and_loses_nothing(tmp_path):
    path = tmp_path / "study.db"
    with pytest.raises(KeyboardInterrupt):
        design(stub.StubJob(), stub.StubSpace(),
               DesignOptions(trials=9, workers=1, study=path, population=4), evaluator=stub,
               progress=_stop_after(4))
    first = [t for t in _trials(path) if t.state == optuna.trial.TrialState.COMPLETE]
    assert len(first) == 4  # each stored the moment it finished
    result = run_stub(path, 9, resume=True, population=4)
    trials = _trials(path)
    done = [t for t in trials if t.state == optuna.trial.TrialState.COMPLETE]
    assert len(done) == 9 == len(result.trials)
    assert not [t for t in trials if t.state == optuna.trial.TrialState.RUNNING]
    for old in first:  # the first run's evaluations, kept as they were
        again = trials[old.number]
        assert (again.params, again.values) == (old.params, old.values)
        assert again.user_attrs[EVALUATION] == old.user_attrs[EVALUATION]
    # resumed without more trials: nothing is evaluated again
    assert len(run_stub(path, 9, resume=True, population=4).trials) == 9
    assert len(_trials(path)) == len(trials)


def test_each_trial_stores_its_evaluation_and_constraints(tmp_path):
    path = tmp_path / "study.db"
    run_stub(path, 6)
    for t in _trials(path):
        found = t.user_attrs[EVALUATION]
        values = {**t.params}
        objectives, constraints = stub.figures(values, {"shift": 0.0, "speed": 0.012})
        assert found["feasible"] == (constraints["reach"] <= 0 and
                                     objectives["motor_use"] <= 1.0)
        assert t.constraints["reach"] == pytest.approx(constraints["reach"])
        assert found["level"] == ("full" if constraints["reach"] <= 0 else "screen")
        if found["feasible"]:
            assert t.values[0] == pytest.approx(objectives["parts_per_hour"])
            assert "params.toml" in found["files"]


def _broken(values, ctx, level="screen"):
    raise ZeroDivisionError("a bug")


def test_evaluations_that_raise_fail_their_trial_then_stop_the_study(tmp_path):
    broken = type("Broken", (), {"OBJECTIVES": stub.OBJECTIVES, "prepare": stub.prepare,
                                 "baseline_values": staticmethod(stub.baseline_values),
                                 "evaluate": staticmethod(_broken)})
    with pytest.raises(SolveError, match="10 design evaluations raised; the first: "
                                         "ZeroDivisionError: a bug"):
        design(stub.StubJob(), stub.StubSpace(),
               DesignOptions(trials=50, workers=1, study=tmp_path / "s.db"), evaluator=broken)
    study = optuna.load_study(study_name="pollard-pin design",
                              storage=f"sqlite:///{tmp_path / 's.db'}")
    assert finished(study) == (10, 0, 10)


def test_a_local_pool_gives_a_study_of_the_same_designs(tmp_path):
    result = run_stub(tmp_path / "pool.db", 8, workers=2)
    assert len(result.trials) == 8
    for row in result.trials:  # each judged as the stand-in judges it, whichever process
        values = {**row, "motor": tuple(stub.MOTORS).index(row["motor"])}  # shown: the name
        objectives, _ = stub.figures(values, {"shift": 0.0})
        if row["feasible"]:
            assert row["kmin"] == pytest.approx(objectives["kmin"])


def test_a_reference_outside_a_bound_is_named_once_in_the_projects_words(recwarn):
    """A bound in radians for a limit in degrees: the thesis robot's −35° lies outside
    [−0.6, 0]; outside_bounds names it (and only it: the bound's ends are inside), and the
    enqueued row's suggest no longer passes on optuna's "Fixed parameter … out of range"."""
    variables = [Variable("limits.theta21.upper", -0.6, 0.0, "float"),
                 Variable("scale.arms", 1.0, 1.8, "float"), Variable("robots", 1, 3, "int")]
    base = {"limits.theta21.upper": -35.0, "scale.arms": 1.0, "robots": 1}
    assert outside_bounds(base, variables) == "limits.theta21.upper = -35 (bound [-0.6, 0])"
    assert outside_bounds({**base, "limits.theta21.upper": -0.6}, variables) is None
    study = optuna.create_study()
    study.enqueue_trial(base)
    assert suggest(study.ask(), variables) == base
    assert not [w for w in recwarn if "Fixed parameter" in str(w.message)], recwarn.list


def test_options_are_checked_once():
    with pytest.raises(InputError, match="trials: must be an integer >= 1"):
        DesignOptions(trials=0)
    with pytest.raises(InputError, match="resume: needs a study file"):
        DesignOptions(resume=True)
    with pytest.raises(InputError, match="seed"):
        DesignOptions(seed=1.5)
    for seed in (-1, 2**32, 2**95):  # numpy's seeds are 0..2^32 − 1
        with pytest.raises(InputError, match=r"seed: must be an integer 0..2\^32 − 1"):
            DesignOptions(seed=seed)
    for flag in ("resume", "screen_only", "ladder"):  # a truthy string is not True
        with pytest.raises(InputError, match=f"DesignOptions.{flag} = 'no': expected True or "
                           "False, got str"):
            DesignOptions(**{flag: "no"})
    with pytest.raises(InputError, match="DesignOptions.progress = 'yes': expected a function "
                       "or None, got str"):
        DesignOptions(progress="yes")
    with pytest.raises(InputError, match=r"trials: must be an integer >= 1, got -1e\+400 \(a "
                       r"401-digit integer\)"):
        DesignOptions(trials=-10**400)


# SIGTERM raised as the command line raises it (pollard_pin.cli.main): an exception that
# unwinds the study, not the end of the process on the spot
SCRIPT = """
import signal, sys
sys.path[:0] = [{root!r}, {tests!r}]
def stop(signum, frame):
    raise KeyboardInterrupt
signal.signal(signal.SIGTERM, stop)
from synthesis_runs import run_stub
run_stub({path!r}, 10000, workers=2)
"""


def test_sigterm_stops_the_study_and_keeps_every_finished_evaluation(tmp_path):
    path = tmp_path / "study.db"
    code = SCRIPT.format(root=str(ROOT), tests=str(ROOT / "tests"), path=str(path))
    env = {**os.environ, "STUB_DELAY": "0.05"}
    proc = subprocess.Popen([sys.executable, "-c", code], env=env, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not _some_finished(path):
            time.sleep(0.2)
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=30)
    finally:
        proc.kill()
    assert proc.returncode != 0, proc.stderr.read().decode()[-2000:]
    err = proc.stderr.read().decode()
    assert "KeyboardInterrupt" in err, err[-2000:]
    # how soon it stops is a figure, not an assertion (no timing asserts): it stopped
    trials = _trials(path)
    assert not [t for t in trials if t.state == optuna.trial.TrialState.RUNNING], err[-2000:]
    done = [t for t in trials if t.state == optuna.trial.TrialState.COMPLETE]
    assert done and all(EVALUATION in t.user_attrs for t in done)


def _some_finished(path):
    """Two evaluations stored, read with sqlite3 read-only: optuna's own loader would create
    its tables in a file the running study is creating (a race on alembic_version)."""
    if not path.is_file():
        return False
    try:
        with contextlib.closing(sqlite3.connect(f"file:{path}?mode=ro", uri=True)) as db:
            (n,) = db.execute("SELECT count(*) FROM trials WHERE state = 'COMPLETE'").fetchone()
        return n >= 2
    except sqlite3.Error:  # being created
        return False


@pytest.mark.parametrize("dask, says", [
    (" ", "DesignOptions.dask: an empty scheduler address; e.g. tcp://127.0.0.1:8786, or None "
          "to run locally"),
    ("", "DesignOptions.dask: an empty scheduler address"),
    ("localhost", "DesignOptions.dask: not a scheduler address: 'localhost' (missing port "
                  "number in address 'localhost'); e.g. tcp://127.0.0.1:8786"),
    ("tpc://127.0.0.1:8786", "DesignOptions.dask: not a scheduler address: "
                             "'tpc://127.0.0.1:8786' (unknown address scheme 'tpc'"),
    (3, "DesignOptions.dask = 3: expected a scheduler address (str), a distributed.Client or "
        "None, got int"),
], ids=["blank", "empty", "no port", "scheme", "int"])
def test_a_blank_or_malformed_scheduler_is_refused_when_the_options_are_made(dask, says):
    # the old options took them: " " was refused after the ladder had started, a malformed
    # one by the connection, and 3 as a TypeError from distributed.Client
    pytest.importorskip("distributed")
    with pytest.raises(InputError) as e:
        DesignOptions(dask=dask)
    assert str(e.value).startswith(says) and "\n" not in str(e.value), str(e.value)


def test_a_well_formed_scheduler_address_is_taken_as_given():
    pytest.importorskip("distributed")
    for address in ("tcp://127.0.0.1:8786", " localhost:8786 ", "inproc://x", None):
        assert DesignOptions(dask=address).dask == address  # --dask's rule: the same ones


def test_a_resumed_studys_seed_wraps_round_numpys_range(monkeypatch):
    """The sampler's seed moves on by the evaluations held (docs/model.md §31.5), within
    numpy's 0..2^32 − 1 (beyond it the sampler raised)."""
    import optuna

    from pollard_pin.synthesis.study import sampler

    seeds = []
    monkeypatch.setattr(optuna.samplers, "NSGAIISampler",
                        lambda population_size, seed: seeds.append(seed))
    sampler(DesignOptions(seed=2**32 - 1), finished=3)
    sampler(DesignOptions(seed=7), finished=3)
    assert seeds == [2, 10]
