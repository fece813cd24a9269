"""The gun's clearance from the part along a planned path (docs/model.md §25).

At every sample of the path (the part at rest: a line's path less the line's displacement),
the gun's body must stay ``clearance`` from the part's mesh. The body is a union of K spheres
on the spray axis behind the tip that holds the gun link (:class:`.spray.gun_body.GunBody`);
its distance from the mesh is the least of |c − mesh| − r over the spheres (c, r) and the
samples, found so:

1. the mesh's faces are sampled on barycentric grids (:func:`surface_samples`) whose every
   sub-triangle's longest edge is at most δ, so any point of the mesh lies within δ of one
   of its own face's samples; a k-d tree gives each centre's distance d̃ to the samples,
   and d̃ − δ − r ≤ |c − mesh| − r ≤ d̃ − r;
2. every COARSE_STRIDE-th sample's spheres set a ceiling (an achieved d̃ − r; with the way
   travelled, asked only within a first ceiling of every 4·COARSE_STRIDE-th, plus the way:
   :func:`_coarse_bounds`); the others are asked only within the ceiling + r + δ (a sphere
   further off cannot hold the least), which keeps the queries short;
3. the EXACT_POINTS spheres of lowest bound get their exact distance: the closest points of
   the faces that own a sample within d̃ + δ of c (``trimesh.triangles.closest_point``).
   The least of them is the figure; the least bound left unchecked says how much less the
   true least over the spheres may be (0 when none is below).

Step 2 skips what it can prove (:func:`may_come_within`): a point that moves at most m
from one sample to another changes its distance from anything fixed by at most m, so a
sphere whose distance at the neighbouring coarse samples, less the way it may travel from
there, is still past the query's bound is answered "past it" (inf) without a query: the
answer the query gives, so every figure is the one of asking every sample.

What lies between the samples may come closer, by at most ``between`` (in the result): that
bound plus half the largest chord a body point travels in one time step (|Δtip| +
reach·|Δaxis|). A path refused is one line naming the time, what the gun does there, the
point on the part [mm] and the distance found against the clearance.
"""
from __future__ import annotations

import hashlib
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from scipy.spatial import cKDTree

from ...analytic.taskspace import rotation
from ...errors import say_less
from ..errors import ClearanceError
from ..spray.gun_body import CLEARANCE, GunBody

if TYPE_CHECKING:  # trimesh (with scipy, networkx) loads where a mesh is made: not for `run`
    import trimesh

SURFACE_STEP = 0.004  # m: the surface samples' sub-triangle edges, at most (δ)
MAX_SURFACE_POINTS = 400_000  # δ grows until the samples fit (≈ 10 MB of k-d tree)
EXACT_POINTS = 512  # the spheres of lowest bound whose exact distance is computed
COARSE_STRIDE = 16  # every this many samples set the ceiling of the bounded queries
SLACK = 1e-9  # m: a proven bound must clear a limit by this (round-off is ~1e-15 m)




@dataclass(frozen=True)
class Clearance:
    """The least distance [m] between the gun's body and the part over a path's samples
    (negative: the body cuts into the part), at ``sample`` (time ``time`` [s]), the part's
    ``point`` nearest the body there and the ``tip``; ``between`` [m] how much closer the
    body may come between samples; ``required`` the clearance asked for."""

    distance: float
    between: float
    required: float
    sample: int
    time: float
    point: tuple[float, float, float]
    tip: tuple[float, float, float]

    def to_dict(self) -> dict:
        return {"min_m": self.distance, "between_samples_m": self.between,
                "required_m": self.required, "time": self.time,
                "point": list(self.point), "tip": list(self.tip)}


def surface_samples(vertices, faces, step: float = SURFACE_STEP):
    """Points on every face (barycentric grids), the face of each, and δ [m]: every point
    of the mesh lies within δ of one of its face's points (a sub-triangle's diameter is its
    longest edge)."""
    tri = np.asarray(vertices, float)[np.asarray(faces)]
    longest = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)
    while True:
        n = np.maximum(1, np.ceil(longest / step)).astype(int)
        if ((n + 1) * (n + 2) // 2).sum() <= MAX_SURFACE_POINTS or n.max() == 1:
            break  # (the vertices alone, 3 a face, whatever their count)
        step *= 1.5
    points, owner = [], []
    for k in np.unique(n):
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
        keep = i + j <= k
        w = np.stack([k - i[keep] - j[keep], i[keep], j[keep]], axis=1) / k  # (G, 3)
        these = np.flatnonzero(n == k)
        points.append(np.einsum("gc,fcx->fgx", w, tri[these]).reshape(-1, 3))
        owner.append(np.repeat(these, len(w)))
    return np.concatenate(points), np.concatenate(owner), float((longest / n).max())


def body_points(poses, body: GunBody):
    """The body's sampled axis points (N, K, 3) for tool poses (N, 6), their radii (K,)."""
    poses = np.asarray(poses, float)
    axis = rotation(poses)[:, :, 0]  # the spray axis a = R·e_x (docs/model.md §20)
    offs, radii = body.axis_points()
    return poses[:, None, :3] - offs[None, :, None] * axis[:, None, :], radii


@dataclass(frozen=True, eq=False)  # arrays and trees: compared by identity
class SurfaceIndex:
    """A mesh's surface samples as :func:`least_distance` asks them (module note 1): its
    ``triangles`` (F, 3, 3), the ``samples`` with their ``owner`` faces and δ, and their
    k-d trees (``distinct``: of the distinct samples, for the nearest; ``every``: of all,
    for the faces near a point). Made once by :func:`surface_index` for every set of
    spheres measured against the same mesh."""

    triangles: np.ndarray
    samples: np.ndarray
    owner: np.ndarray
    delta: float
    distinct: cKDTree
    every: cKDTree


_INDEXES: dict = {}  # the last few meshes' indexes by their content (a study's one part)
_INDEXES_KEPT = 2


def surface_index(mesh: trimesh.Trimesh) -> SurfaceIndex:
    """The :class:`SurfaceIndex` of a mesh: made once per content (its vertices and faces)
    for the last few meshes, every design of a study measured against the same part (the
    same samples and trees, so the same answers to the bit)."""
    v, f = np.ascontiguousarray(mesh.vertices, float), np.ascontiguousarray(mesh.faces)
    key = hashlib.blake2b(v.tobytes() + b"|" + f.tobytes() + repr((v.shape, f.shape, f.dtype))
                          .encode(), digest_size=16).digest()
    index = _INDEXES.get(key)
    if index is None:
        index = _INDEXES[key] = _index(mesh)
        while len(_INDEXES) > _INDEXES_KEPT:
            _INDEXES.pop(next(iter(_INDEXES)))
    return index


def _index(mesh: trimesh.Trimesh) -> SurfaceIndex:
    samples, owner, delta = surface_samples(mesh.vertices, mesh.faces)
    # an unbalanced tree of distinct points answers the far queries several times faster
    tree = cKDTree(distinct_rows(samples), balanced_tree=False, compact_nodes=False)
    return SurfaceIndex(np.asarray(mesh.triangles, float), samples, owner, delta, tree,
                        cKDTree(samples))


def distinct_rows(points) -> np.ndarray:
    """``np.unique(points, axis=0)`` of finite points (N, D): the same rows in the same order
    (of equal rows the first kept, so a zero's sign may be the other's: the same distances),
    by a stable sort on the columns; ≈ 10× faster than numpy's sort of the rows as records
    (a mesh's index, 0.3 s a part)."""
    p = np.asarray(points, float)
    s = p[np.lexsort(p.T[::-1])]
    keep = np.ones(len(s), bool)
    keep[1:] = (s[1:] != s[:-1]).any(axis=1)
    return s[keep]


def travelled(steps) -> np.ndarray:
    """The way travelled (N,) from the first sample, summing ``steps`` (N − 1,), each a bound
    of how far any point moves in its step: the way between samples n < m, travelled[m] −
    travelled[n], bounds how far a point moves between them (docs/model.md §26.4)."""
    return np.concatenate([[0.0], np.cumsum(np.asarray(steps, float))])


def may_come_within(known, at, way, limit, rows=None) -> np.ndarray:
    """Which samples (``rows``, default all; (R, ...)) may come within ``limit`` (broadcast
    over the trailing axes), proven from lower bounds ``known`` (M, ...) of the distances at
    the samples ``at`` (M,), ascending from 0, and the way ``way`` (N,) of :func:`travelled`:
    a distance falls by at most the way travelled, so sample n's is at least the larger of
    known[i] − (way[n] − way[at[i]]) and known[i + 1] − (way[at[i + 1]] − way[n]), at[i] ≤ n
    < at[i + 1] (docs/model.md §26.4). A sample left out is more than ``limit`` + SLACK
    away."""
    known, way, at = np.asarray(known, float), np.asarray(way, float), np.asarray(at)
    n = np.arange(len(way)) if rows is None else np.asarray(rows)
    i = np.searchsorted(at, n, side="right") - 1
    after = np.minimum(i + 1, len(at) - 1)  # past the last: no later one
    shape = (-1,) + (1,) * (known.ndim - 1)
    # in place on the gathered rows (R × a part check's spheres: 10⁷ of them): the same
    # operations on the same numbers (the same bits), two arrays instead of five
    low, later = known[i], known[after]
    np.subtract(low, (way[n] - way[at[i]]).reshape(shape), out=low)
    np.subtract(later, (way[at[after]] - way[n]).reshape(shape), out=later)
    inner = np.broadcast_to((i + 1 < len(at)).reshape(shape), low.shape)
    np.maximum(low, later, out=low, where=inner)
    return low <= np.asarray(limit, float) + SLACK


def least_distance(mesh: trimesh.Trimesh, centres, radii, index: SurfaceIndex | None = None,
                   way=None):
    """The least of |c − mesh| − r found over the spheres of centres ``centres`` (N, K, 3)
    and radii ``radii`` (K,) (module notes 1–3): (that distance, the index (n, k) of its
    sphere, the mesh's closest point there, how much less the least over all may be).
    ``index``: the mesh's :class:`SurfaceIndex` if already made (default: made here);
    ``way`` (N,): the way any centre travels (:func:`travelled`), to skip the queries it
    proves past their bound (module notes; default None: every sphere asked). The answer is
    the same either way. ``centres`` may be any object with ``shape`` (N, K, 3) that gives
    an array for a slice of samples and for (samples, spheres) of integer arrays (or one
    sphere): the centres are then made only where asked."""
    index = surface_index(mesh) if index is None else index
    tri, owner, delta, tree = index.triangles, index.owner, index.delta, index.distinct
    coarse = (tree.query(centres[::COARSE_STRIDE])[0] if way is None else
              _coarse_bounds(tree, centres, radii, delta, way))
    ceiling = float((coarse - radii).min())  # an achieved upper bound of the least
    bound = ceiling + radii + delta  # a query's: a sphere further off cannot hold the least
    if way is None:
        ask = np.ones(centres.shape[:2], bool)
    else:  # d̃ is 1-Lipschitz in c: the coarse samples' d̃ bound the others'
        ask = may_come_within(coarse, np.arange(0, len(centres), COARSE_STRIDE), way,
                              bound)
    approx = np.full(centres.shape[:2], math.inf)
    for k in range(len(radii)):
        rows = np.flatnonzero(ask[:, k])
        if len(rows):
            approx[rows, k] = tree.query(centres[rows, k], distance_upper_bound=bound[k])[0]
    lower = approx - delta  # inf: at least the ceiling
    lower = np.subtract(lower, radii, out=lower).ravel()  # in place: the same bits
    order = np.argsort(lower)[:EXACT_POINTS]
    order = order[np.isfinite(lower[order])]  # the finite sort first: the same as before
    if len(order) == 0:  # no sphere within the ceiling + δ: only round-off can do this
        order = np.array([int(np.argmin(np.where(np.isfinite(approx), approx, coarse.max())))])
    # a face within d ≤ d̃ of c has one of its own samples within d̃ + δ
    near = index.every.query_ball_point(_flat(centres, order), np.minimum(
        approx.ravel()[order], ceiling + radii[order % len(radii)]) + delta)
    sizes = np.fromiter(map(len, near), int, len(near))
    pair = np.unique(np.repeat(np.arange(len(near)) * len(tri), sizes)
                     + owner[np.fromiter(itertools.chain.from_iterable(near), int, sizes.sum())])
    who, face = order[pair // len(tri)], pair % len(tri)
    import trimesh

    at = _flat(centres, who)
    closest = trimesh.triangles.closest_point(tri[face], at)
    dist = np.linalg.norm(closest - at, axis=1) - radii[who % len(radii)]
    j = int(np.argmin(dist))
    best = float(dist[j])
    rest = (np.partition(lower, len(order))[len(order)] if len(lower) > len(order) else
            math.inf)
    floor = min(best, float(rest), ceiling if np.isinf(lower).any() else math.inf)
    return best, divmod(int(who[j]), len(radii)), closest[j], best - floor


def _coarse_bounds(tree, centres, radii, delta: float, way) -> np.ndarray:
    """d̃ (M, K) at every COARSE_STRIDE-th sample where it may hold the ceiling, a lower bound
    of it elsewhere: every 4·COARSE_STRIDE-th sample's spheres set a first ceiling c₁ (an
    achieved d̃ − r); a query bounded at c₁ + r + δ + 2·(the longest way between two
    COARSE_STRIDE-th samples) answers every d̃ under it, the ceiling's among them (the same
    float), and a sphere past it is at least that bound (docs/model.md §25)."""
    first, _ = tree.query(centres[::4 * COARSE_STRIDE])
    steps = np.diff(np.asarray(way, float)[::COARSE_STRIDE])
    upper = (float((first - radii).min()) + radii + delta
             + 2 * (float(steps.max()) if len(steps) else 0.0))
    at = centres[::COARSE_STRIDE]
    out = np.empty(at.shape[:2])
    for k in range(len(radii)):
        out[:, k] = tree.query(at[:, k], distance_upper_bound=upper[k])[0]
    return np.where(np.isinf(out), upper, out)  # past the bound: at least it


def _flat(centres, index) -> np.ndarray:
    """The centres (R, 3) at flat indices ``index`` (R,) of ``centres`` (N, K, 3): those of
    ``centres.reshape(-1, 3)``, without the reshape (a copy where the centres are not
    contiguous, or made only where asked)."""
    n, k = np.divmod(np.asarray(index), centres.shape[1])
    return centres[n, k]


def between_samples(poses, body: GunBody) -> float:
    """How much closer than the samples the body may come [m] (module notes): half the
    largest chord a point of it travels in one time step."""
    poses = np.asarray(poses, float)
    if len(poses) < 2:
        return 0.0
    axis = rotation(poses)[:, :, 0]
    chord = (np.linalg.norm(np.diff(poses[:, :3], axis=0), axis=1)
             + body.reach * np.linalg.norm(np.diff(axis, axis=0), axis=1))
    return float(chord.max()) / 2


def clearance_of(mesh: trimesh.Trimesh, poses, t, body: GunBody | None = None,
                 required: float = CLEARANCE) -> Clearance:
    """The :class:`Clearance` of tool poses (N, 6) at times ``t`` (N,) from the mesh (in
    the same frame), not checked against ``required``."""
    body = GunBody() if body is None else body
    poses = np.asarray(poses, float)
    centres, radii = body_points(poses, body)
    offs = body.axis_points()[0]  # a centre's step is at most the axis ends' (affine in it)
    ends = centres[:, [int(np.argmin(offs)), int(np.argmax(offs))]]
    way = travelled(np.linalg.norm(np.diff(ends, axis=0), axis=2).max(axis=1))
    best, (i, _), point, less = least_distance(mesh, centres, radii, way=way)
    return Clearance(best, less + between_samples(poses, body), float(required), i, float(t[i]),
                     tuple(float(c) for c in point), tuple(float(c) for c in poses[i, :3]))


def check_clearance(mesh: trimesh.Trimesh, poses, t, body: GunBody | None = None,
                    required: float = CLEARANCE,
                    where: Callable[[int], str] | None = None) -> Clearance:
    """:func:`clearance_of`, refused as a :class:`ClearanceError` naming the place (``where``
    of the sample: what the gun does there) when the body comes closer than ``required``
    less what may lie between samples."""
    c = clearance_of(mesh, poses, t, body, required)
    if c.distance - c.between < required:
        x = np.asarray(c.point) * 1e3
        place = f" {where(c.sample)}" if where is not None else ""
        gap = (f"comes {c.distance * 1e3:.1f} mm from" if c.distance >= 0 else
               f"cuts {-c.distance * 1e3:.1f} mm into")
        said = (f"the gun's body {gap} the part at ({x[0]:.0f}, {x[1]:.0f}, {x[2]:.0f}) mm, "
                f"t = {c.time:.3f} s{place}; clearance {required * 1e3:.3g} mm")
        fix = "a larger standoff, or turn the part so nothing stands taller than it"
        raise ClearanceError(say_less(
            f"{said} (± {c.between * 1e3:.1f} mm between samples): {fix}", f"{said}: {fix}",
            f"{said}: a larger standoff"))
    return c


def strided(n: int, stride: int = 1) -> np.ndarray:
    """The samples a clearance check takes of ``n``: every ``stride``-th and the last
    (:attr:`.policy.PlannerPolicy.clearance_stride`)."""
    return np.unique(np.append(np.arange(0, n, stride), n - 1)) if n else np.arange(0)


def job_clearance(robot, job, mesh, poses, t, where=None, stride: int = 1) -> Clearance:
    """:func:`check_clearance` of a planned path (poses in the part's frame) with the
    robot's gun body and the job's ``gun.clearance`` (default CLEARANCE), over every
    ``stride``-th sample (:func:`strided`; the bound between samples is theirs)."""
    from ..spray.gun_body import gun_body

    required = CLEARANCE if getattr(job, "clearance", None) is None else job.clearance
    body = gun_body(getattr(robot, "params", None))
    if stride == 1:
        return check_clearance(mesh, poses, t, body, required, where)
    k = strided(len(t), stride)
    c = check_clearance(mesh, np.asarray(poses)[k], np.asarray(t)[k], body, required,
                        None if where is None else (lambda i: where(int(k[i]))))
    return replace(c, sample=int(k[c.sample]))


def panel_mesh(frame) -> trimesh.Trimesh:
    """A panel (:class:`.workpiece.panel.PanelFrame`) as two triangles."""
    corners = frame.world(np.array([-1, 1, 1, -1]) * frame.width / 2,
                          np.array([-1, -1, 1, 1]) * frame.height / 2)
    import trimesh

    return trimesh.Trimesh(corners, np.array([[0, 1, 2], [0, 2, 3]]), process=False)


__all__ = ["Clearance", "SurfaceIndex", "between_samples", "body_points", "check_clearance",
           "clearance_of", "distinct_rows", "job_clearance", "least_distance", "may_come_within",
           "panel_mesh", "strided", "surface_index", "surface_samples", "travelled"]
