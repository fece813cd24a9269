"""Output files that are never left half-written, and destinations checked before the work.

A regular file (or a new one) is written to a temporary file beside it and renamed onto it
when complete, so a failed run leaves an existing file untouched. Anything else that exists
(a FIFO, a character device such as ``/dev/null``) is written in place: renaming onto it would
replace the device by a regular file. ``-`` is standard output.
"""
from __future__ import annotations

import contextlib
import os
import stat
import sys
import tempfile
from pathlib import Path

from ..errors import DestinationError

STDOUT = "-"


class OutputError(DestinationError):
    """An output destination cannot be written (one line: which path, why)."""


def is_special(path: Path) -> bool:
    """An existing destination that is not a regular file (FIFO, device, socket)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return False
    return not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


def check_destination(path: str | Path, *, folder: bool = False) -> None:
    """Raise :class:`OutputError` unless ``path`` can be written (a folder if ``folder``),
    before any work is done: it or its nearest existing parent must be writable."""
    if str(path) == STDOUT and not folder:
        return
    path = Path(path)
    if path.exists():
        if folder and not path.is_dir():
            raise OutputError(f"{path}: names a file, but a folder is expected")
        if not folder and path.is_dir():
            raise OutputError(f"{path}: is a folder, but a file is expected")
        if is_special(path):
            if not os.access(path, os.W_OK):
                raise OutputError(f"{path}: permission denied")
            return
        why = _cannot_create_in(path if folder else path.parent)
        if why:
            raise OutputError(f"{path}: cannot write it: {why}")
        return
    parent = path.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir():
        raise OutputError(f"{path}: cannot create it, {parent} is a file, not a folder")
    why = _cannot_create_in(parent)
    if why:
        raise OutputError(f"{path}: cannot create it in {parent}: {why}")


def _cannot_create_in(folder: Path) -> str | None:
    """Why no file can be created in ``folder``, or None. A real attempt (a temporary file,
    removed at once): access() says yes to root on read-only and pseudo file systems."""
    try:
        fd, tmp = tempfile.mkstemp(dir=folder if str(folder) else ".", prefix=".pollard-pin-")
    except OSError as exc:
        return exc.strerror or str(exc)
    os.close(fd)
    os.unlink(tmp)
    return None


def make_folder(path: str | Path) -> Path:
    """Create the output folder ``path`` (and parents), or raise :class:`OutputError`."""
    check_destination(path, folder=True)
    path = Path(path)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{path}: cannot create the folder: {exc.strerror}") from None
    return path


@contextlib.contextmanager
def atomic_open(path: str | Path, newline: str | None = None, binary: bool = False):
    """Open ``path`` for writing (text, or bytes if ``binary``); see the module notes."""
    mode = "wb" if binary else "w"
    if str(path) == STDOUT:
        out = sys.stdout.buffer if binary else sys.stdout
        yield out
        out.flush()
        return
    path = Path(path)
    check_destination(path)
    if is_special(path):
        with open(path, mode, **({} if binary else {"newline": newline})) as f:
            yield f
        return
    parent = path.parent if str(path.parent) else Path(".")
    try:
        parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as exc:
        raise OutputError(f"{path}: cannot write: {exc.strerror}") from None
    try:
        with os.fdopen(fd, mode, **({} if binary else {"newline": newline})) as f:
            yield f
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
