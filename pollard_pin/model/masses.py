"""The mass model of a design (docs/model.md §29.1): each link's mass, centre of gravity and
inertia follow from its length, and the motors a link carries add theirs.

A link of the reference design (``models/pollard.toml``) stretched along its own x axis by
s = L/L_ref keeps its section and density: its mass grows as s, its centre of gravity's x as
s, and its central second moments P = ∫ r rᵀ dm as P = s·S P_ref S, S = diag(s, 1, 1), so that
I = tr(P)·1 − P. At s = 1 it is the reference body exactly; the law keeps an inertia physical
(P stays positive semidefinite). A motor on a link is a solid sphere of :data:`MOTOR_DENSITY`
at its place (:data:`MOTOR_PLACES`), put in by the parallel-axis theorem.
"""
from __future__ import annotations

import copy
import math
from collections.abc import Mapping

import numpy as np

from .overrides import ParameterError, lookup

# The length each link is stretched with, dotted keys summed (docs/model.md §29.1).
LINK_LENGTHS = {
    "arm0": ("chain0.x32",),
    "platform": ("chain0.x65", "chain0.x1514"),
    "arm_1": ("leg1.x43",), "arm_2": ("leg2.x43",),
    "link_1": ("leg1.x87",), "link_2": ("leg2.x87",),
}
# The arms' drop z32 moves their centre of gravity down with it (com z = −z32 today).
DROPS = {"arm_1": "leg1.z32", "arm_2": "leg2.z32"}
# The gun keeps its mass and inertia (it is the painter's tool); its centre of gravity sits
# half way along x1918 as today.
TOOL_LENGTH = ("gun", "chain0.x1918")
# Where each actuator's motor sits: None on the base (its stator does not move; only its
# rotor's inertia counts, through the gear: docs/model.md §19), else (body, key of the
# distance along the body's x axis). The wrist's three motors ride on the platform at the
# spherical-joint station, x65 from the U joint.
MOTOR_PLACES = {"theta21": None, "theta21_1": None, "theta21_2": None,
                "theta1615": ("platform", "chain0.x65"), "theta1716": ("platform", "chain0.x65"),
                "theta1817": ("platform", "chain0.x65")}
MOTOR_DENSITY = 5000.0  # kg/m³: a motor with its gearbox (steel, copper, aluminium, air)
# Equivalent aluminium tube section of each link at today's mass per length, for the docs
ALUMINIUM = 2700.0  # kg/m³


def _length(d: Mapping, keys) -> float:
    return float(sum(lookup(d, k) for k in keys))


def stretched(mass: float, com, inertia, s: float) -> tuple[float, np.ndarray, np.ndarray]:
    """A body (mass [kg], centre of gravity [m], central inertia, any unit) stretched by
    ``s`` along its x axis, section and density kept: (mass, com, inertia)."""
    if not (math.isfinite(s) and s > 0):
        raise ParameterError(f"mass model: stretch {s!r} must be a positive number")
    inertia = np.asarray(inertia, dtype=float)
    P = np.trace(inertia) / 2 * np.eye(3) - inertia  # central second moments ∫ r rᵀ dm
    S = np.diag([s, 1.0, 1.0])
    P = s * S @ P @ S
    com = np.asarray(com, dtype=float) * np.array([s, 1.0, 1.0])
    return mass * s, com, np.trace(P) * np.eye(3) - P


def sphere_inertia(mass: float, density: float = MOTOR_DENSITY) -> float:
    """2/5 m r² of a solid sphere of ``mass`` [kg] and ``density`` [kg/m³], kg·m²."""
    r = (3.0 * mass / (4.0 * math.pi * density)) ** (1.0 / 3.0)
    return 0.4 * mass * r * r


def with_points(mass: float, com, inertia, points) -> tuple[float, np.ndarray, np.ndarray]:
    """A body (SI) with point-like solids ``(mass, position, own inertia [kg·m²])`` added
    (parallel-axis theorem): (mass, com, central inertia)."""
    items = [(mass, np.asarray(com, float), np.asarray(inertia, float))]
    items += [(m, np.asarray(p, float), j * np.eye(3)) for m, p, j in points]
    total = sum(m for m, _, _ in items)
    c = sum(m * p for m, p, _ in items) / total
    out = np.zeros((3, 3))
    for m, p, j in items:
        r = p - c
        out += j + m * (r @ r * np.eye(3) - np.outer(r, r))
    return total, c, out


def _si(b: Mapping) -> np.ndarray:
    return np.array(b["inertia"], float) * 1e-6


def design_bodies(reference: Mapping, design: Mapping,
                  motors: Mapping[str, float] | None = None) -> dict:
    """The ``bodies`` table (thesis units: kg, m, kg·mm²) of ``design`` under the mass model.

    Parameters
    ----------
    reference : Mapping
        The thesis-unit dictionary whose bodies go with its lengths (``models/pollard.toml``).
    design : Mapping
        The design's thesis-unit dictionary (its lengths; its bodies are not read).
    motors : Mapping or None, optional
        Actuator joint → its motor's mass [kg] (with the gearbox), placed by
        :data:`MOTOR_PLACES` (default none: the links alone).

    Returns
    -------
    dict
        ``{body: {"mass", "com", "inertia"}}`` for every body of the reference.
    """
    bodies = copy.deepcopy(dict(reference["bodies"]))
    carried: dict[str, list] = {}
    for joint, m in (motors or {}).items():
        if joint not in MOTOR_PLACES:
            raise ParameterError(f"mass model: {joint!r} is not an actuator")
        place = MOTOR_PLACES[joint]
        if place is not None and m > 0:
            body, key = place
            carried.setdefault(body, []).append(
                (float(m), np.array([lookup(design, key), 0.0, 0.0]), sphere_inertia(m)))
    out = {}
    for name, b in bodies.items():
        mass, com = float(b["mass"]), np.array(b["com"], float)
        inertia = None  # None: the reference's, as written
        if name in LINK_LENGTHS:
            s = _length(design, LINK_LENGTHS[name]) / _length(reference, LINK_LENGTHS[name])
            if s != 1.0:  # today's body exactly, not through P's round-off
                mass, com, inertia = stretched(mass, com, _si(b), s)
        if name in DROPS:
            com[2] = com[2] * lookup(design, DROPS[name]) / lookup(reference, DROPS[name])
        if name == TOOL_LENGTH[0]:
            k = TOOL_LENGTH[1]
            com[0] = com[0] * lookup(design, k) / lookup(reference, k)
        if name in carried:
            mass, com, inertia = with_points(mass, com, _si(b) if inertia is None else inertia,
                                             carried[name])
        out[name] = {"mass": mass, "com": [float(c) for c in com],
                     "inertia": [[float(x) for x in row] for row in b["inertia"]]
                     if inertia is None else ((inertia + inertia.T) / 2 * 1e6).tolist()}
    return out


def link_sections(reference: Mapping) -> dict[str, float]:
    """Each link's equivalent aluminium section [mm²] at the reference's mass per length."""
    return {name: float(reference["bodies"][name]["mass"]) / _length(reference, keys)
            / ALUMINIUM * 1e6 for name, keys in LINK_LENGTHS.items()}


__all__ = ["DROPS", "LINK_LENGTHS", "MOTOR_DENSITY", "MOTOR_PLACES", "TOOL_LENGTH",
           "design_bodies", "link_sections", "sphere_inertia", "stretched", "with_points"]
