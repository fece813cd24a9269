"""A design study's database: optuna's RDB storage on one SQLite file, checked before it is
opened, so that every refusal is one line and writes nothing.

The file holds one study, named :data:`STUDY_NAME`, whose user attributes say what it is:
``format`` (:data:`FORMAT`), ``job`` and ``space`` (the fingerprints of the paint job and of
the design space it was started with), ``objectives`` (names and senses). A new study is
refused where a study file already is (``resume`` continues it); a resumed one must have been
started with the same job and space. A path that is not a regular file (a FIFO, a device), a
file that is not SQLite, a SQLite file that is not a study of this format, a damaged one and a
folder that cannot be written are each one line (:class:`StudyFileError`).
"""
from __future__ import annotations

import hashlib
import json
import os
import sqlite3
import stat
from collections.abc import Sequence
from pathlib import Path

from ..errors import InputError
from ..io.atomic import check_destination, make_folder

STUDY_NAME = "pollard-pin design"
FORMAT = "pollard-pin design study 1"
SQLITE_MAGIC = b"SQLite format 3\x00"
OPTUNA_TABLES = {"studies", "trials", "version_info", "study_user_attributes"}


class StudyFileError(InputError):
    """A study database that cannot be used as asked (one line: which file, why)."""


def fingerprint(data) -> str:
    """A short stable digest of JSON-ready ``data`` (sorted keys; other values as text)."""
    text = json.dumps(data, sort_keys=True, default=str, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def job_fingerprint(job) -> str:
    """What makes a paint job the same job: its tables (``to_dict``) and the bytes of the
    files it names (a part's mesh, the actuators file), whatever their paths."""
    files = {}
    for attr in ("mesh", "actuators"):
        path = getattr(job, attr, None)
        if isinstance(path, (str, os.PathLike)):
            path = _job_file(job, path)
            if path.is_file():
                files[attr] = hashlib.sha256(path.read_bytes()).hexdigest()
    table = job.to_dict() if hasattr(job, "to_dict") else repr(job)
    if isinstance(table, dict):  # the files by their content, not by where they are
        table = {k: ({kk: vv for kk, vv in v.items() if kk not in ("mesh", "actuators")}
                     if isinstance(v, dict) else v) for k, v in table.items()}
    return fingerprint({"job": table, "files": files})


def _job_file(job, path) -> Path:
    path = Path(path)
    source = Path(str(getattr(job, "source", "")))
    return path if path.is_absolute() or not source.is_file() else source.parent / path


def check_study_file(path: str | Path, resume: bool) -> None:
    """Refuse, in one line and before anything is written, a study file that cannot be used:
    see the module's docstring.

    Parameters
    ----------
    path : str or Path
        The SQLite file (``DIR/study.db``).
    resume : bool
        Continue the study in ``path`` (it must be there) rather than start one (it must not).

    Raises
    ------
    StudyFileError
        Why ``path`` cannot be used.
    pollard_pin.io.atomic.OutputError
        Its folder cannot be written.
    """
    path = Path(path)
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as exc:
        raise StudyFileError(f"{path}: cannot read the study file ({exc.strerror})") from None
    if mode is not None and stat.S_ISDIR(mode):
        raise StudyFileError(f"{path}: is a folder, not a study file")
    if mode is not None and not stat.S_ISREG(mode):
        raise StudyFileError(f"{path}: not a regular file (a FIFO or a device); a study "
                             "needs a SQLite file")
    check_destination(path.parent, folder=True)  # SQLite writes a journal beside it
    if mode is None:
        if resume:
            raise StudyFileError(f"{path}: no study to resume (leave out --resume to start one)")
        return
    if not os.access(path, os.R_OK | os.W_OK):
        raise StudyFileError(f"{path}: the study file cannot be read and written")
    with open(path, "rb") as f:
        head = f.read(len(SQLITE_MAGIC))
    if head != SQLITE_MAGIC:
        raise StudyFileError(f"{path}: not a study database (not a SQLite file)")
    tables = _tables(path)
    if not OPTUNA_TABLES <= tables:
        raise StudyFileError(f"{path}: a SQLite file, but not a study database (no optuna "
                             "study tables)")
    if not resume:
        raise StudyFileError(f"{path}: holds a study already: use --resume to continue it, or "
                             "another folder")


def _tables(path: Path) -> set[str]:
    """The tables of a SQLite file, read only; a damaged file is one line. Opened as
    immutable: reading a write-ahead-logged file otherwise leaves its -shm file beside it."""
    try:
        con = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro&immutable=1", uri=True)
        try:
            if con.execute("PRAGMA quick_check").fetchone()[0] != "ok":
                raise sqlite3.DatabaseError("quick_check failed")
            return {r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE "
                                              "type = 'table'")}
        finally:
            con.close()
    except sqlite3.Error as exc:
        raise StudyFileError(f"{path}: a damaged study database ({exc})") from None


def open_study(path: str | Path | None, *, job: str, space: str,
               objectives: Sequence[tuple[str, str]], sampler, resume: bool = False):
    """The optuna study in ``path`` (created, or resumed after checking what it is).

    Parameters
    ----------
    path : str or Path or None
        The SQLite file; None: a study in memory (nothing stored).
    job, space : str
        The fingerprints of the paint job and of the design space.
    objectives : Sequence of (str, str)
        (name, ``"maximize"`` or ``"minimize"``), in the study's order.
    sampler : optuna.samplers.BaseSampler
        The study's sampler.
    resume : bool, optional
        Continue the study in ``path``.

    Returns
    -------
    tuple of (optuna.Study, callable)
        The study, with the user attributes ``format``, ``job``, ``space`` and
        ``objectives``, and ``close()``, which closes the file (:func:`close_study`: its
        write-ahead log folded into it, none left beside it).

    Raises
    ------
    StudyFileError
        See :func:`check_study_file`; and a resumed study of another format, job, space or
        objectives.
    """
    optuna = require_optuna()
    directions = [sense for _, sense in objectives]
    named = [[n, s] for n, s in objectives]
    if path is None:
        study = optuna.create_study(study_name=STUDY_NAME, directions=directions,
                                    sampler=sampler)
        _label(study, job, space, named)
        return study, lambda: None
    path = Path(path)
    check_study_file(path, resume)
    if resume:  # refused before the file is opened for writing: it stays as it was
        attrs = _label_of(path)
        if attrs is not None:
            _check_label(path, attrs, job, space, named)
    make_folder(path.parent)
    url = f"sqlite:///{path.resolve()}"
    try:
        storage = optuna.storages.RDBStorage(url, engine_kwargs={"connect_args": {
            "timeout": 30}})
        _fast_commits(storage.engine)
        if not resume:
            study = optuna.create_study(storage=storage, study_name=STUDY_NAME,
                                        directions=directions, sampler=sampler)
            _label(study, job, space, named)
            return study, lambda: close_study(storage.engine, path)
        study = optuna.load_study(storage=storage, study_name=STUDY_NAME, sampler=sampler)
    except (KeyError, ValueError, RuntimeError) as exc:  # no such study, another version
        raise StudyFileError(f"{path}: not a {FORMAT!r} database ({_short(exc)})") from None
    except Exception as exc:  # sqlalchemy's errors: a damaged or locked file
        if type(exc).__module__.startswith("sqlalchemy"):
            raise StudyFileError(f"{path}: cannot open the study ({_short(exc)})") from None
        raise
    try:
        _check_label(path, study.user_attrs, job, space, named)
    except StudyFileError:
        storage.engine.dispose()  # closed: no log files are left beside it
        raise
    return study, lambda: close_study(storage.engine, path)


def close_study(engine, path: str | Path) -> None:
    """Close the study's connections and fold its write-ahead log into the file: a
    checkpoint, then the rollback journal (which SQLite deletes after each commit), so that
    the folder holds ``study.db`` alone, no ``-wal`` or ``-shm`` beside it; a study reopened
    writes ahead again (:func:`_fast_commits`). Another process still holding the file (its
    log then stays until it closes) is no error.

    Parameters
    ----------
    engine : sqlalchemy.engine.Engine
        The study storage's engine.
    path : str or Path
        The study file.
    """
    engine.dispose()
    try:
        con = sqlite3.connect(str(path), timeout=5)
        try:
            con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
            con.execute("PRAGMA journal_mode=DELETE")
        finally:
            con.close()
    except sqlite3.Error:
        pass


def _label_of(path: Path) -> dict | None:
    """The study's user attributes read from the file alone (None: not there to read, e.g.
    still in the log of a killed run: optuna's loader then reads them)."""
    try:
        con = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro&immutable=1", uri=True)
        try:
            rows = con.execute("SELECT a.key, a.value_json FROM study_user_attributes a JOIN "
                               "studies s ON s.study_id = a.study_id WHERE s.study_name = ?",
                               (STUDY_NAME,)).fetchall()
        finally:
            con.close()
        attrs = {k: json.loads(v) for k, v in rows}
    except (sqlite3.Error, ValueError):
        return None
    return attrs if "format" in attrs else None


def _check_label(path: Path, attrs: dict, job: str, space: str, named: list) -> None:
    if attrs.get("format") != FORMAT:
        raise StudyFileError(f"{path}: not a {FORMAT!r} database (format "
                             f"{attrs.get('format')!r})")
    for what, mine in (("job", job), ("space", space)):
        if attrs.get(what) != mine:
            raise StudyFileError(f"{path}: the study was started with another {what} "
                                 f"(fingerprint {attrs.get(what)}, this {what}: {mine}); "
                                 "resume it with the same one, or start one elsewhere")
    if attrs.get("objectives") != named:
        raise StudyFileError(f"{path}: the study judges other objectives "
                             f"({attrs.get('objectives')})")

def _fast_commits(engine) -> None:
    """Write-ahead logging, synced at checkpoints: a commit costs a write, not an fsync
    (~10 ms on a busy disk, and a study commits a few times per design). A killed process
    loses no committed evaluation (the log is replayed when the file is next opened); only
    a power cut may lose the last ones."""
    from sqlalchemy import event

    def pragmas(connection, _record):
        cursor = connection.cursor()
        cursor.execute("PRAGMA journal_mode=WAL")
        cursor.execute("PRAGMA synchronous=NORMAL")
        cursor.close()

    event.listen(engine, "connect", pragmas)
    engine.dispose()  # the connections opened before: reopened with the pragmas


def _label(study, job: str, space: str, named: list) -> None:
    for key, value in (("format", FORMAT), ("job", job), ("space", space),
                       ("objectives", named)):
        study.set_user_attr(key, value)


def _short(exc: BaseException) -> str:
    text = " ".join(str(exc).split("\n")[0].split())
    return text[:120] or type(exc).__name__


def require_optuna():
    """The ``optuna`` module, or one line saying how to install it."""
    try:
        import optuna
    except ImportError:
        raise ImportError("pollard-pin design needs optuna: pip install optuna") from None
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    return optuna
