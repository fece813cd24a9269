"""The cell's clearance along its one clock: every pair of robots, and every robot against
the moving part (docs/model.md §26.4).

Each robot is its capsules (:mod:`...kinematics.capsules`: the links' collision and visual
shapes, the gun's body among them) at the configurations of its tool poses (the package's
batch IK under ``run``'s rules), carried to the world by its base (:class:`.robots.CellRobot`).

- **Robots.** The pairs are compared on the union of the robots' sample times; between its
  own samples a robot's capsule ends move along straight chords (linear interpolation, the
  approximation the gun's check makes: an arc is its chord, second order in the step). Two
  capsules are apart by the distance of their axis segments less both radii
  (:func:`...kinematics.capsules.segment_distance`). Only the capsule pairs whose bounding
  spheres (the segment's midpoint, half its length plus r) come within the best distance
  found so far get the exact distance. Between the coarse samples a sample, or a capsule
  pair there, that the way its capsules travelled proves farther than the least is not
  measured (:func:`.clearance.may_come_within`): the same answer, to the bit.
- **The part.** The part's mesh (world at t = 0) rides the line, at ``velocity``·t. Each
  robot's capsules, in the part's frame, are covered by spheres along their axes (the gun
  body's rule) and measured against the mesh by :func:`.clearance.least_distance`:
  first the gun's capsules, whose least distance is a ceiling; then only the spheres whose
  distance to the mesh's bounding box may beat it.
- **Between samples** a point of a robot moves at most its step's chord (relative to the
  other robot's point, or to the part); a distance can fall by at most half the sum of both
  chords within a step (``between`` in the result). A layout is refused when the least
  distance less that bound is under ``required``.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...errors import InputError
from ...kinematics.capsules import axis_spheres, capsule_layout, link_capsules, segment_distance
from ..cell.robots import CellRobot
from ..errors import ClearanceError
from ..spray.gun_body import AXIS_STEP
from .clearance import SLACK, least_distance, may_come_within, surface_index, travelled
from .spheres import CapsuleSpheres

if TYPE_CHECKING:  # trimesh (with scipy, networkx) loads where a mesh is made: not for `run`
    import trimesh

CHUNK = 4096  # samples a block of the pairwise distances (≈ 40 MB at 25 capsules)
COARSE = 16  # every this many samples, every capsule pair sets the ceiling (and wins a tie)
FIRST = 64  # with steps: every this many samples measured first, every capsule pair
LEVELS = (32, 16, 8, 4, 2, 1)  # the spacings measured in turn between those
PAIRS = 1 << 18  # capsule pairs measured at a time between the coarse samples (≈ 60 MB)
BLOCK = 2048  # samples a block of the distances to the part (their arrays stay in cache)


@dataclass(frozen=True)
class MovingPart:
    """The part in the world, for :func:`cell_clearance` (docs/model.md §26.4).

    Attributes
    ----------
    mesh : trimesh.Trimesh
        The part's mesh in the world at t = 0 [m].
    velocity : tuple of float
        Its velocity [m/s], world axes: the line's speed times its direction (default still).
    """

    mesh: trimesh.Trimesh
    velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class CellClearance:
    """The least distances of a cell along its clock (docs/model.md §26.4).

    Attributes
    ----------
    between_robots : float
        The least distance [m] between two robots' links (inf with one robot).
    pair : tuple of str or None
        The two robots' names at that distance (None with one robot).
    pair_time : float or None
        When [s, the cell's clock].
    robots_between : float
        How much closer [m] two robots may come between samples (a bound).
    to_part : float or None
        The least distance [m] from a robot's links to the part (None without a part).
    robot : str or None
        That robot's name.
    part_time : float or None
        When [s].
    part_between : float or None
        How much closer [m] a robot may come to the part between samples.
    required : float
        The clearance asked for [m].
    """

    between_robots: float
    pair: tuple[str, str] | None
    pair_time: float | None
    robots_between: float
    to_part: float | None
    robot: str | None
    part_time: float | None
    part_between: float | None
    required: float

    def to_dict(self) -> dict:
        finite = math.isfinite(self.between_robots)
        return {"between_robots_m": self.between_robots if finite else None,
                "pair": list(self.pair) if self.pair else None, "pair_at_s": self.pair_time,
                "robots_between_samples_m": self.robots_between if finite else None,
                "to_part_m": self.to_part, "robot": self.robot, "robot_at_s": self.part_time,
                "part_between_samples_m": self.part_between, "required_m": self.required}


@dataclass(frozen=True, eq=False)
class _Sampled:
    """A member's capsules in the world at its own times."""

    name: str
    t: np.ndarray  # (N,)
    a: np.ndarray  # (N, L, 3)
    b: np.ndarray


def _checked(member, i: int) -> tuple[CellRobot, np.ndarray, np.ndarray]:
    try:
        cell_robot, t, poses = member
    except (TypeError, ValueError):
        raise InputError(f"member {i}: expected (CellRobot, t (N,), poses (N, 6))") from None
    if not isinstance(cell_robot, CellRobot):
        raise InputError(f"member {i}: {type(cell_robot).__name__}, not a CellRobot")
    t, poses = np.asarray(t, float), np.asarray(poses, float)
    who = f"robot {cell_robot.name!r}"
    if t.ndim != 1 or len(t) == 0 or poses.shape != (len(t), 6):
        raise InputError(f"{who}: times {t.shape} and poses {poses.shape}: expected (N,) and "
                         "(N, 6), N ≥ 1")
    if not (np.isfinite(t).all() and np.isfinite(poses).all()):
        raise InputError(f"{who}: a time or pose is not finite")
    if (np.diff(t) <= 0).any():
        k = int(np.argmax(np.diff(t) <= 0)) + 1
        raise InputError(f"{who}: t[{k}] = {t[k]:.6g} s does not follow t[{k - 1}] = "
                         f"{t[k - 1]:.6g} s: times must increase")
    return cell_robot, t, poses


def _sample(robot, layout, member, i: int, margins) -> _Sampled:
    from ..errors import ReachError
    from .motion import reach

    cell_robot, t, poses = _checked(member, i)
    try:
        q = reach(robot, poses, margins=margins).q
    except ReachError as exc:
        raise ReachError(f"robot {cell_robot.name!r}: {exc}", exc.sample, exc.pose) from None
    a, b, _ = link_capsules(robot, q, layout)
    return _Sampled(cell_robot.name, t, cell_robot.to_world(a), cell_robot.to_world(b))


def _at(s: _Sampled, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The capsule ends at times ``u``: linear between the member's samples, held outside."""
    if len(s.t) == 1:
        return (np.broadcast_to(s.a, (len(u), *s.a.shape[1:])),
                np.broadcast_to(s.b, (len(u), *s.b.shape[1:])))
    k = np.clip(np.searchsorted(s.t, u, side="right") - 1, 0, len(s.t) - 2)
    w = np.clip((u - s.t[k]) / (s.t[k + 1] - s.t[k]), 0.0, 1.0)[:, None, None]
    return ((1 - w) * s.a[k] + w * s.a[k + 1], (1 - w) * s.b[k] + w * s.b[k + 1])


def _chords(a, b, shift=None) -> np.ndarray:
    """The largest displacement of a capsule point per step (N − 1,): at one of its ends
    (a point's displacement is affine along the segment); ``shift`` (N − 1, 3) is taken
    off each (a moving frame's own step)."""
    da, db = np.diff(a, axis=0), np.diff(b, axis=0)
    if shift is not None:
        da, db = da - shift[:, None], db - shift[:, None]
    return np.maximum(_norm(da), _norm(db)).max(axis=1)


def pair_distance(a1, b1, a2, b2, r1, r2, steps=None,
                  below: float = math.inf) -> tuple[float, int]:
    """The least distance [m] between two robots' capsules over the samples (ends (N, L, 3)
    each, radii (L,)) and its sample. Every pair at every COARSE-th sample sets a ceiling;
    then only the pairs of capsules whose bounding boxes come within it of the other robot's
    (the union of its capsules' boxes) are measured. ``steps`` (N − 1,): how far the two
    robots' points may move apart or together in each step (the sum of both robots' largest
    step, :func:`_chords`), to measure every pair at every FIRST-th sample only and the
    samples between at halving spacings (LEVELS), only those the way travelled from the
    samples measured cannot prove beyond the least so far (or ``below``), there only the
    capsule pairs it cannot prove so (:func:`_pairs_least`, instead of the boxes), and not a
    sample the same as the one before (:func:`_skipping`; default None: every sample); the
    answer is the same either way (docs/model.md §26.4).
    ``below``: only a least under it is sought (default inf); with none, a distance found,
    at least ``below``, and its sample."""
    rr = r1[:, None] + r2[None, :]
    ends = (a1, b1, a2, b2, r1, r2, rr)
    if steps is None:
        best, where, known = _coarse(a1[::COARSE], b1[::COARSE], a2[::COARSE], b2[::COARSE],
                                     r1, r2)
        ceiling, where = best, where * COARSE
        least = _row_least(ends, np.arange(len(a1)), max(best, 0.0))
        if least.min() < ceiling:  # else the coarse samples' first least
            best = float(least.min())
            where = int(np.flatnonzero(least == least.min()).min())
        return best, where
    return _skipping(ends, steps, below)


def _skipping(ends, steps, below: float) -> tuple[float, int]:
    """:func:`pair_distance` with ``steps`` (docs/model.md §26.4). Named: the first COARSE-th
    sample at the least, else the first sample there, as with every sample measured."""
    a1, b1, a2, b2, r1, r2, _ = ends
    best, _, known = _coarse(a1[::FIRST], b1[::FIRST], a2[::FIRST], b2[::FIRST], r1, r2)
    way = travelled(steps)
    # a sample the same as the one before measures the same: not the first least (a COARSE-th
    # is measured all the same: it wins a tie)
    fresh = np.concatenate([[True], np.asarray(steps) > 0])
    fresh[::COARSE] = True
    at, low = np.arange(0, len(a1), FIRST), known.min(axis=(1, 2))
    # `low` is a FIRST-th sample's exact least where that is the least (a pair not measured
    # lies farther than one measured)
    done = [(at, low)]
    for spacing in LEVELS:
        rows = np.arange(spacing, len(a1), 2 * spacing)
        rows = rows[fresh[rows]]
        # a sample left out is further than the least so far: not the least
        limit = min(best, below)
        rows = rows[may_come_within(low, at, way, limit, rows)]
        if len(rows) == 0:
            continue
        least = _pairs_least(ends, rows, known, way, limit)
        best = min(best, float(least.min()))
        done.append((rows, least))
        # a pair not measured is further than the limit
        order = np.argsort(np.concatenate([at, rows]), kind="stable")
        at = np.concatenate([at, rows])[order]
        low = np.concatenate([low, np.minimum(least, limit)])[order]
    rows = np.concatenate([r for r, _ in done])
    held = rows[np.concatenate([d for _, d in done]) == best]
    grid = held[held % COARSE == 0]
    return best, int(grid.min() if len(grid) else held.min())


def _pairs_least(ends, rows, known, way, limit: float) -> np.ndarray:
    """The least distance between the two robots at each sample of ``rows`` (R,), none a
    coarse sample, over the capsule pairs that may come within ``limit`` there (inf where
    none may): a pair's distance falls by at most the way between the coarse samples around
    it, so a pair whose lower bounds ``known`` (M, L1, L2) at both, less that way, are past
    the limit is not measured in between (docs/model.md §26.4). Exact where under the
    limit; ``ends`` (a1, b1, a2, b2, r1, r2, r1 + r2 of each pair). Taken about PAIRS
    capsule pairs at a time."""
    a1, b1, a2, b2, _, _, rr = ends
    start = np.arange(len(known)) * FIRST
    stop = np.minimum(start + FIRST, len(way) - 1)  # the next coarse sample, or the last
    bound = known.copy()  # a pair's least lower bound at the two coarse samples
    bound[:-1] = np.maximum(known[:-1], known[1:])
    may = bound - (way[stop] - way[start])[:, None, None] <= limit + SLACK
    p, i, j = np.nonzero(may)  # the pairs of each interval, in its order
    counts = np.bincount(p, minlength=len(known))
    first = np.cumsum(counts) - counts
    per = counts[rows // FIRST]  # each row's pairs
    out = np.full(len(rows), np.inf)
    cuts = np.searchsorted(np.cumsum(per), np.arange(PAIRS, per.sum(), PAIRS))
    for lo, hi in zip(np.r_[0, cuts], np.r_[cuts, len(rows)]):
        c = per[lo:hi]
        row = np.repeat(np.arange(lo, hi), c)
        k = _ranges(first[rows[lo:hi] // FIRST], c)
        n, ii, jj = rows[row], i[k], j[k]
        np.minimum.at(out, row, segment_distance(a1[n, ii], b1[n, ii], a2[n, jj], b2[n, jj])
                      - rr[ii, jj])
    return out


def _row_least(ends, rows, cut: float) -> np.ndarray:
    """The least distance between the two robots at each sample of ``rows`` (R,) over the
    capsule pairs whose bounding boxes come within ``cut`` of the other robot's (inf where
    none does); ``ends`` (a1, b1, a2, b2, r1, r2, r1 + r2 of each pair). Taken CHUNK samples
    at a time."""
    a1, b1, a2, b2, r1, r2, rr = ends
    out = np.full(len(rows), np.inf)
    for lo in range(0, len(rows), CHUNK):
        k = rows[lo:lo + CHUNK]
        e1, f1, e2, f2 = a1[k], b1[k], a2[k], b2[k]
        (lo1, hi1), (lo2, hi2) = _boxes(e1, f1, r1), _boxes(e2, f2, r2)
        # boxes apart by g hold capsules at least g apart; capsules that cut into each
        # other (best < 0) have touching boxes (g = 0)
        near1 = _box_gap(lo1, hi1, *_union(lo2, hi2)) <= cut
        near2 = _box_gap(lo2, hi2, *_union(lo1, hi1)) <= cut
        n, i, j = _pairs(near1, near2)
        if len(n):
            np.minimum.at(out, lo + n, segment_distance(e1[n, i], f1[n, i], e2[n, j],
                                                        f2[n, j]) - rr[i, j])
    return out


def _pairs(near1, near2) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(n, i, j): every capsule i of near1 (N, L1) with every j of near2 (N, L2) at each
    sample n, in the order of ``np.nonzero(near1[:, :, None] & near2[:, None, :])``, built
    from the two lists alone (not the N × L1 × L2 array)."""
    n1, i1 = np.nonzero(near1)
    n2, j2 = np.nonzero(near2)
    counts = np.bincount(n2, minlength=len(near2))
    rep = counts[n1]  # each (n, i) with every j of its sample
    start = np.cumsum(counts) - counts  # where each sample's j's begin in j2
    return np.repeat(n1, rep), np.repeat(i1, rep), j2[_ranges(start[n1], rep)]


def _ranges(starts, counts) -> np.ndarray:
    """The ranges starts[m] … starts[m] + counts[m] − 1 one after another (integers)."""
    return np.repeat(starts, counts) + np.arange(counts.sum()) - np.repeat(
        np.cumsum(counts) - counts, counts)


def _coarse(a1, b1, a2, b2, r1, r2) -> tuple[float, int, np.ndarray]:
    """(the least distance between two robots' capsules over the samples (ends (M, L, 3)
    each), the first sample where it lies, a lower bound (M, L1, L2) of each pair's). Only the
    capsule pairs whose bounding spheres (the segment's midpoint, half its length plus r)
    may come within the best of each sample's closest pair of spheres are measured: a pair
    left out lies farther apart than one measured, so neither the least nor its first sample
    changes; its spheres' gap bounds its distance below."""
    rr = r1[:, None] + r2[None, :]
    c1, c2 = (a1 + b1) / 2, (a2 + b2) / 2
    h1 = _norm(b1 - a1) / 2 + r1
    h2 = _norm(b2 - a2) / 2 + r2
    gap = _norm(c1[:, :, None] - c2[:, None]) - h1[:, :, None] - h2[:, None]
    # the closest spheres' capsules of each sample: an achieved distance, a ceiling
    m = np.arange(len(gap))
    i, j = np.unravel_index(gap.reshape(len(gap), -1).argmin(axis=1), gap.shape[1:])
    ceiling = float((segment_distance(a1[m, i], b1[m, i], a2[m, j], b2[m, j])
                     - rr[i, j]).min())
    # round-off (~1e-16 m) kept far below the margin; a pair cutting in (gap ≤ 0) kept
    measured = gap <= max(ceiling, 0.0) + 1e-9
    n, i, j = np.nonzero(measured)
    d = segment_distance(a1[n, i], b1[n, i], a2[n, j], b2[n, j]) - rr[i, j]
    k = int(np.argmin(d))  # n ascends: the first sample of the least
    known = np.where(measured, np.inf, gap)
    known[n, i, j] = d
    return float(d[k]), int(n[k]), known


def _boxes(a, b, r) -> tuple[np.ndarray, np.ndarray]:
    """Each capsule's bounding box: its lower and upper corners (N, L, 3) each."""
    return np.minimum(a, b) - r[:, None], np.maximum(a, b) + r[:, None]


def _box_gap(lower, upper, lo, hi) -> np.ndarray:
    """The distance (N, L) of each box (corners ``lower``, ``upper``) from the box lo–hi of
    its sample (each (N, 3))."""
    out = np.maximum(np.maximum(lo[:, None] - upper, lower - hi[:, None]), 0)
    return _norm(out)


def _union(lower, upper) -> tuple[np.ndarray, np.ndarray]:
    """The box (N, 3) corners holding every box (N, L, 3) of a sample: min and max over L,
    taken capsule by capsule (exact, and faster than a reduction over the middle axis)."""
    lo, hi = lower[:, 0].copy(), upper[:, 0].copy()
    for k in range(1, lower.shape[1]):
        np.minimum(lo, lower[:, k], out=lo)
        np.maximum(hi, upper[:, k], out=hi)
    return lo, hi


def _norm(x) -> np.ndarray:
    """|x| over the last axis (of 3): numpy's norm, summed as it sums, (x₀² + x₁²) + x₂², to
    the bit, without a reduction over an axis of three."""
    s = x * x
    return np.sqrt((s[..., 0] + s[..., 1]) + s[..., 2])


def _robots(members: Sequence[_Sampled], r: np.ndarray):
    """(distance, pair, time, between) of the closest pair on the union of times, taken
    CHUNK times at a time (each block overlaps the last by one: the step between them)."""
    if len(members) < 2:
        return math.inf, None, None, 0.0
    u = np.unique(np.concatenate([m.t for m in members]))
    pairs = [(i, j) for i in range(len(members)) for j in range(i + 1, len(members))]
    least = {p: (math.inf, 0.0) for p in pairs}
    between = dict.fromkeys(pairs, 0.0)
    for lo in range(0, len(u), CHUNK):
        uu = u[max(lo - 1, 0):lo + CHUNK]
        ends = [_at(m, uu) for m in members]
        chords = [_chords(a, b) for a, b in ends]
        for i, j in pairs:
            d, k = pair_distance(*ends[i], *ends[j], r, r, chords[i] + chords[j],
                                 least[i, j][0])  # a least not under the last: no use
            if d < least[i, j][0]:
                least[i, j] = (d, float(uu[k]))
            if len(uu) > 1:
                between[i, j] = max(between[i, j], float((chords[i] + chords[j]).max()) / 2)
    i, j = min(pairs, key=lambda p: least[p][0] - between[p])
    return least[i, j][0], (members[i].name, members[j].name), least[i, j][1], between[i, j]


def _to_part(s: _Sampled, layout, part: MovingPart, index):
    """(distance, time, between) of one robot against the moving part (taken BLOCK samples
    at a time: every quantity is a sample's own, so the blocks only keep the arrays small);
    ``index``: the part's mesh's :class:`.clearance.SurfaceIndex`, made once for all."""
    v = np.asarray(part.velocity, float)
    gun, others = np.flatnonzero(layout.gun), np.flatnonzero(~layout.gun)
    owner, _, radii = axis_spheres(layout.a[others], layout.b[others], layout.r[others],
                                   AXIS_STEP)
    rho = np.zeros(len(others))
    np.maximum.at(rho, owner, radii)  # each capsule's largest sphere
    lo, hi = part.mesh.bounds  # a sphere's distance from the box: a lower bound
    centres, lower, chords = [], [], []
    for start in range(0, len(s.t), BLOCK):
        a, b = _in_part(s, v, slice(start, start + BLOCK))  # in the part's frame at t = 0
        guns = CapsuleSpheres.of(a, b, layout, gun)
        centres.append(guns[:])
        ao, bo = a[:, others], b[:, others]
        mid = (ao + bo) / 2
        lower.append(_norm(mid - np.clip(mid, lo, hi)) - rho - _norm(bo - ao) / 2)
        if start:  # the step from the last block's last sample
            a0, b0 = _in_part(s, v, slice(start - 1, start))
            a, b = np.concatenate([a0, a]), np.concatenate([b0, b])
        if len(a) > 1:
            chords.append(_chords(a, b))
    steps = np.concatenate(chords) if chords else np.zeros(0)
    way = travelled(steps)  # a sphere's step is at most its capsule's chord (in the part)
    best, (n, _), _, less = least_distance(part.mesh, np.concatenate(centres), guns.radii,
                                           index, way)
    near = np.concatenate(lower) < best
    rows, caps = np.flatnonzero(near.any(axis=1)), others[near.any(axis=0)]
    if len(rows):
        far = CapsuleSpheres.of(*_in_part(s, v, rows), layout, caps)  # made where asked
        d, (k, _), _, l2 = least_distance(part.mesh, far, far.radii, index, way[rows])
        if d < best:
            best, n, less = d, int(rows[k]), l2
    between = float(steps.max()) / 2 if len(s.t) > 1 else 0.0
    return best, float(s.t[n]), less + between


def _in_part(s: _Sampled, v: np.ndarray, rows):
    """The capsule ends of samples ``rows`` in the part's frame at t = 0 (less its travel)."""
    shift = s.t[rows, None] * v
    return s.a[rows] - shift[:, None], s.b[rows] - shift[:, None]


def cell_clearance(robot, members, part: MovingPart | None = None, required: float = 0.0,
                   margins=None) -> CellClearance:
    """The least distances between a cell's robots and from them to the part, checked on the
    links' capsules along the common clock (docs/model.md §26.4).

    Parameters
    ----------
    robot : Robot
        The model every robot shares (:func:`pollard_pin.load`).
    members : Sequence of tuple
        One ``(CellRobot, t, poses)`` per robot: its
        :class:`~pollard_pin.painting.cell.robots.CellRobot`, the times t (N,) [s] on the
        cell's clock and the tool poses (N, 6) [m, rad] in its base frame.
    part : MovingPart or None, optional
        The moving part (default None: the robots only).
    required : float, optional
        The least distance allowed [m] (default 0).
    margins : Margins or None, optional
        The IK's margins (default ``run``'s).

    Returns
    -------
    CellClearance
        The least distances, who and when.

    Raises
    ------
    pollard_pin.painting.errors.ClearanceError
        One line naming the two robots (or the robot and the part), the time and the
        distance, when a distance less what may lie between samples is under ``required``.
    """
    if isinstance(required, bool) or not (isinstance(required, (int, float))
                                          and 0 <= required < 1):
        raise InputError(f"required = {required!r}: expected a clearance in [0, 1) m")
    layout = capsule_layout(robot)
    sampled = [_sample(robot, layout, m, i, margins) for i, m in enumerate(members)]
    names = [s.name for s in sampled]
    if len(set(names)) < len(names):
        twice = next(n for n in names if names.count(n) > 1)
        raise InputError(f"two members are robot {twice!r}: each robot once")
    d, pair, at, between = _robots(sampled, layout.r)
    if pair is not None and d - between < required:
        raise ClearanceError(f"robots {pair[0]!r} and {pair[1]!r} {_gap(d)} at t = {at:.2f} s "
                             f"(clearance {required * 1e3:.3g} mm, ± {between * 1e3:.1f} mm "
                             "between samples): move a base further along the line")
    near = (None, None, None, None)
    if part is not None:
        index = surface_index(part.mesh)  # one mesh for every robot
        for s in sampled:
            dp, tp, bp = _to_part(s, layout, part, index)
            if near[0] is None or dp - bp < near[0] - near[3]:
                near = (dp, s.name, tp, bp)
        if near[0] - near[3] < required:
            raise ClearanceError(f"robot {near[1]!r} {_gap(near[0], 's', 'the part')} at t = "
                                 f"{near[2]:.2f} s (clearance {required * 1e3:.3g} mm, ± "
                                 f"{near[3] * 1e3:.1f} mm between samples)")
    return CellClearance(d, pair, at, between, near[0], near[1], near[2], near[3],
                         float(required))


def _gap(d: float, s: str = "", what: str = "each other") -> str:
    """'come within 12 mm (of what)' or 'cut 3 mm into what' (``s``: the verb's -s)."""
    if d >= 0:
        return f"come{s} within {d * 1e3:.0f} mm" + ("" if s == "" else f" of {what}")
    return f"cut{s} {-d * 1e3:.0f} mm into {what}"


__all__ = ["CellClearance", "MovingPart", "cell_clearance", "pair_distance"]
