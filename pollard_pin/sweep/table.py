"""The sweep's result table as CSV (:func:`write_sweep_table`) and a text summary."""
from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..io.atomic import atomic_open
from ..model.overrides import plain_value
from ..names import ACTUATED


# --- output -----------------------------------------------------------------------------------
def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)  # round-trips exactly
    if isinstance(value, (list, tuple)):
        return json.dumps(plain_value(value))
    return str(value)


def write_sweep_table(rows: Sequence[Mapping[str, Any]], path: str | Path,
              columns: Sequence[str] | None = None) -> None:
    """The result table as CSV (polars, atomic write). Empty cells: not applicable or
    infeasible; floats as their shortest exact repr, lists as JSON.

    Parameters
    ----------
    rows : Sequence of Mapping
        The result rows (:func:`run_sweep`'s, :func:`evaluate_variant`'s).
    path : str or pathlib.Path
        The CSV file to write (all or nothing).
    columns : Sequence of str, optional
        The columns, in order (default: the first row's keys).
    """
    import polars as pl

    columns = list(columns or (rows[0].keys() if rows else ()))
    table = pl.DataFrame({c: [None if row.get(c) is None else _cell(row.get(c)) for row in rows]
                          for c in columns}, schema={c: pl.String for c in columns})
    with atomic_open(path, binary=True) as f:
        table.write_csv(f)


def summary(rows: Sequence[Mapping[str, Any]], max_rows: int = 20) -> str:
    """A short text table: per variant the worst actuator torque and power, or the failure.

    Parameters
    ----------
    rows : Sequence of Mapping
        The result rows (:func:`run_sweep`'s, :func:`evaluate_variant`'s).
    max_rows : int, optional
        At most this many variants are listed; a last line counts the rest.
    """
    n_ok = sum(1 for r in rows if r["feasible"])
    lines = [f"{len(rows)} variants: {n_ok} feasible, {len(rows) - n_ok} infeasible"]
    width = min(48, max([len("variant")] + [len(str(r["variant"])) for r in rows]))
    lines.append(f"{'variant':{width}s}  {'max|τ| [N·m] (actuator)':>25s}  "
                 f"{'max|P| [W]':>10s}  {'max|λ| [N]':>10s}")
    for r in list(rows)[:max_rows]:
        name = str(r["variant"])
        name = name if len(name) <= width else name[:width - 1] + "…"
        if r["feasible"]:
            peaks = [r[f"peak_tau_{a}"] for a in ACTUATED]
            i = int(np.argmax(peaks))
            pmax = max(r[f"peak_power_{a}"] for a in ACTUATED)
            fmax = max(r["peak_force_leg1"], r["peak_force_leg2"])
            lines.append(f"{name:{width}s}  {peaks[i]:12.4g} ({ACTUATED[i]:>10s})  "
                         f"{pmax:10.4g}  {fmax:10.4g}")
        else:
            where = []
            if r["failure_sample"] is not None:
                where.append(f"sample {r['failure_sample']}")
            if r["failure_time"] is not None:
                where.append(f"t = {r['failure_time']:.4g} s")
            if r["failure_chain"]:
                where.append(str(r["failure_chain"]))
            lines.append(f"{name:{width}s}  INFEASIBLE: {r['failure_kind']}"
                         + (f" ({', '.join(where)})" if where else ""))
    if len(rows) > max_rows:
        lines.append(f"… {len(rows) - max_rows} more in the CSV")
    return "\n".join(lines)
