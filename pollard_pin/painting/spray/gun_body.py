"""The gun's body for the clearance check (docs/model.md §25): two capsules along the spray
axis behind the tool tip, each holding a part of the model's gun link (model/urdf.py): the
nozzle (a cylinder of radius ``nozzle_radius`` over ``nozzle_length`` behind the tip) and the
gun's body (a box of section b × c over ``length`` behind the nozzle, held by a cylinder of
radius √(b² + c²)/2).

A capsule is the set of points within its radius of its axis segment, so it holds its
cylinder; the check measures a union of spheres on the capsules' axes that holds them
(:meth:`GunBody.axis_points`): the front sphere, centred on the tip, reaches its radius
√(r² + (h/2)²) ahead of it (a gun normal to a flat part at standoff s is s minus that from
it: 150 − 4.386 = 145.614 mm with the defaults).
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ...model.urdf import GUN_BOX_SECTION, GUN_BOX_SHARE, NOZZLE_RADIUS

AXIS_STEP = 0.02  # m: the capsules' axes are sampled at most this far apart (and ≤ r)
CLEARANCE = 0.010  # m: the default least distance between the gun's body and the part


@dataclass(frozen=True)
class GunBody:
    """The gun's body as two capsules behind the tip along the spray axis [m] (module
    notes); ``step`` the largest spacing of the spheres' centres on their axes."""

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
        """(offsets (K,) behind the tip along the axis [m], radii (K,) [m]): the centres and
        radii of the spheres whose union holds both capsules. Each capsule's axis is
        sampled at spacing h ≤ min(step, its radius), ends included; a sphere of radius
        √(r² + (h/2)²) there holds the capsule's slice within h/2 of its centre."""
        offs, radii = [], []
        for a, b, r in ((0.0, self.nozzle_length, self.nozzle_radius),
                        (self.nozzle_length, self.nozzle_length + self.length, self.radius)):
            n = max(2, math.ceil((b - a) / min(self.step, r if r > 0 else self.step)) + 1)
            offs.append(np.linspace(a, b, n))
            radii.append(np.full(n, math.hypot(r, (b - a) / (n - 1) / 2)))
        return np.concatenate(offs), np.concatenate(radii)

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
