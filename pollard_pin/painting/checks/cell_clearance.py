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
from ...kinematics.capsules import axis_spheres, capsule_layout, link_capsules
from ..cell.robots import CellRobot
from ..errors import ClearanceError
from ..spray.gun_body import AXIS_STEP
from .capsule_pairs import CHUNK, norm3, pair_distance
from .clearance import least_distance, surface_index, travelled
from .spheres import CapsuleSpheres

if TYPE_CHECKING:  # trimesh (with scipy, networkx) loads where a mesh is made: not for `run`
    import trimesh

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
    return np.maximum(norm3(da), norm3(db)).max(axis=1)


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
        lower.append(norm3(mid - np.clip(mid, lo, hi)) - rho - norm3(bo - ao) / 2)
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
