"""Constant-orientation workspace and dexterity maps (docs/model.md §22): which tool positions
of a plane or a box the robot reaches at a fixed tool orientation, under the rules of ``run``,
how well-conditioned and how strong it is there, and the largest reachable panel of a plane.

    ws = pollard_pin.map_workspace(robot, plane="x=0.55")       # or volume=True
    ws.summary["area"], ws.rectangle, ws.columns["conditioning"]

Points are evaluated in chunks, stacked (:func:`.reach.evaluate`); in volume mode the chunks
can stream to a ``sink`` so that memory stays bounded.
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..checks import callback
from ..errors import say_less, without_asides
from ..model.build import check_robot
from .lattice import AXES, COORD_DECIMALS, Grid, make_grid, parse_plane, reach_sphere
from .options import (
    CHUNK,
    WorkspaceError,
    WorkspaceOptions,
)
from .reach import REASONS, STIFFNESS_COLUMNS, ReachOptions, evaluate, length_scale
from .rectangle import boundary_points, edge_samples, largest_rectangle

COARSE_CELLS = 40  # points per axis of the coarse volume that finds the reachable box
# The largest rectangle's edges are re-checked at this many samples per grid step; a failing
# sample removes its grid neighbours and the search runs again, at most EDGE_ROUNDS times.
EDGE_REFINE = 4
EDGE_ROUNDS = 16


@dataclass(frozen=True)
class Rectangle:
    """The largest axis-aligned rectangle of reachable points of a plane map: ``axes`` (its two
    coordinates), ``size`` [m] along them ((points − 1) × step: from corner point to corner
    point, every edge re-checked at EDGE_REFINE× the grid's sampling), ``centre`` (x, y, z)
    [m], ``points`` along each axis, and its corner points ``low`` and ``high`` (x, y, z) [m],
    reachable (docs/model.md §22)."""

    axes: tuple[str, str]
    size: tuple[float, float]
    centre: tuple[float, float, float]
    points: tuple[int, int]
    low: tuple[float, float, float]
    high: tuple[float, float, float]

    @property
    def area(self) -> float:
        return self.size[0] * self.size[1]

    def as_dict(self) -> dict:
        return {"axes": list(self.axes), "size": list(self.size), "area": self.area,
                "centre": list(self.centre), "points": list(self.points),
                "low": list(self.low), "high": list(self.high)}


@dataclass
class WorkspaceMap:
    """A workspace map (:func:`~pollard_pin.map_workspace`, docs/model.md §22).

    Attributes
    ----------
    grid : pollard_pin.workspace.lattice.Grid
        The regular grid: origin [m], step [m], varying axes and shape.
    orientation : tuple of float
        The tool orientation (ψ, θ, φ) [rad].
    columns : dict or None
        Per-point columns (x, y, z, psi, theta, phi, reachable, reason, wrist_margin,
        sigma_parallel, sigma_serial, conditioning, ...) in grid order; None for a streamed
        volume.
    summary : dict
        What ``workspace.json`` holds: ``area`` [m²] (or ``volume`` [m³]) and its bound, the
        reachable bounding box, the global conditioning index, ``reason_counts``.
    rectangle : pollard_pin.workspace.grid.Rectangle or None
        The largest reachable rectangle (plane mode).
    reasons : tuple of str
        The names of the ``reason`` codes (0: reachable).

    ``image(name)`` is a column as a 2-D array over a plane grid.
    """

    grid: Grid
    orientation: tuple[float, float, float]
    columns: dict | None
    summary: dict
    rectangle: Rectangle | None = None
    reasons: tuple[str, ...] = field(default=REASONS)

    def image(self, name: str) -> np.ndarray:
        """A column as a 2-D array over the plane grid (shape ``grid.shape``)."""
        return np.asarray(self.columns[name]).reshape(self.grid.shape)

    @property
    def smallest_margin(self) -> np.ndarray:
        """Per point, min(|sin θ1716|, σ_parallel, σ_serial): the figure's colour."""
        c = self.columns
        return np.fmin(np.fmin(c["wrist_margin"], c["sigma_parallel"]), c["sigma_serial"])


# --- the map ------------------------------------------------------------------------------------
class _Summary:
    """Running totals over the chunks: reachable count, bounding box, conditioning sum,
    reason counts (bounded memory)."""

    def __init__(self):
        self.reachable = 0
        self.low = np.full(3, np.inf)
        self.high = np.full(3, -np.inf)
        self.conditioning = 0.0
        self.counts = np.zeros(len(REASONS), dtype=np.int64)
        self.payload = [np.inf, -np.inf]
        self.ranges: dict = {}  # the stiffness columns' [min, max] (docs/model.md §27.6)
        self.beyond_linear = 0  # reachable points whose sag is beyond the linear model

    def add(self, pts: np.ndarray, cols: dict) -> None:
        ok = cols["reason"] == 0
        self.counts += np.bincount(cols["reason"], minlength=len(REASONS))
        if ok.any():
            self.reachable += int(ok.sum())
            self.low = np.minimum(self.low, pts[ok].min(axis=0))
            self.high = np.maximum(self.high, pts[ok].max(axis=0))
            self.conditioning += float(cols["conditioning"][ok].sum())
            if "payload_capacity" in cols:
                cap = cols["payload_capacity"][ok]
                self.payload = [min(self.payload[0], float(cap.min())),
                                max(self.payload[1], float(cap.max()))]
            for name in STIFFNESS_COLUMNS:
                if name in cols:
                    x = cols[name][ok]
                    lo, hi = self.ranges.get(name, (np.inf, -np.inf))
                    x = x[~np.isnan(x)]  # the sag beyond the linear model (§27.6): counted
                    self.beyond_linear += int(ok.sum()) - len(x) if name == "sag" else 0
                    if len(x):
                        self.ranges[name] = [min(lo, float(x.min())), max(hi, float(x.max()))]


def map_workspace(robot, plane=None, options: WorkspaceOptions | None = None, *,
                  sink: Callable[[dict], None] | None = None, progress=None,
                  reach_box: tuple | None = None) -> WorkspaceMap:
    """Map where the tool reaches at a fixed orientation (docs/model.md §22): every point of a
    plane grid or of a box, under ``run``'s rules plus the joint limits; each unreachable
    point names the first rule it breaks.

    Parameters
    ----------
    robot : Robot
        The model.
    plane : str or tuple or None, optional
        ``"x=0.55"`` (or ``("x", 0.55)``, metres) for a plane grid; None with
        ``options.volume`` for a box.
    options : WorkspaceOptions or None, optional
        Orientation, resolution, bounds, actuators, margins, ... (default its defaults).
    sink : Callable or None, optional
        ``sink(columns)`` receives every chunk's columns (x, y, z, psi, theta, phi,
        reachable, reason, ...) in grid order (how a volume is streamed to a file).
    progress : Callable or None, optional
        ``progress(done, total)`` per chunk.
    reach_box : tuple or None, optional
        ``pollard_pin.workspace.grid.reachable_box(robot, orientation, ReachOptions(margins))``
        at ``options``' orientation and margins, when the caller has it (a sweep of planes at
        one orientation): a refusal names it instead of computing it again. None (default):
        computed when a refusal needs it.

    Returns
    -------
    WorkspaceMap
        The grid, the per-point columns (plane mode), the largest reachable rectangle (plane
        mode) and the summary of ``workspace.json`` (area or volume, reachable box, global
        conditioning index, counts per reason).

    Raises
    ------
    WorkspaceError
        A bad value, a grid over budget, or a plane or bounds with no reachable point
        (naming the reachable bounding box).

    Examples
    --------
    >>> import pollard_pin as pp
    >>> ws = pp.map_workspace(pp.load(), "x=0.55", pp.WorkspaceOptions(resolution=0.01))
    >>> round(ws.summary["area"], 3), ws.rectangle.size            # m², (m, m)
    (0.189, (0.6, 0.25))
    """
    check_robot(robot)
    o = WorkspaceOptions() if options is None else options
    if not isinstance(o, WorkspaceOptions):
        raise WorkspaceError(f"options must be a WorkspaceOptions, got {type(o).__name__}")
    callback(sink, "sink", error=WorkspaceError)
    callback(progress, "progress", error=WorkspaceError)
    if (plane is None) == (not o.volume):
        raise WorkspaceError("give either a plane (e.g. x=0.55) or volume=True")
    t0 = time.perf_counter()
    orient = o.orientation
    plane_ = None if o.volume else parse_plane(plane)
    opts = ReachOptions(o.margins, o.length_scale, o.actuators)
    params = robot.params
    if plane_ is not None:
        centre, radius = reach_sphere(params, orient)
        a, v = plane_
        if abs(v - centre[a]) > radius:
            raise _missed(robot, orient, opts, reach_box, f"plane {AXES[a]} = {v:g} m misses "
                          f"the robot (its reach at this orientation is {AXES[a]} ∈ "
                          f"[{centre[a] - radius:.3g}, {centre[a] + radius:.3g}] m at most)")
    grid = make_grid(params, orient, o.resolution, plane_, o.bounds)
    keep = plane_ is not None if o.keep is None else o.keep
    totals = _Summary()
    kept = []
    for start in range(0, grid.size, o.chunk):
        flat = np.arange(start, min(start + o.chunk, grid.size))
        pts = grid.points(flat)
        poses = np.concatenate([pts, np.broadcast_to(orient, (len(pts), 3))], axis=1)
        cols = {name: poses[:, i] for i, name in enumerate(("x", "y", "z", "psi", "theta",
                                                            "phi"))}
        cols.update(evaluate(robot, poses, opts))
        totals.add(pts, cols)
        if sink is not None:
            sink(cols)
        if keep:
            kept.append(cols)
        if progress is not None:
            progress(int(flat[-1]) + 1, grid.size)
    if totals.reachable == 0:
        where = (f"plane {AXES[plane_[0]]} = {plane_[1]:g} m" if plane_ is not None
                 else "the volume")
        # the grid's points span less than the bounds when the step does not divide them
        raise _missed(robot, orient, opts, reach_box, f"no point of {where} is reachable "
                      f"on its grid {_bounds_text(grid)} (step {grid.step:g} m)")
    columns = ({k: np.concatenate([c[k] for c in kept]) for k in kept[0]} if keep else None)
    rect = None
    if plane_ is not None and columns is not None:
        rect = _rectangle(robot, grid, columns["reason"].reshape(grid.shape) == 0, orient,
                          opts)
    boundary = (None if plane_ is None or columns is None else
                boundary_points(columns["reason"].reshape(grid.shape) == 0))
    summary = _summary(robot, grid, orient, opts, totals, rect, time.perf_counter() - t0,
                       boundary)
    return WorkspaceMap(grid, orient, columns, summary, rect)


def _bounds_text(grid: Grid) -> str:
    d = grid.as_dict()
    return ", ".join(f"{a} ∈ [{lo:.4g}, {hi:.4g}] m"
                     for a, lo, hi in zip(d["axes"], d["start"], d["stop"]))


def reachable_box(robot, orientation, options: ReachOptions | None = None,
                  cells: int = COARSE_CELLS):
    """(low (3,), high (3,), step) [m]: the bounding box of the reachable points of a coarse
    volume grid (``cells`` points across the reach sphere), or None if none is reachable.
    The true box may exceed it by up to one step."""
    options = ReachOptions() if options is None else options
    centre, radius = reach_sphere(robot.params, orientation)
    h = 2.0 * radius / (cells - 1)
    grid = make_grid(robot.params, orientation, h)
    totals = _Summary()
    for start in range(0, grid.size, CHUNK):
        pts = grid.points(np.arange(start, min(start + CHUNK, grid.size)))
        # only the points in the ball that holds every reachable tip (reach_sphere): the
        # cube's corners beyond it (half its points) reach nothing
        pts = pts[np.linalg.norm(pts - centre, axis=1) <= radius * (1 + 1e-9)]
        if not len(pts):
            continue
        poses = np.concatenate([pts, np.broadcast_to(orientation, (len(pts), 3))], axis=1)
        totals.add(pts, evaluate(robot, poses, options))
    return None if totals.reachable == 0 else (totals.low, totals.high, h)


def _missed(robot, orient, opts, box, what: str) -> WorkspaceError:
    """The refusal ``what``, naming the reachable box ``box`` (None: computed here)."""
    box = reachable_box(robot, orient, ReachOptions(opts.margins)) if box is None else box
    if box is None:
        return WorkspaceError(f"{what}; no tool position at all is reachable at orientation "
                              f"(psi, theta, phi) = {_deg(orient)} deg")
    lo, hi, h = box
    span = ", ".join(f"{a} ∈ [{lo[i]:.3f}, {hi[i]:.3f}]" for i, a in enumerate(AXES))
    return WorkspaceError(say_less(
        f"{what}; at orientation (psi, theta, phi) = {_deg(orient)} deg the reachable region "
        f"spans {span} m (±{h:.2g} m)",
        f"{what}; at orientation {_deg(orient)} deg the reachable region spans {span} m",
        f"{without_asides(what)}; at orientation {_deg(orient)} deg the "
        f"reachable region spans {span} m"))


def _deg(orient) -> str:
    return "(" + ", ".join(f"{math.degrees(a):.4g}" for a in orient) + ")"


def _rectangle(robot, grid: Grid, mask: np.ndarray, orient, opts) -> Rectangle | None:
    """The largest rectangle of reachable points whose four edges, sampled EDGE_REFINE times
    per step between its corner points, are reachable too (docs/model.md §22)."""
    mask = mask.copy()
    for _ in range(EDGE_ROUNDS):
        found = largest_rectangle(mask)
        if found is None:
            return None
        r0, r1, c0, c1 = found
        rc = edge_samples(r0, r1 - 1, c0, c1 - 1, EDGE_REFINE)
        pts = _plane_points(grid, rc)
        poses = np.concatenate([pts, np.broadcast_to(orient, (len(pts), 3))], axis=1)
        bad = rc[evaluate(robot, poses, ReachOptions(opts.margins))["reason"] != 0]
        if not len(bad):
            break
        for r, c in bad:  # the grid points on either side of a failing edge sample
            mask[math.floor(r):math.ceil(r) + 1, math.floor(c):math.ceil(c) + 1] = False
    else:
        return None
    lo = grid.points(np.array([np.ravel_multi_index((r0, c0), grid.shape)]))[0]
    hi = grid.points(np.array([np.ravel_multi_index((r1 - 1, c1 - 1), grid.shape)]))[0]
    names = tuple(AXES[a] for a in grid.axes)
    size = (round((r1 - r0 - 1) * grid.step, COORD_DECIMALS),
            round((c1 - c0 - 1) * grid.step, COORD_DECIMALS))
    return Rectangle(names, size, tuple(np.round(0.5 * (lo + hi), COORD_DECIMALS).tolist()),
                     (r1 - r0, c1 - c0), tuple(lo.tolist()), tuple(hi.tolist()))


def _plane_points(grid: Grid, rc: np.ndarray) -> np.ndarray:
    """(n, 3) positions of fractional grid indices (n, 2) of a plane grid."""
    pts = np.tile(np.asarray(grid.origin, dtype=float), (len(rc), 1))
    for k, a in enumerate(grid.axes):
        pts[:, a] += grid.step * rc[:, k]
    return pts


def _summary(robot, grid, orient, opts, totals: _Summary, rect, wall,
             boundary: int | None = None) -> dict:
    plane = len(grid.axes) == 2
    measure = "area" if plane else "volume"
    out = {"grid": grid.as_dict(),
           measure: totals.reachable * grid.cell,
           **({} if boundary is None else {"area_bound": boundary * grid.cell,
                                           "boundary_points": boundary}),
           "reachable_points": totals.reachable,
           "bounding_box": {"low": totals.low.tolist(), "high": totals.high.tolist()},
           "global_conditioning_index": totals.conditioning / totals.reachable,
           "reason_counts": {r: int(c) for r, c in zip(REASONS, totals.counts) if c},
           "reason_codes": {str(i): r for i, r in enumerate(REASONS)}}
    if plane:
        out["largest_rectangle"] = None if rect is None else rect.as_dict()
    if opts.actuators is not None:
        out["payload_capacity"] = {"min": totals.payload[0], "max": totals.payload[1],
                                   "over": "reachable points", "unit": "kg"}
    if totals.ranges:
        units = {"kmin": "N/m", "f1": "Hz", "sag": "m"}
        out["stiffness"] = {name: {"min": lo, "max": hi, "unit": units[name]}
                            for name, (lo, hi) in totals.ranges.items()}
        out["stiffness"]["over"] = "reachable points"
    if totals.beyond_linear:
        out.setdefault("stiffness", {})["sag_beyond_linear_points"] = totals.beyond_linear
    from ..version import __version__

    out["metadata"] = {
        "pollard_pin": __version__, "params": robot.params.source,
        "orientation": {"psi": orient[0], "theta": orient[1], "phi": orient[2], "unit": "rad"},
        "orientation_deg": [math.degrees(a) for a in orient],
        **opts.margins.as_dict(),
        "length_scale": length_scale(robot.params, opts),
        "actuators": None if opts.actuators is None else opts.actuators.source,
        "wall_seconds": wall, "us_per_point": 1e6 * wall / grid.size}
    return out


def largest_panel(robot, plane, options: WorkspaceOptions | None = None) -> Rectangle | None:
    """The largest axis-aligned rectangle (corner to corner through reachable grid points) of
    reachable tool positions in a plane (e.g. "x=0.55": the panel surface minus the
    standoff) at ``options.orientation`` — the biggest panel the robot can sweep there
    (docs/model.md §22). The paint planner's own search, a float scale of a job's panel, is
    ``pollard_pin.painting.plan.panel.largest_scale``.

    Parameters
    ----------
    robot : Robot
        The model.
    plane : str or tuple
        ``"x=0.55"`` or ``("x", 0.55)`` [m].
    options : WorkspaceOptions or None, optional
        As :func:`~pollard_pin.map_workspace`'s.

    Returns
    -------
    pollard_pin.workspace.grid.Rectangle or None
        Its ``axes``, ``size`` [m], ``centre`` and corners ``low``, ``high`` (x, y, z) [m];
        None when no rectangle of reachable points exists.

    Raises
    ------
    WorkspaceError
        As :func:`~pollard_pin.map_workspace`.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> panel = pp.largest_panel(pp.load(), "x=0.55", pp.WorkspaceOptions(resolution=0.01))
    >>> panel.axes, panel.size, panel.centre
    (('y', 'z'), (0.6, 0.25), (0.55, 0.0, 0.095))
    """
    return map_workspace(robot, plane, options).rectangle
