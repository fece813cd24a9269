"""Trajectory files: reading ``t,x,y,z,psi,theta,phi`` CSV into a
:class:`~pollard_pin.paths.trajectory.Trajectory` and writing one back (the type and the
curves live in :mod:`pollard_pin.paths`)."""
from __future__ import annotations

import csv
import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np

from ..analytic.taskspace import TASK_NAMES
from ..checks import file_path, instance, shorten
from ..kinematics.ik_common import MIN_TIME_STEP
from ..model.params import did_you_mean
from ..model.values import float_text_problem, open_regular, parse_float, shown_path
from ..paths.splines import QuinticSpline
from ..paths.trajectory import MAX_TIME, Trajectory, TrajectoryError

MAX_LENGTH = 3.0  # m: a coordinate beyond this is almost surely in mm
MAX_ANGLE = 2.0 * math.pi  # rad: an angle beyond this is almost surely in degrees
PARQUET_MAGIC = b"PAR1"  # the first (and last) four bytes of every Parquet file
# Given d_* columns must agree with the positions: the largest gap between q(t) − q(t0) and
# the running trapezoid integral of q̇, relative to the largest excursion |q(t) − q(t0)| (the
# motion's scale), at most this. Exact rates give < 0.05; wrong units (deg/s: ×57), zeros
# (1) or a flipped sign (2) are refused.
DERIVATIVE_TOLERANCE = 0.5
# The same for dd_* against d_*, looser: a time-optimal retiming's s̈ jumps at every sample
# and a file holds one side of each jump (up to 2.2 seen); deg/s² (×57) is refused, and so is
# an all-zero dd_* column whose rates change.
ACCELERATION_TOLERANCE = 10.0
# The paint gun's trigger: the fraction of its flow sprayed, in [0, 1] (absent: 1 throughout).
SPRAY = "spray"


def from_csv(path: str | Path) -> Trajectory:
    """Read ``t,x,y,z,psi,theta,phi`` (+ optional ``d_*``, ``dd_*`` and ``spray``, the paint
    gun's trigger, kept as the trajectory's ``spray``) from a CSV file.

    Without derivative columns, derivatives come from a quintic interpolating spline and a
    :class:`UserWarning` says so.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV: a header row, then one row per sample; times [s] strictly increasing,
        positions [m], angles [rad] (ZYZ), rates and accelerations in the same units per s
        and s². A ``.units.json`` sidecar, when present, must agree.

    Returns
    -------
    Trajectory
        Named after the file's stem; ``derivatives`` says where the rates came from
        (``"file columns"`` or the spline), ``curve`` the path between the samples.

    Raises
    ------
    TrajectoryError
        A missing or unreadable file, a bad header, a cell that is not a finite number
        (the message names the row and column), times that do not increase, angles that
        jump by a turn, units that disagree with the sidecar.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> pp.to_csv(pp.thesis_trajectory(samples=101), "thesis.csv")
    >>> traj = pp.from_csv("thesis.csv")
    >>> len(traj), traj.derivatives
    (101, 'file columns')
    """
    path = file_path(path, "path", error=TrajectoryError)
    rows, lines = _read_rows(path)
    header = _check_header(path, rows)
    col = _parse_cells(path, rows, lines, header)
    t = _check_times(path, col, lines)
    poses = np.column_stack([col[n] for n in TASK_NAMES])
    _check_units(path, poses, lines)
    check_angle_wraps(path, t, poses, lines)
    d, dd, source, curve = _derivatives(path, t, poses, col)
    return Trajectory(t, poses, d, dd, name=path.stem, derivatives=source, curve=curve,
                      spray=col.get(SPRAY))


def _read_rows(path: Path) -> tuple[list[list[str]], list[int]]:
    """The CSV rows that are not comments, and the 1-based file line of each."""
    try:
        with open_regular(path, "rb") as f:  # not a FIFO: it would block forever
            magic = f.read(4)
        # -sig: a BOM is no column
        with open_regular(path, "r", newline="", encoding="utf-8-sig") as f:
            reader = csv.reader(f)
            rows, lines = [], []  # lines: 1-based file line of each kept row
            for r in reader:
                if r and not r[0].lstrip().startswith("#"):
                    rows.append(r)
                    lines.append(reader.line_num)
    except OSError as exc:
        raise TrajectoryError(f"cannot read trajectory file {shown_path(path)}: "
                              f"{exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        if magic == PARQUET_MAGIC:
            raise TrajectoryError(f"{path}: a Parquet file; trajectories are read from CSV "
                                  "text (t,x,y,z,psi,theta,phi)") from None
        raise TrajectoryError(f"{path}: not UTF-8 text (byte {exc.start}: "
                              f"{exc.object[exc.start:exc.start + 1]!r}); save it as UTF-8 "
                              "CSV") from None
    except csv.Error as exc:  # a field over the csv module's limit: not a trajectory
        # the csv module has read the offending line when it refuses it: line_num is its own
        raise TrajectoryError(f"{path}: line {reader.line_num}: not CSV ({exc})") from None
    if magic == PARQUET_MAGIC:  # Parquet bytes that happen to decode as UTF-8
        raise TrajectoryError(f"{path}: a Parquet file; trajectories are read from CSV text "
                              "(t,x,y,z,psi,theta,phi)")
    nul = next((i for i, r in enumerate(rows) if any("\0" in c for c in r)), None)
    if nul is not None:
        raise TrajectoryError(f"{path}: line {lines[nul]} holds NUL bytes: a binary file, "
                              "not CSV text")
    if not rows:
        raise TrajectoryError(f"{path}: empty file (expected a header t,x,y,z,psi,theta,phi)")
    return rows, lines


def _check_header(path: Path, rows: list[list[str]]) -> list[str]:
    """The column names of the first row: known, each once, the base ones all there."""
    header = [h.strip() for h in rows[0]]
    base = ("t",) + TASK_NAMES
    allowed = (base + tuple(f"d_{n}" for n in TASK_NAMES) + tuple(f"dd_{n}" for n in TASK_NAMES)
               + (SPRAY,))
    for h in header:
        if h not in allowed:
            raise TrajectoryError(f"{path}: unknown column {shorten(h)}{did_you_mean(h, allowed)}; "
                                  f"expected {', '.join(base)} and optional d_*, dd_*, {SPRAY}")
    again = next((i for i, h in enumerate(header) if h in header[:i]), None)
    if again is not None:
        first = header.index(header[again])
        raise TrajectoryError(f"{path}: duplicate column {shorten(header[again])} (columns "
                              f"{first + 1} and {again + 1})")
    missing = [c for c in base if c not in header]
    if missing:
        raise TrajectoryError(f"{path}: missing column(s) {', '.join(missing)}")
    return header


def _parse_cells(path: Path, rows, lines, header) -> dict[str, np.ndarray]:
    """Every cell a finite number, each row full; the columns by name (at least 2 samples,
    ``spray`` in [0, 1])."""
    data = _all_cells(rows[1:], len(header))
    if data is None:  # a short row or a bad cell: found and named cell by cell
        data = _cell_by_cell(path, rows, lines, header)
    if len(data) < 2:
        raise TrajectoryError(f"{path}: need at least 2 samples, found {len(data)}")
    col = {h: data[:, i] for i, h in enumerate(header)}
    if SPRAY in col:  # the gun's trigger (paint): the motion does not depend on it
        bad = (col[SPRAY] < 0) | (col[SPRAY] > 1)
        if bad.any():
            r = int(np.argmax(bad))
            raise TrajectoryError(f"{path}: row {lines[r + 1]}, column {SPRAY!r}: "
                                  f"{float(col[SPRAY][r])!r} is outside [0, 1] (the fraction "
                                  "of the gun's flow)")
    return col


def _all_cells(rows, width: int) -> np.ndarray | None:
    """The cells (n, width) read at once, when every row has ``width`` cells and every cell
    is a finite number as :func:`parse_float` reads it (its value is ``float``'s: the same
    bits); else None."""
    if any(len(row) != width for row in rows):
        return None
    cells = [cell for row in rows for cell in row]
    if float_text_problem("".join(cells)):  # what parse_float refuses and float takes
        return None
    try:
        data = np.fromiter(map(float, cells), float, len(cells)).reshape(len(rows), width)
    except ValueError:
        return None
    return data if np.isfinite(data).all() else None


def _cell_by_cell(path: Path, rows, lines, header) -> np.ndarray:
    """The cells one by one: the first short row or bad cell raises, naming its line."""
    data = np.empty((len(rows) - 1, len(header)))
    for r, row in enumerate(rows[1:]):
        line = lines[r + 1]  # file line, comment and blank lines counted
        if len(row) != len(header):
            raise TrajectoryError(f"{path}: row {line} has {len(row)} fields, "
                                  f"expected {len(header)}")
        for c, cell in enumerate(row):
            try:
                data[r, c] = parse_float(cell)
            except ValueError as exc:
                why = "" if "float" in str(exc) else f" ({exc})"  # float()'s own: no news
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"{shorten(cell)} is not a number{why}") from None
            if not math.isfinite(data[r, c]):
                raise TrajectoryError(f"{path}: row {line}, column {header[c]!r}: "
                                      f"value {shorten(cell)} is not finite")
    return data


def _check_times(path: Path, col, lines) -> np.ndarray:
    """The times: in seconds, increasing strictly by at least the solver's least step."""
    t = col["t"]
    big = np.abs(t) > MAX_TIME
    if np.any(big):
        r = int(np.argmax(big))
        raise TrajectoryError(f"{path}: row {lines[r + 1]}, column 't': {float(t[r]):.4g} s is "
                              f"beyond ±{MAX_TIME:g} s (seconds, not ms?)")
    dt = np.diff(t)
    if np.any(dt <= 0):
        r = int(np.argmax(dt <= 0))
        kind = "duplicate" if dt[r] == 0 else "decreasing"
        raise TrajectoryError(f"{path}: row {lines[r + 2]}, column 't': {kind} time "
                              f"{float(t[r + 1])!r} after {float(t[r])!r} (times must "
                              "increase strictly)")
    small = dt < MIN_TIME_STEP  # the solver's rule (ik_common); the spline would overflow
    if np.any(small):
        r = int(np.argmax(small))
        raise TrajectoryError(f"{path}: row {lines[r + 2]}, column 't': time step too small: "
                              f"{float(t[r + 1])!r} after {float(t[r])!r} is "
                              f"{float(dt[r]):.3g} s, below {MIN_TIME_STEP:g} s (times in "
                              "seconds?)")
    return t


def _check_units(path: Path, poses: np.ndarray, lines) -> None:
    """Refuse coordinates that look like millimetres and angles that look like degrees."""
    for c, name in enumerate(TASK_NAMES):
        limit, unit = (MAX_LENGTH, "millimetres (expected m)") if c < 3 else \
            (MAX_ANGLE, "degrees (expected rad)")
        big = np.abs(poses[:, c]) > limit
        if np.any(big):
            r = int(np.argmax(big))
            raise TrajectoryError(f"{path}: row {lines[r + 1]}, column {name!r}: "
                                  f"{float(poses[r, c])!r} looks like {unit}; "
                                  f"|value| > {limit:.4g}")


def _derivatives(path: Path, t, poses, col):
    """(d_poses, dd_poses, their source, the curve between samples or None): the file's
    d_*/dd_* columns (full sets, checked against the positions), else a quintic spline's,
    with a warning."""
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
        # stacklevel 3: the warning names from_csv's caller
        warnings.warn(f"{path}: no {absent} columns; derivatives taken from a quintic "
                      "interpolating spline through the samples", UserWarning, stacklevel=3)
    check_derivatives(path, t, poses, derivs[0], derivs[1], *derivs_given)
    return derivs[0], derivs[1], source, curve


def check_angle_wraps(path, t: np.ndarray, poses: np.ndarray, lines) -> None:
    """Refuse an angle that jumps by more than π between consecutive samples: a wrap at ±π
    (the robot's angles never turn half a revolution in one step), which a spline or the given
    rates would read as a spin of ~2π per step."""
    jumps = np.abs(np.diff(poses[:, 3:], axis=0))
    if np.any(jumps > math.pi):
        r, c = np.unravel_index(int(np.argmax(jumps > math.pi)), jumps.shape)
        name = TASK_NAMES[3 + c]
        raise TrajectoryError(
            f"{path}: row {lines[r + 2]}, column {name!r}: jumps by "
            f"{poses[r + 1, 3 + c] - poses[r, 3 + c]:.4g} rad from the previous sample "
            f"(t = {t[r]:.6g} -> {t[r + 1]:.6g} s): an angle wrap at ±π? unwrap the angles so "
            "consecutive samples differ by less than π rad")


def _mismatch(step: np.ndarray, integral: np.ndarray) -> np.ndarray:
    """Per column: max |Σ (integral − step)| over the running sums, over max |Σ step| (the
    excursion), each column's scale floored at 1e-2 of its group's (lengths, angles) largest,
    so a nearly still column is not judged by its own round-off. Running sums: one-sided
    values at jumps (a retiming's s̈) err by turns and cancel."""
    with np.errstate(all="ignore"):  # absurd columns (1e200) give inf: refused, no warning
        scale = np.abs(np.cumsum(step, axis=0)).max(axis=0)
        err = np.abs(np.cumsum(integral - step, axis=0)).max(axis=0)
    for g in (slice(0, 3), slice(3, 6)):
        scale[g] = np.maximum(scale[g], max(1e-2 * scale[g].max(), 1e-300))
    return np.where(np.isfinite(err), err / scale, np.inf)


def check_derivatives(path, t: np.ndarray, poses: np.ndarray, d: np.ndarray, dd: np.ndarray,
                      given_d: bool = True, given_dd: bool = True) -> None:
    """Refuse given (``given_d``, ``given_dd``) ``d_*``/``dd_*`` columns that do not integrate
    to the positions (rates) within :data:`DERIVATIVE_TOLERANCE`
    (:data:`ACCELERATION_TOLERANCE`) of the motion's scale: wrong units, zeros, another
    curve's derivatives. The running trapezoid rule (for the rates Euler–Maclaurin corrected
    with the accelerations)."""
    h = np.diff(t)[:, None]
    checks = []
    if given_d:
        integral = 0.5 * h * (d[1:] + d[:-1]) + h * h / 12.0 * (dd[:-1] - dd[1:])
        checks.append(("d_", np.diff(poses, axis=0), integral, "positions",
                       DERIVATIVE_TOLERANCE))
    if given_dd:
        still = ~np.any(dd, axis=0) & np.any(np.diff(d, axis=0), axis=0)
        if np.any(still):
            raise TrajectoryError(f"{path}: column dd_{TASK_NAMES[int(np.argmax(still))]} is "
                                  "all zero while its rate changes: missing accelerations? "
                                  "(leave the dd_* columns out to have them from a spline)")
        checks.append(("dd_", np.diff(d, axis=0), 0.5 * h * (dd[1:] + dd[:-1]), "d_* rates",
                       ACCELERATION_TOLERANCE))
    for prefix, step, integral, against, tolerance in checks:
        rel = _mismatch(step, integral)
        c = int(np.argmax(rel))
        if rel[c] > tolerance:
            unit = ("m/s" if c < 3 else "rad/s") + ("²" if prefix == "dd_" else "")
            raise TrajectoryError(
                f"{path}: column {prefix}{TASK_NAMES[c]!s} disagrees with the {against} by "
                f"{rel[c]:.3g}× the motion's scale (its running integral vs the excursion; "
                f"tolerance {tolerance:g}): wrong units (expected {unit}), zeros or another "
                "curve's derivatives?")


def to_csv(traj: Trajectory, path: str | Path, spray=None) -> None:
    """Write the trajectory in the ``run`` input format (``t``, poses, ``d_*``, ``dd_*``; every
    float64 exact), atomically, units in the ``.units.json`` sidecar.

    Parameters
    ----------
    traj : Trajectory
        The trajectory to write.
    path : str or pathlib.Path
        The CSV to write (replaced whole or not at all).
    spray : ndarray or None, optional
        (N,) the gun's trigger in [0, 1], written as a last column (absent: on throughout;
        default: the trajectory's own, if any).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> pp.to_csv(pp.thesis_trajectory(samples=5), "path.csv")
    >>> open("path.csv").readline().split(",")[:7]
    ['t', 'x', 'y', 'z', 'psi', 'theta', 'phi']
    """
    from .table import write_table

    instance(traj, "traj", Trajectory, "a Trajectory", error=TrajectoryError)
    cols = {"t": traj.t}
    for prefix, arr in (("", traj.poses), ("d_", traj.d_poses), ("dd_", traj.dd_poses)):
        cols.update({prefix + n: arr[:, i] for i, n in enumerate(TASK_NAMES)})
    if spray is not None:  # checked as a trajectory's own (shape, [0, 1]): readable back
        traj = dataclasses.replace(traj, spray=spray)
    if traj.spray is not None:
        cols[SPRAY] = traj.spray
    write_table(path, cols, {"trajectory": traj.name, "derivatives": traj.derivatives},
                fmt="csv")


GRAVITY_KEY = "gravity_base"  # a path.csv's metadata: gravity in the robot's base [m/s²]
# what a trajectory's sidecar says about the robot that runs it: carried on by every file that
# carries the trajectory on (``size --retime``)
CARRIED_KEYS = ("frame", "robot", GRAVITY_KEY)


def _sidecar_metadata(path: str | Path) -> tuple[Path, dict]:
    import json

    from .table import units_path

    side = units_path(path)
    if not side.is_file():
        return side, {}
    try:
        meta = json.loads(side.read_text(encoding="utf-8")).get("metadata") or {}
    except (OSError, UnicodeDecodeError, ValueError, AttributeError) as exc:
        raise TrajectoryError(f"{side}: unreadable units sidecar: {exc}") from None
    return side, meta if isinstance(meta, dict) else {}


def trajectory_gravity(path: str | Path):
    """The gravity [m/s²] a trajectory CSV's units sidecar records for the robot that runs it
    (a paint cell's turned robot, docs/model.md §26.1), checked (three finite numbers, 9.81
    m/s² ± 10 %); None when the file records none (gravity (0, 0, −9.81) then)."""
    from ..model.gravity import check_gravity

    side, meta = _sidecar_metadata(path)
    if GRAVITY_KEY not in meta:
        return None
    return check_gravity(meta[GRAVITY_KEY], f"{side}: metadata {GRAVITY_KEY!r}")


def carried_metadata(path: str | Path) -> dict:
    """The entries of a trajectory CSV's sidecar metadata that describe the robot running it
    (:data:`CARRIED_KEYS`: its frame, its base, its gravity, the gravity checked), for a file
    that carries the trajectory on (a retimed copy); empty when it records none.

    Parameters
    ----------
    path : str or Path
        The trajectory CSV.
    """
    _, meta = _sidecar_metadata(path)
    out = {k: meta[k] for k in CARRIED_KEYS if k in meta}
    if GRAVITY_KEY in out:
        out[GRAVITY_KEY] = [float(c) for c in trajectory_gravity(path)]
    return out


__all__ = ["CARRIED_KEYS", "GRAVITY_KEY", "carried_metadata", "check_angle_wraps",
           "check_derivatives", "from_csv", "to_csv", "trajectory_gravity"]
