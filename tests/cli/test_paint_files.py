"""What paint says (cli/paint_files.py): the --resolution refusal names the flag, and the
'wrote' line names one path.csv, or a cell's one per robot."""
from pathlib import Path

import pytest

from pollard_pin.cli.common import UsageError
from pollard_pin.cli.paint_files import say_written, spacing
from pollard_pin.painting.errors import ResolutionError


def test_a_refused_resolution_names_the_flag():
    def rule(job, resolution):
        if resolution < 1e-3:
            raise ResolutionError("a coarser resolution")
        return resolution

    assert spacing(rule, None, 0.005) == 0.005
    with pytest.raises(UsageError, match="^--resolution: a coarser resolution$"):
        spacing(rule, None, 1e-6)


def test_the_wrote_line(capsys):
    say_written(Path("out"), Path("out/thickness.csv"))
    say_written(Path("out"), Path("out/thickness.parquet"), ["r1", "r2"])
    assert capsys.readouterr().err.splitlines() == [
        "wrote out/path.csv, thickness.csv, film.ply, paint.json, thickness.png",
        "wrote out/r1/path.csv, out/r2/path.csv, thickness.parquet, film.ply, paint.json, "
        "thickness.png"]
