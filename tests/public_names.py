"""The package's public names, one rule for the documentation tests: the top level's
``pollard_pin.__all__`` and every subpackage's ``__all__`` (the command line's excepted: its
reference is docs/cli.rst, written from the parser)."""
import importlib
import sys
from pathlib import Path

import pollard_pin

# the dotted-name rule the site's reference links use too
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "docs" / "_ext"))
from dotted import MISSING, lookup  # noqa: E402,F401

PACKAGE = Path(pollard_pin.__file__).resolve().parent
NOT_API = ("pollard_pin.cli",)


def subpackages() -> list[str]:
    """Every package folder under pollard_pin/ (one with an ``__init__.py``), dotted."""
    return sorted(".".join(p.parent.relative_to(PACKAGE.parent).parts)
                  for p in PACKAGE.rglob("__init__.py") if p.parent != PACKAGE)


def public_names() -> dict[str, object]:
    """{full dotted name: object} of every public name, the top level's first."""
    out = {f"pollard_pin.{n}": getattr(pollard_pin, n) for n in pollard_pin.__all__}
    for name in subpackages():
        if name.startswith(NOT_API):
            continue
        module = importlib.import_module(name)
        out |= {f"{name}.{n}": getattr(module, n) for n in module.__all__}
    return out


def public_objects() -> dict[str, object]:
    """{first public name: object}, each object once (a top-level name is also its
    subpackage's)."""
    seen, out = set(), {}
    for full, obj in public_names().items():
        if id(obj) not in seen:
            seen.add(id(obj))
            out[full] = obj
    return out
