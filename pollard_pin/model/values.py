"""One home for reading what the user gives: input files opened safely, TOML parsed within
limits, numbers checked; values are shown short in messages by
:func:`pollard_pin.checks.shorten` and :func:`~pollard_pin.checks.clip` (their home, below the
model: imported from there, not from here).

Every reader of the package (parameter, actuator, paint job and grid files, trajectory CSVs,
result tables, command-line numbers) uses these, so that a FIFO, a 5,000-digit integer,
arrays nested 3,000 deep, ``0.5_5`` or full-width digits get the same one-line answer
everywhere. Each function raises the caller's error class (an
:class:`~pollard_pin.errors.InputError`).
"""
from __future__ import annotations

import errno
import math
import os
import stat
import sys
import tomllib
from pathlib import Path
from typing import Any

from ..checks import NUL_IN_PATH, is_integer, problem, shorten

MAX_DEPTH = 32  # nested arrays/tables: a parameter file needs 3 (an inertia matrix)
MAX_TOML_BYTES = 1 << 20  # 1 MiB: the shipped parameter file is ~5 kB


def shown_path(path: str | Path, width: int = 160) -> str:
    """A path quoted for a message: whole up to ``width`` characters, else its start (a
    quarter) and its end (the file name stays)."""
    text = repr(str(path))
    head = width // 4
    return text if len(text) <= width else f"{text[:head]}…{text[-(width - head - 1):]}"


# --- files ------------------------------------------------------------------------------------
def open_regular(path: str | Path, mode: str = "rb", **kwargs):
    """``open(path, mode)`` for reading that refuses what is not a regular file (a FIFO with
    no writer would block forever, a device never ends) with an :class:`OSError` whose
    ``strerror`` says so; a NUL in the name is an OSError too, not a ValueError."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except ValueError:  # "embedded null byte"
        raise OSError(errno.EINVAL, NUL_IN_PATH, str(path)) from None
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(path))
        if not stat.S_ISREG(st.st_mode):
            kind = ("a FIFO" if stat.S_ISFIFO(st.st_mode) else
                    "a device" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode) else
                    "a socket" if stat.S_ISSOCK(st.st_mode) else "special")
            raise OSError(errno.EINVAL, f"not a regular file ({kind})", str(path))
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        return open(fd, mode, **kwargs)
    except BaseException:
        os.close(fd)
        raise


def read_bytes(path: str | Path, what: str, error: type[Exception],
               limit: int | None = None) -> bytes:
    """The bytes of the regular file ``path`` (at most ``limit``); a missing, unreadable,
    special or too large file raises ``error`` naming ``what`` (e.g. "parameter file")."""
    shown = shown_path(path)
    try:
        with open_regular(path) as f:
            data = f.read(-1 if limit is None else limit + 1)
    except FileNotFoundError:
        raise error(f"{what} {shown} does not exist") from None
    except OSError as exc:
        raise error(f"{what} {shown} cannot be read: {exc.strerror or exc}") from None
    if limit is not None and len(data) > limit:
        raise error(f"{what} {shown} is over {limit / 2**20:.4g} MiB, the limit")
    return data


def read_toml(path: str | Path, what: str, error: type[Exception]) -> dict:
    """The TOML file ``path`` as a dictionary; a missing, unreadable, special, over-large,
    non-UTF-8, malformed or absurdly nested file raises ``error`` with one line naming
    ``what`` (e.g. "parameter file") and the cause."""
    data = read_bytes(path, what, error, MAX_TOML_BYTES)
    where = f"{what} {shown_path(path)}"
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{where} is not UTF-8 text (byte {exc.start}: "
                    f"{data[exc.start:exc.start + 1]!r})") from None
    return loads_toml(text, where, error)


class _Beyond(float):
    """A TOML float written beyond the float range (``1e400`` reads as inf, ``1e-400`` as 0),
    shown as written: a message then says what the file says."""

    text = ""

    def __repr__(self) -> str:
        return self.text


def _parse_float(text: str) -> float:
    """tomllib's float reader, marking a written number that does not survive it: one of
    magnitude beyond about 1.8e308, or below the smallest float and not zero."""
    value = float(text)
    digits = text.lower().split("e")[0]
    if (math.isinf(value) and "inf" not in text) or (value == 0 and digits.strip("+-0.")):
        value = _Beyond(value)
        value.text = text
    return value


def loads_toml(text: str, where: str, error: type[Exception], ints: bool = True) -> dict:
    """``tomllib.loads`` within limits: nesting deeper than :data:`MAX_DEPTH`, an integer
    beyond Python's digit limit or (``ints``) a number beyond the float range (an integer, or
    a float written as ``1e400`` or ``1e-400``) raise ``error`` (one line); with ``ints``
    false they go on to the value's own check, shown as written."""
    try:
        data = tomllib.loads(text, parse_float=_parse_float)
    except tomllib.TOMLDecodeError as exc:
        raise error(f"{where} is not valid TOML: {exc}") from None
    except RecursionError:
        data = None
    except ValueError:  # int(): more digits than sys.get_int_max_str_digits()
        limit = sys.get_int_max_str_digits() if hasattr(sys, "get_int_max_str_digits") else 0
        raise error(f"{where}: an integer of more than {limit} digits; numbers are at most "
                    "about 1.8e308") from None
    if data is None:
        raise error(f"{where}: arrays or tables nested more than {MAX_DEPTH} deep")
    _check_tree(data, where, error, ints)
    return data


def _check_tree(data: dict, where: str, error: type[Exception], ints: bool) -> None:
    """Depth and integer range of a parsed TOML tree, iteratively (no recursion to blow)."""
    stack: list[tuple[Any, str, int]] = [(data, "", 0)]
    while stack:
        node, key, depth = stack.pop()
        if depth > MAX_DEPTH:
            raise error(f"{where}: {shorten(key.split('[')[0])} nests arrays or tables more "
                        f"than {MAX_DEPTH} deep")
        if isinstance(node, dict):
            stack.extend((v, f"{key}.{k}" if key else str(k), depth + 1) for k, v in node.items())
        elif isinstance(node, list):
            stack.extend((v, f"{key}[{i}]", depth + 1) for i, v in enumerate(node))
        elif ints and isinstance(node, int) and not isinstance(node, bool) \
                and not _fits_float(node):
            raise error(f"{where}: '{key}' = {shorten(node)}: must be within the float range "
                        "(about ±1.8e308)")
        elif ints and isinstance(node, _Beyond):
            rule = ("within the float range (about ±1.8e308)" if node else
                    "0, or at least about 4.9e-324 in magnitude (it reads as 0)")
            raise error(f"{where}: '{key}' = {node.text}: must be {rule}")


def _fits_float(value: int) -> bool:
    try:
        float(value)
    except OverflowError:
        return False
    return True


# --- numbers ----------------------------------------------------------------------------------
def number(value: Any, key: str, error: type[Exception], prefix: str = "", *,
           positive: bool = False, nonnegative: bool = False, limit: float | None = None,
           limit_rule: str | None = None) -> float:
    """``value`` as a float, or ``error``: ``{prefix}'{key}' = {value}: {rule}``.

    Rules, in order: a number (not a bool), finite (an integer beyond float too), > 0 if
    ``positive``, >= 0 if ``nonnegative``, ``|value| <= limit`` (``limit_rule`` says it)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        fail(error, prefix, key, value, "must be a number")
    try:
        v = float(value)
    except OverflowError:
        fail(error, prefix, key, value, "must be within the float range (about ±1.8e308)")
    wrong = problem(v, 0.0 if positive or nonnegative else -math.inf, above=positive)
    if wrong is not None:  # the one rule: checks.problem
        fail(error, prefix, key, value, wrong)
    if limit is not None and abs(v) > limit:
        fail(error, prefix, key, value, limit_rule or f"must be within ±{limit:g}")
    return v


def integer(value: Any, key: str, error: type[Exception], prefix: str = "",
            minimum: int = 1) -> int:
    """A whole number ``>= minimum`` (pollard_pin.checks.is_integer), or ``error``."""
    if not is_integer(value, minimum):
        fail(error, prefix, key, value, f"must be a whole number >= {minimum}")
    return int(value)


def fail(error: type[Exception], prefix: str, key: str, value: Any, rule: str):
    """Raise ``error("{prefix}'{key}' = {short value}: {rule}")`` with ``.key`` = ``key``:
    the key whose own rule it is, for a caller that tells it from another key's."""
    exc = error(f"{prefix}'{key}' = {shorten(value)}: {rule}")
    exc.key = key
    raise exc


def parse_float(text: str) -> float:
    """A number written as text (a CSV cell, a command-line value): Python's ``float`` syntax
    without what it also takes but a user never means: ``_`` digit separators (``0.5_5``) and
    non-ASCII digits (full-width ``０.５５``). ValueError says why."""
    value = float(text)
    why = float_text_problem(text)
    if why:
        raise ValueError(why)
    return value


def float_text_problem(text: str) -> str | None:
    """Why :func:`parse_float` refuses ``text`` that ``float`` reads, or None: the one home
    of that rule (a whole file's cells may be checked at once, joined)."""
    if "_" in text:
        return "'_' digit separators are not accepted"
    if not text.isascii():
        char = next(c for c in text if not c.isascii())
        return f"{char!r} is not an ASCII digit"
    return None


def parse_int(text: str) -> int:
    """A whole number written as text: ASCII digits, optional sign, at most 30 digits."""
    body = text.strip()
    digits = body[1:] if body.startswith(("+", "-")) else body
    if not (digits.isascii() and digits.isdigit() and len(digits) <= 30):
        raise ValueError("not an integer")
    return int(body)


__all__ = ["MAX_DEPTH", "MAX_TOML_BYTES", "fail", "float_text_problem", "integer",
           "loads_toml", "number", "open_regular", "parse_float", "parse_int", "read_bytes",
           "read_toml", "shown_path"]
