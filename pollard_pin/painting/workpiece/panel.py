"""The panel (docs/model.md §21): its frame, centre, normal towards the robot and in-plane
axes, from a job's [panel]."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..job import PaintJob


@dataclass(frozen=True)
class PanelFrame:
    """The panel: centre ``c``, unit normal ``n`` (towards the robot), in-plane unit axes
    ``u`` (width, = n × v) and ``v`` (height: world z projected on the plane), sizes [m]."""

    c: np.ndarray
    n: np.ndarray
    u: np.ndarray
    v: np.ndarray
    width: float
    height: float

    @property
    def rotation(self) -> np.ndarray:
        """The tool orientation spraying along −n: R = [−n, u, v] (a proper rotation:
        (−n) × u = v), so the tool's x (spray) axis is a = −n."""
        return np.column_stack([-self.n, self.u, self.v])

    def world(self, U, V, offset: float = 0.0) -> np.ndarray:
        """World points c + U u + V v + offset·n, for arrays U, V → (..., 3)."""
        U, V = np.asarray(U, dtype=float), np.asarray(V, dtype=float)
        return (self.c + U[..., None] * self.u + V[..., None] * self.v
                + offset * self.n)


def panel_frame(job: PaintJob) -> PanelFrame:
    """The job's panel frame: v the world z projected on the plane, u = n × v."""
    n = np.asarray(job.normal, dtype=float)
    n = n / np.linalg.norm(n)
    ez = np.array([0.0, 0.0, 1.0])
    v = ez - (ez @ n) * n
    v /= np.linalg.norm(v)
    u = np.array([n[1] * v[2] - n[2] * v[1], n[2] * v[0] - n[0] * v[2],
                  n[0] * v[1] - n[1] * v[0]])
    return PanelFrame(np.asarray(job.center, dtype=float), n, u, v, job.width, job.height)


__all__ = ["PanelFrame", "panel_frame"]
