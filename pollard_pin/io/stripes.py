"""Measured spray stripes (``pollard-pin calibrate --stripes STRIPES.toml``, docs/formats.md):
the TOML file that lists them and the CSV profile of each, read and checked.

A stripe is one straight pass of the gun over a flat test panel at a fixed standoff and speed,
its dried film measured across the pass: a CSV with the columns ``position`` [m] and
``thickness`` [m]. Every rule broken is one :class:`StripeError` line naming the file (the line
of the CSV where there is one) and what to measure or write instead. The checks here are of
the data alone (a file, a number, an order, a unit); those that need the pattern (noise, the
stripe's ends) are the calibration's (pollard_pin.painting.spray.calibrate).
"""
from __future__ import annotations

import csv
import io
import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..checks import file_path, shorten
from ..errors import InputError
from ..model.params import did_you_mean
from ..model.values import parse_float, read_bytes, read_toml

TOP_KEYS = ("solids", "standoff", "stripe")
STRIPE_KEYS = ("file", "standoff", "speed", "flow", "direction")
COLUMNS = ("position", "thickness")
DIRECTIONS = ("across", "along")  # the stroke, against the pattern's long axis
MAX_STRIPES = 64  # each adds an unknown (its centre): 32 take ~7 s CPU to fit; 4-16 suffice
MIN_POINTS = 10  # a profile of fewer points cannot show a spot's shape
MAX_CSV_BYTES = 16 << 20  # a profilometer scan of 100,000 points is ~3 MB
# Unit slips: beyond these a value is in other units (mm for m, mm/s for m/s, l/min for m³/s)
MAX_STANDOFF = 2.0  # m: a spray gun paints from 0.1-0.3 m
# m: nearer, no gun sprays a pattern; the fit divides by the standoff (1e-300 divided by zero)
MIN_STANDOFF = 0.01
MAX_SPEED = 10.0  # m/s: a gun moves at 0.1-1 m/s
MAX_FLOW = 1e-4  # m³/s: 6 l/min; a gun sprays 0.05-1 l/min
MAX_SPAN = 1.0  # m: no spray pattern is wider than a metre
MAX_THICKNESS = 1e-3  # m: a dry film of 1 mm is no paint stripe


class StripeError(InputError):
    """A stripe file or value the calibration cannot use (one line: which stripe, what to
    measure or write instead)."""


def _fail(where: str, what: str) -> None:
    raise StripeError(f"{where}: {what}")


def _value(where: str, key: str, value, high: float, unit: str, slip: str,
           low: float = 0.0) -> float:
    """A positive finite number at most ``high`` (beyond: the unit slip ``slip`` named) and
    at least ``low``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        _fail(where, f"{key} = {shorten(value)}: must be a number [{unit}]")
    try:
        v = float(value)
    except OverflowError:
        v = math.inf
    if not math.isfinite(v) or v <= 0:
        _fail(where, f"{key} = {shorten(value)}: must be a finite number > 0 [{unit}]")
    if v > high:
        _fail(where, f"{key} = {shorten(value)}: over {high:g} {unit}: {slip}")
    if v < low:
        _fail(where, f"{key} = {shorten(value)}: under {low:g} {unit}: no spray gun paints that "
                     "close (0.1-0.3 m)")
    return v


def _column(where: str, key: str, values) -> np.ndarray:
    """A profile's column as floats: real numbers only (a complex one is no reading)."""
    try:
        a = np.asarray(values)
        if a.dtype.kind not in "iuf":
            raise TypeError
        return np.array(a, dtype=float)
    except (TypeError, ValueError):
        _fail(where, f"{key} = {shorten(values, 30)}: expected an array of real numbers [m]")


def check_profile(where: str, position: np.ndarray, thickness: np.ndarray,
                  label=lambda i: f"point {i + 1}") -> None:
    """The data rules of one profile: two 1-D columns of one length, at least
    :data:`MIN_POINTS`, finite, positions strictly monotone and spanning at most
    :data:`MAX_SPAN`, films at most :data:`MAX_THICKNESS`. ``label(i)`` names the i-th point
    (a CSV's line)."""
    if position.ndim != 1 or position.shape != thickness.shape:
        _fail(where, f"position {position.shape} and thickness {thickness.shape}: expected "
                     "two 1-D columns of one length")
    if len(position) < MIN_POINTS:
        n = len(position)
        _fail(where, f"{n} point{'s' * (n != 1)}: measure at least {MIN_POINTS} across the "
                     "stripe, from bare panel to bare panel")
    for name, col in zip(COLUMNS, (position, thickness)):
        bad = ~np.isfinite(col)
        if bad.any():
            i = int(np.argmax(bad))
            _fail(where, f"{label(i)}: {name} is {col[i]}: measure that point again or drop "
                         "its row")
    step = np.diff(position)
    if not ((step > 0).all() or (step < 0).all()):
        i = int(np.argmax(step <= 0)) if step[0] > 0 else int(np.argmax(step >= 0))
        _fail(where, f"{label(i + 1)}: position {position[i + 1]:.6g} m after "
                     f"{position[i]:.6g} m: positions must rise (or fall) all the way; "
                     "one scan per file, sorted")
    span = abs(float(position[-1] - position[0]))
    if span > MAX_SPAN:
        _fail(where, f"the positions span {span:.4g} m, a pattern wider than "
                     f"{MAX_SPAN:g} m: positions in mm? give metres")
    peak = float(np.max(np.abs(thickness)))
    if peak > MAX_THICKNESS:
        unit = "mm" if peak < 1.0 else "µm"  # 10-100 µm of film: 0.01-0.1 mm, 10-100 µm
        _fail(where, f"thickness up to {peak:.4g} m, over {MAX_THICKNESS * 1e3:g} mm of dry "
                     f"film: thickness in {unit}? give metres")


@dataclass(frozen=True, eq=False)
class Stripe:
    """One measured stripe: the dried film across a straight pass of the gun (SI units).

    Parameters
    ----------
    position : ndarray
        (N,) positions across the stripe [m], strictly monotone (stored rising).
    thickness : ndarray
        (N,) the dry film at each position [m].
    standoff : float
        The gun's distance to the panel [m] (the spray axis normal to the panel).
    speed : float
        The gun's speed along the stripe [m/s].
    flow : float
        The liquid paint the gun sprays [m³/s].
    direction : str
        The stroke against the pattern's long axis: ``"across"`` or ``"along"``.
    source : str, optional
        What messages call the stripe (its file).
    """

    position: np.ndarray
    thickness: np.ndarray
    standoff: float
    speed: float
    flow: float
    direction: str
    source: str = "<python>"

    def __post_init__(self):
        where = self.source
        x, t = (_column(where, k, getattr(self, k)) for k in COLUMNS)
        check_profile(where, x, t)
        if x[-1] < x[0]:  # scanned the other way: stored rising
            x, t = x[::-1].copy(), t[::-1].copy()
        for a in (x, t):
            a.setflags(write=False)
        object.__setattr__(self, "position", x)
        object.__setattr__(self, "thickness", t)
        object.__setattr__(self, "standoff", _value(where, "standoff", self.standoff,
                                                    MAX_STANDOFF, "m", "in mm? give metres",
                                                    MIN_STANDOFF))
        object.__setattr__(self, "speed", _value(where, "speed", self.speed, MAX_SPEED, "m/s",
                                                 "in mm/s? give m/s"))
        object.__setattr__(self, "flow", _value(where, "flow", self.flow, MAX_FLOW, "m³/s",
                                                "in ml/min or l/min? give m³/s of liquid paint"))
        if self.direction not in DIRECTIONS:
            _fail(where, f"direction = {shorten(self.direction)}: must be 'across' or 'along' "
                         f"(the stroke against the pattern's long axis)"
                         f"{did_you_mean(str(self.direction), DIRECTIONS)}")


@dataclass(frozen=True)
class StripeSet:
    """The stripes of one STRIPES.toml: the paint's ``solids`` (the dry share of the liquid's
    volume), the reference ``standoff`` of the gun to write (None: the most common stripe
    standoff), the stripes, and the file's name for messages."""

    stripes: tuple[Stripe, ...]
    solids: float
    standoff: float | None = None
    source: str = "<python>"
    files: tuple[Path, ...] = field(default=(), repr=False)  # the CSVs read (not outputs)

    def __post_init__(self):
        where = self.source
        stripes = tuple(self.stripes)
        if not stripes or not all(isinstance(s, Stripe) for s in stripes):
            _fail(where, "no stripes: list each measured stripe as a [[stripe]] table (file, "
                         "standoff, speed, flow, direction)")
        if len(stripes) > MAX_STRIPES:
            _fail(where, f"{len(stripes)} stripes: at most {MAX_STRIPES} (4-16 calibrate a "
                         "gun: two standoffs, both directions); split them or average repeats")
        object.__setattr__(self, "stripes", stripes)
        solids = self.solids
        if isinstance(solids, (bool, np.bool_)) or not isinstance(solids, numbers.Real) \
                or not 0 < float(solids) <= 1:
            _fail(where, f"solids = {shorten(solids)}: must be the dry share of the paint's "
                         "volume, in (0, 1] (a percentage? give 0.45 for 45 %)")
        object.__setattr__(self, "solids", float(solids))
        if self.standoff is not None:
            object.__setattr__(self, "standoff", _value(where, "standoff", self.standoff,
                                                        MAX_STANDOFF, "m", "in mm? give metres",
                                                        MIN_STANDOFF))


def read_profile(path: Path, where: str) -> tuple[np.ndarray, np.ndarray]:
    """(position, thickness) of a stripe CSV, every data rule checked (:func:`check_profile`,
    each point named by its line)."""
    name = path.name
    try:  # read_bytes' own refusal of a large file would name the stripe as its kind
        large = path.stat().st_size > MAX_CSV_BYTES
    except OSError:  # read_bytes says why
        large = False
    if large:
        _fail(name, f"over {MAX_CSV_BYTES >> 20} MiB: a profile of 100,000 points is ~3 MB; "
                    "one scan per file")
    data = read_bytes(path, f"{where}: file", StripeError, MAX_CSV_BYTES)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        _fail(name, f"not UTF-8 text (another format?): a stripe is a CSV with the columns "
                    f"{', '.join(COLUMNS)}")
    reader, rows = csv.reader(io.StringIO(text)), []
    try:
        for r in reader:  # line_num: a quoted cell may span lines
            if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#"):
                rows.append((reader.line_num, r))
    except csv.Error as exc:  # a cell over the csv module's limit (128 kB), a NUL
        _fail(name, f"line {reader.line_num}: not CSV ({exc})")
    if not rows:
        _fail(name, f"empty: a stripe is a CSV with the columns {', '.join(COLUMNS)}")
    header = [c.strip() for c in rows[0][1]]
    for sep in (";", "\t"):
        if len(header) == 1 and sep in header[0]:
            _fail(name, f"line {rows[0][0]}: cells separated by {sep!r}: write a "
                        "comma-separated CSV (position,thickness), decimal points")
    # other columns (a profilometer's own: time, flags) are ignored; ours once each
    if any(header.count(c) != 1 for c in COLUMNS):
        _fail(name, f"line {rows[0][0]}: columns {shorten(','.join(header), 40)}: expected "
                    f"'position,thickness' once each (m, m; another format or other units?)")
    cols = {c: header.index(c) for c in COLUMNS}
    lines, values = [], []
    for line, r in rows[1:]:
        if len(r) != len(header):
            _fail(name, f"line {line}: {len(r)} cells, expected {len(header)} (position, "
                        "thickness)")
        row = []
        for c in COLUMNS:
            cell = r[cols[c]].strip()
            try:
                row.append(parse_float(cell))
            except (ValueError, OverflowError):
                _fail(name, f"line {line}: {c} {shorten(cell, 30)} is not a number")
        lines.append(line)
        values.append(row)
    arr = np.array(values, dtype=float).reshape(-1, 2)
    check_profile(name, arr[:, 0], arr[:, 1], lambda i: f"line {lines[i]}")
    return arr[:, 0], arr[:, 1]


def stripes_from_dict(d: Mapping, folder: Path, source: str = "<python>") -> StripeSet:
    """The stripes of a parsed STRIPES.toml (``file`` paths relative to ``folder``)."""
    if not isinstance(d, Mapping):
        _fail(source, "expected the tables of a STRIPES.toml (solids, [[stripe]])")
    for k in d:
        if k not in TOP_KEYS:
            _fail(source, f"unknown key {shorten(k, 30)}{did_you_mean(k, TOP_KEYS)}; the file "
                          "takes solids, standoff and [[stripe]] tables")
    if "solids" not in d:
        _fail(source, "'solids' is missing: the dry share of the paint's volume (0.45 for "
                      "45 % volume solids), the thickness being dry film")
    tables = d.get("stripe", [])
    if not isinstance(tables, list) or not all(isinstance(t, Mapping) for t in tables):
        _fail(source, "'stripe' must be [[stripe]] tables (file, standoff, speed, flow, "
                      "direction)")
    stripes, files, seen = [], [], {}
    for i, t in enumerate(tables, 1):
        where = f"{source}: stripe {i}"
        for k in t:
            if k in TOP_KEYS and k != "standoff":  # the paint's: one per calibration
                _fail(where, f"{k} is the paint's, given once at the top: calibrate stripes of "
                             "another paint on their own")
            if k not in STRIPE_KEYS:
                _fail(where, f"unknown key {shorten(k, 30)}{did_you_mean(k, STRIPE_KEYS)}; "
                             f"[[stripe]] takes {', '.join(STRIPE_KEYS)}")
        missing = [k for k in STRIPE_KEYS if k not in t]
        if missing:
            _fail(where, f"'{missing[0]}' is missing ([[stripe]] needs "
                         f"{', '.join(STRIPE_KEYS)})")
        if not isinstance(t["file"], str) or not t["file"]:
            _fail(where, f"file = {shorten(t['file'])}: must be the CSV's name (a string)")
        path = folder / file_path(t["file"], "file", error=StripeError)
        if path.resolve() in seen:
            _fail(where, f"file {shorten(t['file'], 60)} again (stripe {seen[path.resolve()]} "
                         "has it): one [[stripe]] per scan")
        seen[path.resolve()] = i
        position, thickness = read_profile(path, where)
        stripes.append(Stripe(position, thickness, t["standoff"], t["speed"], t["flow"],
                              t["direction"], source=f"{where} ({path.name})"))
        files.append(path)
    return StripeSet(tuple(stripes), d["solids"], d.get("standoff"), source, tuple(files))


def read_stripes(path: str | Path) -> StripeSet:
    """Read and check a STRIPES.toml and the CSV of each of its stripes (format:
    docs/formats.md, example: ``examples/stripes/stripes.toml``).

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file: ``solids`` (the dry share of the paint's volume), optional ``standoff``
        [m] (the reference standoff of the gun written), and ``[[stripe]]`` tables (``file``,
        ``standoff`` [m], ``speed`` [m/s], ``flow`` [m³/s of liquid paint], ``direction``).

    Returns
    -------
    StripeSet
        The stripes, each checked.

    Raises
    ------
    StripeError
        A missing, unreadable or malformed file, an unknown or missing key, a value in other
        units, a profile that breaks a rule (one line: where, and what to measure).
    """
    path = file_path(path, "stripes", error=StripeError)
    d = read_toml(path, "stripes file", StripeError)
    return stripes_from_dict(d, path.parent, path.name)


__all__ = ["COLUMNS", "DIRECTIONS", "STRIPE_KEYS", "TOP_KEYS", "Stripe", "StripeError",
           "StripeSet", "check_profile", "read_profile", "read_stripes", "stripes_from_dict"]
