"""The sweep of tests/sweep_grid.py, loaded and run on the local process pool once for every
sweep test (package scope)."""
import pytest
from sweep_grid import GRID

from pollard_pin.sweep import load_grid, run_sweep


@pytest.fixture(scope="package")
def grid_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "grid.toml"
    path.write_text(GRID)
    return path


@pytest.fixture(scope="package")
def sweep(grid_file):
    return load_grid(grid_file)


@pytest.fixture(scope="package")
def pool_rows(sweep):
    return run_sweep(sweep, workers=2)  # the local process pool
