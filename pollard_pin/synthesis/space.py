"""The design space (docs/model.md §31.2): which parameters a design may change, within which
bounds, the motors it chooses from, and how many robots the cell may have.

The file ``S.toml`` (format: ``examples/design/space.toml``)::

    catalogue = "motors.toml"          # the motor catalogue, beside this file
    robots = [1, 2]                    # or robots = N (fixed)
    params = "base.toml"               # optional: the reference design (default: the shipped)

    [bounds]                           # dotted key → [low, high], units of models/pollard.toml
    "leg1.x87" = [0.30, 0.60]

    [[scale]]                          # one factor for all of its keys
    name = "arms"                      # optional (default: its number, 1, 2, …)
    keys = ["chain0.x32", "leg1.x43", "leg2.x43"]
    range = [1.0, 1.8]

    [motors]                           # optional: actuators sharing one choice of motor and
    base = ["theta21", "theta21_1", "theta21_2"]   # gear ratio (default: one per actuator)
    wrist = ["theta1615", "theta1716", "theta1817"]

    [place]                            # optional: how far [m] the robots stand back from the
    back = [0.0, 0.4]                  # world origin, away from the part (default 0)

A design is one value per :meth:`DesignSpace.variables`: each bound's key, ``scale.NAME``,
``motor.GROUP`` and ``ratio.GROUP`` (indices into the catalogue's motors and its ratios),
``place.back`` and ``robots`` when they are free.
"""
from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..checks import file_path, is_real, shorten
from ..model.overrides import ParameterError, apply_overrides, lookup
from ..model.params import did_you_mean, merge_partial, read_params_dict
from ..model.values import read_toml
from ..names import ACTUATED
from .catalogue import Catalogue, load_catalogue
from .space_checks import (
    SpaceError,
    check_ends,
    check_home,
    check_limits,
    given_once,
    lengths_nonnegative,
)

MAX_ROBOTS = 16  # as paint --robots (pollard_pin.painting.cell.robots.MAX_ROBOTS)
KEYS = ("catalogue", "robots", "params", "bounds", "scale", "motors", "place")
# Keys a design does not choose: the mass model owns the bodies (§31.1), the motors the
# limits' effort and velocity, and a side or a branch is no continuous quantity.
FIXED = ("bodies.", "branches.", "leg1.side", "leg2.side")

@dataclass(frozen=True)
class ScaleGroup:
    """One factor in [low, high] multiplying every one of ``keys``.

    Attributes
    ----------
    name : str
        Its name: the variable is ``scale.NAME``.
    keys : tuple of str
        The dotted keys it multiplies.
    low, high : float
        Its range.
    """

    name: str
    keys: tuple[str, ...]
    low: float
    high: float


@dataclass(frozen=True)
class Variable:
    """What the optimiser samples.

    Attributes
    ----------
    name : str
        The key of the design's values.
    low, high : float
        Its range (a categorical's: 0 and the last index).
    kind : str
        "float" (in [low, high]), "int" (low..high) or "categorical" (an index 0..high into
        ``choices``).
    choices : tuple
        A categorical's choices (motor names, gear ratios); () otherwise.
    """

    name: str
    low: float
    high: float
    kind: str
    choices: tuple = ()


def _one_per_actuator() -> tuple[tuple[str, tuple[str, ...]], ...]:
    return tuple((j, (j,)) for j in ACTUATED)


@dataclass(frozen=True)
class DesignSpace:
    """A checked design space (:func:`load_space`, :func:`space_from_dict`).

    Attributes
    ----------
    bounds : dict
        Dotted key → (low, high), thesis units (models/pollard.toml's).
    scales : tuple of ScaleGroup
        The shared length factors.
    catalogue : Catalogue
        The motors on offer.
    robots : tuple of int
        (fewest, most) robots in the cell; equal: fixed.
    source : str
        Where it was read from.
    motor_groups : tuple
        (group, actuator joints) pairs sharing a motor and a gear ratio.
    reference : dict
        The reference design's thesis-unit dictionary (its masses go with its lengths).
    back : tuple of float
        (low, high) [m]: how far the robots stand back from the world origin, away from the
        part along its facing (docs/model.md §31.3); equal: fixed.
    """

    bounds: dict[str, tuple[float, float]]
    scales: tuple[ScaleGroup, ...]
    catalogue: Catalogue
    robots: tuple[int, int]
    source: str = "<dict>"
    motor_groups: tuple = field(default_factory=_one_per_actuator)
    reference: dict = field(default_factory=read_params_dict, repr=False, compare=False)
    back: tuple[float, float] = (0.0, 0.0)

    def variables(self) -> list[Variable]:
        """What the optimiser samples, in a fixed order."""
        out = [Variable(k, lo, hi, "float") for k, (lo, hi) in self.bounds.items()]
        out += [Variable(f"scale.{g.name}", g.low, g.high, "float") for g in self.scales]
        names, ratios = self.catalogue.names, self.catalogue.ratios
        for group, _ in self.motor_groups:
            out.append(Variable(f"motor.{group}", 0, len(names) - 1, "categorical", names))
            out.append(Variable(f"ratio.{group}", 0, len(ratios) - 1, "categorical", ratios))
        if self.back[0] < self.back[1]:
            out.append(Variable("place.back", *self.back, "float"))
        if self.robots[0] < self.robots[1]:
            out.append(Variable("robots", *self.robots, "int"))
        return out

    def fingerprint(self) -> str:
        """A stable hash of everything that decides an evaluation (resume checks)."""
        doc = {"bounds": sorted((k, list(v)) for k, v in self.bounds.items()),
               "scales": [asdict(g) for g in self.scales],
               "catalogue": [asdict(m) for m in self.catalogue.motors],
               "robots": list(self.robots), "motors": [[g, list(j)] for g, j in
                                                       self.motor_groups],
               "reference": self.reference, "back": list(self.back)}
        text = json.dumps(doc, sort_keys=True, default=list, separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def overrides(self, values: Mapping[str, Any]) -> dict[str, float]:
        """The dotted-key overrides of a design's lengths (bounds, then scales), thesis
        units; a key left out of ``values`` takes the middle of its bound (a factor: 1)."""
        out: dict[str, float] = {}
        for k, (lo, hi) in self.bounds.items():
            out[k] = float(values.get(k, (lo + hi) / 2))
        for g in self.scales:
            f = float(values.get(f"scale.{g.name}", 1.0))
            for k in g.keys:
                out[k] = out.get(k, float(lookup(self.reference, k))) * f
        return out

    def design_dict(self, values: Mapping[str, Any]) -> dict:
        """The reference's thesis-unit dictionary with a design's lengths put in (its bodies
        still the reference's: :func:`pollard_pin.model.masses.design_bodies` replaces
        them)."""
        return apply_overrides(self.reference, self.overrides(values))

    def motors(self, values: Mapping[str, Any]) -> dict[str, tuple]:
        """Actuator joint → (Motor, gear ratio) of a design (index values; default 0)."""
        names, ratios = self.catalogue.motors, self.catalogue.ratios
        out = {}
        for group, joints in self.motor_groups:
            m = names[_index(values.get(f"motor.{group}", 0), len(names), f"motor.{group}")]
            n = m.ratio_near(ratios[_index(values.get(f"ratio.{group}", 0), len(ratios),
                                           f"ratio.{group}")])
            out.update({j: (m, n) for j in joints})
        return out

    def place_back(self, values: Mapping[str, Any]) -> float:
        """How far [m] the design's robots stand back (the low bound when not given)."""
        lo, hi = self.back
        v = values.get("place.back", lo)
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating)) \
                or not lo - 1e-12 <= float(v) <= hi + 1e-12:
            raise SpaceError(f"place.back = {shorten(v)}: expected a distance in [{lo:g}, "
                             f"{hi:g}] m")
        return float(v)

    def robot_count(self, values: Mapping[str, Any]) -> int:
        """The design's number of robots (the fewest when free and not given)."""
        lo, hi = self.robots
        n = values.get("robots", lo)
        if isinstance(n, bool) or int(n) != n or not lo <= int(n) <= hi:
            raise SpaceError(f"robots = {shorten(n)}: expected a whole number in {lo}..{hi}")
        return int(n)


def _index(v, n: int, name: str) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer, float)) or int(v) != v \
            or not 0 <= int(v) < n:
        raise SpaceError(f"{name} = {shorten(v)}: expected an index 0..{n - 1}")
    return int(v)


def _pair(value: Any, key: str, where: str) -> tuple[float, float]:
    if (not isinstance(value, (list, tuple)) or len(value) != 2
            or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in value)):
        raise SpaceError(f"{where}: {key} = {shorten(value)}: expected [low, high]")
    if not all(is_real(v) for v in value):  # NaN, inf, or an integer beyond a float (10**400)
        shown = ", ".join(shorten(v) for v in value)
        raise SpaceError(f"{where}: {key} = [{shown}]: bounds must be finite")
    lo, hi = (float(v) for v in value)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise SpaceError(f"{where}: {key} = {shorten(value)}: bounds must be finite")
    if not lo < hi:
        raise SpaceError(f"{where}: {key} = {shorten(value)}: an empty bound (low must be "
                         "below high)")
    return lo, hi


def _check_key(ref: Mapping, key: Any, where: str) -> str:
    if not isinstance(key, str):
        raise SpaceError(f"{where}: key {shorten(key)} is not a dotted parameter key")
    if key.startswith(FIXED):
        raise SpaceError(f"{where}: {key!r} is not a design variable (the mass model sets "
                         "bodies, and sides and branches are fixed)")
    if key.startswith("limits.") and key.rsplit(".", 1)[-1] in ("effort", "velocity"):
        raise SpaceError(f"{where}: {key!r} is not a design variable (the chosen motor sets it)")
    try:
        value = lookup(ref, key)
    except ParameterError:
        close = did_you_mean(key, _all_keys(ref))
        raise SpaceError(f"{where}: {key!r} names no parameter of models/pollard.toml"
                         f"{close}") from None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SpaceError(f"{where}: {key!r} is a list; bound one component, e.g. {key}[0]")
    return key


def _all_keys(d: Mapping, prefix: str = "") -> list[str]:
    out = []
    for k, v in d.items():
        key = f"{prefix}{k}"
        out += _all_keys(v, key + ".") if isinstance(v, Mapping) else [key]
    return out


def _robots(value: Any, where: str) -> tuple[int, int]:
    pair = value if isinstance(value, list) else [value, value]
    if (len(pair) != 2 or any(isinstance(v, bool) or not isinstance(v, int) for v in pair)
            or not 1 <= pair[0] <= pair[1] <= MAX_ROBOTS):
        raise SpaceError(f"{where}: robots = {shorten(value)}: expected N or [1, N], "
                         f"1 <= N <= {MAX_ROBOTS}")
    return int(pair[0]), int(pair[1])


MAX_BACK = 2.0  # m: further back than this is beyond any reach of these robots


def _back(value: Any, where: str) -> tuple[float, float]:
    if value is None:
        return (0.0, 0.0)
    if not isinstance(value, Mapping) or set(value) != {"back"}:
        raise SpaceError(f"{where}: [place] holds back = [low, high] (m) or back = D only")
    b = value["back"]
    if isinstance(b, (int, float)) and not isinstance(b, bool):
        if not is_real(b):
            raise SpaceError(f"{where}: place.back = {shorten(b)}: must be a finite distance")
        lo = hi = float(b)
    else:
        lo, hi = _pair(b, "place.back", where)
    if not (0.0 <= lo and hi <= MAX_BACK):
        raise SpaceError(f"{where}: place.back = {shorten(value['back'])}: expected distances "
                         f"in [0, {MAX_BACK:g}] m (a bound below zero?)")
    return lo, hi


def _motor_groups(value: Any, where: str) -> tuple:
    if value is None:
        return _one_per_actuator()
    if not isinstance(value, Mapping):
        raise SpaceError(f"{where}: [motors] must be a table: group = [actuator joints]")
    seen: list[str] = []
    groups = []
    for g, joints in value.items():
        if not isinstance(joints, list) or not joints:
            raise SpaceError(f"{where}: motors.{g} must be a list of actuator joints")
        for j in joints:
            if j not in ACTUATED:
                raise SpaceError(f"{where}: motors.{g}: {shorten(j)} is not an actuator"
                                 f"{did_you_mean(j, ACTUATED)}")
            if j in seen:
                raise SpaceError(f"{where}: motors.{g}: {j} is in two groups")
            seen.append(j)
        groups.append((str(g), tuple(joints)))
    groups += [(j, (j,)) for j in ACTUATED if j not in seen]  # the rest: one each
    return tuple(groups)


def space_from_dict(d: Mapping, source: str = "<dict>", folder: str | Path = ".",
                    catalogue: Catalogue | None = None) -> DesignSpace:
    """Check a parsed design space (the layout of ``S.toml``; docs/model.md §31.2).

    Parameters
    ----------
    d : Mapping
        The parsed file.
    source : str, optional
        Its name, for messages.
    folder : str or pathlib.Path, optional
        Where ``catalogue`` and ``params`` file names are read from (default: here).
    catalogue : Catalogue or None, optional
        The catalogue, if already read (default: ``d["catalogue"]``'s file).

    Returns
    -------
    DesignSpace
        The checked space.

    Raises
    ------
    SpaceError
        An unknown or misspelt key, a bound below zero (a length) or empty, a catalogue
        missing, bounds under which the home pose is never reachable (one line).
    """
    if not isinstance(d, Mapping):
        raise SpaceError(f"{source}: expected a table")
    for k in d:
        if k not in KEYS:
            raise SpaceError(f"{source}: unknown key {shorten(k)}{did_you_mean(k, KEYS)} "
                             f"(expected {', '.join(KEYS)})")
    folder = Path(folder)
    ref = read_params_dict()
    if "params" in d:  # a file name: a number or a list is no name (nor an empty string)
        ref = merge_partial(ref, read_params_dict(
            folder / file_path(d["params"], f"{source}: params", error=SpaceError)))
    if catalogue is None:
        if not isinstance(d.get("catalogue"), str):
            raise SpaceError(f"{source}: catalogue = \"FILE\" (the motor catalogue) is missing")
        catalogue = load_catalogue(folder / file_path(d["catalogue"], f"{source}: catalogue",
                                                      error=SpaceError))
    bounds_in = d.get("bounds", {})
    if not isinstance(bounds_in, Mapping):
        raise SpaceError(f"{source}: [bounds] must be a table of key = [low, high]")
    bounds = {}
    for k, v in bounds_in.items():
        if isinstance(v, Mapping):  # a bare dotted key is a TOML table: leg1.x87 = [...]
            raise SpaceError(f"{source} [bounds]: {shorten(k)} holds a table; quote a dotted "
                             f"key: \"{k}.KEY\" = [low, high]")
        key = _check_key(ref, k, f"{source} [bounds]")
        bounds[key] = _pair(v, repr(key), f"{source} [bounds]")
        lengths_nonnegative(key, bounds[key][0], f"{source} [bounds]")
    scales = []
    raw = d.get("scale", [])
    if not isinstance(raw, list) or any(not isinstance(t, Mapping) for t in raw):
        raise SpaceError(f"{source}: [[scale]] must be tables of keys = [...], range = [lo, hi]")
    for i, t in enumerate(raw, start=1):
        where = f"{source} [[scale]] {i}"
        extra = [k for k in t if k not in ("name", "keys", "range")]
        if extra:
            raise SpaceError(f"{where}: unknown key {shorten(extra[0])} (expected name, keys, "
                             "range)")
        keys = t.get("keys")
        if not isinstance(keys, list) or not keys:
            raise SpaceError(f"{where}: keys = [...] (the parameters it scales) is missing")
        keys = tuple(_check_key(ref, k, where) for k in keys)
        lo, hi = _pair(t.get("range"), "range", where)
        if lo <= 0:
            raise SpaceError(f"{where}: range = [{lo:g}, {hi:g}]: a bound below zero (a "
                             "factor must be > 0)")
        scales.append(ScaleGroup(str(t.get("name", i)), keys, lo, hi))
    if len({g.name for g in scales}) != len(scales):
        raise SpaceError(f"{source}: two [[scale]] tables share a name")
    given_once(bounds, scales, source)
    if "robots" not in d:
        raise SpaceError(f"{source}: robots = N or [1, N] is missing")
    space = DesignSpace(bounds, tuple(scales), catalogue, _robots(d["robots"], source), source,
                        _motor_groups(d.get("motors"), source), ref,
                        _back(d.get("place"), source))
    check_ends(space)
    check_limits(space)
    check_home(space)
    return space


def load_space(path: str | Path) -> DesignSpace:
    """Read and check a design space file ``S.toml`` (docs/model.md §31.2).

    Parameters
    ----------
    path : str or pathlib.Path
        The file (format: the module's help, ``examples/design/space.toml``); its
        ``catalogue`` and ``params`` file names are read beside it.

    Returns
    -------
    DesignSpace
        The checked space.

    Raises
    ------
    SpaceError
        As :func:`space_from_dict`, or an unreadable file.
    pollard_pin.synthesis.catalogue.CatalogueError
        A bad catalogue.
    """
    path = Path(path)
    return space_from_dict(read_toml(path, "design space", SpaceError), path.name, path.parent)


__all__ = ["DesignSpace", "ScaleGroup", "SpaceError", "Variable", "check_home", "load_space",
           "space_from_dict"]
