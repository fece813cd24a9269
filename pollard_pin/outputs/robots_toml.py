"""A cell's ``[[robot]]`` tables as a TOML file (``paint --robots``' ``DIR/robots.toml``,
docs/model.md §26.5): read back by the job reader unchanged."""
from __future__ import annotations

from pathlib import Path

from ..io.atomic import atomic_open, check_outputs
from ..io.job_file import toml_value


def _numbers(xs) -> str:
    return toml_value([float(x) + 0.0 for x in xs])  # TOML floats; no -0.0


def robots_toml(robots, header: str = "") -> str:
    """The ``[[robot]]`` tables of ``robots`` (CellRobots), ``header`` as comment lines."""
    lines = [f"# {h}" if h else "#" for h in header.splitlines()]
    for r in robots:
        base, turn = f"base = {_numbers(r.base)}", f"rotation = {_numbers(r.rotation)}"
        width = max(len(base), len(turn)) + 2
        lines += ["", "[[robot]]", f"name = {toml_value(r.name)}", f"{base:<{width}}# m, world",
                  f"{turn:<{width}}# deg about world x, y, z (R = Rx·Ry·Rz)"]
    return "\n".join(lines).lstrip("\n") + "\n"


def write_robots(robots, path: str | Path, header: str = "") -> Path:
    """Write the ``[[robot]]`` tables to ``path`` (all or nothing); the path.

    Parameters
    ----------
    robots : tuple of CellRobot
        The cell's robots (``paint --robots``' proposal).
    path : str or Path
        The TOML file (robots.toml).
    header : str, optional
        Comment lines written above the tables.
    """
    check_outputs(path)
    text = robots_toml(robots, header)
    with atomic_open(path) as f:
        f.write(text)
    return Path(path)


__all__ = ["robots_toml", "write_robots"]
