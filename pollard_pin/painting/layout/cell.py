"""A cell's layout for a part: where to put n robots (docs/model.md §26.5).

The part's strokes are split into n equal zones stacked along the cell's axis (the first and
last with today's run-on past the part's free edges, the others R = 4σ past each seam). A
robot at the world origin, unturned, has its band along the axis at the part's depth
(:mod:`.cell.bands`, the strokes continued past the part); robot i is that robot moved along the
axis so that its band's middle is its zone's (run-outs included) middle, the bands' overlaps
holding the seams' run-outs, and set ``spacing`` further down the line than robot i − 1
(default: the tip's reach window along the line at the part's depth plus twice the base's
footprint, the room one robot sweeps painting). The proposal is then split by
:func:`.split.split_cell`, which checks it as any given cell. :func:`.auto.fewest_robots`
tries n = 1, 2, … until :func:`pollard_pin.painting.paint` paints the job with the proposal.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, replace

import numpy as np

from ...checks import instance, is_real, shorten
from ...errors import InputError
from ...model.build import check_robot
from ...workspace.reach import evaluate
from ..cell.bands import STEP, Band, Strokes, axis_name, base_poses, job_strokes, robot_band
from ..cell.robots import MAX_DISTANCE, MAX_ROBOTS, CellRobot, base_footprint, check_spacing
from ..cell.split import split_cell
from ..errors import CellError
from ..job import check_job
from ..policy import PlannerPolicy

WINDOW_STEP = 0.005  # m between the shifts scanning the reach window along the line
REFERENCE_STROKES = 5  # distinct stroke shapes the reference band is taken over
EDGE_TRIES = 10  # bands computed at most to move a robot onto its zone (or its edge)
MAX_ROOM = 0.5  # m: LayoutOptions.edge_room at most (a robot's band is ~0.25 m)
MAX_PITCH = 45.0  # deg: LayoutOptions.end_pitch at most
EDGE_RATE = 0.2  # the slowest a band is taken to move with its base (edge moves ≤ 5× the gap)


@dataclass(frozen=True)
class LayoutOptions:
    """How :func:`propose_layout` places robots (docs/model.md §26.5).

    Attributes
    ----------
    spacing : float or None
        The distance [m] between neighbours along the line, in (0, 10] (default None: the
        reach window along the line plus twice the base's footprint).
    prefix : str
        The robots' names: prefix1, prefix2, … (1–24 letters or digits; default "robot").
    edge_room : float
        The end robots hold this much [m] more past the part's free edges than the run-on,
        in [0, 0.5] (default 0): room for the ramps there (a ramp runs on v·τ/2 past its
        pass, 22 mm at the first guess on a 0.33 m bevelled door, docs/model.md §26.5).
    end_pitch : float
        The last robot along the cell's axis (the top one) turned this much [deg] about the
        line, in [-45, 45] (default 0; the line along a world axis): away from the wrist's
        singularity at a bevelled top edge (−5° on the 0.33 m door, docs/model.md §26.5).

    Raises
    ------
    pollard_pin.errors.InputError
        A spacing, prefix, room or pitch out of range.
    """

    spacing: float | None = None
    prefix: str = "robot"
    edge_room: float = 0.0
    end_pitch: float = 0.0

    def __post_init__(self):
        s = self.spacing
        if s is not None and not is_real(s, 0.0, 10.0, above=True):
            raise InputError(f"LayoutOptions.spacing = {shorten(s)}: expected a distance in "
                             "(0, 10] m (or None)")
        if not (isinstance(self.prefix, str) and self.prefix.isalnum() and
                len(self.prefix) <= 24):
            raise InputError(f"LayoutOptions.prefix = {shorten(self.prefix)}: expected 1-24 "
                             "letters or digits")
        if not is_real(self.edge_room, 0.0, MAX_ROOM):
            raise InputError(f"LayoutOptions.edge_room = {shorten(self.edge_room)}: expected "
                             f"a length in [0, {MAX_ROOM:g}] m")
        object.__setattr__(self, "edge_room", float(self.edge_room))
        if not is_real(self.end_pitch, -MAX_PITCH, MAX_PITCH):
            raise InputError(f"LayoutOptions.end_pitch = {shorten(self.end_pitch)}: expected "
                             f"an angle in [-{MAX_PITCH:g}, {MAX_PITCH:g}] deg")
        object.__setattr__(self, "end_pitch", float(self.end_pitch))


def zone_needs(strokes: Strokes, n: int, ends: tuple[float, float] | None = None
               ) -> list[tuple[float, float]]:
    """The stretches of the axis n zones need in reach, run-outs included: equal zones, or
    the first and last ``ends`` [m] long (n ≥ 2; two zones share the part in that ratio)
    and the others equal."""
    e0, e1 = strokes.extent
    if ends is None or n < 2:
        cut = np.linspace(e0, e1, n + 1)
    elif n == 2:
        cut = np.array([e0, e0 + (e1 - e0) * ends[0] / (ends[0] + ends[1]), e1])
    else:
        cut = np.concatenate([[e0], np.linspace(e0 + ends[0], e1 - ends[1], n - 1), [e1]])
    return [strokes.needed(-math.inf if i == 0 else float(cut[i]),
                           math.inf if i == n - 1 else float(cut[i + 1])) for i in range(n)]


def fewest_for(strokes: Strokes, width: float) -> int | None:
    """The fewest equal zones whose needs fit a band ``width`` [m] wide (None: none up to
    MAX_ROBOTS)."""
    for n in range(1, MAX_ROBOTS + 1):
        if max(b - a for a, b in zone_needs(strokes, n)) <= width:
            return n
    return None


def reference_band(robot, strokes: Strokes) -> Band:
    """The band of a robot at the world origin, unturned, over the strokes continued across
    its reach (the part's depth; its few distinct strokes)."""
    from ..line.reach import reach_ball

    ref = CellRobot("reference")
    band = robot_band(robot, ref, strokes, margin=2 * reach_ball(robot.params)[1], step=STEP,
                      most=REFERENCE_STROKES)
    if band.empty:
        raise CellError("a robot reaches no point of the part's plane at its depth at any "
                        "height: move the part within the robot's reach across the line")
    return band


def reach_window(robot, strokes: Strokes, band: Band) -> float:
    """The width [m] along the line over which the origin robot holds the gun pose at its
    band's middle on the middle stroke (the tip's reach window along the line)."""
    w, tips, spray = strokes.grid(0.0, STEP)
    k = len(tips) // 2
    mid = (band.lo + band.hi) / 2
    tip = np.array([np.interp(mid, w, tips[k, :, i]) for i in range(3)])
    a = np.array([np.interp(mid, w, spray[k, :, i]) for i in range(3)])
    pose = base_poses(CellRobot("reference"), tip[None], (a / np.linalg.norm(a))[None],
                       strokes.panel, strokes.facing)[0]
    xs = np.arange(-2.0, 2.0 + WINDOW_STEP / 2, WINDOW_STEP)
    poses = np.repeat(pose[None], len(xs), axis=0)
    poses[:, :3] += xs[:, None] * strokes.direction
    ok = evaluate(robot, poses)["reachable"] > 0
    return float(np.ptp(xs[ok])) if ok.any() else 0.0


def propose_layout(robot, job, n: int, options: LayoutOptions | None = None,
                   part=None, policy: PlannerPolicy | None = None, reference=None
                   ) -> tuple[CellRobot, ...]:
    """Bases for n robots for this part on this line: their zones stacked across the travel,
    the robots spaced along the line to clear each other (docs/model.md §26.5).

    Parameters
    ----------
    robot : Robot
        The model every robot shares (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        A job with ``[line]`` and no ``[[robot]]`` tables.
    n : int
        The number of robots (1–16).
    options : LayoutOptions or None, optional
        The spacing and the names (default :class:`LayoutOptions`).
    part : object or None, optional
        The job's painted part if already read (default None: read here).
    policy : PlannerPolicy or None, optional
        The planner's knobs, checked (default None: the defaults): its ``seam_run``, how far
        [m] the strokes run past a seam (None: R), is what the proposal's split holds past a
        seam where R does not fit (its bands are spaced for R: room for the ramps,
        docs/model.md §26.5).
    reference : tuple or None, optional
        The job's strokes and the reference robot's band (``reference_band``) if at
        hand: ``fewest_robots`` (:mod:`pollard_pin.painting.layout.auto`) tries several n
        on one (default None: made here).

    Returns
    -------
    tuple of CellRobot
        One :class:`~pollard_pin.painting.cell.robots.CellRobot` per robot (name, base [m],
        rotation [deg]), checked by :func:`split_cell`.

    Raises
    ------
    pollard_pin.painting.errors.CellError
        One line when n robots' bands cannot hold n equal zones with their run-outs (naming
        the fewest that can), or the job has robots or no line.
    """
    check_robot(robot)
    check_job(job)
    options = instance(options, "options", LayoutOptions, "LayoutOptions or None",
                       none=True) or LayoutOptions()
    if isinstance(n, bool) or not isinstance(n, numbers.Integral) or not 1 <= n <= MAX_ROBOTS:
        raise CellError(f"n = {shorten(n)}: expected 1..{MAX_ROBOTS} (a whole number of robots)")
    instance(policy, "policy", PlannerPolicy, "PlannerPolicy or None", none=True)
    return _propose(robot, job, n, options, part, reference, policy)


def check_layout_job(job) -> None:
    """A layout is proposed for a job on a line without its own robots; else one line."""
    if job.line is None:
        raise CellError(f"{job.source}: a cell's layout needs the job's [line]")
    if job.robots:
        raise CellError(f"{job.source}: the job already places its {len(job.robots)} "
                        "robot(s) ([[robot]]): a layout is proposed for a job without them")


def _propose(robot, job, n: int, options: LayoutOptions, part, reference=None,
             policy: PlannerPolicy | None = None):
    """:func:`propose_layout` of checked arguments; ``reference``: the job's (strokes,
    reference band) if already at hand; ``policy``: its ``seam_run`` the split's run past a
    seam."""
    check_layout_job(job)
    strokes, band = reference or (None, None)
    if reference is None:
        strokes = job_strokes(job, part)
        band = reference_band(robot, strokes)
    if options.edge_room:  # the end robots hold more past the free edges (§26.5)
        strokes = replace(strokes, room=options.edge_room)
    needs = zone_needs(strokes, n)
    narrow = narrow_refusal(strokes, band, n)
    if narrow:
        raise CellError(f"{job.source}: {narrow}")
    foot = base_footprint(robot.model)
    spacing = (options.spacing if options.spacing is not None else
               reach_window(robot, strokes, band) + 2 * foot)
    middle = (band.lo + band.hi) / 2

    def placed(needs):
        return tuple(CellRobot(f"{options.prefix}{i + 1}", _triple(
            ((a + b) / 2 - middle) * strokes.axis + i * spacing * strokes.direction))
            for i, (a, b) in enumerate(needs))

    robots, held = cover_edges(robot, placed(needs), strokes, needs)
    if not held and n >= 2:  # an edge's band is shorter than the reference's: end zones
        ends = _edge_zones(robot, robots, strokes)  # that fit it, the rest shared
        if ends is not None:
            needs = zone_needs(strokes, n, ends)
            if max(b - a for a, b in needs[1:-1] or [(0.0, 0.0)]) <= band.width + 1e-9:
                robots = cover_edges(robot, placed(needs), strokes, needs)[0]
    if options.end_pitch:  # the top robot turned, moved onto the top edge (§26.5)
        robots = (*robots[:-1], _pitched(robot, robots[-1], strokes, options.end_pitch,
                                         job.source))
    _check_bounds(robots, spacing, job.source)
    check_spacing(robots, 2 * foot, job.source)
    split_cell(robot, replace(job, robots=robots), robots, part, policy=policy)
    return robots


def _pitched(robot, top: CellRobot, strokes: Strokes, deg: float, source: str) -> CellRobot:
    """The top robot turned ``deg`` about the line (a world axis: about one axis
    R = Rx·Ry·Rz is that axis's turn alone), moved as far down as it still holds the top
    edge's need (:func:`cover_edge`)."""
    e = np.asarray(strokes.direction, float)
    if np.abs(e).max() < 1 - 1e-9:
        raise CellError(f"{source}: LayoutOptions.end_pitch turns a robot about the line, "
                        "which must run along a world axis")
    hi = strokes.needed(-math.inf, math.inf)[1]
    turned = replace(top, rotation=_triple(deg * np.round(e)))
    moved = cover_edge(robot, turned, strokes, (hi - STEP, hi), toward=-1.0)
    if moved is None:
        raise CellError(f"{source}: robot {top.name!r} turned {deg:g}° about the line holds "
                        f"no stretch up to the top edge's run-on ({hi:.3f} m)")
    return moved


def narrow_refusal(strokes: Strokes, band: Band, n: int) -> str:
    """Why n robots' bands cannot hold n equal zones with their run-outs, naming the fewest
    that can ('' if they can)."""
    widest = max(b - a for a, b in zone_needs(strokes, n))
    if widest <= band.width + 1e-9:
        return ""
    least = fewest_for(strokes, band.width)
    more = f"at least {least} robots" if least is not None else f"more than {MAX_ROBOTS} robots"
    return (f"{n} robot(s) cannot paint the part: each zone needs {widest:.3f} m along "
            f"{axis_name(strokes.axis)} with its run-outs, a robot's band is {band.width:.3f} m "
            f"({more})")


def _shortfall(band: Band, need: tuple[float, float]) -> float | None:
    """How far [m along the axis] the band falls short of ``need``: < 0 below it (move
    down), > 0 above it (move up), 0 if one stretch holds it, None if the band is too short
    for it (its stretches reach both ends, none both)."""
    a, b = need
    if band.empty:
        return None
    w, n = band.grid
    starts, ends = w[n > 0], w[np.flatnonzero(n > 0) + n[n > 0] - 1]
    if starts.min() > a + 1e-9:
        return a - float(starts.min())
    if ends.max() < b - 1e-9:
        return b - float(ends.max())
    return 0.0 if band.holding(lo=a).hi >= b - 1e-9 else None


def cover_edge(robot, cell_robot: CellRobot, strokes: Strokes, need: tuple[float, float],
               tries: int = EDGE_TRIES, toward: float = 0.0) -> CellRobot | None:
    """The robot moved along the cell's axis until one stretch of its band holds ``need``
    (its zone with its run-outs, at an edge its run-on), or None if no move does within
    ``tries`` bands. Where the strokes bend towards an edge (a chamfer, a rounded or scanned
    edge) the gun stands off the surface along the turned normal and tilts, so the band
    moves slower than its base there (docs/model.md §26.5): each move is the shortfall over
    the rate seen so far, bisected once the need is bracketed. ``toward`` (±1): once it
    holds, keep moving that way (bisecting, to STEP) while it still holds."""
    axis = np.asarray(strokes.axis, float)
    at, rate, last = 0.0, 1.0, None
    low, high = -math.inf, math.inf  # moves known to need a move up / down
    best = None
    for _ in range(tries):
        gap = _shortfall(robot_band(robot, _moved(cell_robot, at, axis), strokes), need)
        if gap is None:  # the band is too short for the need here
            if not toward or best is None:
                break
            gap = -toward * STEP  # gone too far past the edge: back
        if gap == 0.0:
            best = at
            if not toward:
                break
        if gap > 0 or (gap == 0.0 and toward > 0):
            low = at
        else:
            high = at
        if math.isfinite(low) and math.isfinite(high):
            if high - low <= STEP:
                break
            nxt = (low + high) / 2  # bracketed: bisect
        else:
            if gap == 0.0:  # holds: try as far again the way asked
                gap = math.copysign(max(abs(last[0]) if last else 0.0, 4 * STEP), toward)
            elif last is not None and last[0] and last[1] != gap:
                rate = min(1.0, max(EDGE_RATE, abs(last[1] - gap) / abs(last[0])))
            nxt = at + math.copysign(max(abs(gap / rate), STEP), gap)
        last = (nxt - at, gap)
        at = nxt
    return None if best is None else _moved(cell_robot, best, axis)


def _moved(cell_robot: CellRobot, by: float, axis) -> CellRobot:
    return replace(cell_robot, base=_triple(cell_robot.origin + by * axis))


def cover_edges(robot, robots: tuple[CellRobot, ...], strokes: Strokes,
                needs: list[tuple[float, float]]) -> tuple[tuple[CellRobot, ...], bool]:
    """Each robot moved so that its band holds its zone's need (:func:`cover_edge`; one
    that cannot is left where it was), and whether all do: on a flat part none moves;
    where the strokes bend towards an edge the band lags its base over the whole smoothed
    corner, not only at the outermost robots."""
    moved = [cover_edge(robot, r, strokes, need) for r, need in zip(robots, needs)]
    return (tuple(r if m is None else m for r, m in zip(robots, moved)),
            all(m is not None for m in moved))


def _edge_zones(robot, robots, strokes: Strokes) -> tuple[float, float] | None:
    """The longest first and last zones [m] the end robots' bands hold past the part's
    edges with their run-ons and a seam's run-out (one grid step spare), each robot moved
    onto its edge; None if an edge leaves no zone."""
    lo, hi = strokes.needed(-math.inf, math.inf)
    out = []
    for r, need, low in ((robots[0], (lo, lo + STEP), True),
                         (robots[-1], (hi - STEP, hi), False)):
        at = cover_edge(robot, r, strokes, need, toward=1.0 if low else -1.0)
        if at is None:
            return None
        band = robot_band(robot, at, strokes)
        held = band.holding(lo=lo).hi - lo if low else hi - band.holding(hi=hi).lo
        out.append(held - strokes.run_on - strokes.room - strokes.runout - STEP)
    return None if min(out) <= strokes.runout else (out[0], out[1])


def _check_bounds(robots, spacing: float, source: str) -> None:
    """Refuse, in one line, a layout the job reader would refuse: a base beyond ±MAX_DISTANCE
    in a coordinate (what is proposed must read back as a ``[[robot]]`` table)."""
    for r in robots:
        far = max(abs(c) for c in r.base)
        if far > MAX_DISTANCE:
            raise CellError(f"{source}: {len(robots)} robots {spacing:.3f} m apart along the "
                            f"line put robot {r.name!r} at {far:.3f} m, beyond a base's "
                            f"±{MAX_DISTANCE:g} m: fewer robots or a closer spacing")


def _triple(v) -> tuple[float, float, float]:
    return tuple(round(float(c), 6) + 0.0 for c in v)


__all__ = ["EDGE_RATE", "EDGE_TRIES", "LayoutOptions", "REFERENCE_STROKES", "check_layout_job",
           "cover_edge", "cover_edges", "fewest_for", "narrow_refusal", "propose_layout",
           "reach_window", "reference_band", "zone_needs"]
