"""The value rules every layer shares (a real number, finite, within bounds; an argument of
the expected type; a file path; a Dask scheduler's address) and the one way a value is shown
in a message (:func:`shorten`), written once. No numpy: the CLI's argument types use them too.
Each caller passes its own error family (a callable taking the one-line message), so a library
error still speaks of values and units and the CLI adds the flag name. The public entry points
check their arguments with these once, where they are called, so a user's mistake in Python is
the same one line the CLI gives, never a traceback from deep inside."""
from __future__ import annotations

import math
import numbers
import os
from pathlib import Path

from .errors import InputError

SHOWN = 60  # characters of a value shown in a message
NUL_IN_PATH = "a path with a NUL character"  # the words of that refusal, every reader's
EXAMPLE_ADDRESS = "tcp://127.0.0.1:8786"  # a Dask scheduler's address, as refusals show one
SEEDS = 2**32  # numpy's random seeds: 0..2^32 − 1 (a sampler's, a study's)


def shorten(value, width: int = SHOWN) -> str:
    """``repr(value)`` cut to ``width`` characters; an integer beyond 16 digits as ``:.4g``
    (never a 700-digit number echoed back)."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**16:
        try:
            return f"{float(value):.4g}"
        except OverflowError:  # beyond float: :.4g by hand (str() may refuse the integer)
            n, digits = abs(value), int((abs(value).bit_length() - 1) * math.log10(2))
            while 10**digits <= n:
                digits += 1
            lead = n // 10 ** (digits - 4) / 1000  # the first four digits, d.ddd
            return f"{'-' if value < 0 else ''}{lead:.4g}e+{digits - 1} (a {digits}-digit integer)"
    try:
        text = repr(value)
    except (ValueError, RecursionError):  # a huge integer or deep nesting inside
        return f"<{type(value).__name__}>"
    if len(text) <= width:
        return text
    end = text[-1] if text[-1] in "'\")]}" else ""  # a cut list still reads as a list
    return text[:width - 1 - len(end)] + "…" + end


def clip(text: str, width: int = 120) -> str:
    """``text`` on one line, cut to ``width`` characters (a library's own message, a path)."""
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[:width - 1] + "…"


def problem(x: float, low: float = -math.inf, high: float = math.inf,
            above: bool = False) -> str | None:
    """What is wrong with the number x under the rule low ≤ x ≤ high (low < x with ``above``),
    x finite: "must be a finite number", "must be >= 0", "must be > 0", "must be at most 1";
    None when nothing is."""
    if not math.isfinite(x):
        return "must be a finite number"
    if x < low or (above and x == low):
        return f"must be {'>' if above else '>='} {low:g}"
    if x > high:
        return f"must be at most {high:g}"
    return None


def is_real(value, low: float = -math.inf, high: float = math.inf, *,
            above: bool = False) -> bool:
    """Whether ``value`` is a real number (not a bool or a string) that :func:`problem` passes;
    an integer beyond a float (10**400) is not, where ``math.isfinite`` would raise."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        return problem(float(value), low, high, above) is None
    except OverflowError:
        return False


def real(value, name: str, low: float = -math.inf, high: float = math.inf, *,
         above: bool = False, why: str = "", error=InputError) -> float:
    """``value`` as a float, checked by :func:`problem`; a string, a bool or anything that is
    not a number is refused too. Raises ``error("<name> = <value>: <problem><why>")``."""
    try:
        if isinstance(value, (str, bytes, bool)):
            raise TypeError
        x = float(value)
    except (TypeError, ValueError):
        raise error(f"{name} = {shorten(value)}: is not a number{why}") from None
    except OverflowError:  # an integer beyond a float (10**400)
        raise error(f"{name} = {shorten(value)}: must be a finite number{why}") from None
    wrong = problem(x, low, high, above)
    if wrong is not None:
        raise error(f"{name} = {shorten(value)}: {wrong}{why}")
    return x


def is_integer(value, low: int | None = None, high: int | None = None) -> bool:
    """Whether ``value`` is an integer (Python's or numpy's, not a bool, not a float such as
    2.0) within ``low <= value <= high`` (a bound None: none on that side): the one rule of a
    count, a seed or an index, whose callers word their refusal as their tests pin it."""
    return (isinstance(value, numbers.Integral) and not isinstance(value, bool)
            and (low is None or value >= low) and (high is None or value <= high))


def integer(value, name: str, low: int | None = None, high: int | None = None, *,
            error=InputError) -> int:
    """``value`` as an int, checked by :func:`is_integer`; else ``error("<name> = <value>: is
    not an integer")`` or ``"...: must be >= <low>"`` / ``"...: must be at most <high>"``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise error(f"{name} = {shorten(value)}: is not an integer")
    if not is_integer(value, low, high):
        bound = f">= {low}" if low is not None and value < low else f"at most {high}"
        raise error(f"{name} = {shorten(value)}: must be {bound}")
    return int(value)


def instance(value, name: str, kinds, expected: str, *, none: bool = False,
             error=InputError):
    """``value`` when it is one of ``kinds`` (or None, with ``none``); else
    ``error("<name> = <value>: expected <expected>, got <type>")``."""
    if (none and value is None) or isinstance(value, kinds):
        return value
    raise error(f"{name} = {shorten(value)}: expected {expected}, got {type(value).__name__}")


def callback(value, name: str, *, error=InputError):
    """``value`` when it is a function (any callable) or None; else
    ``error("<name> = <value>: expected a function or None, got <type>")``, said before any
    work rather than as a TypeError at the first call."""
    if value is None or callable(value):
        return value
    raise error(f"{name} = {shorten(value)}: expected a function or None, got "
                f"{type(value).__name__}")


def file_path(value, name: str, *, error=InputError) -> Path:
    """``value`` (a str or an os.PathLike naming a file, not empty, no NUL) as a Path; else
    ``error("<name> = <value>: ...")``."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise error(f"{name} = {shorten(value)}: expected a file path (str or pathlib.Path), "
                    f"got {type(value).__name__}")
    if not value or "\0" in value:
        raise error(f"{name} = {shorten(value)}: "
                    + ("an empty path" if not value else NUL_IN_PATH))
    return Path(value)


def float_array(value, name: str, *, error=InputError):
    """``value`` as an ndarray of floats; anything else (strings, complex or bool values,
    objects, ragged lists, an integer beyond a float) raises ``error("<name>: ...")``, so a
    wrong value is refused with one line before it reaches numpy or Pinocchio. numpy is
    imported here only: the CLI's argument types import this module."""
    import numpy as np

    try:
        arr = np.asarray(value)
        if arr.dtype.kind == "O":  # Python numbers numpy could not type (10**400), or worse
            arr = arr.astype(float)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{name} = {_one_line(value)}: expected an array of real numbers") from None
    if arr.dtype.kind not in "iuf":
        raise error(f"{name} = {_one_line(value)}: expected an array of real numbers, got "
                    f"{arr.dtype} values")
    return arr.astype(float, copy=False)


def _one_line(value) -> str:
    """:func:`shorten` on one line (an array's repr spans lines), made only for a refusal."""
    return " ".join(shorten(value).split())


def address_problem(text: str) -> str | None:
    """What is wrong with ``text`` as a Dask scheduler's address: empty (blank), or malformed
    by dask.distributed's rules (a known scheme, a host and a port in 1..65535) when it is
    installed ("not a scheduler address: '…' (why)"); None when nothing is. The one rule of
    ``--dask``, :class:`~pollard_pin.synthesis.DesignOptions` and the runners, so that a typo
    is refused before the work that comes before connecting."""
    address = text.strip()
    if not address:
        return "an empty scheduler address"
    try:
        from distributed.comm.addressing import parse_address, parse_host_port
        from distributed.comm.registry import get_backend
    except ImportError:  # the extra is missing: connecting says so, before any work
        return None
    try:
        scheme, location = parse_address(address)
        get_backend(scheme)  # ValueError: an unknown scheme
        if scheme in ("tcp", "tls", "ws", "wss"):
            port = parse_host_port(location)[1]  # ValueError: no port, a malformed host
            if not 0 < port < 65536:
                raise ValueError(f"port {port} is not in 1..65535")
    except (ValueError, TypeError) as exc:
        return f"not a scheduler address: {shorten(address)} ({clip(str(exc), 100)})"
    return None


def scheduler_address(value, name: str, *, error=InputError):
    """``value`` when it is None, a ``distributed.Client`` or an address :func:`address_problem`
    passes; else ``error("<name>: <problem>; e.g. tcp://127.0.0.1:8786, or None to run
    locally")`` or ``error("<name> = <value>: expected …, got <type>")``."""
    if value is None:
        return value
    if isinstance(value, str):
        wrong = address_problem(value)
        if wrong is not None:
            raise error(f"{name}: {wrong}; e.g. {EXAMPLE_ADDRESS}, or None to run locally")
        return value
    try:
        from distributed import Client
    except ImportError:
        Client = ()  # nothing is a client then
    return instance(value, name, Client, "a scheduler address (str), a distributed.Client or "
                    "None", error=error)
