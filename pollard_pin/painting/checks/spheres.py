"""Spheres along capsules' axes, their centres made only where they are asked
(docs/model.md §26.4): a part check's second stage would make 10⁷ of them and ask a few 10⁴."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...kinematics.capsules import axis_spheres
from ..spray.gun_body import AXIS_STEP


@dataclass(frozen=True, eq=False)
class CapsuleSpheres:
    """The centres (N, S, 3) of the spheres holding some capsules (ends ``a``, ``b``
    (N, L, 3)), made where they are asked (:func:`.clearance.least_distance` takes them
    so): sphere s on capsule ``cap[s]`` at ``frac[s]`` along it, a + frac·(b − a), the same
    operations on the same numbers wherever they are made (the same bits as the whole
    array; a part check's second stage would make 10⁷ of them and ask a few 10⁴)."""

    a: np.ndarray
    b: np.ndarray
    cap: np.ndarray  # (S,) each sphere's capsule
    frac: np.ndarray  # (S,)
    radii: np.ndarray  # (S,)

    @classmethod
    def of(cls, a, b, layout, caps: np.ndarray) -> CapsuleSpheres:
        owner, frac, radii = axis_spheres(layout.a[caps], layout.b[caps], layout.r[caps],
                                          AXIS_STEP)
        return cls(a, b, caps[owner], frac, radii)

    @property
    def shape(self) -> tuple[int, int, int]:
        return (len(self.a), len(self.cap), 3)

    def __len__(self) -> int:
        return len(self.a)

    def __getitem__(self, key) -> np.ndarray:
        if isinstance(key, slice):  # samples: every sphere, capsule by capsule
            a, b = self.a[key], self.b[key]
            out = np.empty((len(a), len(self.cap), 3))
            for c in np.unique(self.cap):
                k = np.flatnonzero(self.cap == c)
                these = out[:, k[0]:k[-1] + 1]  # a capsule's spheres are consecutive
                np.multiply(self.frac[k][None, :, None], (b[:, c] - a[:, c])[:, None],
                            out=these)
                np.add(a[:, c, None], these, out=these)
            return out
        n, k = key  # samples and spheres (arrays, or one sphere)
        c = self.cap[k]
        f = self.frac[k]
        start = self.a[n, c]
        return start + (f if np.ndim(f) == 0 else f[:, None]) * (self.b[n, c] - start)


__all__ = ["CapsuleSpheres"]
