"""The pollard-pin command: a thin layer over the public API.

Every command loads the model (the shipped one, or --params FILE.toml and --set KEY=VALUE),
solves, and writes its output only when all went well. Errors are one line on standard error
with exit status 2; outputs are checked for writability before the work starts. This module
assembles the parser from one module per command (``add_parser(sub, parents)``,
``run(args)``), turns the project's errors into one line, and handles signals.
"""
from __future__ import annotations

import argparse
import contextlib
import ctypes
import errno
import logging
import os
import re
import signal
import sys
import threading

from ..errors import LONGEST_LINE, say_less
from ..io.atomic import STDOUT
from ..version import __version__
from . import (
    calibrate,
    design,
    export,
    info,
    paint,
    place,
    plot,
    report,
    run,
    simulate,
    size,
    stiffness,
    sweep,
    urdf,
    view,
    workspace,
)
from .common import HelpFormatter, Parser, say_notes

DESCRIPTION = """\
Verified multibody model of the Pollard spray-painting parallel robot (Pinocchio).

Solve a painting trajectory for every joint's motion and every actuator's torque, view it in
a browser, plot it, size the actuators, sweep the design, and plan how to paint a panel. See
docs/model.md for the model and its conventions.
"""

COMMANDS = (urdf, info, run, sweep, view, plot, report, size, simulate, paint, place, export,
            workspace, stiffness, calibrate, design)


def build_parser() -> argparse.ArgumentParser:
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-v", "--verbose", action="count", default=argparse.SUPPRESS,
                        help="log what happens (-vv: debug)")
    ap = Parser(prog="pollard-pin", description=DESCRIPTION, formatter_class=HelpFormatter)
    ap.add_argument("--version", action="version", version=f"pollard-pin {__version__}")
    ap.add_argument("-v", "--verbose", action="count", default=0,
                    help="log what happens (-vv: debug)")
    sub = ap.add_subparsers(dest="command", required=True, metavar="COMMAND",
                            parser_class=Parser)
    for module in COMMANDS:
        module.add_parser(sub, [common])
    return ap


def _errors() -> tuple[type[BaseException], ...]:
    """The project's own errors (one root), a missing optional dependency and memory: each is
    one line for the user, never a traceback."""
    from ..errors import PollardError

    return (PollardError, ImportError, MemoryError)


def main(argv=None) -> int:
    _survive_any_encoding()
    args = build_parser().parse_args(argv)
    if sys.stdout is None:  # started with standard output closed (>&-): nowhere to say
        print(f"pollard-pin {args.command}: error: standard output is closed: give it a file "
              "or /dev/null", file=sys.stderr)  # (stderr closed too: print says nothing)
        return 2
    logging.basicConfig(level=logging.WARNING - 10 * min(args.verbose, 2),
                        format="%(levelname)s %(name)s: %(message)s", stream=sys.stderr)
    errors = _errors()
    previous = _catch_signals()
    args.notes = []  # said after the work: on an error, the error is the only line
    try:
        code = args.func(args)
        say_notes(args)
        if not _flushed_stdout(args.command):
            return 2
        return code
    except errors as exc:
        message = " ".join(str(exc).split()) or type(exc).__name__
        if isinstance(exc, MemoryError):  # the hint only where there is a --samples to lower
            hint = ": fewer samples?" if hasattr(args, "samples") else ""
            message = f"not enough memory ({message}){hint}"
        limits = (" (--ignore-limits waives the joint limits)"
                  if _is_limit_error(exc) and hasattr(args, "ignore_limits") else "")
        out = getattr(args, "out", None) or getattr(args, "html", None)
        written = ("", "")
        if out and out != STDOUT:
            written = (f" (nothing written to {out})", " (nothing written)")
            if getattr(exc, "kept", None):  # what a failed command kept (design's study)
                written = (f" ({exc.kept})", "")
        head = f"pollard-pin {args.command}: error: "
        named = re.sub(r"^\S*/([^/\s]+): ", r"\1: ", message)  # a leading path: its name
        # one line within LONGEST_LINE: the suffixes and the path's folders give way before
        # the cause (say_less)
        print(say_less(*(head + m + limits + w for m in (message, named) for w in written),
                       head + named + limits, head + named, width=LONGEST_LINE),
              file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        return _interrupted(args.command, isinstance(exc, _Terminated))
    except ctypes.ArgumentError:  # the interrupt raised converting a ctypes call's argument
        if not _SIGNALLED:  # (rtree's queries): the same one line
            raise
        return _interrupted(args.command, _SIGNALLED[-1] == signal.SIGTERM)
    except UnicodeEncodeError as exc:  # a text stream _survive_any_encoding could not fix
        print(f"pollard-pin {args.command}: error: standard output cannot show "
              f"{exc.object[exc.start:exc.end]!a} in {exc.encoding}: set PYTHONIOENCODING=utf-8",
              file=sys.stderr)
        return 2
    except OSError as exc:
        if exc.errno == errno.ENAMETOOLONG and _too_long(args.command, exc.filename):
            return 2  # an input's name, asked by Path.exists or is_dir (outputs: check_name)
        if exc.errno in _FULL and not _broken_pipe(exc):
            # the outputs' own write errors are OutputErrors (above): this is the text the
            # command prints, to a full or failing standard output
            _stdout_failed(args.command, exc)
            return 2
        if not _broken_pipe(exc):
            raise
        # The reader of standard output or of a FIFO stopped (`run --out - | head`): stop
        # quietly like any Unix filter, 128 + SIGPIPE, with no flush error at exit.
        with contextlib.suppress(OSError, ValueError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    finally:
        for signum, handler in previous:
            signal.signal(signum, handler)


def _too_long(command: str, path) -> bool:
    """Say in one line (as io.atomic.check_name words it) that ``path`` is too long for the
    file system; whether it was."""
    from ..io.atomic import OutputError, check_name

    try:
        check_name(path)
    except OutputError as exc:
        print(f"pollard-pin {command}: error: {exc}", file=sys.stderr)
        return True
    except (TypeError, ValueError):  # no path to name (None)
        pass
    return False


def _flushed_stdout(command: str) -> bool:
    """Flush what the command printed (a summary is held in the buffer until now when standard
    output is a file): a full or failing destination is one line, not an 'Exception ignored'
    at exit. A closed pipe stays a broken pipe (141)."""
    try:
        sys.stdout.flush()
    except OSError as exc:
        if _broken_pipe(exc):
            raise
        _stdout_failed(command, exc)
        return False
    return True


# errno of a destination that is full or failing (not a closed reader: that is EPIPE)
_FULL = {errno.ENOSPC, errno.EIO, errno.EDQUOT, errno.EFBIG}


def _stdout_failed(command: str, exc: OSError) -> None:
    """One line for standard output that cannot take the command's text (worded as
    io.atomic's write errors); no second failure when Python flushes it at exit."""
    why = exc.strerror or str(exc)
    print(f"pollard-pin {command}: error: standard output: cannot write: "
          f"{why[:1].lower() + why[1:]}", file=sys.stderr)
    with contextlib.suppress(OSError, ValueError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


def _survive_any_encoding() -> None:
    """The text the commands print (θ, µ, σ, ±, →) on a terminal or pipe whose encoding lacks
    them (PYTHONIOENCODING=ascii, a Latin-1 locale): written as backslash escapes, never a
    crash after the work. Files are UTF-8 whatever the locale (io.atomic)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            "θµσ±→×–²∈…".encode(stream.encoding or "ascii")
        except (UnicodeEncodeError, LookupError):
            with contextlib.suppress(AttributeError, ValueError):
                stream.reconfigure(errors="backslashreplace")
        except AttributeError:  # no encoding: not a text stream we can fix
            pass


def _is_limit_error(exc: BaseException) -> bool:
    from ..kinematics.errors import JointLimitError

    return isinstance(exc, JointLimitError)


class _Terminated(KeyboardInterrupt):
    """SIGTERM (kill, a scheduler's time limit) raised like Ctrl-C, so that the temporary
    output files are removed; Python's default would end the process on the spot."""


_SIGNALLED: list[int] = []  # the signals caught: an exception wrapping their raise maps too


def _catch_signals() -> list:
    """SIGTERM raises :class:`_Terminated` and SIGINT KeyboardInterrupt (main thread only; an
    ignored SIGINT stays ignored), each noted in _SIGNALLED; the previous handlers."""
    if threading.current_thread() is not threading.main_thread():
        return []

    def terminate(signum, frame):
        _SIGNALLED.append(signum)
        raise _Terminated

    def interrupt(signum, frame):
        _SIGNALLED.append(signum)
        raise KeyboardInterrupt

    previous = [(signal.SIGTERM, signal.signal(signal.SIGTERM, terminate))]
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        previous.append((signal.SIGINT, signal.signal(signal.SIGINT, interrupt)))
    return previous


def _interrupted(command: str, terminated: bool) -> int:
    how = "terminated" if terminated else "interrupted"
    print(f"pollard-pin {command}: {how}, nothing written", file=sys.stderr)
    return 143 if terminated else 130


def _broken_pipe(exc: OSError) -> bool:
    """EPIPE, from Python or from polars' writer (a plain OSError naming the Rust os error)."""
    return (isinstance(exc, BrokenPipeError) or exc.errno == errno.EPIPE
            or f"(os error {errno.EPIPE})" in str(exc))


if __name__ == "__main__":
    sys.exit(main())
