"""The film a part's plan leaves (docs/model.md §23): film points on the painted faces and on
every face a gun tip lies in front of and sees, the film with shadows and the trigger, the
transfer efficiency."""
from __future__ import annotations

import numpy as np

from ...analytic.taskspace import rotation
from ..plan.part import SurfacePlan
from ..spray.deposition import BLOCK_ELEMENTS, gun_of
from ..spray.occlusion import visible
from ..workpiece.mesh import Part
from .grid import film_spacing
from .mesh import MeshFilm, mesh_film
from .points import surface_points

PROBES = 7  # probe points a face: its centroid, corners and edges' midpoints
PROBE_PULL = 0.05  # of the way from a corner or midpoint towards the centroid
TIP_BLOCK = 256  # tips a face tries at a time, nearest first


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


def face_probes(part: Part, faces) -> np.ndarray:
    """(K, PROBES, 3) the probe points of faces ``faces`` (K,): the centroid, the corners and
    the edges' midpoints, each pulled PROBE_PULL of the way towards the centroid (off the
    edges, where a neighbouring wall grazes the ray)."""
    v = part.vertices[part.faces[np.asarray(faces, dtype=np.int64)]]
    c = v.mean(axis=1, keepdims=True)
    pts = np.concatenate([c, v, (v + np.roll(v, -1, axis=1)) / 2], axis=1)
    return pts + PROBE_PULL * (c - pts)


def seen_from_tips(part: Part, tips, faces=None, intersector=None) -> np.ndarray:
    """(F,) True for the faces (``faces`` (F,) bool, default all) that some tip lies in front
    of and that see one (:func:`.spray.occlusion.visible`) from one of their probe points
    (:func:`face_probes`): the tips nearest the face's centroid are tried first, TIP_BLOCK at
    a time, and a face is kept at its first lit probe. A face none of whose probes sees any
    tip in front of it is dark (the inside of a box behind its front, docs/model.md §23)."""
    tips = np.asarray(tips, dtype=float)
    F = len(part.faces)
    idx = np.flatnonzero(np.ones(F, dtype=bool) if faces is None else faces)
    out = np.zeros(F, dtype=bool)
    if not len(idx) or not len(tips):
        return out
    probes = face_probes(part, idx)
    for k, f in enumerate(idx):
        n = part.normals[f]
        c = probes[k, 0]
        front = tips[tips @ n > part.vertices[part.faces[f, 0]] @ n]
        front = front[np.argsort(np.einsum("ij,ij->i", front - c, front - c), kind="stable")]
        for start in range(0, len(front), TIP_BLOCK):
            p = front[start:start + TIP_BLOCK]
            pp = np.repeat(p, PROBES, axis=0)
            ss = np.tile(probes[k], (len(p), 1))
            if visible(part, pp, ss, np.broadcast_to(n, ss.shape), intersector,
                       faces=np.full(len(ss), f)).any():
                out[f] = True
                break
    return out


def surface_film(plan: SurfacePlan, resolution: float | None = None):
    """(film points on the painted faces and on every face a tip lies in front of and sees,
    their film :class:`.film.mesh.MeshFilm`, the painted mask over the points, the transfer
    efficiency): the film of the plan's path with shadows and the trigger. Faces behind every
    tip get exactly nothing (:func:`live_faces`), faces dark from every tip at their probes
    only what pairs outside the spot would bring (:func:`seen_from_tips`, docs/model.md §23),
    so the volume landed on the points is the volume landed on the part."""
    job = plan.job
    tr = plan.trajectory
    on = plan.spray > 0
    tips = tr.poses[on, :3]
    live = live_faces(plan.part, tips) & ~plan.part.painted
    faces = seen_from_tips(plan.part, tips, live) | plan.part.painted
    pts = surface_points(plan.part, resolution, sigma=job.sigma, faces=faces)
    axes = rotation(tr.poses)  # the spot turns with the gun (docs/model.md §20)
    film: MeshFilm = mesh_film(gun_of(job), tr.t, tr.poses[:, :3], axes, pts, plan.part,
                               plan.spray)
    efficiency = film.landed / film.sprayed if film.sprayed > 0 else float("nan")
    return pts, film, plan.part.painted[pts.faces], efficiency


__all__ = ["PROBES", "PROBE_PULL", "TIP_BLOCK", "face_probes", "live_faces", "part_resolution",
           "seen_from_tips", "surface_film"]
