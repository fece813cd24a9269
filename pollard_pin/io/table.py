"""Result tables on disk: CSV and Parquet, written chunk by chunk, read back exactly.

* CSV (polars ``write_csv``): one header row with the column names, every float64 written so
  that reading it back gives the same bits. Units and run metadata go to a sidecar JSON file
  beside it, ``NAME.units.json`` (not written for standard output or a FIFO/device).
* Parquet (pyarrow, zstd): units and run metadata in the file's key-value metadata
  (``pollard_pin.units``, ``pollard_pin.metadata``, JSON).

Column units follow docs/model.md §15; :func:`column_unit` derives them from the names.
"""
from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..checks import clip, file_path, shorten
from ..errors import InputError
from ..model.values import open_regular
from ..names import JOINTS
from .atomic import STDOUT, OutputError, all_or_nothing, atomic_open, check_destination, is_special
from .json_text import finite_json

UNITS_KEY, META_KEY = "pollard_pin.units", "pollard_pin.metadata"
FORMATS = ("csv", "parquet")
_TASK_LENGTHS = ("x", "y", "z")
_FIXED = {"t": "s", "closure_residual": "m", "wrist_margin": "1", "sigma_parallel": "m",
          "sigma_serial": "mixed (m, 1)", "kinetic_energy": "J", "potential_energy": "J",
          # closed-loop simulation, docs/model.md §18
          "tip_position_error": "m", "tip_orientation_error": "rad", "desired_x": "m",
          "desired_y": "m", "desired_z": "m",
          # paint film map, docs/model.md §21
          "u": "m", "v": "m", "thickness": "m",
          # paint on a part's mesh: the trigger, film point normals and area shares
          "spray": "1", "nx": "1", "ny": "1", "nz": "1", "area": "m²",
          # workspace maps, docs/model.md §22
          "reachable": "1", "reason": "code (workspace.json reason_codes)",
          "conditioning": "1", "payload_capacity": "kg",
          # stiffness, docs/model.md §27
          "dx": "m", "dy": "m", "dz": "m", "rx": "rad", "ry": "rad", "rz": "rad",
          **{f"f{i}": "Hz" for i in range(1, 7)}, "kmin": "N/m", "sag": "m"}
_PREFIX = (("tau_", "N·m"), ("power_", "W"), ("work_", "J"),
           ("F_", "N"), ("M_", "N·m"))  # joint loads, docs/model.md §17


def column_unit(name: str) -> str:
    """SI unit of a result column from its name (docs/model.md §15)."""
    if name in _FIXED:
        return _FIXED[name]
    for prefix, unit in _PREFIX:
        if name.startswith(prefix):
            return unit
    if len(name) == 4 and name[0] == "f" and name[2] == "_":  # f1_x … f2_z
        return "N"
    order = 2 if name.startswith("dd_") else 1 if name.startswith("d_") else 0
    base = name.split("_", order)[-1] if order else name
    length = base in _TASK_LENGTHS
    return ("m" if length else "rad") + ("", "/s", "/s²")[order]


_RATES = ("", "d_", "dd_")
_KNOWN = frozenset((*_FIXED, *(f"f{i}_{a}" for i in (1, 2) for a in "xyz"),
                    *(r + n for r in _RATES for n in (*TASK_NAMES, *JOINTS)),
                    *(f"{p}{j}" for p in ("tau_", "power_", "work_") for j in JOINTS),
                    # flexible drives' motors, docs/model.md §28
                    *(f"{p}{j}" for p in ("phi_", "d_phi_", "deflection_") for j in JOINTS),
                    *(f"{p}{j}_{a}" for p in ("F_", "M_") for j in JOINTS for a in "xyz")))


def is_result_column(name: str) -> bool:
    """Whether ``name`` is a column that pollard-pin writes (its unit comes from the name)."""
    return name in _KNOWN


def table_format(path: str | Path, fmt: str | None = None) -> str:
    """``csv`` or ``parquet``: ``fmt`` if given, else from the file name (default CSV)."""
    if fmt is not None:
        if fmt not in FORMATS:
            raise OutputError(f"unknown table format {fmt!r} (expected csv or parquet)")
        return fmt
    return "parquet" if str(path).lower().endswith((".parquet", ".pq")) else "csv"


def units_path(path: str | Path) -> Path:
    """The sidecar of a CSV table: ``run.csv`` → ``run.units.json``."""
    path = Path(path)
    return path.with_name(path.stem + ".units.json")


# names of another format's file: a table written there (as CSV) would be misread by name
NOT_TABLES = (".png", ".jpg", ".jpeg", ".svg", ".pdf", ".html", ".json", ".toml", ".md",
              ".ply", ".stl", ".obj", ".db", ".zip", ".gz")


def _writable_name(path: str | Path, fmt: str | None) -> None:
    """OutputError when a table with no format given would be written under another
    format's name (``run.png``: CSV text in a file every viewer takes for an image)."""
    suffix = Path(str(path)).suffix.lower()
    if fmt is None and suffix in NOT_TABLES:
        raise OutputError(f"{path}: a {suffix} name for a table: name it .csv or .parquet")


def table_files(path: str | Path, fmt: str | None = None) -> tuple:
    """Every file a table at ``path`` is written to: the table, and for a CSV file its units
    sidecar (none for standard output, a FIFO or a device). Check them all before the work."""
    _writable_name(path, fmt)
    if table_format(path, fmt) == "csv" and str(path) != STDOUT and not is_special(Path(path)):
        return (path, units_path(path))
    return (path,)


class TableWriter:
    """Write a table in chunks of columns (``write({name: array})``), atomically.

    The column names are fixed by the first chunk; ``metadata`` (JSON-ready) is stored with the
    units. Use as a context manager: the file (and its sidecar) appears only if the block
    completes (one :func:`~.atomic.all_or_nothing` block, joined to the caller's if any).
    """

    def __init__(self, path: str | Path, metadata: Mapping | None = None,
                 fmt: str | None = None):
        _writable_name(path, fmt)
        self.path, self.fmt = path, table_format(path, fmt)
        self.metadata = dict(metadata or {})
        finite_json(self.metadata, f"{path}: metadata")  # refused before anything is written
        self.columns: list[str] | None = None
        self.rows = 0
        self._ctx = self._file = self._parquet = None

    def __enter__(self) -> TableWriter:
        if self.fmt == "csv":  # imported here, so that write() times only the writing
            import polars  # noqa: F401

            if self._sidecar():  # it follows the table: check it before anything is written
                check_destination(units_path(self.path))
        else:
            import pyarrow.parquet  # noqa: F401
        self._outputs = all_or_nothing()  # the table and its sidecar: both or neither
        self._outputs.__enter__()
        try:
            self._ctx = atomic_open(self.path, binary=True)
            self._file = self._ctx.__enter__()
        except BaseException as error:
            self._outputs.__exit__(type(error), error, error.__traceback__)
            raise
        return self

    def write(self, chunk: Mapping[str, np.ndarray]) -> None:
        if self.columns is None:
            self.columns = list(chunk)
        elif list(chunk) != self.columns:
            raise ValueError("every chunk must have the same columns, in the same order")
        if self.fmt == "csv":
            import polars as pl

            pl.DataFrame({k: np.asarray(v, dtype=np.float64) for k, v in chunk.items()}) \
                .write_csv(self._file, include_header=self.rows == 0)
        else:
            self._write_parquet(chunk)
        self.rows += len(next(iter(chunk.values())))

    def _write_parquet(self, chunk) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.table({k: np.asarray(v, dtype=np.float64) for k, v in chunk.items()})
        if self._parquet is None:
            schema = table.schema.with_metadata({
                UNITS_KEY: json.dumps(self.units()),
                META_KEY: finite_json(self.metadata, f"{self.path}: metadata")})
            self._parquet = pq.ParquetWriter(self._file, schema, compression="zstd")
        self._parquet.write_table(table.replace_schema_metadata(self._parquet.schema.metadata))

    def units(self) -> dict[str, str]:
        return {c: column_unit(c) for c in self.columns or ()}

    def __exit__(self, kind, exc, tb) -> None:
        try:
            try:
                if self._parquet is not None:
                    self._parquet.close()
            finally:
                self._ctx.__exit__(kind, exc, tb)
            if kind is None and self.fmt == "csv" and self._sidecar():
                with atomic_open(units_path(self.path)) as f:
                    f.write(finite_json({"units": self.units(), "metadata": self.metadata},
                                        f"{self.path}: metadata", indent=1, ensure_ascii=False))
                    f.write("\n")
        except BaseException as error:
            self._outputs.__exit__(type(error), error, error.__traceback__)
            raise
        self._outputs.__exit__(kind, exc, tb)

    def _sidecar(self) -> bool:
        return str(self.path) != STDOUT and not is_special(Path(self.path))


def write_table(path: str | Path, chunks: Iterable[Mapping[str, np.ndarray]] | Mapping,
                metadata: Mapping | None = None, fmt: str | None = None) -> int:
    """Write one table (a dict of columns, or an iterable of such chunks); returns the rows."""
    if isinstance(chunks, Mapping):
        chunks = (chunks,)
    with TableWriter(path, metadata, fmt) as w:
        for chunk in chunks:
            w.write(chunk)
    return w.rows


@dataclass
class ResultTable:
    """A result read back: ``columns`` (name → float64 array), ``units``, ``metadata``."""

    columns: dict[str, np.ndarray]
    units: dict[str, str] = field(default_factory=dict)
    metadata: dict = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()))) if self.columns else 0


class ResultFileError(InputError):
    """A result table that cannot be read back (one line: which file, why)."""


def read_result(path: str | Path) -> ResultTable:
    """Read a result table (``run``, ``simulate``, ``size --retime``, a paint ``path.csv``),
    CSV or Parquet: every column float64.

    Parameters
    ----------
    path : str or pathlib.Path
        A ``.csv`` (units and metadata from its ``.units.json`` sidecar) or ``.parquet``
        (units and metadata inside).

    Returns
    -------
    pollard_pin.io.table.ResultTable
        ``columns`` (name → float64 array), ``units`` (name → unit) and ``metadata``;
        ``table[name]`` is one column.

    Raises
    ------
    pollard_pin.io.table.ResultFileError
        A missing, unreadable, malformed or empty file, one with text columns (such as a
        ``sweep`` table), or a CSV whose columns no command writes and that has no units
        sidecar.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> result = pp.run_pipeline(pp.load(), pp.thesis_trajectory(samples=11))
    >>> pp.write_run_table(result, "run.csv")
    >>> table = pp.read_result("run.csv")
    >>> len(table), table.units["theta21"], table.units["tau_theta21"]
    (11, 'rad', 'N·m')
    """
    path = file_path(path, "path", error=ResultFileError)
    if path.is_dir():
        raise ResultFileError(f"{path}: is a folder, not a result file")
    if not path.exists():
        raise ResultFileError(f"{path}: no such result file")
    if not path.is_file():
        raise ResultFileError(f"{path}: not a regular file")
    fmt = table_format(path)
    try:
        table = _read_parquet(path) if fmt == "parquet" else _read_csv(path)
    except ResultFileError:
        raise
    except (OSError, ValueError, RecursionError, _polars_error()) as exc:  # pyarrow: the first 2
        cause = clip(exc) or type(exc).__name__
        raise ResultFileError(f"{path}: not a readable {fmt} result table ({cause})") from None
    if len(table) == 0:
        raise ResultFileError(f"{path}: no rows (no command writes an empty table)")
    return table


def _polars_error() -> type[Exception]:
    from polars.exceptions import PolarsError

    return PolarsError


def _read_parquet(path: Path) -> ResultTable:
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    meta = table.schema.metadata or {}
    cols = {n: np.asarray(table.column(n).to_numpy(), dtype=np.float64)
            for n in table.column_names}
    return ResultTable(cols, json.loads(meta.get(UNITS_KEY.encode(), b"{}")),
                       json.loads(meta.get(META_KEY.encode(), b"{}")))


def _read_csv(path: Path) -> ResultTable:
    import codecs

    import polars as pl

    with open_regular(path) as f:  # polars reads a bad header lossily: check it is UTF-8
        head = f.read(1 << 16)
    try:
        codecs.getincrementaldecoder("utf-8")().decode(head, final=False)
    except UnicodeDecodeError as exc:
        raise ResultFileError(f"{path}: not UTF-8 text (byte {exc.start}: "
                              f"{head[exc.start:exc.start + 1]!r})") from None
    header = head.split(b"\n", 1)[0].decode("utf-8", "replace").strip().split(",")
    twice = [n for i, n in enumerate(header) if n in header[:i]]
    if twice:  # polars would rename the second one
        raise ResultFileError(f"{path}: duplicate column {shorten(twice[0])}")
    frame = pl.read_csv(path, infer_schema_length=0)  # strings first: float64 for every column
    for n in frame.columns:  # an empty cell or a short row: never written, a damaged file
        if frame[n].null_count():
            k = int(frame[n].is_null().arg_true()[0])
            raise ResultFileError(f"{path}: line {k + 2}, column {shorten(n)}: no value (a "
                                  "truncated or edited file)")
    cols = {n: frame[n].cast(pl.Float64).to_numpy() for n in frame.columns}
    side = units_path(path)
    try:
        extra = json.loads(side.read_text(encoding="utf-8")) if side.is_file() else {}
    except (ValueError, RecursionError) as exc:  # JSON, UTF-8, or nested too deep
        raise ResultFileError(f"{side}: not a readable units sidecar ({clip(exc)})") from None
    if not isinstance(extra, dict):
        raise ResultFileError(f"{side}: not a readable units sidecar (expected a JSON object)")
    if not extra:  # no sidecar: the units come from the names, so the names must be ours
        unknown = [c for c in cols if not is_result_column(c)]
        if unknown:
            raise ResultFileError(f"{path}: column {shorten(unknown[0])} is not one pollard-pin "
                                  f"writes, and no sidecar {side.name} gives its unit")
    return ResultTable(cols, extra.get("units", {c: column_unit(c) for c in cols}),
                       extra.get("metadata", {}))
