"""The film a part's plan leaves (docs/model.md §23): film points on the painted faces and on
every face a gun tip lies in front of and sees, the film with shadows and the trigger, the
transfer efficiency."""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from ...analytic.taskspace import rotation
from ..plan.part import SurfacePlan
from ..spray.deposition import BLOCK_ELEMENTS, gun_of
from ..spray.occlusion import visible
from ..workpiece.mesh import Part
from .grid import film_spacing
from .mesh import MeshFilm, mesh_film
from .points import lattice, surface_points

PROBE_PULL = 0.05  # of the way from a lattice point towards the face's centroid
NEAR_TIPS = 16  # tips every face tries first, all faces at once: those nearest its centroid
TIP_BLOCK = 256  # tips a face still dark tries first, nearest first (then twice as many)
PAIR_BLOCK = 1_000_000  # (probe, tip) pairs at most per ray test (~100 MB of temporaries)
COARSE_SIGMAS = 1.0  # film point spacing on the faces not painted, in spot σ (§23)


def part_resolution(job, resolution: float | None = None) -> float:
    """The film point spacing [m] on a part: the rule of :func:`.film.grid.film_spacing`."""
    return film_spacing(job.sigma, resolution, "film point spacing")


def live_faces(part: Part, tips) -> np.ndarray:
    """Faces (F,) bool that some gun tip lies in front of: a point s on a face of normal n
    gets nothing from a tip p with (p − s)·n ≤ 0 (the rate's cos i, docs/model.md §20), and
    s·n is the same over a flat face, so a face with max_p p·n ≤ v₀·n gets exactly 0."""
    level = np.einsum("ij,ij->i", part.vertices[part.faces[:, 0]], part.normals)
    ahead = np.full(len(part.faces), -np.inf)
    block = max(1, BLOCK_ELEMENTS // len(part.faces))  # (block × F) products: ~8 MB each
    for start in range(0, len(tips), block):
        ahead = np.maximum(ahead, (tips[start:start + block] @ part.normals.T).max(axis=0))
    return ahead > level


def face_probes(part: Part, faces, spacing: float | None = None) -> tuple:
    """(probes (M, 3), owner (M,)) of faces ``faces`` (K,): each face's centroid (the first
    K rows, in order) and the points of its lattice cut n = max(2, ⌈longest edge / spacing⌉)
    times (:func:`.film.points.lattice`; n = 2 without ``spacing``: the corners and the
    edges' midpoints), each pulled PROBE_PULL of the way towards the centroid (off the
    edges, where a neighbouring wall grazes the ray); ``owner``: the index into ``faces``
    of each probe's face."""
    faces = np.asarray(faces, dtype=np.int64)
    tri = part.vertices[part.faces[faces]]
    c = tri.mean(axis=1)
    n = np.full(len(faces), 2.0)
    if spacing is not None:
        edges = np.linalg.norm(tri - np.roll(tri, -1, axis=1), axis=2).max(axis=1)
        n = np.maximum(2.0, np.ceil(edges / spacing - 1e-9))
    pts, owner = [c], [np.arange(len(faces))]
    for m in np.unique(n):
        sel = np.flatnonzero(n == m)
        bary, _ = lattice(int(m))
        p = np.einsum("kc,fcx->fkx", bary, tri[sel])
        pts.append((p + PROBE_PULL * (c[sel, None, :] - p)).reshape(-1, 3))
        owner.append(np.repeat(sel, len(bary)))
    return np.concatenate(pts), np.concatenate(owner)


def seen_from_tips(part: Part, tips, faces=None, spacing: float | None = None,
                   intersector=None) -> np.ndarray:
    """(F,) True for the faces (``faces`` (F,) bool, default all) that one of their probe
    points (:func:`face_probes` at ``spacing`` [m]) sees (:func:`.spray.occlusion.visible`)
    from some tip that lies in front of the face. First every face at once with its
    NEAR_TIPS tips nearest its centroid; then each face still dark with every tip in front
    of it, nearest first, TIP_BLOCK at a time and twice as many each time, to its first lit
    pair. A face none of whose probes sees any tip in front of it is dark (the inside of a
    box behind its front, docs/model.md §23)."""
    tips = np.asarray(tips, dtype=float).reshape(-1, 3)
    F = len(part.faces)
    idx = np.flatnonzero(np.ones(F, dtype=bool) if faces is None else faces)
    out = np.zeros(F, dtype=bool)
    if not len(idx) or not len(tips):
        return out
    probes, owner = face_probes(part, idx, spacing)
    n = part.normals[idx]
    level = np.einsum("ij,ij->i", part.vertices[part.faces[idx, 0]], n)
    near = cKDTree(tips).query(probes[:len(idx)], k=min(NEAR_TIPS, len(tips)))[1]
    near = near.reshape(len(idx), -1)
    lit = np.zeros(len(idx), dtype=bool)
    step = max(1, PAIR_BLOCK // near.shape[1])
    for start in range(0, len(probes), step):  # every face at once, its nearest tips
        j = np.repeat(np.arange(start, min(start + step, len(probes))), near.shape[1])
        k = owner[j]
        t = near[k, np.tile(np.arange(near.shape[1]), len(j) // near.shape[1])]
        front = np.einsum("ij,ij->i", tips[t], n[k]) > level[k]
        j, k, t = j[front], k[front], t[front]
        vis = visible(part, tips[t], probes[j], n[k], intersector, faces=idx[k])
        lit[k[vis]] = True
    order = np.argsort(owner, kind="stable")
    ends = np.searchsorted(owner[order], np.arange(len(idx) + 1))
    for k in np.flatnonzero(~lit):  # the rest: every tip in front, nearest first
        pk = probes[order[ends[k]:ends[k + 1]]]
        front = tips[tips @ n[k] > level[k]]
        front = front[np.argsort(np.einsum("ij,ij->i", front - pk[0], front - pk[0]),
                                 kind="stable")]
        start, block = 0, TIP_BLOCK
        while start < len(front) and not lit[k]:
            p = front[start:start + block]
            pp, ss = np.repeat(p, len(pk), axis=0), np.tile(pk, (len(p), 1))
            lit[k] = visible(part, pp, ss, np.broadcast_to(n[k], ss.shape), intersector,
                             faces=np.full(len(ss), idx[k])).any()
            start += block
            block = min(2 * block, max(TIP_BLOCK, PAIR_BLOCK // len(pk)))
    out[idx[lit]] = True
    return out


def film_points(part: Part, tips, job, resolution: float | None = None):
    """The film points of a part that gun tips ``tips`` (T, 3; the part's frame) spray: on
    the painted faces, and on every face a tip lies in front of and sees (:func:`live_faces`,
    :func:`seen_from_tips`, docs/model.md §23), so the volume landed on the points is the
    volume landed on the part. The faces not painted, whose film counts only in that volume,
    take points COARSE_SIGMAS × σ apart (:func:`.film.points.strips`); the painted faces the
    lattice at ``resolution``. One rule for a robot's film and a cell's."""
    live = live_faces(part, tips) & ~part.painted
    seen = seen_from_tips(part, tips, live)
    return surface_points(part, resolution, sigma=job.sigma, faces=seen | part.painted,
                          coarse=(seen, max(COARSE_SIGMAS * job.sigma,
                                            part_resolution(job, resolution))))


def surface_film(plan: SurfacePlan, resolution: float | None = None):
    """(film points (:func:`film_points`), their film :class:`.film.mesh.MeshFilm`, the
    painted mask over the points, the transfer efficiency): the film of the plan's path with
    shadows and the trigger. Faces behind every tip get exactly nothing, faces dark from every
    tip at their probes only what pairs outside the spot would bring."""
    job = plan.job
    tr = plan.trajectory
    pts = film_points(plan.part, tr.poses[plan.spray > 0, :3], job, resolution)
    axes = rotation(tr.poses)  # the spot turns with the gun (docs/model.md §20)
    film: MeshFilm = mesh_film(gun_of(job), tr.t, tr.poses[:, :3], axes, pts, plan.part,
                               plan.spray)
    efficiency = film.landed / film.sprayed if film.sprayed > 0 else float("nan")
    return pts, film, plan.part.painted[pts.faces], efficiency


__all__ = ["COARSE_SIGMAS", "NEAR_TIPS", "PAIR_BLOCK", "PROBE_PULL", "TIP_BLOCK", "face_probes",
           "film_points", "live_faces", "part_resolution", "seen_from_tips", "surface_film"]
