"""Output files that are never left half-written, and destinations checked before the work.

The rules every command follows (docs/model.md §15, end):

* A regular file (or a new one) is written to a temporary file beside it and renamed onto it
  when complete, so a failed run leaves an existing file untouched. Inside
  :func:`all_or_nothing`, every such file is only staged: all are renamed together when the
  block succeeds, all removed when anything fails, so a command with several outputs replaces
  all of them or none.
* Anything else that exists (a FIFO, a character device such as ``/dev/null``) is written in
  place: renaming onto it would replace the device by a regular file, and it cannot be rolled
  back, so a command writes it last. A FIFO with no reader within :data:`FIFO_WAIT` s is an
  :class:`OutputError`, not a hang. ``-`` is standard output.
* A symbolic link to a file is written through: its target is replaced (atomically, beside
  the target) and the link stays. A dangling link or a link loop is refused up front.
* :func:`check_outputs` checks every destination of a command before the work starts, and
  refuses two outputs that name the same file.
* Any operating-system error while writing (a full disk, a lost device) becomes one
  :class:`OutputError` line naming the path and the reason.
"""
from __future__ import annotations

import contextlib
import contextvars
import errno
import io
import os
import re
import stat
import sys
import tempfile
import time
from pathlib import Path

from ..errors import DestinationError, PollardError
from ..model.values import shown_path

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


def _broken_link(path: Path) -> str | None:
    """Why ``path`` or one of its parents is a symbolic link that leads nowhere, or None."""
    for p in (path, *path.parents):
        if os.path.islink(p) and not os.path.exists(p):
            what = "" if p == path else f"{p} is "
            try:
                os.stat(p)
            except OSError as exc:
                if exc.errno == errno.ELOOP:
                    return f"{what}a symbolic link loop"
            return f"{what}a dangling symbolic link (to {os.readlink(p)})"
    return None


def _target(path: Path) -> Path:
    """The file ``path`` names: a symbolic link's final target (written through)."""
    return Path(os.path.realpath(path)) if os.path.islink(path) else path


NAME_MAX, PATH_MAX = 255, 4096  # bytes: a name, a whole path (Linux, macOS: 255 and 1024+)


def check_name(path: str | Path) -> None:
    """Raise :class:`OutputError` if ``path`` holds a name longer than a file system takes
    (:data:`NAME_MAX` bytes) or is longer than :data:`PATH_MAX` bytes: the system's refusal
    (ENAMETOOLONG) came from the first ``Path.exists`` as a traceback. The message shows the
    path cut short (the name itself is too long for a line)."""
    whole = len(os.fsencode(os.path.abspath(path)))
    longest = max((len(os.fsencode(part)) for part in Path(path).parts), default=0)
    if longest > NAME_MAX or whole >= PATH_MAX:
        what = (f"holds a name of {longest} bytes, over the {NAME_MAX} a file system takes"
                if longest > NAME_MAX else
                f"is {whole} bytes long, over the {PATH_MAX} a file system takes")
        raise OutputError(f"{shown_path(path, 50)}: {what}: give a shorter one")


def _check_climb(path: str | Path) -> None:
    """Refuse a '..' out of a folder that does not exist (``w/../w2``): the system resolves it
    only once the folder is made, and the folder would be left behind, empty, whether the
    command succeeds or fails. Out of an existing folder, '..' is the system's to resolve."""
    parts = Path(path).parts
    for i, part in enumerate(parts):
        if part == ".." and i > 0 and parts[i - 1] != ".." and not os.path.lexists(
                Path(*parts[:i])):
            # the first missing folder on: below it no link can make '..' mean other than
            # what it says, so the rest is resolved as text
            m = next(k for k in range(i) if not os.path.lexists(Path(*parts[:k + 1])))
            meant = Path(*parts[:m], os.path.normpath(Path(*parts[m:])))
            raise OutputError(f"{path}: '..' climbs out of {Path(*parts[:i])}, which does "
                              f"not exist (it would be made only to be left empty): give "
                              f"{meant}")


def check_destination(path: str | Path, *, folder: bool = False) -> None:
    """Raise :class:`OutputError` unless ``path`` can be written (a folder if ``folder``),
    before any work is done: it or its nearest existing parent must be writable."""
    if str(path) == STDOUT and not folder:
        return
    check_name(path)
    _check_climb(path)
    if not folder and str(path).endswith(("/", os.sep)):  # Path() would drop it: r.csv/ → r.csv
        raise OutputError(f"{path}: ends in '/', as a folder's name does, but a file is expected")
    path = Path(path)
    broken = _broken_link(path)
    if broken:
        raise OutputError(f"{path}: {broken}; refusing to write through it")
    path = _target(path)
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


def check_outputs(*files: str | Path | None, folders: tuple = ()) -> None:
    """Check every output of one command before the work (``None``: not written): each can be
    written, and no two name the same file (one would overwrite the other; a character device
    such as ``/dev/null`` may take several)."""
    seen: dict = {}
    for path, folder in [(d, True) for d in folders if d is not None] + \
                        [(f, False) for f in files if f is not None]:
        check_destination(path, folder=folder)
        key = _identity(path)
        if key is None:
            continue
        if key in seen:
            same = (f"{path}" if str(path) == str(seen[key]) else f"{seen[key]} and {path}")
            raise OutputError(f"{same}: named by two outputs, one would overwrite the other: "
                              "give each output its own name")
        seen[key] = path


def check_not_inputs(outputs, inputs) -> None:
    """Refuse, before the work, an output that is one of the command's inputs (writing it
    would destroy what was read). ``outputs``: paths (``None``: not written); ``inputs``:
    (what, path) pairs, e.g. ``("the mesh", mesh)``. Identity as :func:`check_outputs` sees it:
    the same file through a symbolic link or a hard link is the same file; standard output
    and character devices (``/dev/null``) are never inputs."""
    read = {}
    for what, path in inputs:
        if path is not None and str(path) != STDOUT and os.path.exists(path):
            read.setdefault(_identity(path), (what, path))
    for out in outputs:
        if out is None or str(out) == STDOUT:
            continue
        key = _identity(out)
        if key is not None and key in read:
            what, path = read[key]
            also = "" if os.path.abspath(out) == os.path.abspath(path) else f", {path}"
            raise OutputError(f"{out}: is one of the inputs ({what}{also}): writing it would "
                              "destroy it, give another path")


def _identity(path: str | Path):
    if str(path) == STDOUT:
        return STDOUT
    try:
        st = os.stat(path)
    except OSError:
        return os.path.realpath(path)
    return None if stat.S_ISCHR(st.st_mode) else (st.st_dev, st.st_ino)


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


# s a FIFO's reader may take to open it (`pollard-pin run --out f & reader < f`)
FIFO_WAIT = 2.0


def _open_special(path: Path, target: Path) -> int:
    """A descriptor writing to the device or FIFO ``target``. A FIFO is opened without
    blocking: with no reader within :data:`FIFO_WAIT` s, one line rather than a hang."""
    if not stat.S_ISFIFO(os.stat(target).st_mode):
        try:
            return os.open(target, os.O_WRONLY)
        except OSError as exc:
            raise OutputError(f"{path}: cannot write: {_why(exc)}") from None
    deadline = time.monotonic() + FIFO_WAIT
    while True:
        try:
            fd = os.open(target, os.O_WRONLY | os.O_NONBLOCK)
        except OSError as exc:
            if exc.errno != errno.ENXIO:  # ENXIO: no reader yet
                raise OutputError(f"{path}: cannot write: {_why(exc)}") from None
            if time.monotonic() >= deadline:
                raise OutputError(f"{path}: a FIFO that no one reads (none opened it in "
                                  f"{FIFO_WAIT:g} s): start its reader first") from None
            time.sleep(0.02)
            continue
        os.set_blocking(fd, True)  # a reader is there: write as to any file
        return fd


def _why(exc: OSError) -> str:
    """'no space left on device': the reason of an OSError, also of one from Rust (polars)."""
    why = exc.strerror
    if not why:
        code = re.search(r"\(os error (\d+)\)", str(exc))
        why = os.strerror(int(code.group(1))) if code else str(exc) or type(exc).__name__
    return why[:1].lower() + why[1:]


def _broken_pipe(exc: OSError) -> bool:
    return (isinstance(exc, BrokenPipeError) or exc.errno == errno.EPIPE
            or f"(os error {errno.EPIPE})" in str(exc))


@contextlib.contextmanager
def _write_errors(path):
    """An OSError while writing ``path`` becomes one :class:`OutputError` line; a closed pipe
    stays what it is (the command stops quietly, like any Unix filter)."""
    try:
        yield
    except OSError as exc:
        if isinstance(exc, PollardError) or _broken_pipe(exc):
            raise
        where = "standard output" if str(path) == STDOUT else str(path)
        raise OutputError(f"{where}: cannot write: {_why(exc)}") from None


# --- all or nothing: the outputs of one command -------------------------------------------------
class _Transaction:
    """Staged files (temporary, beside their targets), stale files to remove and folders
    created, of the :func:`all_or_nothing` block running."""

    def __init__(self):
        self.staged: list[tuple[str, Path]] = []
        self.stale: list[Path] = []
        self.folders: list[Path] = []

    def stage(self, tmp: str, target: Path) -> None:
        if any(os.path.realpath(t) == os.path.realpath(target) for _, t in self.staged):
            os.unlink(tmp)
            raise OutputError(f"{target}: written twice by one command: give each output its "
                              "own name")
        self.staged.append((tmp, target))

    def commit(self) -> None:
        for i, (tmp, target) in enumerate(self.staged):
            try:
                os.replace(tmp, target)
            except OSError as exc:
                self.staged = self.staged[i:]
                self.abort()
                raise OutputError(f"{target}: cannot write: {_why(exc)}") from None
        for path in self.stale:  # after the new outputs are in place
            with contextlib.suppress(OSError):
                path.unlink()

    def abort(self) -> None:
        for tmp, _ in self.staged:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        for folder in self.folders:  # deepest first; only while empty
            try:
                folder.rmdir()
            except OSError:
                break


_ACTIVE: contextvars.ContextVar[_Transaction | None] = contextvars.ContextVar(
    "pollard_pin_outputs", default=None)


@contextlib.contextmanager
def all_or_nothing():
    """Within this block every :func:`atomic_open` (and so every writer of the package) only
    stages its file; at the end of the block all are renamed onto their targets together, and
    the files given to :func:`remove_stale` are removed. If anything fails, every staged file
    and every folder created is removed and no output changes. Nested blocks join the outer."""
    if _ACTIVE.get() is not None:
        yield
        return
    tx = _Transaction()
    token = _ACTIVE.set(tx)
    try:
        yield
    except BaseException:
        _ACTIVE.reset(token)
        tx.abort()
        raise
    _ACTIVE.reset(token)
    tx.commit()


def remove_stale(*paths: str | Path) -> None:
    """Remove earlier outputs this command replaces by others (the other table format): at
    the end of the :func:`all_or_nothing` block running (at once outside one). Only files
    and links: a folder of that name is left alone."""
    tx = _ACTIVE.get()
    for path in map(Path, paths):
        if path.is_symlink() or path.is_file():
            if tx is None:
                path.unlink()
            else:
                tx.stale.append(path)


def make_folder(path: str | Path) -> Path:
    """Create the output folder ``path`` (and parents), or raise :class:`OutputError`; inside
    :func:`all_or_nothing` the folders created are removed again if the block fails."""
    check_destination(path, folder=True)
    path = Path(path)
    created = [p for p in (path, *path.parents) if not p.exists()]  # deepest first
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{path}: cannot create the folder: {_why(exc)}") from None
    tx = _ACTIVE.get()
    if tx is not None:
        tx.folders[:0] = created  # deeper (later) folders go first
    return path


@contextlib.contextmanager
def atomic_open(path: str | Path, newline: str | None = None, binary: bool = False):
    """Open ``path`` for writing (text as UTF-8, or bytes if ``binary``); see the module
    notes."""
    mode = "wb" if binary else "w"
    text = {} if binary else {"newline": newline, "encoding": "utf-8"}
    if str(path) == STDOUT:
        with _write_errors(path):
            sys.stdout.flush()
            if binary or not hasattr(sys.stdout, "buffer"):
                out = sys.stdout.buffer if binary else sys.stdout
                yield out
                out.flush()
                return
            out = io.TextIOWrapper(sys.stdout.buffer, **text)  # UTF-8 whatever the locale
            try:
                yield out
                out.flush()
            finally:
                out.detach()
        return
    path = Path(path)
    check_destination(path)
    target = _target(path)
    if is_special(target):
        fd = _open_special(path, target)
        with _write_errors(path), os.fdopen(fd, mode, **text) as f:
            yield f
        return
    parent = target.parent if str(target.parent) else Path(".")
    make_folder(parent)
    try:
        fd, tmp = tempfile.mkstemp(dir=parent, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as exc:
        raise OutputError(f"{path}: cannot write: {_why(exc)}") from None
    try:
        with _write_errors(path), os.fdopen(fd, mode, **text) as f:
            yield f
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600
        tx = _ACTIVE.get()
        if tx is not None:
            tx.stage(tmp, target)
        else:
            os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
