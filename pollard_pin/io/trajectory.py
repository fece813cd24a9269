"""Trajectory files: reading ``t,x,y,z,psi,theta,phi`` CSV into a
:class:`~pollard_pin.paths.trajectory.Trajectory` and writing one back (the type and the
curves live in :mod:`pollard_pin.paths`)."""
from __future__ import annotations

import csv
import math
import warnings
from pathlib import Path

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..model.params import did_you_mean
from ..paths.splines import QuinticSpline
from ..paths.trajectory import Trajectory, TrajectoryError

MAX_LENGTH = 3.0  # m: a coordinate beyond this is almost surely in mm
MAX_ANGLE = 2.0 * math.pi  # rad: an angle beyond this is almost surely in degrees
PARQUET_MAGIC = b"PAR1"  # the first (and last) four bytes of every Parquet file


def from_csv(path: str | Path) -> Trajectory:
    """Read ``t,x,y,z,psi,theta,phi`` (+ optional ``d_*`` and ``dd_*``) from a CSV file.

    Without derivative columns, derivatives come from a quintic interpolating spline and a
    :class:`UserWarning` says so.
    """
    path = Path(path)
    try:
        with open(path, "rb") as f:
            magic = f.read(4)
        with open(path, newline="", encoding="utf-8-sig") as f:  # -sig: a BOM is no column
            reader = csv.reader(f)
            rows, lines = [], []  # lines: 1-based file line of each kept row
            for r in reader:
                if r and not r[0].lstrip().startswith("#"):
                    rows.append(r)
                    lines.append(reader.line_num)
    except OSError as exc:
        raise TrajectoryError(f"cannot read trajectory file {str(path)!r}: "
                              f"{exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        if magic == PARQUET_MAGIC:
            raise TrajectoryError(f"{path}: a Parquet file; trajectories are read from CSV "
                                  "text (t,x,y,z,psi,theta,phi)") from None
        raise TrajectoryError(f"{path}: not UTF-8 text (byte {exc.start}: "
                              f"{exc.object[exc.start:exc.start + 1]!r}); save it as UTF-8 "
                              "CSV") from None
    except csv.Error as exc:  # a field over the csv module's limit: not a trajectory
        raise TrajectoryError(f"{path}: line {reader.line_num + 1}: not CSV ({exc})") from None
    if magic == PARQUET_MAGIC:  # Parquet bytes that happen to decode as UTF-8
        raise TrajectoryError(f"{path}: a Parquet file; trajectories are read from CSV text "
                              "(t,x,y,z,psi,theta,phi)")
    nul = next((i for i, r in enumerate(rows) if any("\0" in c for c in r)), None)
    if nul is not None:
        raise TrajectoryError(f"{path}: line {lines[nul]} holds NUL bytes: a binary file, "
                              "not CSV text")
    if not rows:
        raise TrajectoryError(f"{path}: empty file (expected a header t,x,y,z,psi,theta,phi)")
    header = [h.strip() for h in rows[0]]
    base = ("t",) + TASK_NAMES
    allowed = base + tuple(f"d_{n}" for n in TASK_NAMES) + tuple(f"dd_{n}" for n in TASK_NAMES)
    for h in header:
        if h not in allowed:
            raise TrajectoryError(f"{path}: unknown column {h!r}{did_you_mean(h, allowed)}; "
                                  f"expected {', '.join(base)} and optional d_*, dd_*")
    if len(set(header)) != len(header):
        raise TrajectoryError(f"{path}: duplicate column names in header {header}")
    missing = [c for c in base if c not in header]
    if missing:
        raise TrajectoryError(f"{path}: missing column(s) {', '.join(missing)}")
    data = np.empty((len(rows) - 1, len(header)))
    for r, row in enumerate(rows[1:]):
        line = lines[r + 1]  # file line, comment and blank lines counted
        if len(row) != len(header):
            raise TrajectoryError(f"{path}: row {line} has {len(row)} fields, "
                                  f"expected {len(header)}")
        for c, cell in enumerate(row):
            try:
                data[r, c] = float(cell)
            except ValueError:
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"{cell!r} is not a number") from None
            if not math.isfinite(data[r, c]):
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"value {cell!r} is not finite")
    if len(data) < 2:
        raise TrajectoryError(f"{path}: need at least 2 samples, found {len(data)}")
    col = {h: data[:, i] for i, h in enumerate(header)}
    t = col["t"]
    dt = np.diff(t)
    if np.any(dt <= 0):
        r = int(np.argmax(dt <= 0))
        kind = "duplicate" if dt[r] == 0 else "decreasing"
        raise TrajectoryError(f"{path}: row {lines[r + 2]}, column 't': {kind} time "
                              f"{float(t[r + 1])!r} after {float(t[r])!r} (times must "
                              "increase strictly)")
    poses = np.column_stack([col[n] for n in TASK_NAMES])
    for c, name in enumerate(TASK_NAMES):
        limit, unit = (MAX_LENGTH, "millimetres (expected m)") if c < 3 else \
            (MAX_ANGLE, "degrees (expected rad)")
        big = np.abs(poses[:, c]) > limit
        if np.any(big):
            r = int(np.argmax(big))
            raise TrajectoryError(f"{path}: row {lines[r + 1]}, column {name!r}: "
                                  f"{float(poses[r, c])!r} looks like {unit}; "
                                  f"|value| > {limit:.4g}")
    derivs = []
    for prefix in ("d_", "dd_"):
        names = [prefix + n for n in TASK_NAMES]
        present = [n for n in names if n in col]
        if present and len(present) != 6:
            absent = [n for n in names if n not in col]
            raise TrajectoryError(f"{path}: derivative columns must come as a full set; "
                                  f"missing {', '.join(absent)}")
        derivs.append(np.column_stack([col[n] for n in names]) if present else None)
    source, curve = "file columns", None
    derivs_given = [d is not None for d in derivs]
    if not all(derivs_given):
        if len(t) < 6:
            raise TrajectoryError(f"{path}: {len(t)} samples are too few for the quintic spline "
                                  "that supplies missing derivatives (need >= 6)")
        spline = QuinticSpline(t, poses)
        _, d_spl, dd_spl = spline(t)
        if derivs[0] is None and derivs[1] is None:
            curve = spline  # the path between the samples is the spline itself
        if derivs[0] is None:
            derivs[0] = d_spl
        if derivs[1] is None:
            derivs[1] = dd_spl
        source = "quintic spline"
        absent = "/".join(p + "*" for p, d in zip(("d_", "dd_"), derivs_given) if not d)
        warnings.warn(f"{path}: no {absent} columns; derivatives taken from a quintic "
                      "interpolating spline through the samples", UserWarning, stacklevel=2)
    return Trajectory(t, poses, derivs[0], derivs[1], name=path.stem, derivatives=source,
                      curve=curve)


def to_csv(traj: Trajectory, path: str | Path) -> None:
    """Write the trajectory in the ``run`` input format (``t``, poses, ``d_*``, ``dd_*``; every
    float64 exact) through :mod:`pollard_pin.io.table`, atomically, units in the sidecar."""
    from .table import write_table

    cols = {"t": traj.t}
    for prefix, arr in (("", traj.poses), ("d_", traj.d_poses), ("dd_", traj.dd_poses)):
        cols.update({prefix + n: arr[:, i] for i, n in enumerate(TASK_NAMES)})
    write_table(path, cols, {"trajectory": traj.name, "derivatives": traj.derivatives},
                fmt="csv")


__all__ = ["from_csv", "to_csv"]
