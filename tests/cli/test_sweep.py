"""``pollard-pin sweep`` (cli/sweep.py): the CSV and summary of a grid, and a bad grid is one
line with nothing written."""
import pytest
from sweep_grid import GRID


@pytest.fixture(scope="module")
def grid_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "grid.toml"
    path.write_text(GRID)
    return path


def test_cli_sweep(grid_file, tmp_path, capsys):
    from pollard_pin.cli import main

    out = tmp_path / "sub" / "sweep.csv"
    assert main(["sweep", "--grid", str(grid_file), "--out", str(out), "--workers", "1",
                 "--quiet"]) == 0
    lines = out.read_text().splitlines()
    assert lines[0].startswith("variant,chain0.x32,bodies.gun.mass,leg1.x87,bodies.gun.com[0],"
                               "feasible,failure_kind,failure,")
    assert len(lines) == 8
    text = capsys.readouterr().out
    assert "7 variants: 5 feasible, 2 infeasible" in text
    assert "INFEASIBLE: UnreachablePoseError" in text

    bad = tmp_path / "bad.toml"
    bad.write_text('[grid]\n"chain0.nope" = [1.0]\n')
    assert main(["sweep", "--grid", str(bad), "--out", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err
    assert "'chain0.nope'" in err and "nothing written" in err
    assert not (tmp_path / "x.csv").exists()
