"""Model parameters (docs/model.md §3, §5, §9): a frozen, validated object loaded from TOML.

The TOML file uses the thesis' units (m, deg, kg, kg·mm²; joint limits in deg, N·m, rad/s);
:class:`Params` holds SI values (m, rad, kg, kg·m², N·m, rad/s). Every rule that fails
raises :class:`ParameterError` naming the key, the value and the rule.
"""
from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..checks import file_path
from ..names import ACTUATED, BODIES, TREE_JOINTS
from .overrides import ParameterError, apply_overrides, plain_value
from .paths import models_dir
from .values import fail, number, read_toml

DEFAULT_PARAMS = "pollard.toml"

CHAIN0_KEYS = ("z10", "x32", "x65", "x1514", "x1918")
LEG_KEYS = ("side", "y10", "z32", "x43", "beta54", "x87", "x1211", "z1312", "beta1413")
LEG_ANGLES = ("beta54", "beta1413")  # given in deg
LEG_LENGTHS = ("y10", "z32", "x43", "x87")  # strictly positive
LEG_OFFSETS = ("x1211", "z1312")  # may be zero, not negative
BODY_KEYS = ("mass", "com", "inertia")
HOME_KEYS = ("tip", "orientation")
BRANCH_KEYS = ("chain0", "leg1", "leg2")
LIMIT_KEYS = ("lower", "upper", "effort", "velocity")  # deg, deg, N·m, rad/s
SECTIONS = ("chain0", "leg1", "leg2", "bodies", "home", "branches", "limits")


@dataclass(frozen=True)
class Leg:
    """Geometry of leg i (docs/model.md §3, §4), SI units."""

    side: int  # s_i, the thesis "signo"
    y10: float
    z32: float
    x43: float
    beta54: float  # rad
    x87: float
    x1211: float
    z1312: float
    beta1413: float  # rad

    @property
    def attachment(self) -> np.ndarray:
        """Point A_i without the x65 term: offset of the spherical joint in the platform frame."""
        c, s = math.cos(-self.beta1413), math.sin(-self.beta1413)
        return np.array([-self.x1211 * c, -self.x1211 * s, -self.z1312])


@dataclass(frozen=True)
class Body:
    """Mass [kg], centre of gravity [m] and inertia about it [kg·m²], in the body frame."""

    mass: float
    com: tuple[float, float, float]
    inertia: tuple[tuple[float, float, float], ...]

    @property
    def inertia_matrix(self) -> np.ndarray:
        return np.array(self.inertia, dtype=float)


@dataclass(frozen=True)
class JointLimits:
    """URDF ``<limit>`` of one joint (docs/model.md §3): position [rad], effort [N·m] (0 for
    a passive joint: no actuator), velocity [rad/s]."""

    lower: float
    upper: float
    effort: float
    velocity: float


@dataclass(frozen=True)
class Params:
    """All model numbers, SI units. Build with :func:`~pollard_pin.load_params`; never mutated.

    Attributes
    ----------
    z10, x32, x65, x1514, x1918 : float
        Chain 0 and wrist lengths [m] (docs/model.md §5; thesis symbols).
    legs : tuple of pollard_pin.model.params.Leg
        Legs 1 and 2: their base positions, lengths and attachment points [m].
    bodies : tuple of tuple
        ``(name, Body)`` pairs (:class:`pollard_pin.model.params.Body`): mass [kg], centre of
        gravity [m] and inertia [kg·m²] of each body.
    home_pose : tuple of float
        The home tool pose (x, y, z [m], ψ, θ, φ [rad]; docs/model.md §9).
    branches : tuple of int
        Assembly branches of chain 0, leg 1 and leg 2 (docs/model.md §7).
    limits : tuple of tuple
        ``(joint, JointLimits)`` pairs (:class:`pollard_pin.model.params.JointLimits`): the
        limits [rad] of each tree joint.
    source : str
        Where the numbers came from (a file name, or ``"<python>"``).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> p = pp.load_params(overrides={"bodies.gun.mass": 0.05})
    >>> p.body("gun").mass
    0.05
    """

    z10: float
    x32: float
    x65: float
    x1514: float
    x1918: float
    legs: tuple[Leg, Leg]
    bodies: tuple[tuple[str, Body], ...]  # ordered (name, Body) pairs, BODIES order
    home_pose: tuple[float, ...]  # (x, y, z, psi, theta, phi), m and rad
    branches: tuple[int, int, int]  # chain0, leg1, leg2
    limits: tuple[tuple[str, JointLimits], ...]  # ordered (joint, limits), TREE_JOINTS order
    source: str = "<python>"

    def body(self, name: str) -> Body:
        return dict(self.bodies)[name]

    def joint_limits(self, name: str) -> JointLimits:
        return dict(self.limits)[name]

    def attachment(self, i: int) -> np.ndarray:
        """A_i of docs/model.md §4 in the platform frame (i = 0 or 1 for legs 1 and 2)."""
        return np.array([self.x65, 0.0, 0.0]) + self.legs[i].attachment

    @property
    def total_mass(self) -> float:
        return sum(b.mass for _, b in self.bodies)

    def to_toml_dict(self) -> dict:
        """The thesis-unit dictionary that ``params_from_dict`` reads back."""
        d: dict[str, Any] = {"chain0": {k: getattr(self, k) for k in CHAIN0_KEYS}}
        for i, leg in enumerate(self.legs, start=1):
            entry = {k: getattr(leg, k) for k in LEG_KEYS}
            for k in LEG_ANGLES:
                entry[k] = math.degrees(entry[k])
            d[f"leg{i}"] = entry
        d["bodies"] = {
            name: {"mass": b.mass, "com": list(b.com),
                   "inertia": (np.array(b.inertia) * 1e6).tolist()}
            for name, b in self.bodies
        }
        d["home"] = {"tip": list(self.home_pose[:3]),
                     "orientation": [math.degrees(a) for a in self.home_pose[3:]]}
        d["branches"] = dict(zip(BRANCH_KEYS, self.branches))

        def deg(a):  # 9 decimals: deg → rad → deg gives the same number back
            return round(math.degrees(a), 9)

        d["limits"] = {n: {"lower": deg(lim.lower), "upper": deg(lim.upper),
                           "effort": lim.effort, "velocity": lim.velocity}
                       for n, lim in self.limits}
        return d


def _fail(key: str, value: Any, rule: str) -> None:
    fail(ParameterError, "parameter ", key, plain_value(value), rule)


def _check_keys(key: str, table: Any, expected: tuple[str, ...]) -> None:
    if not isinstance(table, Mapping):
        _fail(key, table, "must be a table")
    missing = [k for k in expected if k not in table]
    unknown = [k for k in table if k not in expected]
    if missing:
        _fail(f"{key}.{missing[0]}" if key else missing[0], None,
              f"missing key (expected keys: {', '.join(expected)})")
    if unknown:
        _fail(f"{key}.{unknown[0]}" if key else unknown[0], table[unknown[0]],
              f"unknown key (expected keys: {', '.join(expected)})")


def _number(key: str, value: Any, **rules) -> float:
    return number(plain_value(value), key, ParameterError, "parameter ", **rules)


MAX_LENGTH = 10.0  # m: a longer link is a unit slip (mm?) and overflows the closed form
_LENGTH_RULE = f"must be at most {MAX_LENGTH:g} m (lengths are in metres, not mm)"
# A body heavier (a larger inertia) is a unit slip, and the dynamics' squares overflow: the
# heaviest body is 0.19 kg; 1000 kg at 10 m gives 1e11 kg·mm².
MAX_MASS, MAX_INERTIA = 1e3, 1e11
_TIP_RULE = f"must be within ±{MAX_LENGTH:g} m (metres, not mm)"


def _positive(key: str, value: Any, limit: float | None = None) -> float:
    return _number(key, value, positive=True, limit=limit, limit_rule=_LENGTH_RULE)


def _nonnegative(key: str, value: Any, limit: float | None = None) -> float:
    return _number(key, value, nonnegative=True, limit=limit, limit_rule=_LENGTH_RULE)


def _sign(key: str, value: Any) -> int:
    if isinstance(value, bool) or value not in (-1, 1):
        _fail(key, value, "must be -1 or +1")
    return int(value)


def _vector(key: str, value: Any, n: int, **rules) -> list[float]:
    if not isinstance(value, (list, tuple)) or len(value) != n:
        _fail(key, value, f"must be a list of {n} numbers")
    return [_number(f"{key}[{j}]", v, **rules) for j, v in enumerate(value)]


def _inertia(key: str, value: Any) -> tuple[tuple[float, ...], ...]:
    """kg·mm² in, kg·m² out; a physical rigid-body inertia or ParameterError."""
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        _fail(key, value, "must be a 3x3 matrix (list of 3 rows)")
    rows = [_vector(f"{key}[{r}]", row, 3, limit=MAX_INERTIA, limit_rule=f"must be within "
                    f"±{MAX_INERTIA:g} kg·mm² (kg·mm², not g·mm²)") for r, row in enumerate(value)]
    m = np.array(rows)
    scale = max(np.abs(m).max(), 1e-300)
    if np.abs(m - m.T).max() > 1e-9 * scale:
        _fail(key, rows, "inertia tensor must be symmetric")
    eig = np.linalg.eigvalsh(m)
    if eig[0] <= 0.0:
        _fail(key, rows, f"inertia tensor must be positive definite (eigenvalues {eig.tolist()})")
    if eig[0] + eig[1] < eig[2] * (1.0 - 1e-12):
        _fail(key, rows, "principal moments violate the triangle inequality "
              f"I1 + I2 >= I3 ({eig[0]:.6g} + {eig[1]:.6g} < {eig[2]:.6g})")
    return tuple(tuple(float(x) * 1e-6 for x in row) for row in rows)


def _joint_limits(key: str, t: Any, actuated: bool) -> JointLimits:
    """One ``limits.<joint>`` table (deg, deg, N·m, rad/s) → :class:`JointLimits` (SI)."""
    _check_keys(key, t, LIMIT_KEYS)
    # each bound is checked on its own first, so that the message names the bad one
    lower, upper = (_number(f"{key}.{k}", t[k], limit=720.0, limit_rule="must be within "
                            "±720 deg (two turns)") for k in ("lower", "upper"))
    if not lower < upper:
        _fail(f"{key}.upper", t["upper"], f"must be greater than {key}.lower = {lower:.4g} deg")
    if upper - lower > 360.0:  # a revolute joint's range; wider is a placeholder
        exc = ParameterError(f"parameter '{key}.lower' = {lower:.4g}, '{key}.upper' = "
                             f"{upper:.4g}: the range {upper - lower:.4g} deg exceeds one turn "
                             "(360)")
        exc.key = f"{key}.lower"  # the key named first, as fail() names its key
        raise exc
    effort = _number(f"{key}.effort", t["effort"])
    if actuated and effort <= 0.0:
        _fail(f"{key}.effort", t["effort"], "must be > 0 N·m (an actuated joint)")
    if not actuated and effort != 0.0:
        _fail(f"{key}.effort", t["effort"], "must be 0 (a passive joint has no actuator)")
    return JointLimits(math.radians(lower), math.radians(upper), effort,
                       _positive(f"{key}.velocity", t["velocity"]))


def params_from_dict(d: Mapping[str, Any], source: str = "<dict>",
                     check_home: bool = True) -> Params:
    """Validate a thesis-unit dictionary (the TOML layout) and build :class:`Params`."""
    _check_keys("", d, SECTIONS)
    _check_keys("chain0", d["chain0"], CHAIN0_KEYS)
    chain0 = {k: _positive(f"chain0.{k}", d["chain0"][k], MAX_LENGTH) for k in CHAIN0_KEYS}
    legs = []
    for i in (1, 2):
        sec = f"leg{i}"
        t = d[sec]
        _check_keys(sec, t, LEG_KEYS)
        vals: dict[str, Any] = {"side": _sign(f"{sec}.side", t["side"])}
        for k in LEG_LENGTHS:
            vals[k] = _positive(f"{sec}.{k}", t[k], MAX_LENGTH)
        for k in LEG_OFFSETS:
            vals[k] = _nonnegative(f"{sec}.{k}", t[k], MAX_LENGTH)
        for k in LEG_ANGLES:
            vals[k] = math.radians(_number(f"{sec}.{k}", t[k]))
        legs.append(Leg(**vals))
    if legs[0].side == legs[1].side:
        _fail("leg2.side", legs[1].side, "the two legs must stand on opposite sides (s_1 = -s_2)")
    _check_keys("bodies", d["bodies"], BODIES)
    bodies = []
    for name in BODIES:
        key = f"bodies.{name}"
        t = d["bodies"][name]
        _check_keys(key, t, BODY_KEYS)
        mass = _number(f"{key}.mass", t["mass"], positive=True, limit=MAX_MASS,
                       limit_rule=f"must be at most {MAX_MASS:g} kg (masses are in kg, not g)")
        bodies.append((name, Body(mass=mass,
                                  com=tuple(_vector(f"{key}.com", t["com"], 3, limit=MAX_LENGTH,
                                                    limit_rule=_TIP_RULE)),
                                  inertia=_inertia(f"{key}.inertia", t["inertia"]))))
    _check_keys("home", d["home"], HOME_KEYS)
    tip = _vector("home.tip", d["home"]["tip"], 3, limit=MAX_LENGTH, limit_rule=_TIP_RULE)
    ori = [math.radians(a) for a in _vector("home.orientation", d["home"]["orientation"], 3)]
    _check_keys("branches", d["branches"], BRANCH_KEYS)
    branches = tuple(_sign(f"branches.{k}", d["branches"][k]) for k in BRANCH_KEYS)
    _check_keys("limits", d["limits"], TREE_JOINTS)
    limits = tuple((n, _joint_limits(f"limits.{n}", d["limits"][n], n in ACTUATED))
                   for n in TREE_JOINTS)
    p = Params(**chain0, legs=tuple(legs), bodies=tuple(bodies), home_pose=tuple(tip + ori),
               branches=branches, limits=limits, source=source)
    if check_home:
        _check_home_reachable(p)
    return p


def _check_home_reachable(p: Params) -> None:
    # Closed-form IK (docs/model.md §7) at the home pose; it raises with the chain and the
    # shortfall.
    from ..analytic.closed_form import UnreachableError, position_ik
    from ..analytic.taskspace import TaskInputError

    pose = "[" + ", ".join(f"{x:.4g}" for x in p.home_pose) + "]"
    try:
        position_ik(p, np.asarray(p.home_pose, dtype=float)[None, :])
    except TaskInputError as exc:  # e.g. an absurd angle: one line, not the solver's error
        raise ParameterError(f"home pose {pose} (home.tip, home.orientation): "
                             f"{exc.detail}") from None
    except UnreachableError as exc:
        raise ParameterError(f"home pose {pose} (home.tip, home.orientation) "
                             "is unreachable with these parameters: "
                             f"{str(exc).replace(' at sample 0', '')}") from None


def did_you_mean(word: str, choices) -> str:
    """`` (did you mean 'x'?)`` for the closest of ``choices`` to a misspelt ``word``, or ""."""
    import difflib

    # str(): a key built in Python may be any object (1, None); a file's is always a str
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def read_params_dict(path: str | Path | None = None) -> dict:
    """The raw thesis-unit dictionary of a parameter file (default: the shipped one), as
    written: a partial file gives a partial dictionary (see :func:`merge_partial`)."""
    path = (file_path(path, "path", error=ParameterError) if path is not None
            else models_dir() / DEFAULT_PARAMS)
    return read_toml(path, "parameter file", ParameterError)


def merge_partial(base: Mapping, partial: Mapping, prefix: str = "") -> dict:
    """``base`` (a complete thesis-unit dictionary) with the values of ``partial`` put in.

    A parameter file may list only what differs from the shipped one; a key or section that
    the base does not have is an error (a typo must not pass silently)."""
    if not isinstance(partial, Mapping):
        _fail(prefix, partial, "must be a table")
    out = copy.deepcopy(dict(base))
    for k, v in partial.items():
        key = f"{prefix}.{k}" if prefix else k
        if k not in out:
            _fail(key, v, f"unknown key (expected keys: {', '.join(out)})")
        out[k] = merge_partial(out[k], v, key) if isinstance(out[k], Mapping) else v
    return out


def load_params(path: str | Path | None = None, overrides: Mapping[str, Any] | None = None,
                check_home: bool = True) -> Params:
    """Load and validate parameters: the shipped file, with the keys of the file ``path``
    (which may list only some parameters) and then ``overrides`` put in.

    Parameters
    ----------
    path : str or pathlib.Path or None, optional
        A parameter TOML in the format of ``models/pollard.toml`` (thesis units: m, deg, kg,
        kg·mm²); it may list only the keys that differ. None: the shipped values alone.
    overrides : Mapping or None, optional
        Dotted keys in thesis units to values, applied last, e.g.
        ``{"chain0.x32": 0.34, "bodies.gun.mass": 0.05, "home.tip[2]": 0.2}``
        (``key[i]`` is one component of a vector parameter).
    check_home : bool, optional
        Check that the home pose is reachable on the assembly branches (default True).

    Returns
    -------
    Params
        The validated numbers, converted to SI units.

    Raises
    ------
    ParameterError
        An unknown key, a value that is not finite or breaks its rule (a non-positive length
        or mass, an inertia that is not physical, an unreachable home pose); the message
        names the key, the value and the rule.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> p = pp.load_params(overrides={"chain0.x32": 0.34})
    >>> p.x32, p.source
    (0.34, 'pollard.toml')
    >>> pp.load_params(overrides={"chain0.x32": -1.0})
    Traceback (most recent call last):
    ...
    pollard_pin.model.overrides.ParameterError: ...
    """
    d = read_params_dict()
    if path is not None:  # a partial file overrides the shipped values
        d = merge_partial(d, read_params_dict(path))
    d = apply_overrides(d, overrides or {})
    src = str(path) if path is not None else DEFAULT_PARAMS
    return params_from_dict(d, source=src, check_home=check_home)


def replace(p: Params, overrides: Mapping[str, Any]) -> Params:
    """A new validated :class:`Params` with thesis-unit dotted-key overrides applied."""
    d = apply_overrides(p.to_toml_dict(), overrides)
    return params_from_dict(d, source=p.source + " (modified)")


__all__ = ["Params", "Leg", "Body", "JointLimits", "ParameterError", "load_params",
           "params_from_dict", "read_params_dict", "replace"]
