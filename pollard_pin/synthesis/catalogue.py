"""The motor catalogue a design chooses from (docs/model.md §31.2): one table per motor (a
gearmotor: the motor with the gearboxes it is sold with), read once, and the
:class:`~pollard_pin.dynamics.motors.Actuator` a choice of motor and gear ratio makes.

The file (format: ``examples/design/motors.toml``)::

    [motors.NAME]
    rated_torque = 0.2      # N·m, motor side, continuous (the RMS limit)
    peak_torque = 0.6       # N·m, motor side
    speed = 500.0           # rad/s, motor side
    rotor_inertia = 5e-6    # kg·m²
    mass = 0.30             # kg, the motor with its gearbox
    ratios = [50, 100]      # the gear ratios on offer (motor angle = N × joint angle)
    price = 300.0           # optional, any currency (the cost objective uses it when every
                            # motor has one)
    stiffness = 3000.0      # optional, N·m/rad joint side (the gearbox as a spring; kmin)
    viscous = 1e-6          # optional, N·m·s/rad motor side (default 0)
    coulomb = 1e-3          # optional, N·m motor side (default 0)
"""
from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..checks import shorten
from ..dynamics.motors import MAX_VALUE, MIN_POSITIVE, Actuator, check_run_up
from ..errors import InputError
from ..model.params import did_you_mean
from ..model.values import fail, number, read_toml

REQUIRED = ("rated_torque", "peak_torque", "speed", "rotor_inertia", "mass", "ratios")
OPTIONAL = ("price", "stiffness", "viscous", "coulomb")
UNITS = {"rated_torque": "N·m", "peak_torque": "N·m", "speed": "rad/s",
         "rotor_inertia": "kg·m²", "mass": "kg", "stiffness": "N·m/rad",
         "viscous": "N·m·s/rad", "coulomb": "N·m", "price": ""}
MAX_RATIO = 1e4  # a gear ratio above it is a typo (harmonic drives stop near 160)
NAME = re.compile(r"^[A-Za-z0-9_.-]{1,40}$")
MAX_MOTORS = 200  # a catalogue longer than this is a unit list, not a choice


class CatalogueError(InputError):
    """A motor catalogue that breaks a rule (one line)."""


@dataclass(frozen=True)
class Motor:
    """One catalogue motor with its gearboxes (SI units, motor side unless said).

    Attributes
    ----------
    name : str
        The catalogue's name for it.
    rated_torque, peak_torque : float
        Continuous (RMS) and peak torque [N·m].
    speed : float
        Maximum speed [rad/s].
    rotor_inertia : float
        Jm [kg·m²].
    mass : float
        The motor with its gearbox [kg] (docs/model.md §31.1 places it).
    ratios : tuple of float
        The gear ratios on offer, increasing.
    price : float or None
        The catalogue price (None: not given).
    stiffness : float or None
        The gearbox's torsional stiffness [N·m/rad], joint side (None: not given).
    viscous, coulomb : float
        Friction [N·m·s/rad], [N·m] (default 0).
    """

    name: str
    rated_torque: float
    peak_torque: float
    speed: float
    rotor_inertia: float
    mass: float
    ratios: tuple[float, ...]
    price: float | None = None
    stiffness: float | None = None
    viscous: float = 0.0
    coulomb: float = 0.0

    def ratio_near(self, ratio: float) -> float:
        """The ratio on offer nearest ``ratio`` (in log: 80 between 50 and 100 is 100)."""
        return min(self.ratios, key=lambda n: (abs(math.log(n / ratio)), n))

    def actuator(self, ratio: float) -> Actuator:
        """The actuator this motor makes behind the offered ratio nearest ``ratio``."""
        return Actuator(gear_ratio=self.ratio_near(ratio), rotor_inertia=self.rotor_inertia,
                        viscous=self.viscous, coulomb=self.coulomb,
                        peak_torque=self.peak_torque, continuous_torque=self.rated_torque,
                        max_speed=self.speed, stiffness=self.stiffness)


@dataclass(frozen=True)
class Catalogue:
    """The motors on offer, in the file's order; ``ratios`` every ratio any of them offers,
    increasing (the gear ratio a design chooses is one of them, docs/model.md §31.2).

    Attributes
    ----------
    motors : tuple of Motor
        The motors.
    source : str
        The file they were read from.
    """

    motors: tuple[Motor, ...]
    source: str = "<python>"

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(m.name for m in self.motors)

    @property
    def ratios(self) -> tuple[float, ...]:
        return tuple(sorted({n for m in self.motors for n in m.ratios}))

    @property
    def priced(self) -> bool:
        """Every motor has a price."""
        return all(m.price is not None for m in self.motors)

    def __getitem__(self, name: str) -> Motor:
        return self.motors[self.names.index(name)]


def _value(source: str, key: str, value: Any, positive: bool, unit: str) -> float:
    low = f"between {MIN_POSITIVE:g} and" if positive else "at most"
    rule = f"must be {low} {MAX_VALUE:g}{(' ' + unit) if unit else ''}"
    v = number(value, key, CatalogueError, f"{source}: ", positive=positive, nonnegative=True,
               limit=MAX_VALUE, limit_rule=rule)
    if positive and v < MIN_POSITIVE:
        fail(CatalogueError, f"{source}: ", key, value, rule)
    return v


def _ratios(source: str, key: str, value: Any) -> tuple[float, ...]:
    if not isinstance(value, list) or not value:
        fail(CatalogueError, f"{source}: ", key, value, "must be a list of gear ratios")
    out = []
    for i, n in enumerate(value):
        r = number(n, f"{key}[{i}]", CatalogueError, f"{source}: ", limit=MAX_RATIO,
                   limit_rule=f"must be a gear ratio of at most {MAX_RATIO:g}")
        if not r > 0:
            fail(CatalogueError, f"{source}: ", f"{key}[{i}]", n,
                 "a gear ratio must be > 0 (motor angle = N × joint angle)")
        out.append(r)
    return tuple(sorted(set(out)))


def motor_from_dict(name: str, t: Any, source: str = "<python>") -> Motor:
    """One ``[motors.NAME]`` table, checked."""
    key = f"motors.{name}"
    if not NAME.match(name):
        raise CatalogueError(f"{source}: motor name {shorten(name)}: expected 1-40 letters, "
                             "digits, '-', '_' or '.'")
    if not isinstance(t, Mapping):
        fail(CatalogueError, f"{source}: ", key, t, "must be a table")
    missing = [k for k in REQUIRED if k not in t]
    if missing:
        raise CatalogueError(f"{source}: '{key}.{missing[0]}' is missing (every motor needs "
                             f"{', '.join(REQUIRED)})")
    unknown = [k for k in t if k not in REQUIRED + OPTIONAL]
    if unknown:
        fail(CatalogueError, f"{source}: ", f"{key}.{unknown[0]}", t[unknown[0]],
             f"unknown column{did_you_mean(unknown[0], REQUIRED + OPTIONAL)}")
    v = {k: _value(source, f"{key}.{k}", t[k], k not in ("viscous", "coulomb", "price"),
                   UNITS[k]) for k in REQUIRED + OPTIONAL if k in t and k != "ratios"}
    if v["rated_torque"] > v["peak_torque"]:
        fail(CatalogueError, f"{source}: ", f"{key}.rated_torque", t["rated_torque"],
             f"exceeds {key}.peak_torque = {v['peak_torque']:.4g}")
    check_run_up(v, "speed", f"{key}.rotor_inertia", t["rotor_inertia"], f"{source}: ",
                 CatalogueError)
    return Motor(name=name, ratios=_ratios(source, f"{key}.ratios", t["ratios"]), **v)


def catalogue_from_dict(d: Mapping, source: str = "<python>") -> Catalogue:
    """A parsed catalogue (``{"motors": {NAME: table}}``), checked."""
    if not isinstance(d, Mapping) or not isinstance(d.get("motors"), Mapping):
        raise CatalogueError(f"{source}: expected [motors.NAME] tables, one per motor")
    extra = [k for k in d if k != "motors"]
    if extra:
        raise CatalogueError(f"{source}: unknown key '{str(extra[0])[:40]}' (a catalogue holds "
                             "[motors.NAME] tables only)")
    motors = d["motors"]
    if not 1 <= len(motors) <= MAX_MOTORS:
        raise CatalogueError(f"{source}: expected 1 to {MAX_MOTORS} motors, got {len(motors)}")
    return Catalogue(tuple(motor_from_dict(str(n), t, source) for n, t in motors.items()),
                     source)


def load_catalogue(path: str | Path) -> Catalogue:
    """Read and check a motor catalogue file (docs/model.md §31.2).

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file: one ``[motors.NAME]`` table per motor (see the module's help, or
        ``examples/design/motors.toml``).

    Returns
    -------
    Catalogue
        The motors on offer.

    Raises
    ------
    CatalogueError
        A missing or malformed file, a missing or unknown column, a value out of its range, a
        gear ratio of 0 (one line).
    """
    return catalogue_from_dict(read_toml(path, "motor catalogue", CatalogueError),
                               Path(path).name)


__all__ = ["Catalogue", "CatalogueError", "Motor", "catalogue_from_dict", "load_catalogue",
           "motor_from_dict"]
