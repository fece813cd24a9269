"""The study file (synthesis/storage.py): refused in one line, with nothing written, when it is
a FIFO, another format, damaged, another study, or not to be resumed; fingerprints."""
import os
import sqlite3

import pytest
import synthesis_stub as stub
from synthesis_runs import run_stub

from pollard_pin.synthesis.storage import (
    StudyFileError,
    check_study_file,
    fingerprint,
    job_fingerprint,
)
from pollard_pin.synthesis.study import DesignOptions


def _listing(folder):
    return sorted((p.name, p.stat().st_size) for p in folder.iterdir())


def _refused(path, match, resume=True):
    before = _listing(path.parent)
    with pytest.raises(StudyFileError, match=match) as info:
        check_study_file(path, resume)
    assert "\n" not in str(info.value) and len(str(info.value)) < 220
    assert _listing(path.parent) == before  # nothing written


def test_a_fifo_is_refused(tmp_path):
    os.mkfifo(tmp_path / "study.db")
    _refused(tmp_path / "study.db", "not a regular file")


def test_another_format_is_refused(tmp_path):
    (tmp_path / "study.db").write_text("trial,value\n1,2\n")
    _refused(tmp_path / "study.db", "not a SQLite file")


def test_a_sqlite_file_of_something_else_is_refused(tmp_path):
    con = sqlite3.connect(tmp_path / "study.db")
    con.execute("CREATE TABLE parts (name TEXT)")
    con.commit()
    con.close()
    _refused(tmp_path / "study.db", "no optuna study tables")


def test_a_damaged_study_is_refused(tmp_path):
    path = tmp_path / "study.db"
    run_stub(path, 3)
    data = bytearray(path.read_bytes())
    data[100:4096] = b"\xff" * (4096 - 100)  # the first page's b-tree, past the header
    path.write_bytes(bytes(data))
    _refused(path, "damaged study database")


def test_a_study_is_not_started_over_nor_resumed_from_nothing(tmp_path):
    _refused(tmp_path / "study.db", "no study to resume", resume=True)
    check_study_file(tmp_path / "study.db", resume=False)  # a new one: fine
    held = tmp_path / "held"
    held.mkdir()
    run_stub(held / "study.db", 2)
    _refused(held / "study.db", "use --resume to continue it", resume=False)
    _refused(tmp_path, "is a folder", resume=True)


def test_resuming_with_another_space_or_job_is_refused(tmp_path):
    path = tmp_path / "study.db"
    run_stub(path, 4)
    before = path.stat().st_mtime_ns, _listing(tmp_path)
    with pytest.raises(StudyFileError, match="started with another space"):
        run_stub(path, 8, resume=True, space=stub.StubSpace(shift=0.5))
    from pollard_pin.synthesis.api import design

    with pytest.raises(StudyFileError, match="started with another job"):
        design(stub.StubJob(speed=0.02), stub.StubSpace(),
               DesignOptions(trials=8, workers=1, study=path, resume=True), evaluator=stub)
    assert (path.stat().st_mtime_ns, _listing(tmp_path)) == before


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes anywhere")
def test_an_unwritable_folder_is_refused(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(Exception, match="ro"):
            check_study_file(folder / "study.db", resume=False)
    finally:
        folder.chmod(0o700)


def test_fingerprints_follow_the_content():
    assert fingerprint({"a": 1, "b": [1, 2]}) == fingerprint({"b": [1, 2], "a": 1})
    assert fingerprint({"a": 1}) != fingerprint({"a": 2})
    assert job_fingerprint(stub.StubJob()) == job_fingerprint(stub.StubJob())
    assert job_fingerprint(stub.StubJob()) != job_fingerprint(stub.StubJob(speed=0.02))


def test_optuna_missing_gives_one_line(tmp_path):
    import subprocess
    import sys

    code = ("import sys; sys.modules['optuna'] = None\nfrom pollard_pin.cli import main\n"
            f"sys.exit(main(['design', '--job', 'j.toml', '--space', 's.toml', '--out', "
            f"{str(tmp_path / 'out')!r}]))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2, r.stderr
    assert r.stderr.strip().splitlines() == [
        "pollard-pin design: error: pollard-pin design needs optuna: pip install optuna "
        "(nothing written to " + str(tmp_path / "out") + ")"]
    assert not (tmp_path / "out").exists()
