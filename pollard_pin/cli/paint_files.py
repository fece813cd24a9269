"""What ``paint`` says for every kind of job: the --resolution refusal and the 'wrote' line
(the lines it prints: :meth:`pollard_pin.painting.result.PaintedJob.summary_lines`; the
files themselves: pollard_pin.outputs.paint_files)."""
from __future__ import annotations

import sys
from pathlib import Path

from .common import UsageError


def spacing(rule, job, resolution) -> float:
    """The film point spacing [m] by ``rule(job, --resolution)`` (a panel's grid or a part's
    points), its refusal as a usage error naming the flag."""
    from ..painting.errors import ResolutionError

    try:
        return rule(job, resolution)
    except ResolutionError as exc:
        raise UsageError(f"--resolution: {exc}") from None


def say_written(out: Path, table: Path, robots=()) -> None:
    """The line on standard error naming what paint wrote in ``out`` (a cell: a path.csv in
    each robot's folder)."""
    paths = (", ".join(f"{out}/{r}/path.csv" for r in robots) if robots else
             f"{out}/path.csv")
    print(f"wrote {paths}, {table.name}, film.ply, paint.json, thickness.png",
          file=sys.stderr)
