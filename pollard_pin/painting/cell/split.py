"""Which robot of a cell paints which zone of the part (docs/model.md §26.2).

Robots are grouped by the side of the part they face (the faces towards their gun, world
−R·x̂ of the base: gun along base +x). Within a group each robot has its band along the
cell's axis (:mod:`.bands`); robots are stacked by their bands' middles and the seams
w_1 < … < w_{n−1} chosen so that robot i's zone [w_{i−1}, w_i] with its run-outs (R past a
seam where the bands allow it, else as much of R as they do, at least the planner's shorter
``seam_run`` (``Strokes.past_seam``), :func:`seam_runs`;
today's run-on past a free edge) lies in its band, the longest zone as short as the
bands allow (equal stroke lengths: the slowest program sets the line's speed), and, among
such seams, each midway between the lowest and highest the bands allow.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...checks import instance
from ..errors import CellError
from ..job import PartJob
from ..line.reach import reach_ball
from ..passes.raster import SPOT_RADIUS
from ..policy import PlannerPolicy
from .bands import Band, Strokes, axis_name, job_strokes, robot_band
from .robots import CellRobot
from .zones import Split, Zone

SAME_SIDE = math.cos(math.radians(60.0))  # two facings this close paint the same faces
MIN_ZONE = 1.0  # σ: the shortest zone worth a robot
BISECT = 1e-5  # m: the longest zone found to this
WIDE_STEP = 0.01  # m: the grid saying where a robot reaches when it reaches none of the part
EDGE_TOL = 1e-9  # m: a band ending on the edge's run-on, up to rounding, holds it


def seen_facing(cell_robot: CellRobot) -> np.ndarray:
    """The world facing of the faces a robot paints: towards its gun, −R·x̂."""
    return -cell_robot.R[:, 0]


def group_by_side(robots, facing) -> list[tuple[tuple | None, list[CellRobot]]]:
    """[(facing or None for the job's, robots)], the job's side first, in order of the
    robots given."""
    facing = np.asarray(facing, float)
    groups: list[tuple[np.ndarray | None, list]] = [(None, [])]
    for r in robots:
        f = seen_facing(r)
        if f @ facing >= SAME_SIDE:
            groups[0][1].append(r)
            continue
        for g, members in groups[1:]:
            if f @ g >= SAME_SIDE:
                members.append(r)
                break
        else:
            groups.append((f, [r]))
    return [(None if g is None else tuple(round(float(c), 12) + 0.0 for c in g), m)
            for g, m in groups if m]


def _mm(x: float) -> str:
    return f"{x + 0.0:.3f}".replace("-0.000", "0.000")


def _span(name: str, a: float, b: float) -> str:
    return f"{name} {_mm(a)}…{_mm(b)} m"


def _unreached(robot, cell_robot: CellRobot, strokes: Strokes, source: str) -> CellError:
    """A robot that reaches no part of the part, saying where it reaches at the part's depth
    (the strokes continued across the whole reach ball, on a coarser grid)."""
    name = axis_name(strokes.axis)
    lo, hi = strokes.needed(-math.inf, math.inf)
    wide = robot_band(robot, cell_robot, strokes, margin=2 * reach_ball(robot.params)[1],
                      step=WIDE_STEP)
    where = (f"reaches {_span(name, *wide.reached)} at the part's depth"
             if wide.reached is not None else "reaches no point at the part's depth at any "
             "place on the line")
    return CellError(f"{source}: robot {cell_robot.name!r} {where}; the part spans "
                     f"{_span(name, *strokes.extent)} ({_mm(lo)}…{_mm(hi)} m with its "
                     "strokes' run-ons)")


def _longest_zone_ok(T, lo_bounds, hi_bounds, e_lo, e_hi, least):
    """Seams (forward greedy, as high as possible) with every zone ≤ T, or None. The upper
    bounds are first tightened backwards so that each leaves room for the zones above; then
    pushing a seam higher never hurts the next, and the greedy is exact."""
    top, upper = e_hi, []
    for b in hi_bounds[::-1]:
        top = min(b, top - least)
        upper.append(top)
    w, seams = e_lo, []
    for a, u in zip(lo_bounds, upper[::-1]):
        w_next = min(u, w + T)
        if w_next < max(a, w + least):
            return None
        w = w_next
        seams.append(w)
    return seams if e_hi - w <= T + 1e-12 and e_hi - w >= least - 1e-12 else None


def _backward(T, lo_bounds, hi_bounds, e_lo, e_hi, least):
    """Seams as low as possible with every zone ≤ T, or None (the mirror of the above)."""
    seams = _longest_zone_ok(T, [-b for b in hi_bounds[::-1]], [-a for a in lo_bounds[::-1]],
                             -e_hi, -e_lo, least)
    return None if seams is None else [-s for s in seams[::-1]]


def seam_runs(bands: list[Band], strokes: Strokes, room: bool = True) -> list[float]:
    """The run-out each seam of stacked ``bands`` holds on each side: R
    (``Strokes.runout``) where their overlap allows it, else (``room``) as much of R as the
    overlap does, at least the planner's run (``Strokes.past_seam``; room for a ramp there,
    docs/model.md §26.5), or (not ``room``) that run at every seam."""
    R, run = strokes.runout, strokes.past_seam
    if not room:
        return [run] * (len(bands) - 1)
    return [min(R, max(run, (a.hi - b.lo) / 2)) for a, b in zip(bands, bands[1:])]


def seams_between(bands: list[Band], strokes: Strokes, least: float,
                  room: bool = True) -> list[float] | None:
    """The seams of stacked ``bands`` (in order along the axis) over the part's extent, each
    holding its :func:`seam_runs` past it, the longest zone shortest, each seam midway in
    what that allows; None if the bands leave a region unreached or a zone too short for its
    run-outs."""
    e_lo, e_hi = strokes.extent
    need_lo, need_hi = strokes.needed(-math.inf, math.inf)
    if bands[0].lo > need_lo + EDGE_TOL or bands[-1].hi < need_hi - EDGE_TOL:
        return None
    runs = seam_runs(bands, strokes, room)
    B = [bands[i].hi - r for i, r in enumerate(runs)]  # seam i's highest ...
    A = [min(bands[i + 1].lo + r, B[i]) if r > strokes.past_seam else bands[i + 1].lo + r
         for i, r in enumerate(runs)]  # ... and lowest (one point if its run is the overlap's)
    if _longest_zone_ok(e_hi - e_lo, A, B, e_lo, e_hi, least) is None:
        return None
    lo, hi = 0.0, e_hi - e_lo
    while hi - lo > BISECT:
        mid = (lo + hi) / 2
        if _longest_zone_ok(mid, A, B, e_lo, e_hi, least) is None:
            lo = mid
        else:
            hi = mid
    up = _longest_zone_ok(hi, A, B, e_lo, e_hi, least)
    down = _backward(hi, A, B, e_lo, e_hi, least)
    return [(a + b) / 2 for a, b in zip(up, down)]


def _why_not(source: str, bands: list[Band], strokes: Strokes, least: float) -> CellError:
    """The first reason stacked ``bands`` cannot cover the part: an end, a gap or an overlap
    too short for a seam's run-outs, or a band with no room for a zone."""
    name = axis_name(strokes.axis)
    lo, hi = strokes.needed(-math.inf, math.inf)
    R = strokes.past_seam
    run = "R" if strokes.seam_run is None else "seam_run"
    if bands[0].lo > lo + EDGE_TOL:
        return CellError(f"{source}: no robot reaches {_span(name, lo, bands[0].lo)} (the "
                         f"part's edge {_mm(strokes.extent[0])} m and its run-on; the lowest "
                         f"band starts at {_mm(bands[0].lo)} m, robot {bands[0].robot!r})")
    if bands[-1].hi < hi - EDGE_TOL:
        return CellError(f"{source}: no robot reaches {_span(name, bands[-1].hi, hi)} (the "
                         f"part's edge {_mm(strokes.extent[1])} m and its run-on; the highest "
                         f"band ends at {_mm(bands[-1].hi)} m, robot {bands[-1].robot!r})")
    for a, b in zip(bands, bands[1:]):
        if a.hi < b.lo:
            return CellError(f"{source}: no robot reaches {_span(name, a.hi, b.lo)} between "
                             f"robots {a.robot!r} (up to {_mm(a.hi)} m) and {b.robot!r} "
                             f"(from {_mm(b.lo)} m)")
        if a.hi - b.lo < 2 * R - EDGE_TOL:
            return CellError(f"{source}: robots {a.robot!r} and {b.robot!r} overlap along "
                             f"{name} by {1e3 * (a.hi - b.lo):.0f} mm ({_mm(b.lo)}…"
                             f"{_mm(a.hi)} m), less than the {2e3 * R:.0f} mm a seam's "
                             f"run-outs need ({run} = {1e3 * R:.0f} mm each side)")
    short = min(bands, key=lambda b: b.width)
    return CellError(f"{source}: the bands leave robot {short.robot!r} "
                     f"({_span(name, short.lo, short.hi)}) no zone of at least "
                     f"{1e3 * least:.0f} mm with its run-outs "
                     f"({1e3 * R:.0f} mm past each seam) between its neighbours' seams")


def split_group(robot, robots, strokes: Strokes, source: str, facing=None) -> list[Zone]:
    """The zones of robots facing the same side, from the bands over ``strokes``."""
    bands = [robot_band(robot, r, strokes) for r in robots]
    lo, hi = strokes.needed(-math.inf, math.inf)
    for r, b in zip(robots, bands):
        if b.empty or b.hi < lo or b.lo > hi:
            raise _unreached(robot, r, strokes, source)
    bands.sort(key=lambda b: (b.lo + b.hi) / 2)
    # the end robots hold the part's edges with their run-ons if any stretch of theirs does
    # (the longest may stop short of an edge whose strokes bend: docs/model.md §26.2)
    if len(bands) == 1:
        bands[0] = bands[0].holding(lo, hi)
    else:
        bands[0], bands[-1] = bands[0].holding(lo=lo), bands[-1].holding(hi=hi)
    least = MIN_ZONE * strokes.runout / SPOT_RADIUS  # σ (R = SPOT_RADIUS σ)
    # R past each seam where the bands allow it, else as much of R as they do (room for the
    # ramps there, docs/model.md §26.5), else the policy's shorter run at every seam
    seams = seams_between(bands, strokes, least)
    if seams is None and strokes.seam_run is not None:
        seams = seams_between(bands, strokes, least, room=False)
    if seams is None:
        raise _why_not(source, bands, strokes, least)
    edges = [-math.inf, *seams, math.inf]
    return [Zone(b.robot, float(edges[i]), float(edges[i + 1]), facing)
            for i, b in enumerate(bands)]


def split_cell(robot, job, robots, part=None, seams=None,
               policy: PlannerPolicy | None = None) -> Split:
    """Which robot paints which zone of the job's part: each zone within its robot's reach
    over the part's whole passage, the programs balanced (docs/model.md §26.2).

    Parameters
    ----------
    robot : Robot
        The model every robot shares, its reach rules (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        A job with ``[line]``.
    robots : Sequence of CellRobot
        The cell's robots (:class:`~pollard_pin.painting.cell.robots.CellRobot`).
    part : object or None, optional
        The painted part if already read (default None: read here; a panel has none).
    seams : tuple of float or None, optional
        The seams of the robots facing the job's side, increasing (default None: the bands',
        balanced; ``PlannerPolicy.seams``).
    policy : PlannerPolicy or None, optional
        The planner's knobs, checked (default None: the defaults): its ``seam_run``, how far
        [m] the strokes run past a seam (None: R), is the run-out each band holds past a
        seam (``Strokes.past_seam``).

    Returns
    -------
    Split
        The zones and their seams.

    Raises
    ------
    pollard_pin.painting.errors.CellError
        One line if a robot reaches none of the part (where the part passes it), no split
        covers it (the region no robot reaches), or ``seams`` do not fit the robots.
    """
    robots = tuple(robots)
    if not robots:
        raise CellError(f"{job.source}: a cell needs at least one robot")
    if job.line is None:
        raise CellError(f"{job.source}: a cell's robots paint the part as the line carries "
                        "it past them: the job needs [line]")
    instance(policy, "policy", PlannerPolicy, "PlannerPolicy or None", none=True)
    seam_run = None if policy is None else policy.seam_run  # checked by the policy
    strokes = replace(job_strokes(job, part), seam_run=seam_run)
    zones, axis = [], strokes.axis
    groups = group_by_side(robots, strokes.facing)
    if groups[0][0] is not None:
        raise CellError(f"{job.source}: no robot faces the job's painted faces (facing "
                        f"{_vec(strokes.facing)}): turn one robot towards them")
    for facing, members in groups:
        if facing is not None and not isinstance(job, PartJob):
            r = members[0]
            raise CellError(f"{job.source}: robot {r.name!r} faces the panel's back (its gun "
                            f"points along {_vec(-np.asarray(facing))}; the panel's normal is "
                            f"{_vec(strokes.facing)}): a panel is painted on its front only")
        side = (strokes if facing is None else
                replace(job_strokes(job, None, facing), seam_run=seam_run))
        if facing is not None and abs(float(side.axis @ axis)) < 1 - 1e-6:
            raise CellError(f"{job.source}: the faces robot {members[0].name!r} sees (facing "
                            f"{_vec(facing)}) are not parallel to the job's: one axis across "
                            "the travel serves both sides only for faces parallel to it")
        zones += split_group(robot, members, side, job.source, facing)
    key = [(0 if z.facing is None else 1, z.facing or (), z.lo) for z in zones]
    order = sorted(range(len(zones)), key=lambda i: key[i])
    if seams is not None:  # the job's side's zones, in order, cut where asked (§26.5)
        zones = [zones[i] for i in order]
        zones[:len(groups[0][1])] = _cut_at(zones[:len(groups[0][1])], seams, strokes.extent,
                                            job.source)
        order = range(len(zones))
    return Split(tuple(float(c) for c in axis), tuple(zones[i] for i in order),
                 float(strokes.runout))


def _cut_at(zones: list[Zone], seams, extent, source: str) -> list[Zone]:
    """``zones`` (stacked, bottom first) with their seams moved to ``seams``, each within
    the part's ``extent``."""
    seams = [float(s) for s in seams]
    if len(seams) != len(zones) - 1:
        raise CellError(f"{source}: {len(seams)} seam(s) given for {len(zones)} robots "
                        f"facing the painted faces: expected {len(zones) - 1}")
    inside = [s for s in seams if not extent[0] < s < extent[1]]
    if inside:
        raise CellError(f"{source}: the seam at {inside[0]:.4g} m lies off the part "
                        f"({_mm(extent[0])}…{_mm(extent[1])} m along the split's axis)")
    edges = [-math.inf, *seams, math.inf]
    return [Zone(z.robot, edges[i], edges[i + 1], z.facing) for i, z in enumerate(zones)]


def _vec(v) -> str:
    return "(" + ", ".join(f"{float(c) + 0.0:.3g}" for c in v) + ")"


__all__ = ["MIN_ZONE", "SAME_SIDE", "group_by_side", "seam_runs", "seams_between",
           "seen_facing", "split_cell", "split_group"]
