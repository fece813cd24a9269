"""A paint job written back as TOML (``place`` writes the placed job): the tables of
:meth:`pollard_pin.painting.job.PartJob.to_dict`, file paths made relative to the written
file's folder so that ``load_job`` finds the same mesh and actuators."""
from __future__ import annotations

import math
import os
from pathlib import Path

from .atomic import atomic_open, check_outputs

_PATHS = {("part", "mesh"), ("job", "actuators")}


def _value(x) -> str:
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, (int, float)):
        if isinstance(x, float) and not math.isfinite(x):
            raise ValueError(f"{x!r} has no TOML form here")
        return repr(float(x)) if isinstance(x, float) else str(x)
    if isinstance(x, str):
        return '"' + x.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(_value(v) for v in x) + "]"
    raise ValueError(f"{type(x).__name__} has no TOML form here")


def job_toml(job, folder: Path, header: str = "") -> str:
    """The job's TOML text, its file paths relative to ``folder`` (absolute where no
    relative path exists, another drive)."""
    lines = [f"# {line}" for line in header.splitlines()]
    for table, keys in job.to_dict().items():
        lines += ["", f"[{table}]"]
        for k, v in keys.items():
            if (table, k) in _PATHS:
                try:
                    v = os.path.relpath(Path(v).resolve(), folder.resolve())
                except ValueError:
                    v = str(Path(v).resolve())
                v = Path(v).as_posix()
            lines.append(f"{k} = {_value(v)}")
    return "\n".join(lines).lstrip("\n") + "\n"


def write_job(job, path: Path, header: str = "") -> Path:
    """Write the job to ``path`` (all or nothing); the path."""
    check_outputs(path)
    text = job_toml(job, Path(path).parent, header)
    with atomic_open(path) as f:
        f.write(text)
    return Path(path)


__all__ = ["job_toml", "write_job"]
