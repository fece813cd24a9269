"""Progress bars over the planner's long loops (the film's blocks, the compliance film, the
line speed search, the layout search), shown only when asked (``PaintOptions.progress``: the
command line asks) and on a terminal (tqdm's ``disable=None``): a Python caller's standard
error stays as it was."""
from __future__ import annotations

import contextlib
import sys
from contextvars import ContextVar

_SHOWN: ContextVar[bool] = ContextVar("pollard_pin_progress", default=False)


@contextlib.contextmanager
def showing(on: bool):
    """Bars within the block when ``on`` (:func:`bar`)."""
    token = _SHOWN.set(bool(on))
    try:
        yield
    finally:
        _SHOWN.reset(token)


def bar(iterable, desc: str, total: int | None = None, unit: str = "block"):
    """``iterable`` itself, or wrapped in a tqdm bar on standard error inside
    :func:`showing` (True) when standard error is a terminal; the bar is cleared at its end."""
    if not _SHOWN.get():
        return iterable
    from tqdm import tqdm

    return tqdm(iterable, desc=desc, total=total, unit=unit, disable=None, leave=False,
                file=sys.stderr)


@contextlib.contextmanager
def ticking(desc: str, unit: str):
    """A bar of no known length inside :func:`showing` (True) on a terminal: yields a
    ``tick()`` that counts one more ``unit`` (a no-op otherwise)."""
    if not _SHOWN.get():
        yield lambda: None
        return
    from tqdm import tqdm

    with tqdm(desc=desc, unit=unit, disable=None, leave=False, file=sys.stderr) as counter:
        yield lambda: counter.update(1)


__all__ = ["bar", "showing", "ticking"]
