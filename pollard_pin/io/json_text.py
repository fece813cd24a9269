"""JSON text for every file the package writes: finite numbers only. A NaN or an infinity is
not JSON (``json.dumps`` would write ``NaN``/``Infinity``, which strict readers refuse), so a
writer refuses it in one line naming the key, before anything is written."""
from __future__ import annotations

import json
import math

from ..errors import SolveError


class NonFiniteError(SolveError, ValueError):
    """A figure to be written as JSON is not finite (one line naming its key)."""


def _first_non_finite(value, where: str):
    if isinstance(value, float) and not math.isfinite(value):
        return where, value
    if isinstance(value, dict):
        items = ((f"{where}.{k}" if where else str(k), v) for k, v in value.items())
    elif isinstance(value, (list, tuple)):
        items = ((f"{where}[{i}]", v) for i, v in enumerate(value))
    else:
        return None
    for key, v in items:
        found = _first_non_finite(v, key)
        if found is not None:
            return found
    return None


def finite_json(value, what: str, **kwargs) -> str:
    """``json.dumps(value, allow_nan=False, **kwargs)``, or :class:`NonFiniteError` naming
    the first non-finite number's key.

    Parameters
    ----------
    value : object
        Plain JSON data (dicts, lists, strings, numbers, booleans, None).
    what : str
        The file or entry, for the message (``paint.json``).
    **kwargs
        Passed on to :func:`json.dumps` (``indent``, ``ensure_ascii``).
    """
    try:
        return json.dumps(value, allow_nan=False, **kwargs)
    except ValueError:
        key, x = _first_non_finite(value, "") or ("?", float("nan"))
        raise NonFiniteError(f"{what}: {key or 'the value'} = {x!r} is not a finite number "
                             "and cannot be written as JSON") from None


__all__ = ["NonFiniteError", "finite_json"]
