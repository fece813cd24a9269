"""A design study's tables (synthesis/table.py): text and empty cells, units beside or inside,
read back as written."""
import json

import pytest

from pollard_pin.io.table import UNITS_KEY
from pollard_pin.synthesis.table import read_rows, write_rows

ROWS = [{"design": 1, "motor": "small", "kmin": 1.5e4, "binding": None},
        {"design": 2, "motor": "large", "kmin": None, "binding": "reach", "extra": 0.1}]
UNITS = {"design": "1", "kmin": "N/m", "extra": "m"}


@pytest.mark.parametrize("name", ["t.csv", "t.parquet"])
def test_rows_round_trip_with_their_units(tmp_path, name):
    assert write_rows(tmp_path / name, ROWS, UNITS, {"chosen": 1}, first=("kmin",)) == 2
    rows, units = read_rows(tmp_path / name)
    assert list(rows[0]) == ["kmin", "design", "motor", "binding", "extra"]  # first, then met
    assert rows[0]["kmin"] == 1.5e4 and rows[1]["kmin"] is None
    assert rows[1]["motor"] == "large" and rows[0]["extra"] is None
    assert units == {"kmin": "N/m", "design": "1", "motor": "", "binding": "", "extra": "m"}


def test_csv_units_go_to_the_projects_sidecar(tmp_path):
    write_rows(tmp_path / "front.csv", ROWS, UNITS, {"chosen": 1})
    side = json.loads((tmp_path / "front.units.json").read_text())
    assert side["units"]["kmin"] == "N/m" and side["metadata"] == {"chosen": 1}
    import pyarrow.parquet as pq

    write_rows(tmp_path / "t.parquet", ROWS, UNITS)
    meta = pq.read_table(tmp_path / "t.parquet").schema.metadata
    assert json.loads(meta[UNITS_KEY.encode()])["kmin"] == "N/m"
