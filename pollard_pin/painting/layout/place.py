"""Where a part fits: the placement (position, and a turn about the facing axis within the
bounds allowed) that puts every gun pose its passes need within reach with the most margin
(docs/model.md §22's reach rule, §23's passes).

    result = pollard_pin.place(robot, pollard_pin.load_job("part.toml"))
    result.job.position, result.turn, result.margin
    result.write("placed.toml")         # a job ``paint`` accepts as is

The gun poses are the passes' own (:func:`.passes.surface.surface_layout`: the tip at the
standoff along the smoothed normal, the run-on past the edges included); moving the part
moves them, its turn changes them. For each turn a coarse grid of positions (``step``) is
checked at a few extreme poses, then at ``samples`` of them; the margin of a position is
its distance to the nearest failing one (a Euclidean distance transform), and the best
position is then centred along each world axis in its reachable interval at ``step``/8.
The turnarounds beyond the run-ons are not checked here: ``paint`` checks them. A job on a
line is placed as if still, across the line: where it starts along the line stays the job's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from scipy import ndimage

from ...analytic.taskspace import angles_from_rotation
from ...checks import file_path, instance, is_real, shorten
from ...errors import InputError
from ...model.build import check_robot
from ...workspace.grid import reachable_box
from ...workspace.options import CHUNK
from ...workspace.reach import evaluate
from ..errors import PlaceError, PlanError
from ..job import PartJob
from ..passes.program import pass_poses
from ..passes.surface import surface_frame, surface_layout
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..workpiece.mesh import MAX_ANGLE, Part, load_job_part, load_part, make_part, placement

# gun poses checked at every coarse position after the extreme ones
SAMPLES = 400
# best grid positions by the extreme poses checked at every sampled pose, at most
VERIFY = 50
# the directions whose extreme tips are checked first (axes, face and body diagonals)
_DIRS = np.array([d for d in np.ndindex(3, 3, 3) if any(d)], dtype=float) - 1.0




@dataclass(frozen=True)
class PlaceOptions:
    """How :func:`~pollard_pin.place` searches, validated once.

    Parameters
    ----------
    step : float, optional
        The coarse grid of positions [m], in [0.001, 0.2] (default 0.02).
    max_turn : float, optional
        Turns about the facing axis tried within ±``max_turn`` [deg], in [0, 180] (default
        90; 0: the job's orientation only).
    turn_step : float, optional
        Every ``turn_step`` degrees, in [1, 180] (default 30).
    samples : int, optional
        The gun poses checked per position, in [20, 100000] (default 400).

    Raises
    ------
    pollard_pin.errors.InputError
        A value that is not a number in its range.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> pp.PlaceOptions(max_turn=60.0).turns         # degrees, the job's own first
    (0.0, 30.0, -30.0, 60.0, -60.0)
    """

    step: float = 0.02
    max_turn: float = 90.0
    turn_step: float = 30.0
    samples: int = SAMPLES

    def __post_init__(self):
        for name, lo, hi in (("step", 1e-3, 0.2), ("max_turn", 0.0, 180.0),
                             ("turn_step", 1.0, 180.0)):
            v = getattr(self, name)
            if not is_real(v, lo, hi):
                raise InputError(f"PlaceOptions.{name} = {shorten(v)}: expected a number in "
                                 f"[{lo:g}, {hi:g}]")
        s = self.samples
        if isinstance(s, bool) or not isinstance(s, int) or not 20 <= s <= 100_000:
            raise InputError(f"PlaceOptions.samples = {shorten(s)}: expected a whole number in "
                             "[20, 100000]")

    @property
    def turns(self) -> tuple[float, ...]:
        """The turns tried [deg], the job's own (0) first, then outwards."""
        k = int(math.floor(self.max_turn / self.turn_step + 1e-9))
        return (0.0, *[s * i * self.turn_step for i in range(1, k + 1) for s in (1, -1)
                       if not (s < 0 and i * self.turn_step >= 180 - 1e-9)])


@dataclass(frozen=True)
class PlaceResult:
    """What :func:`~pollard_pin.place` returns.

    Attributes
    ----------
    job : pollard_pin.painting.job.PartJob
        The placed job (its position and rotation set).
    turn : float
        The turn about the facing axis it took [deg].
    margin : float
        How far the part can move along any world axis before a gun pose leaves the reach
        [m].
    poses : int
        The gun poses checked.
    turns : dict
        Each turn tried [deg] and its coarse margin [m] (negative: none fits).

    ``write(path)`` writes the placed job as TOML (``paint --job`` reads it as is).
    """

    job: PartJob
    turn: float
    margin: float
    poses: int
    turns: dict

    def write(self, path: str | Path) -> Path:
        """Write the placed job as TOML (``paint --job`` reads it as is)."""
        from ...io.job_file import write_job

        return write_job(self.job, file_path(path, "path"), f"placed by pollard-pin place: turned "
                         f"{self.turn:+g}° about the facing axis, margin "
                         f"{self.margin * 1e3:.0f} mm along every axis")


def _turned(job: PartJob, base: Part, turn: float) -> Part:
    """The part turned by ``turn`` degrees about its facing axis through the origin."""
    R = _axis_rotation(np.asarray(base.facing), math.radians(turn))
    return make_part(base.vertices @ R.T, base.faces, base.facing, base.max_angle,
                     base.source, job.unit)


def _axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


def _gun_poses(part: Part, job: PartJob, samples: int, policy: PlannerPolicy):
    """(all poses (N, 6) of the passes at the part's place, the ``samples`` checked, the
    extreme ones checked first)."""
    layout = surface_layout(part, job, policy=policy)
    poses = np.concatenate(pass_poses(layout))
    ends = np.concatenate([[0, len(p.s) - 1] for p in layout.passes])
    starts = np.cumsum([0] + [len(p.s) for p in layout.passes[:-1]])
    ends = (ends.reshape(-1, 2) + starts[:, None]).ravel()
    pick = np.unique(np.concatenate([ends, np.linspace(0, len(poses) - 1, samples).astype(int)]))
    tips = poses[:, :3] @ _DIRS.T
    ang = poses[:, 3:]
    axes = np.flatnonzero(np.abs(_DIRS).sum(1) == 1)
    first = np.unique(tips[:, axes].argmax(0))
    extreme = np.unique(np.concatenate([tips.argmax(0), ang.argmin(0), ang.argmax(0), ends]))
    return poses, poses[pick], (poses[first], poses[extreme])


def _all_reachable(robot, poses: np.ndarray, shifts: np.ndarray) -> np.ndarray:
    """(G,) whether every pose moved by each shift (G, 3) is reachable (run's rules)."""
    ok = np.zeros(len(shifts), dtype=bool)
    per = max(1, CHUNK // len(poses))
    for a in range(0, len(shifts), per):
        s = shifts[a:a + per]
        moved = np.repeat(poses[None], len(s), axis=0)
        moved[..., :3] += s[:, None, :]
        r = evaluate(robot, moved.reshape(-1, 6))["reachable"].reshape(len(s), len(poses))
        ok[a:a + per] = r.all(axis=1)
    return ok


@dataclass(frozen=True)
class _Fit:
    turn: float
    margin: float  # coarse, from the distance transform; −1 where nothing fits
    shift: np.ndarray
    part: Part
    poses: np.ndarray
    checked: np.ndarray


def _coarse(robot, job, part, turn, box, opts: PlaceOptions, policy: PlannerPolicy) -> _Fit:
    """The best grid position of the turned part (its shift from the origin)."""
    poses, checked, extreme = _gun_poses(part, job, opts.samples, policy)
    lo, hi, hb = box
    h = opts.step
    tlo, thi = poses[:, :3].min(0), poses[:, :3].max(0)
    a, b = lo - hb - tlo, hi + hb - thi  # shifts keeping every tip in the reachable box
    if np.any(b < a):
        return _Fit(turn, -1.0, np.zeros(3), part, poses, checked)
    axes = [np.arange(a[k], b[k] + h / 2, h) if b[k] - a[k] >= h else
            np.array([(a[k] + b[k]) / 2]) for k in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    shifts = grid.reshape(-1, 3)
    ok = np.ones(len(shifts), dtype=bool)
    for stage in extreme:  # the few extreme poses first: most shifts fail there
        ok[ok] = _all_reachable(robot, stage, shifts[ok])
    for _ in range(VERIFY):  # the best by the extremes, checked at every sampled pose
        if not ok.any():
            break
        dist = ndimage.distance_transform_edt(np.pad(ok.reshape(grid.shape[:3]), 1))
        dist = dist[1:-1, 1:-1, 1:-1].ravel() * h
        best = np.flatnonzero(dist >= dist.max() - 1e-12)
        centre = shifts[ok].mean(0)  # of equals, the nearest the region's centre
        k = best[np.argmin(np.linalg.norm(shifts[best] - centre, axis=1))]
        if _all_reachable(robot, checked, shifts[k:k + 1])[0]:
            return _Fit(turn, float(dist[k]), shifts[k], part, poses, checked)
        ok[k] = False
    return _Fit(turn, -1.0, np.zeros(3), part, poses, checked)


def _centre(robot, fit: _Fit, opts: PlaceOptions, rounds: int = 2):
    """The shift centred along each world axis in its reachable interval, and the margin:
    the least half-width of those intervals [m]."""
    shift = fit.shift.copy()
    half = np.zeros(3)
    for _ in range(rounds):
        for k in range(3):
            lo, hi = (_travel(robot, fit.checked, shift, k, s, fit.margin + 2 * opts.step,
                              opts.step / 8) for s in (-1.0, 1.0))
            shift[k] += (hi - lo) / 2
            half[k] = (hi + lo) / 2
    return shift, float(half.min())


def _travel(robot, poses, shift, axis: int, sign: float, reach: float, tol: float) -> float:
    """How far [m] the part moves from ``shift`` along ``sign``·e_axis before a pose leaves
    the reach (scanned every 4 ``tol``, then bisected to ``tol``; at most ``reach``)."""
    d = np.arange(0.0, reach + 1e-12, 4 * tol)
    trial = np.repeat(shift[None], len(d), axis=0)
    trial[:, axis] += sign * d
    ok = _all_reachable(robot, poses, trial)
    if ok.all():
        return float(d[-1])
    k = int(np.argmin(ok))
    if k == 0:
        return 0.0
    lo, hi = d[k - 1], d[k]
    while hi - lo > tol:
        mid = (lo + hi) / 2
        trial = shift.copy()
        trial[axis] += sign * mid
        lo, hi = (mid, hi) if _all_reachable(robot, poses, trial[None])[0] else (lo, mid)
    return float(lo)


def place(robot, job: PartJob, options: PlaceOptions | None = None,
          policy: PlannerPolicy = DEFAULT_POLICY) -> PlaceResult:
    """The placement of the job's part with the most margin: the position, and a turn about
    the facing axis, that puts every gun pose of the part's passes (run-ons included) within
    reach with the most margin. What ``pollard-pin place`` does.

    Parameters
    ----------
    robot : Robot
        The model.
    job : pollard_pin.painting.job.PartJob
        A part's job (:func:`~pollard_pin.load_job` on a job with ``[part]``).
    options : PlaceOptions or None, optional
        The search's grid, turns and samples.
    policy : pollard_pin.painting.policy.PlannerPolicy, optional
        The planners' knobs: the passes' budget (default the planners' own).

    Returns
    -------
    PlaceResult
        The placed job, its turn [deg] and margin [m]; ``.write(path)`` writes the job.

    Raises
    ------
    PlaceError
        Nothing fits: the message says by how much the part misses (taller or wider than the
        reach).
    pollard_pin.errors.InputError
        A job that is not a part's, options of the wrong type.
    """
    check_robot(robot)
    instance(job, "job", PartJob, "a part's job (PartJob, from load_job on a job with [part])")
    opts = PlaceOptions() if options is None else options
    instance(opts, "options", PlaceOptions, "PlaceOptions or None")
    instance(policy, "policy", PlannerPolicy, "PlannerPolicy")
    base = load_part(job.mesh, job.unit, (0.0, 0.0, 0.0), job.rotation, job.facing,
                     MAX_ANGLE if job.max_angle is None else job.max_angle)
    first = _turned(job, base, 0.0)
    poses0 = np.concatenate(pass_poses(surface_layout(first, job, policy=policy)))
    orient = np.median(poses0[:, 3:], axis=0)
    box = reachable_box(robot, orient)
    if box is None:
        raise PlaceError(f"{job.source}: no tool position is reachable with the gun along the "
                         "part's facing axis: a part facing the robot (part.facing)?")
    fits = [_coarse(robot, job, first, 0.0, box, opts, policy)]
    for t in opts.turns[1:]:
        try:
            fits.append(_coarse(robot, job, _turned(job, base, t), t, box, opts, policy))
        except PlanError:  # passes the gun cannot follow at this turn: not a candidate
            continue
    top = max(f.margin for f in fits)
    if top < 0:
        raise PlaceError(f"{job.source}: {_missed(robot, fits[0], orient, box, len(fits))}")
    # the coarse margin ranks the turns to a step; those within one of the best are refined
    # and the refined margin decides (to half a centring tolerance, the smaller turn first)
    near = [(f, *_centre(robot, f, opts)) for f in fits if f.margin >= top - opts.step]
    best, shift, margin = max(near, key=lambda c: (round(c[2] / opts.step * 16),
                                                   -abs(c[0].turn)))
    R = _axis_rotation(np.asarray(base.facing), math.radians(best.turn))
    rotation = _rotation_angles(R @ placement((0, 0, 0), job.rotation, job.source)[0])
    if job.line is not None:  # on a line: where it starts along the line stays the job's
        d = np.asarray(job.line.direction, dtype=float)
        d /= np.linalg.norm(d)
        shift = shift + (np.dot(job.position, d) - np.dot(shift, d)) * d
    placed = replace(job, position=tuple(round(float(x), 6) + 0.0 for x in shift),
                     rotation=rotation)
    return PlaceResult(placed, best.turn, margin, len(best.checked),
                       {f.turn: f.margin for f in fits})


def _rotation_angles(R: np.ndarray) -> tuple[float, float, float]:
    """(rx, ry, rz) [deg] of R = Rx·Ry·Rz (:func:`.workpiece.mesh.placement`); at ry = ±90°
    (the gimbal lock of a part turned to face the robot) rz = 0 and rx takes the rest."""
    a = angles_from_rotation(R)  # (ψ, θ, φ) of Rx(θ)·Ry(ψ)·Rz(φ)
    rot = tuple(round(math.degrees(float(x)), 9) + 0.0 for x in (a[1], a[0], a[2]))
    if np.abs(placement((0, 0, 0), rot)[0] - R).max() > 1e-9:
        rx = math.degrees(math.atan2(R[2, 1], R[1, 1]))  # R·e_y = Rx(rx)·e_y when rz = 0
        rot = (round(rx, 9) + 0.0, rot[1], 0.0)
    return rot


def _runs(mask: np.ndarray, axis: int) -> int:
    """The longest run of True along ``axis`` of a 2-D mask (cells)."""
    m = np.moveaxis(mask, axis, 0).astype(int)
    run = np.zeros(m.shape[1], dtype=int)
    best = 0
    for row in m:
        run = (run + 1) * row
        best = max(best, int(run.max()))
    return best


def _missed(robot, fit: _Fit, orient, box, turns: int) -> str:
    """How the part misses: the rectangle of its passes' tips (run-ons included) against
    the plane maps at the median orientation, every 3 cm of depth: taller than the tallest
    reachable rectangle of its width, wider than the widest of its height (the smaller
    first); a side longer than the reach's longest extent along it (at any depth, any extent
    across) is said alone, by how much it exceeds that extent, since no change of the other
    side makes it fit; where it fits as a rectangle, the gun's tilt is what fails."""
    frame = surface_frame(fit.part)
    u, v, n = frame.along, frame.across, frame.n
    tips = fit.poses[:, :3]
    height, width = np.ptp(tips @ v), np.ptp(tips @ u)
    h = 0.01
    best = (0, 0)  # the tallest reachable rectangle at the passes' width, the widest at
    # their height (cells), over the depths
    most = (0, 0)  # the reach's tallest and widest runs at any extent across (cells)
    wc, hc = (max(1, math.ceil(x / h - 1e-9)) for x in (width, height))
    lo, hi, hb = box  # the reachable box's corners in the frame (u, v, n) bound the scan
    corners = np.array([[(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]]
                        for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    span = [(float((corners @ e).min()) - hb, float((corners @ e).max()) + hb) for e in (u, v, n)]
    gu, gv = (np.arange(a, b + h / 2, h) for a, b in span[:2])
    for depth in np.arange(span[2][0], span[2][1] + h / 2, 3 * h):
        pts = depth * n + gu[:, None, None] * u + gv[None, :, None] * v
        poses = np.concatenate([pts.reshape(-1, 3), np.broadcast_to(orient, (pts.size // 3, 3))],
                               axis=1)
        ok = evaluate(robot, poses)["reachable"].reshape(len(gu), len(gv)) > 0
        if ok.any():
            tall_at_w = _runs(ndimage.binary_erosion(ok, np.ones((wc, 1), bool)), 1)
            wide_at_h = _runs(ndimage.binary_erosion(ok, np.ones((1, hc), bool)), 0)
            best = (max(best[0], tall_at_w), max(best[1], wide_at_h))
            most = (max(most[0], _runs(ok, 1)), max(most[1], _runs(ok, 0)))
    tall, wide = height - best[0] * h, width - best[1] * h
    turned = f" at any of {turns} turns" if turns > 1 else ""
    alone = [(x, what) for x, what in ((height - most[0] * h, "taller"),
                                       (width - most[1] * h, "wider")) if x > 0]
    if alone:  # a side longer than the reach along it: only shortening that side helps
        said = " and ".join(f"{what} than the reach{turned} by {x * 1e3:.0f} mm" if i == 0 else
                            f"{what} by {x * 1e3:.0f} mm" for i, (x, what) in enumerate(alone))
        return (f"the part is {said} (passes {width:.3f} × {height:.3f} m, reach at most "
                f"{most[1] * h:.2f} × {most[0] * h:.2f} m): a line or a cell of robots would "
                "paint it")
    if tall > 0 and wide > 0:  # the passes' rectangle fits at no depth
        (x, what), (y, other) = sorted([(tall, "taller"), (wide, "wider")])
        return (f"the part is {what} than the reach{turned} by {x * 1e3:.0f} mm "
                f"(or {other} by {y * 1e3:.0f} mm; passes {width:.3f} × "
                f"{height:.3f} m): a line or a cell of robots would paint it")
    return (f"no position{turned} reaches every gun pose of the passes "
            f"({width:.3f} × {height:.3f} m; reach {best[1] * h:.2f} × {best[0] * h:.2f} m "
            "with the gun level): the gun tilts too far on the curves; a flatter part or a "
            "line")


def reach_hint(robot, job: PartJob, paints=None,
               policy: PlannerPolicy = DEFAULT_POLICY) -> str:
    """What would bring a still part whose passes leave the reach within it: vertical passes
    where they reach as placed (and ``paints(vertical job)`` is true: the whole program
    holds), else the move to :func:`place`'s placement, else by how much the part misses
    (taller or wider than the reach); ``policy`` the planner's."""
    if job.direction == "horizontal":
        vertical = replace(job, direction="vertical")
        part = load_job_part(job)
        try:
            poses = np.concatenate(pass_poses(surface_layout(part, vertical, policy=policy)))
        except PlanError:
            poses = None
        if (poses is not None and evaluate(robot, poses)["reachable"].all()
                and (paints is None or paints(vertical))):
            return 'direction = "vertical" paints it as placed'
    try:
        r = place(robot, job, PlaceOptions(max_turn=0.0), policy)
    except PlaceError as exc:
        return str(exc).split(": ", 1)[1]
    except PlanError:
        return "pollard-pin place may find where it fits"
    d = np.subtract(r.job.position, job.position)
    return (f"move the part by ({d[0]:+.3f}, {d[1]:+.3f}, {d[2]:+.3f}) m ({r.margin * 1e3:.0f} "
            "mm of margin; pollard-pin place writes that job)")


__all__ = ["SAMPLES", "PlaceOptions", "PlaceResult", "place", "reach_hint"]
