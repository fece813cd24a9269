"""A full dotted name's object, one rule for the site's reference links (pollard_docs.py) and
the documentation tests (tests/test_docs.py). Plain Python: no Sphinx needed."""
from __future__ import annotations

import importlib

MISSING = object()  # what names nothing (None is a value a name may hold)


def lookup(full: str):
    """The object a full dotted name names, or :data:`MISSING`: attribute by attribute from
    the package, importing a submodule only where no attribute has its name
    (``pollard_pin.paint`` is the function, whatever folder an old install left)."""
    parts = full.split(".")
    try:
        obj = importlib.import_module(parts[0])
    except ImportError:
        return MISSING
    for i, part in enumerate(parts[1:], 2):
        if hasattr(obj, part):
            obj = getattr(obj, part)
            continue
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            return MISSING
    return obj
