"""The zones of a paint cell and the seams between them (docs/model.md §26.3).

Every robot runs the same strokes of the whole part, planned relative to the part across the
travel: the same offsets along the travel, pass speed and spacing. The part is split along
the across-travel ``axis`` into zones; robot i paints [lo_i, hi_i]. Its strokes are the shared
ones clipped to [lo_i − R, hi_i + R] (R the constant-speed run-on, :func:`seam_runout`; at a
free edge the planner's own run-on), turnarounds beyond; its trigger is open only while the
aim point lies within [lo_i, hi_i]. The film is linear in the trigger's time intervals, so
two robots whose triggers switch at the same point of the same constant-speed stroke lay
down exactly what one unbroken stroke would (§26.3).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import PlanError
from ..line.phases import Relative
from ..passes.raster import SPOT_RADIUS, spot_runon
from ..passes.surface import EXTENSION

OPEN = (-math.inf, math.inf)  # a piece's trigger window open throughout
CLOSED = (math.inf, -math.inf)  # ... shut throughout


@dataclass(frozen=True)
class Zone:
    """The band a robot paints (docs/model.md §26.2).

    Attributes
    ----------
    robot : str
        The robot's name.
    lo, hi : float
        The band's limits [m] along ``Split.axis`` (the part at t = 0, world coordinates;
        ∓inf: a free edge of the part), lo < hi.
    facing : tuple of float or None
        The faces painted look along this world direction (None: the job's).

    Raises
    ------
    PlanError
        An empty band (lo ≥ hi).
    """

    robot: str
    lo: float
    hi: float
    facing: tuple[float, float, float] | None = None

    def __post_init__(self):
        if not self.lo < self.hi:
            raise PlanError(f"robot {self.robot!r}: its zone {self.lo:.4g}..{self.hi:.4g} m "
                            "is empty")


@dataclass(frozen=True)
class Split:
    """Which robot paints which band of the part (docs/model.md §26.2).

    Attributes
    ----------
    axis : tuple of float
        The world unit vector across the travel along which the zones lie.
    zones : tuple of Zone
        Sorted by (facing, lo); neighbours share a seam (hi_i == lo_{i+1}).
    runout : float
        The run-on R [m] of a robot's strokes past a seam (§26.3).
    """

    axis: tuple[float, float, float]
    zones: tuple[Zone, ...]
    runout: float

    def zone_of(self, name: str) -> Zone:
        for z in self.zones:
            if z.robot == name:
                return z
        raise PlanError(f"robot {name!r} has no zone in the split")

    def seams(self) -> list[float]:
        """The finite zone limits that two zones share [m along the axis]."""
        his = {z.hi for z in self.zones if math.isfinite(z.hi)}
        return sorted(h for h in his if any(z.lo == h for z in self.zones))

    def to_dict(self, name: str) -> dict:
        z = self.zone_of(name)
        return {"lo": None if math.isinf(z.lo) else z.lo,
                "hi": None if math.isinf(z.hi) else z.hi, "axis": list(self.axis),
                "facing": None if z.facing is None else list(z.facing),
                "runout": self.runout}


def seam_runout(job) -> float:
    """R [m]: the run-on past a seam, the planner's free-edge rule (a panel's SPOT_RADIUS σ,
    a part's EXTENSION σ, within a finite spot's reach: :func:`.passes.raster.spot_runon`), so a
    seam is crossed as an edge is."""
    from ..job import PartJob

    return spot_runon(job.sigma, job.spot, EXTENSION if isinstance(job, PartJob) else SPOT_RADIUS)


def past_seam(runout: float, seam_run: float | None) -> float:
    """The run [m] a robot's strokes make past a seam: the planner's ``seam_run``
    (``PlannerPolicy.seam_run``) if set, else R = ``runout`` (docs/model.md §26.5): what a
    split, a layout and a seating hold in reach and a robot's program runs."""
    return runout if seam_run is None else seam_run


def window(lo: float, hi: float, start: float, rate: float, duration: float) -> tuple:
    """The local times [τ0, τ1] ⊂ [0, duration] at which a coordinate start + rate·τ lies
    within [lo, hi] (∓inf allowed); CLOSED if never."""
    with np.errstate(invalid="ignore"):
        a, b = sorted(((lo - start) / rate, (hi - start) / rate))
    a, b = max(a, 0.0), min(b, duration)
    if a > b:
        return CLOSED
    return (-math.inf if a == 0.0 else a, math.inf if b == duration else b)


@dataclass(frozen=True, eq=False)
class ZoneRelative(Relative):
    """A relative program whose trigger is open in each piece's window [τ0, τ1] (local
    times, ±inf: from its start or to its end) and shut elsewhere (docs/model.md §26.3)."""

    windows: tuple = ()

    def trigger(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        i = np.clip(np.searchsorted(self.start, t, side="right") - 1, 0, len(self.start) - 1)
        w = np.array(self.windows, dtype=float).reshape(-1, 2)
        tau = t - self.start[i]
        return ((tau >= w[i, 0]) & (tau <= w[i, 1])).astype(float)

    def seam_times(self) -> np.ndarray:
        """The program times at which the trigger switches inside a piece: the seams."""
        out = [s + x for s, (a, b) in zip(self.start, self.windows) for x in (a, b)
               if math.isfinite(x) and a <= b]
        return np.array(sorted(out))


def seam_fractions(t, spray, seams, tol: float = 1e-9) -> np.ndarray:
    """The trigger at the samples ``t`` with the seam instants among them: at a seam sample
    the fraction h_on/(h_before + h_after) of its trapezoid weight that falls on the open
    side, so that the trapezoid rule over the samples integrates a trigger switching exactly
    there (docs/model.md §26.3)."""
    s = np.array(spray, dtype=float)
    for ts in seams:
        k = int(np.argmin(np.abs(t - ts)))
        if not (0 < k < len(t) - 1) or abs(t[k] - ts) > tol:
            continue
        before, after = s[k - 1] > 0, s[k + 1] > 0
        h1, h2 = t[k] - t[k - 1], t[k + 1] - t[k]
        if before and not after:
            s[k] = h1 / (h1 + h2)
        elif after and not before:
            s[k] = h2 / (h1 + h2)
    return s


def with_samples(t, extra, tol: float) -> np.ndarray:
    """The times ``t`` with ``extra`` among them: a sample within ``tol`` of one is moved
    onto it, else it is inserted."""
    t = np.array(t, dtype=float)
    extra = np.asarray(extra, dtype=float)
    add = []
    for x in extra:
        k = int(np.argmin(np.abs(t - x)))
        if abs(t[k] - x) <= tol and 0 < k < len(t) - 1:
            t[k] = x
        else:
            add.append(x)
    return np.unique(np.concatenate([t, add]))


__all__ = ["CLOSED", "OPEN", "Split", "Zone", "ZoneRelative", "seam_fractions",
           "past_seam", "seam_runout", "window", "with_samples"]
