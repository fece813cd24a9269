"""Data in and out: ``trajectory`` (trajectory CSVs), ``table`` (result tables, CSV or
Parquet), ``atomic`` (writes that never leave a half-written file), ``mjcf`` (the MuJoCo
model), ``retime`` (a retimed trajectory's file); the paint outputs' writers ``paint_files`` and
``paint_cell_files`` sit above the planner (import them as modules)."""
from .table import ResultFileError, read_result
from .trajectory import from_csv, to_csv

__all__ = ["from_csv", "to_csv", "read_result", "ResultFileError"]
