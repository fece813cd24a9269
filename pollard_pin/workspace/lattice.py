"""The regular grid of a workspace map (docs/model.md §22): :class:`Grid`, the plane and
bounds a user asks for, checked (:func:`parse_plane`, :func:`check_bounds`), the ball that
holds the reach (:func:`reach_sphere`), and :func:`make_grid`, which covers it within the
memory and time budgets."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..analytic.taskspace import rotation
from .options import WorkspaceError, finite_value

AXES = ("x", "y", "z")
# A plane map is kept in memory (its columns, for the table, the figure and the rectangle):
# about BYTES_PER_POINT each, within MEMORY_BUDGET. A volume streams, but its point count is
# capped (MAX_VOLUME_POINTS: about an hour at 15 µs per point, some 30 GB of CSV).
BYTES_PER_POINT = 200
MEMORY_BUDGET = 2 * 1024 ** 3
MAX_VOLUME_POINTS = 200_000_000
COORD_DECIMALS = 10  # grid coordinates rounded to 0.1 nm [m]
BOUND_MARGIN_CELLS = 2  # default bounds: the reach sphere widened by this many cells


@dataclass(frozen=True)
class Grid:
    """A regular grid: ``origin`` (3,) [m], ``step`` [m], ``axes`` (indices of the varying
    coordinates among x, y, z) and ``shape`` (points along each, C order: the last varies
    fastest). A plane fixes the other coordinate at origin's value."""

    origin: tuple[float, float, float]
    step: float
    axes: tuple[int, ...]
    shape: tuple[int, ...]

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def cell(self) -> float:
        """Area (plane) or volume of one cell [m² or m³]."""
        return self.step ** len(self.axes)

    def coordinates(self, axis: int) -> np.ndarray:
        """The grid values along varying axis ``axis`` (index into ``axes``)."""
        a = self.axes[axis]
        return self.origin[a] + self.step * np.arange(self.shape[axis])

    def points(self, flat: np.ndarray) -> np.ndarray:
        """(n, 3) positions of the points with flat indices ``flat`` (C order)."""
        pts = np.tile(np.asarray(self.origin, dtype=float), (len(flat), 1))
        for i, k in zip(self.axes, np.unravel_index(flat, self.shape)):
            pts[:, i] += self.step * k
        return np.round(pts, COORD_DECIMALS)  # 0.1 nm: no 0.30000000000000004 in the outputs

    def as_dict(self) -> dict:
        fixed = [a for a in range(3) if a not in self.axes]
        return {"axes": [AXES[a] for a in self.axes], "shape": list(self.shape),
                "step": self.step, "points": self.size,
                "start": [self.origin[a] for a in self.axes],
                "stop": [self.origin[a] + self.step * (n - 1)
                         for a, n in zip(self.axes, self.shape)],
                **({"plane": {AXES[fixed[0]]: self.origin[fixed[0]]}} if fixed else {})}


# --- inputs -------------------------------------------------------------------------------------
def parse_plane(plane) -> tuple[int, float]:
    """"x=0.55" or ("x", 0.55) → (axis index, value [m])."""
    if isinstance(plane, str):
        axis, sep, value = plane.partition("=")
        if not sep:
            raise WorkspaceError(f"plane {plane!r}: expected AXIS=VALUE, e.g. x=0.55")
    else:
        try:
            axis, value = plane
        except (TypeError, ValueError):
            raise WorkspaceError(f"plane {plane!r}: expected AXIS=VALUE, e.g. x=0.55") from None
    axis = str(axis).strip().lower()
    if axis not in AXES:
        raise WorkspaceError(f"plane {plane!r}: the axis must be x, y or z, got {axis!r}")
    # any finite value: one far off misses the robot, and that error names the reachable box
    return AXES.index(axis), finite_value(value, f"plane {axis}", "m", math.inf)


def check_bounds(bounds) -> dict:
    """{axis: (low, high)} [m] with low < high, axes among x, y, z."""
    if bounds is None:
        return {}
    if not isinstance(bounds, Mapping):
        raise WorkspaceError(f"bounds {bounds!r}: expected {{axis: (low, high)}} in m")
    out = {}
    for axis, pair in bounds.items():
        a = str(axis).strip().lower()
        if a not in AXES:
            raise WorkspaceError(f"bounds: axis {axis!r} must be x, y or z")
        try:
            lo, hi = pair
        except (TypeError, ValueError):
            raise WorkspaceError(f"bounds of {a}: expected (low, high) in m, got "
                                 f"{pair!r}") from None
        lo = finite_value(lo, f"lower bound of {a}", "m")
        hi = finite_value(hi, f"upper bound of {a}", "m")
        if not lo < hi:
            raise WorkspaceError(f"bounds of {a}: the lower bound {lo:g} m must be below the "
                                 f"upper bound {hi:g} m")
        out[a] = (lo, hi)
    return out


def reach_sphere(params, orientation) -> tuple[np.ndarray, float]:
    """(centre (3,), radius) [m] of a ball holding every reachable tip position at this
    orientation: the wrist centre lies within x32 + (x65 + x1514) of chain 0's base joint
    (0, 0, z10), and the tip x1918 beyond it along the spray axis R·e_x (docs/model.md §2)."""
    R = rotation(np.array([0.0, 0.0, 0.0, *orientation]))
    centre = np.array([0.0, 0.0, params.z10]) + params.x1918 * R[:, 0]
    return centre, params.x32 + params.x65 + params.x1514


def make_grid(params, orientation, resolution, plane=None, bounds=None) -> Grid:
    """The grid of a plane (``(axis, value)``) or, with ``plane`` None, of a box: ``bounds``
    where given, else the reach sphere widened by BOUND_MARGIN_CELLS cells, snapped outward
    to multiples of the resolution (so that finer grids of step h/k contain the coarser)."""
    h = finite_value(resolution, "resolution", "m")
    if not h > 0:
        raise WorkspaceError(f"resolution = {resolution!r} m must be > 0")
    bounds = check_bounds(bounds)
    centre, radius = reach_sphere(params, orientation)
    axes = tuple(a for a in range(3) if plane is None or a != plane[0])
    origin = [0.0, 0.0, 0.0]
    if plane is not None:
        origin[plane[0]] = plane[1]
        if AXES[plane[0]] in bounds:
            raise WorkspaceError(f"bounds: the plane fixes {AXES[plane[0]]} = {plane[1]:g} m; "
                                 "give bounds for the other two axes only")
    spans, cells = [], []
    for a in axes:
        if AXES[a] in bounds:
            lo, hi = bounds[AXES[a]]
        else:
            pad = radius + BOUND_MARGIN_CELLS * h
            lo, hi = centre[a] - pad, centre[a] + pad
        spans.append(hi - lo)
        # The budget first, in floats: 1e-300 m asks for 1e300 points per axis (no integer).
        with np.errstate(over="ignore"):
            if AXES[a] not in bounds:  # snapped outward to multiples of the resolution
                lo = float(np.floor(lo / h)) * h
                hi = float(np.ceil(hi / h)) * h
            cells.append(float(np.floor((hi - lo) / h * (1 + 1e-12))) + 1)
        origin[a] = lo
    size = math.prod(cells)
    limit = MAX_VOLUME_POINTS if plane is None else MEMORY_BUDGET // BYTES_PER_POINT
    if not size <= limit:
        need = (f"{size * BYTES_PER_POINT / 2 ** 30:.3g} GiB of memory (budget "
                f"{MEMORY_BUDGET / 2 ** 30:.3g} GiB)" if plane is not None else
                f"about {size * 15e-6 / 3600:.3g} h and {size * 150 / 1e9:.3g} GB of "
                f"CSV (limit {MAX_VOLUME_POINTS:.3g} points)")
        coarser = 1.05 * (math.prod(spans) / limit) ** (1.0 / len(axes))
        if not math.isfinite(size):
            need = "more than any machine has"
        raise WorkspaceError(
            f"resolution = {h:.4g} m gives a grid of {min(size, 1e308):.4g} points (budget "
            f"{limit:.4g}), which would need {need}; use a resolution of at least "
            f"{coarser:.3g} m or narrower bounds")
    shape = [int(c) for c in cells]
    return Grid(tuple(origin), h, axes, tuple(shape))


__all__ = ["AXES", "BOUND_MARGIN_CELLS", "BYTES_PER_POINT", "COORD_DECIMALS", "MAX_VOLUME_POINTS",
           "MEMORY_BUDGET", "Grid", "check_bounds", "make_grid", "parse_plane", "reach_sphere"]
