"""Data in and out: ``trajectory`` (trajectory CSVs), ``table`` (result tables, CSV or
Parquet), ``atomic`` (writes that never leave a half-written file), ``mjcf`` (the MuJoCo
model), ``retime`` (a retimed trajectory's file)."""
