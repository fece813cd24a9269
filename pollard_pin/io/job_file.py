"""A paint job written back as TOML (``place`` writes the placed job): the tables of
:meth:`pollard_pin.painting.job.JobBase.to_dict` (a cell's robots as ``[[robot]]`` tables), file
paths made relative to the written file's folder so that ``load_job`` finds the same mesh and
actuators. Values are written by :func:`toml_value`, the one TOML value writer (robots.toml's
too): strings as TOML basic strings with the spec's escapes, so any path reads back as itself."""
from __future__ import annotations

import math
import os
from pathlib import Path

from ..errors import InputError
from .atomic import atomic_open, check_outputs

_PATHS = {("part", "mesh"), ("job", "actuators")}


# TOML's basic-string escapes (toml.io v1.0.0, "String"); other control characters as \uXXXX
_ESCAPES = {"\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r", '"': '\\"',
            "\\": "\\\\"}


def toml_string(s: str) -> str:
    """``s`` as a TOML basic string: quoted, the spec's escapes, every other control character
    (U+0000-U+001F, U+007F) as ``\\uXXXX``; a lone surrogate (no Unicode character) is
    refused."""
    if any("\ud800" <= c <= "\udfff" for c in s):
        raise InputError(f"{s[:60]!r}…: not Unicode text (a lone surrogate); TOML cannot "
                         "hold it")
    return '"' + "".join(_ESCAPES.get(c) or (f"\\u{ord(c):04X}" if c < " " or c == "\x7f"
                                             else c) for c in s) + '"'


def toml_value(x) -> str:
    """A bool, finite number, string or list of them as its TOML value text."""
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, (int, float)):
        if isinstance(x, float) and not math.isfinite(x):
            raise InputError(f"{x!r} has no TOML form here")
        return repr(float(x)) if isinstance(x, float) else str(x)
    if isinstance(x, str):
        return toml_string(x)
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in x) + "]"
    raise InputError(f"{type(x).__name__} has no TOML form here")


def job_toml(job, folder: Path, header: str = "") -> str:
    """The job's TOML text, its file paths relative to ``folder`` (absolute where no
    relative path exists, another drive)."""
    lines = [f"# {line}" for line in header.splitlines()]
    for table, keys in job.to_dict().items():
        # an array of tables (a cell's [[robot]]) or one table
        for entry in keys if isinstance(keys, list) else [keys]:
            lines += ["", f"[[{table}]]" if isinstance(keys, list) else f"[{table}]"]
            for k, v in entry.items():
                if (table, k) in _PATHS:
                    v = _relative(v, folder)
                lines.append(f"{k} = {toml_value(v)}")
    return "\n".join(lines).lstrip("\n") + "\n"


def _relative(path: str, folder: Path) -> str:
    """``path`` relative to ``folder`` (absolute where no relative path exists, another
    drive), with forward slashes."""
    try:
        v = os.path.relpath(Path(path).resolve(), folder.resolve())
    except ValueError:
        v = str(Path(path).resolve())
    return Path(v).as_posix()


def write_job(job, path: Path, header: str = "") -> Path:
    """Write the job to ``path`` (all or nothing); the path."""
    check_outputs(path)
    text = job_toml(job, Path(path).parent, header)
    with atomic_open(path) as f:
        f.write(text)
    return Path(path)


__all__ = ["job_toml", "toml_string", "toml_value", "write_job"]
