"""Which stretch of the part's strokes a cell's robot reaches as the part passes it: its band
along the cell's axis (docs/model.md §26.2).

The strokes are the shared ones of the whole part, across the travel (a panel's raster, a
part's surface passes), each continued straight past its ends at the part's depth (so a band
may run past the part, and a robot above the part is told where it reaches). They are
sampled on a common grid w along the cell's ``axis`` (the aim point's coordinate, world at
t = 0). A robot paints stroke k's stretch [a, b] at one shift x of the part along the line:
every gun pose of it with w in [a, b], moved by x along the line and taken into the robot's
base frame (gun roll referred to the base's own axes, as the planner plans it there), must
pass the workspace map's per-pose rules (``run``'s, docs/model.md §22). The band is the
longest [a, b] that every stroke holds at some shift of its own: the stroke's drift while it
is painted (line speed × its duration, a centimetre or two) is left to the planner, which
checks every sample of the world path.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ...analytic.taskspace import angles_from_rotation
from ...workspace.reach import evaluate
from ..errors import CellError
from ..job import PartJob
from ..line.reach import ball_shift_range
from ..passes.program import gun_frame
from ..passes.raster import spot_runon
from ..passes.surface import EXTENSION, reference_axis
from .robots import CellRobot
from .zones import past_seam

STEP = 0.005  # m between grid points along the axis
SHIFT_STEP = 0.01  # m between the shifts of the part tried along the line
MARGIN = 0.1  # m: the strokes continued this far past the part's extent along the axis
MAX_STROKES = 24  # distinct stroke shapes checked at most (evenly chosen, ends included)
CHUNK = 50_000  # poses per call of the workspace rules
SAME = 1e-6  # m: two strokes the same shape up to a shift along the line


@dataclass(frozen=True, eq=False)
class Strokes:
    """The part's shared strokes seen along the cell's axis (arrays compared by identity).

    ``axis``, ``facing`` and ``direction`` (the line's) are world unit vectors; ``samples``
    holds per stroke (w (K,) increasing, tips (K, 3), spray axes (K, 3)) at its own samples;
    ``extent`` = (lo, hi) the painted faces along the axis [m]; ``run_on`` the free edge's
    run-on [m] (4σ on a panel, 3σ on a part, within a finite spot's reach:
    :func:`.passes.raster.spot_runon`), ``runout`` R = 4σ (so bounded) past a seam;
    ``panel``: the gun's roll referred to base z (a panel's frame), else to
    :func:`.passes.surface.reference_axis` of the facing; ``room`` [m] more held past a free
    edge (a layout's room for the ramps there, docs/model.md §26.5); ``seam_run`` [m] how far
    the strokes run past a seam when the planner says (``PlannerPolicy.seam_run``; None: R)."""

    axis: np.ndarray
    facing: np.ndarray
    direction: np.ndarray
    samples: tuple
    extent: tuple[float, float]
    run_on: float
    runout: float
    panel: bool
    room: float = 0.0
    seam_run: float | None = None

    @property
    def past_seam(self) -> float:
        """The run [m] a robot's strokes make past a seam (:func:`.zones.past_seam`)."""
        return past_seam(self.runout, self.seam_run)

    def needed(self, lo: float, hi: float) -> tuple[float, float]:
        """The stretch of the axis a zone [lo, hi] (±inf: a free edge) needs in reach:
        :attr:`past_seam` past a seam, the run-on (and ``room``) past a free edge."""
        a = self.extent[0] - self.run_on - self.room if lo == -math.inf else lo - self.past_seam
        b = self.extent[1] + self.run_on + self.room if hi == math.inf else hi + self.past_seam
        return a, b

    def grid(self, margin: float = MARGIN, step: float = STEP):
        """(w (M,), tips (S, M, 3), spray (S, M, 3)): every stroke on the common grid over
        the extent ± (run-on + ``margin``), continued straight past its ends."""
        lo, hi = self.extent[0] - self.run_on - margin, self.extent[1] + self.run_on + margin
        w = lo + step * np.arange(int(math.ceil((hi - lo) / step)) + 1)
        tips = np.stack([_along(w, ws, t) for ws, t, _ in self.samples])
        spray = np.stack([_along(w, ws, a, straight=False) for ws, _, a in self.samples])
        spray /= np.linalg.norm(spray, axis=-1, keepdims=True)
        return w, tips, spray


def _along(w, ws, x, straight: bool = True) -> np.ndarray:
    """``x`` (K, 3) sampled at ``ws`` interpolated at ``w``; past the ends continued along
    the end's slope (``straight``) or held."""
    out = np.column_stack([np.interp(w, ws, x[:, i]) for i in range(3)])
    if straight and len(ws) > 1:
        for end, nxt, side in ((0, 1, w < ws[0]), (-1, -2, w > ws[-1])):
            slope = (x[end] - x[nxt]) / (ws[end] - ws[nxt])
            out[side] = x[end] + (w[side] - ws[end])[:, None] * slope
    return out


def cell_axis(facing, direction) -> np.ndarray:
    """The unit axis across the travel in the painted faces' plane: facing × direction, its
    sign making its largest of (z, y, x) components, in that order of preference, > 0."""
    f, e = np.asarray(facing, float), np.asarray(direction, float)
    a = np.array([f[1] * e[2] - f[2] * e[1], f[2] * e[0] - f[0] * e[2],
                  f[0] * e[1] - f[1] * e[0]])
    n = float(np.linalg.norm(a))
    if not n > 1e-9:
        raise CellError(f"the line's direction {tuple(round(float(c), 3) for c in e)} runs "
                        "along the painted faces' facing: the part does not pass the robots "
                        "side on")
    a /= n
    for i in (2, 1, 0):
        if abs(a[i]) > 1e-9:
            return (a if a[i] > 0 else -a) + 0.0  # no -0.0
    return a


def axis_name(axis) -> str:
    """'z' for a world axis (either sign folded by :func:`cell_axis`), else the vector."""
    a = np.asarray(axis, float)
    for i, name in enumerate("xyz"):
        if abs(a[i]) > 1 - 1e-9:
            return name
    return "w along (" + ", ".join(f"{c:.3f}" for c in a) + ")"


def panel_strokes(job) -> Strokes:
    """A panel's raster strokes on the line (:func:`.plan.layout.panel_layout`, run across
    the travel)."""
    from ..line.panel import pass_direction
    from ..plan.layout import panel_layout
    from ..workpiece.panel import panel_frame

    e = np.asarray(job.line.direction, float)
    frame = panel_frame(job)
    horizontal = pass_direction(frame, e)
    lay = panel_layout(replace(job, direction="horizontal" if horizontal else "vertical"))
    ep, es = (frame.u, frame.v) if horizontal else (frame.v, frame.u)
    axis = cell_axis(frame.n, e)
    length = job.width if horizontal else job.height
    corners = frame.world(np.array([-1, 1, 1, -1]) * job.width / 2,
                          np.array([-1, -1, 1, 1]) * job.height / 2) @ axis
    U = np.linspace(-length / 2, length / 2, 3) * (1 if ep @ axis > 0 else -1)
    samples = []
    for o in lay.offsets:
        aim = frame.c + U[:, None] * ep + o * es
        samples.append((aim @ axis, aim + job.standoff * frame.n, np.tile(-frame.n, (3, 1))))
    return Strokes(axis, frame.n.copy(), e, tuple(samples),
                   (float(corners.min()), float(corners.max())),
                   spot_runon(job.sigma, job.spot), spot_runon(job.sigma, job.spot), True)


def part_strokes(job: PartJob, part=None) -> Strokes:
    """A part's surface passes on the line (:func:`.passes.surface.surface_layout`, run
    across the travel); ``part`` its painted mesh if already read."""
    from ..line.part import across_the_travel
    from ..passes.surface import surface_layout
    from ..spray.occlusion import load_painted_part

    part = load_painted_part(job) if part is None else part
    e = np.asarray(job.line.direction, float)
    job_x = replace(job, direction="horizontal" if across_the_travel(part, e) else "vertical")
    layout = surface_layout(part, job_x)
    axis = cell_axis(part.facing, e)
    samples = []
    for p in layout.passes:
        w = p.surface @ axis
        order = np.argsort(w, kind="stable")
        w = np.maximum.accumulate(w[order])  # a stroke bent back along the axis: held
        keep = np.concatenate([[True], np.diff(w) > 1e-9])
        samples.append((w[keep], p.tip[order][keep], p.axis[order][keep]))
    ext = part.vertices[part.faces[part.painted]].reshape(-1, 3) @ axis
    return Strokes(axis, np.asarray(part.facing, float), e, tuple(samples),
                   (float(ext.min()), float(ext.max())),
                   spot_runon(job.sigma, job.spot, EXTENSION), spot_runon(job.sigma, job.spot),
                   False)


def job_strokes(job, part=None, facing=None) -> Strokes:
    """The job's strokes (a panel's or a part's), a part's faces seen from ``facing`` (world;
    None: the job's)."""
    if not isinstance(job, PartJob):
        return panel_strokes(job)
    if facing is not None:
        job, part = replace(job, facing=tuple(float(c) for c in facing)), None
    return part_strokes(job, part)


@dataclass(frozen=True)
class Band:
    """A robot's band: the longest stretch [lo, hi] of the axis [m] (world, the part at
    t = 0) every stroke holds in reach at one shift along the line (empty: lo > hi); the
    ``reached`` stretch, any point of any stroke at any shift (None: none); ``grid`` (w, L):
    the grid and the number of grid points held from each (every stretch it holds, from
    which :meth:`holding` picks; None: only [lo, hi] known)."""

    robot: str
    lo: float
    hi: float
    reached: tuple[float, float] | None
    grid: tuple | None = field(default=None, repr=False, compare=False)

    @property
    def empty(self) -> bool:
        return not self.lo <= self.hi

    @property
    def width(self) -> float:
        return max(0.0, self.hi - self.lo)

    def holds(self, a: float, b: float) -> bool:
        return not self.empty and self.lo <= a and b <= self.hi

    def holding(self, lo: float | None = None, hi: float | None = None) -> Band:
        """The held stretch reaching down to ``lo`` (starting at or below it) and reaching
        furthest up, or reaching up to ``hi`` and starting lowest: on a part whose strokes
        bend at an edge the longest stretch may stop short of the edge while a shorter one
        holds it (docs/model.md §26.2). Self if it already does, or no stretch does."""
        if self.grid is None or self.empty or ((lo is None or self.lo <= lo) and
                                               (hi is None or self.hi >= hi)):
            return self
        w, n = self.grid
        j = np.arange(len(w))
        end = np.where(n > 0, j + n - 1, -1)
        ok = n > 0
        if lo is not None:
            ok &= w <= lo + 1e-9
        if hi is not None:
            ok &= w[np.maximum(end, 0)] >= hi - 1e-9
        if not ok.any():
            return self
        # the furthest end among those starting low enough, then the lowest start for it
        k = int(np.flatnonzero(ok)[0]) if lo is None else \
            int(np.flatnonzero(ok & (end == end[ok].max()))[0])
        return replace(self, lo=float(w[k]), hi=float(w[end[k]]))


def base_poses(cell_robot: CellRobot, tips, spray, panel: bool, facing) -> np.ndarray:
    """Gun poses (..., 6) in the robot's base frame, the roll referred to its own axes."""
    tb = cell_robot.to_base(tips)
    ab = cell_robot.direction_to_base(spray).reshape(-1, 3)
    ref = (0.0, 0.0, 1.0) if panel else reference_axis(cell_robot.direction_to_base(facing))
    ang = angles_from_rotation(gun_frame(ab, ref)).reshape(tb.shape)
    return np.concatenate([tb, ang], axis=-1)


def _shifts(params, tips_b, e_b, step: float = SHIFT_STEP) -> np.ndarray:
    """The shifts along the line (base-frame unit ``e_b``) at which some tip can be in the
    reach ball, ``step`` apart (empty: none)."""
    span = ball_shift_range(params, tips_b, e_b)
    if span is None:
        return np.empty(0)
    a, b = span
    return a + step * np.arange(int((b - a) / step) + 1)


def _runs(ok: np.ndarray) -> np.ndarray:
    """The number of consecutive True from each entry on along the last axis."""
    run = np.zeros(ok.shape, dtype=int)
    nxt = np.zeros(ok.shape[:-1], dtype=int)
    for j in range(ok.shape[-1] - 1, -1, -1):
        nxt = np.where(ok[..., j], nxt + 1, 0)
        run[..., j] = nxt
    return run


def distinct(tips, spray, e, most: int = MAX_STROKES) -> list[int]:
    """Strokes of distinct shape (up to a shift along the line), at most ``most`` of them
    evenly chosen, the first and last kept."""
    e = np.asarray(e, float)
    keys, picked = [], []
    for k in range(len(tips)):
        rel = tips[k] - (tips[k, 0] @ e) * e
        if not any(np.abs(rel - r).max() < SAME and np.abs(spray[k] - s).max() < SAME
                   for r, s in keys):
            keys.append((rel, spray[k]))
            picked.append(k)
    if len(picked) > most:
        picked = [picked[int(i)] for i in np.unique(np.linspace(0, len(picked) - 1,
                                                                most).round())]
    return picked


def robot_band(robot, cell_robot: CellRobot, strokes: Strokes, margin: float = MARGIN,
               step: float = STEP, most: int = MAX_STROKES,
               shift_step: float = SHIFT_STEP) -> Band:
    """The band of ``cell_robot`` (``robot``: the model, its reach rules) over ``strokes``,
    on the grid of :meth:`Strokes.grid` (``margin``, ``step``), at most ``most`` distinct
    strokes checked, the part shifted along the line ``shift_step`` [m] apart (a coarser
    grid: the design's screen, docs/model.md §29.3)."""
    w, tips, spray = strokes.grid(margin, step)
    e_b = cell_robot.direction_to_base(strokes.direction)
    longest = np.full(len(w), np.iinfo(int).max)
    seen = np.zeros(len(w), dtype=bool)
    for k in distinct(tips, spray, strokes.direction, most):
        poses = base_poses(cell_robot, tips[k], spray[k], strokes.panel, strokes.facing)
        xs = _shifts(robot.params, poses[:, :3], e_b, shift_step)
        if not len(xs):
            longest[:] = 0
            continue
        moved = np.repeat(poses[None], len(xs), axis=0)
        moved[..., :3] += xs[:, None, None] * e_b
        flat = moved.reshape(-1, 6)
        ok = np.concatenate([evaluate(robot, flat[i:i + CHUNK])["reachable"] > 0
                             for i in range(0, len(flat), CHUNK)]).reshape(len(xs), len(w))
        seen |= ok.any(axis=0)
        longest = np.minimum(longest, _runs(ok).max(axis=0))
    j = int(np.argmax(longest))
    n = int(longest[j])
    reached = (float(w[seen].min()), float(w[seen].max())) if seen.any() else None
    held = (w, longest)
    if n == 0:
        return Band(cell_robot.name, math.inf, -math.inf, reached, held)
    return Band(cell_robot.name, float(w[j]), float(w[j + n - 1]), reached, held)


__all__ = ["Band", "CHUNK", "MARGIN", "MAX_STROKES", "SHIFT_STEP", "STEP", "Strokes",
           "axis_name", "base_poses", "cell_axis", "distinct", "job_strokes", "panel_strokes",
           "part_strokes", "robot_band"]
