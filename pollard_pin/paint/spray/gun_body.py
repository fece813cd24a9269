"""The gun's body for the clearance check (docs/model.md §25): two capsules along the spray
axis behind the tool tip, each holding a part of the model's gun link (model/urdf.py): the
nozzle (a cylinder of radius ``nozzle_radius`` over ``nozzle_length`` behind the tip) and the
gun's body (a box of section b × c over ``length`` behind the nozzle, held by a cylinder of
radius √(b² + c²)/2).

A capsule is the set of points within its radius of its axis segment, so it holds its
cylinder and reaches its radius past each end: the nozzle's capsule reaches ``nozzle_radius``
ahead of the tip (a gun normal to a flat part at standoff h is h − nozzle_radius from it).
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ...model.urdf import GUN_BOX_SECTION, GUN_BOX_SHARE, NOZZLE_RADIUS

AXIS_STEP = 0.005  # m: the capsules' axes are sampled at most this far apart
CLEARANCE = 0.010  # m: the default least distance between the gun's body and the part


@dataclass(frozen=True)
class GunBody:
    """The gun's body as two capsules behind the tip along the spray axis [m] (module
    notes); ``step`` the largest spacing of the points sampled on their axes."""

    nozzle_radius: float = NOZZLE_RADIUS
    nozzle_length: float = (1 - GUN_BOX_SHARE) * 0.06
    radius: float = math.hypot(*GUN_BOX_SECTION) / 2
    length: float = GUN_BOX_SHARE * 0.06
    step: float = AXIS_STEP

    def __post_init__(self):
        for name in ("nozzle_radius", "nozzle_length", "radius", "length", "step"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, numbers.Real) or not (
                    math.isfinite(v) and 0 <= v <= 1.0) or (name == "step" and v == 0):
                raise InputError(f"GunBody.{name} = {v!r}: expected a length in [0, 1] m"
                                 + (", > 0" if name == "step" else ""))

    def axis_points(self) -> tuple[np.ndarray, np.ndarray]:
        """(offsets (K,) behind the tip along the axis [m], radii (K,) [m]): both capsules'
        axes sampled at most ``step`` apart, their ends included."""
        offs, radii = [], []
        for a, b, r in ((0.0, self.nozzle_length, self.nozzle_radius),
                        (self.nozzle_length, self.nozzle_length + self.length, self.radius)):
            n = max(2, math.ceil((b - a) / self.step) + 1)
            offs.append(np.linspace(a, b, n))
            radii.append(np.full(n, r))
        return np.concatenate(offs), np.concatenate(radii)

    @property
    def axis_gap(self) -> float:
        """Half the largest spacing of :meth:`axis_points` [m]: every point of a capsule's
        axis lies within it of a sampled one."""
        offs, _ = self.axis_points()
        return float(np.diff(offs).max() / 2)

    @property
    def reach(self) -> float:
        """How far the body extends behind the tip [m] (the far capsule's axis end)."""
        return self.nozzle_length + self.length


def gun_body(params=None) -> GunBody:
    """The gun's body of a model's parameters (its tip distance x1918; None: the shipped
    model's 0.06 m), the capsules holding the gun link of model/urdf.py."""
    x = 0.06 if params is None else float(params.x1918)
    return GunBody(nozzle_length=(1 - GUN_BOX_SHARE) * x, length=GUN_BOX_SHARE * x)


__all__ = ["AXIS_STEP", "CLEARANCE", "GunBody", "gun_body"]
