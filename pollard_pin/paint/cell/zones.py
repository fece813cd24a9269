"""A cell's split of the part into zones, one per robot (docs/model.md §26.2): the types the
planner (programs, film) and the split share."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Zone:
    """The part's stretch [lo, hi] along :attr:`Split.axis` a robot paints."""

    robot: str                 # the robot's name
    # m along Split.axis, the part's frame at t = 0 (world coordinates); -inf: a free edge
    lo: float
    hi: float                  # +inf: a free edge
    facing: tuple[float, float, float] | None = None   # world; None: the job's facing


@dataclass(frozen=True)
class Split:
    """The zones of a cell, stacked along ``axis``, each robot's strokes running ``runout``
    on past its seams, gun off."""

    axis: tuple[float, float, float]   # world unit vector across the travel
    # sorted by (facing, lo); neighbours share a seam: hi_i == lo_{i+1}
    zones: tuple[Zone, ...]
    runout: float                      # m, R


__all__ = ["Split", "Zone"]
