"""A design study's tables (the front, every evaluation) on disk, with their units as the
project's result tables keep them (:mod:`pollard_pin.io.table`): a CSV file with the sidecar
``NAME.units.json``, a Parquet file with the units and metadata in its key-value metadata.

Unlike a run's tables, these hold text (a motor's name, the binding constraint) and empty
cells (a figure an infeasible design does not have), so they are written from rows here; the
file names, the sidecar and the metadata keys are io.table's.
"""
from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path

from ..io.atomic import atomic_open
from ..io.json_text import finite_json
from ..io.table import META_KEY, UNITS_KEY, table_format, units_path


def _columns(rows: Sequence[Mapping], first: Sequence[str]) -> list[str]:
    cols = list(first)
    for row in rows:
        cols += [k for k in row if k not in cols]
    return cols


def _cell(value):
    if isinstance(value, float) and value != value:  # NaN: an empty cell
        return None
    if isinstance(value, (list, tuple, dict)):
        return json.dumps(value)
    return value


def write_rows(path: str | Path, rows: Sequence[Mapping], units: Mapping[str, str],
               metadata: Mapping | None = None, first: Sequence[str] = ()) -> int:
    """Write ``rows`` (dicts; missing keys are empty cells) to ``path``, CSV or Parquet by
    its name, with ``units`` (column → unit) beside (CSV) or inside (Parquet); the rows.

    Parameters
    ----------
    path : str or Path
        ``*.csv`` or ``*.parquet``.
    rows : Sequence of Mapping
        The rows; the columns are ``first`` then every other key, in order of appearance.
    units : Mapping
        Each column's unit (a column without one: ``""``).
    metadata : Mapping or None, optional
        JSON-ready data kept with the units.
    first : Sequence of str, optional
        The leading columns.

    Returns
    -------
    int
        The rows written.
    """
    import pyarrow as pa

    cols = _columns(rows, first)
    unit = {c: units.get(c, "") for c in cols}
    meta = dict(metadata or {})
    table = pa.table({c: pa.array([_cell(r.get(c)) for r in rows]) for c in cols})
    if table_format(path) == "parquet":
        import pyarrow.parquet as pq

        table = table.replace_schema_metadata({
            UNITS_KEY: json.dumps(unit), META_KEY: finite_json(meta, f"{path}: metadata")})
        with atomic_open(path, binary=True) as f:
            pq.write_table(table, f, compression="zstd")
        return len(rows)
    import polars as pl

    with atomic_open(path, binary=True) as f:
        pl.from_arrow(table).write_csv(f)
    with atomic_open(units_path(path)) as f:
        f.write(finite_json({"units": unit, "metadata": meta}, f"{path}: metadata", indent=1,
                            ensure_ascii=False))
        f.write("\n")
    return len(rows)


def read_rows(path: str | Path) -> tuple[list[dict], dict]:
    """The rows and the units of a table :func:`write_rows` wrote (for checks and tests).

    Parameters
    ----------
    path : str or Path
        ``*.csv`` (with its sidecar) or ``*.parquet``.

    Returns
    -------
    tuple of (list of dict, dict)
        The rows (a CSV's cells as polars reads them) and the units.
    """
    if table_format(path) == "parquet":
        import pyarrow.parquet as pq

        table = pq.read_table(path)
        units = json.loads((table.schema.metadata or {}).get(UNITS_KEY.encode(), b"{}"))
        return table.to_pylist(), units
    import polars as pl

    units = json.loads(units_path(path).read_text(encoding="utf-8"))["units"]
    return pl.read_csv(path).to_dicts(), units
