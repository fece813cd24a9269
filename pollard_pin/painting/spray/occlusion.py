"""Which surface points the spray reaches: paint travels in straight lines from the nozzle
(docs/model.md §20), so a point receives paint from a gun position only if the segment from
the nozzle to it crosses no face of the part.

Only pairs (gun sample, point) inside the spray spot are tested: those whose deposition
rate exceeds RATE_FLOOR = exp(−SPOT_SIGMAS²/2) = 3.7e-6 of the spot's centre at the standoff,
flow/(2πσ²) (for a point at the standoff facing the gun: ρ < 5σ). Every other pair counts
as visible: a shadow there changes the film by less than that share of the spot's rate.

The ray starts at the point moved off its own face along the point's outward normal, by
OFFSET_M or OFFSET × the part's size if larger: well above Embree's float32 resolution (a
float32 step is 6e-8 m at 0.7 m) and trimesh's numpy intersector, which counts hits up to
1e-6 m behind a ray's origin; 10 µm is nothing beside the spray's millimetres. The ray runs
to the nozzle; the first face it meets, if any, shades the pair when it lies closer than the
nozzle. A face met within 2 × the offset is grazed (a point at the foot of a wall lies in the
wall's plane) and the ray goes on past it: into a closed part's material, where it meets the
inside of another face.
The first hit comes from :func:`ray_engine` (Embree through ``embreex``, installed with the
package where it has wheels, else trimesh's numpy intersector on ``rtree``: the same verdicts,
10-35x slower on the example parts) or any object with trimesh's ``intersects_first``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import MeshError
from ..workpiece.mesh import Part, load_job_part
from .deposition import BLOCK_ELEMENTS, Gun, deposition_rate
from .spots import RoundGaussian

SPOT_SIGMAS = 5.0
RATE_FLOOR = math.exp(-SPOT_SIGMAS ** 2 / 2)
OFFSET = 1e-5  # of the part's size (the largest side of its bounding box)
OFFSET_M = 1e-5  # m, at least
GRAZES = 4  # a ray restarts past at most this many grazed faces (corners where walls meet)
RAY_BLOCK = 500_000  # rays per intersector call (~100 MB of temporaries)


def in_spot(gun: Gun, rate) -> np.ndarray:
    """True where a deposition ``rate`` [m/s] (any shape) is above RATE_FLOOR of the spot's
    centre at the standoff: the pairs worth a ray."""
    if type(gun.spot) is RoundGaussian:
        return np.asarray(rate) > RATE_FLOOR * gun.flow / (2.0 * math.pi * gun.sigma ** 2)
    return np.asarray(rate) > RATE_FLOOR * gun.peak_rate


def offset(part: Part) -> float:
    """How far [m] a ray's origin is moved off its point along the normal."""
    return max(OFFSET_M, OFFSET * part.size)


def ray_engine(part: Part):
    """The part's first-hit ray engine: Embree (``embreex``, a dependency where it has wheels)
    or else trimesh's numpy intersector, which needs ``rtree``: one line when neither is
    installed (the numpy intersector would fail deep inside its first query)."""
    import trimesh.ray

    if not trimesh.ray.has_embree:
        try:
            import rtree  # noqa: F401
        except ImportError:
            raise ImportError("the spray's shadow rays on a part's mesh need Embree (embreex) "
                              "or rtree, and neither is installed: pip install rtree") from None
    return part.mesh.ray


def visible(part: Part, p, s, n, intersector=None, faces=None) -> np.ndarray:
    """(K,) True where the segment from nozzle p (K, 3) to point s (K, 3) of outward normal
    n (K, 3) crosses no face of ``part`` (the point moved :func:`offset` along n first).
    ``faces`` (K,): the face each point lies on (of normal n), whose pairs need no ray where
    :func:`open_pairs` says the segment cannot meet the part."""
    p, s, n = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, s, n))
    out = np.ones(len(s), dtype=bool)
    eps = offset(part)
    todo = np.arange(len(s))
    if faces is not None:
        todo = np.flatnonzero(~open_pairs(part, faces, np.einsum("ij,ij->i", p - s, n)))
    if not len(todo):
        return out
    ray = ray_engine(part) if intersector is None else intersector
    for start in range(0, len(todo), RAY_BLOCK):
        sl = todo[start:start + RAY_BLOCK]
        o = s[sl] + eps * n[sl]
        d = p[sl] - o
        length = np.linalg.norm(d, axis=1)
        out[sl] = ~_shaded(part, ray, o, d / length[:, None], length, eps)
    return out


def open_pairs(part: Part, faces, height) -> np.ndarray:
    """True where the segment from a nozzle ``height`` [m] above the plane of a point's face
    (``faces``, the last axis of ``height``: (K,) or (T, K)) to the point cannot meet the
    part: the part rises at most offset/4 above that plane (``Part.rise``: every face lies
    below it) and the nozzle more than offset/2, so the segment from the ray's origin
    (offset above the point) to the nozzle stays clear of every face by offset/4 (some 40
    float32 steps at 1 m: Embree's arithmetic). Such a pair is lit: it needs no ray."""
    eps = offset(part)
    low = np.asarray(part.rise)[np.asarray(faces, dtype=np.int64)] <= eps / 4
    return low & (np.asarray(height) > eps / 2)


def _shaded(part: Part, ray, o, u, length, eps) -> np.ndarray:
    """Rays o + λu, 0 < λ < length: does one meet a face? A face met within 2·eps of where
    the ray starts is grazed, not crossed (a point at the foot of a wall lies in the wall's
    plane): the ray starts again eps beyond it, up to GRAZES times (then it counts as
    shaded)."""
    fn = part.normals
    shaded = np.zeros(len(o), dtype=bool)
    todo, done = np.arange(len(o)), np.zeros(len(o))  # rays to cast, distance travelled
    for _ in range(GRAZES + 1):
        if not len(todo):
            return shaded
        oo = o[todo] + done[todo, None] * u[todo]
        first = np.asarray(ray.intersects_first(oo, u[todo]))
        hit = first >= 0
        f, k = first[hit], todo[hit]
        # the distance to the face's plane along the ray (exact, float64)
        with np.errstate(divide="ignore", invalid="ignore"):
            dist = (np.einsum("ij,ij->i", fn[f], part.vertices[part.faces[f, 0]] - oo[hit])
                    / np.einsum("ij,ij->i", fn[f], u[k]))
        graze = ~(dist >= 2 * eps)  # nan: a ray in a face's plane grazes it too
        shaded[k[~graze & (dist < length[k] - done[k])]] = True
        todo = k[graze]
        done[todo] += np.maximum(np.nan_to_num(dist[graze]), 0.0) + eps
    shaded[todo] = True
    return shaded


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class Occlusion:
    """The pairs inside the spray spot, ``sample`` (K,) and ``point`` (K,) indices, and
    whether the point sees the nozzle, ``visible`` (K,)."""

    sample: np.ndarray
    point: np.ndarray
    visible: np.ndarray

    @property
    def shaded(self) -> int:
        return int((~self.visible).sum())


def occlusion(part: Part, gun: Gun, p, a, s, n, intersector=None, origin=None) -> Occlusion:
    """Every pair (gun sample of p (T, 3), a (T, 3); point s (P, 3), n) inside the spray spot
    (:func:`in_spot`) and its visibility (:func:`visible`), in blocks of samples; positions
    taken relative to ``origin`` for the rate (default: the points' mean)."""
    p, a, s = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, a, s))
    n = np.broadcast_to(np.asarray(n, dtype=float), s.shape)
    o = s.mean(axis=0) if origin is None else np.asarray(origin, dtype=float)
    block = max(1, BLOCK_ELEMENTS // max(len(s), 1))
    ti, pi, vis = [], [], []
    for start in range(0, len(p), block):
        sl = slice(start, start + block)
        t_k, p_k = np.nonzero(in_spot(gun, deposition_rate(gun, p[sl] - o, a[sl], s - o, n)))
        ti.append(t_k + start)
        pi.append(p_k)
        vis.append(visible(part, p[sl][t_k], s[p_k], n[p_k], intersector))
    if not ti:
        empty = np.zeros(0, dtype=int)
        return Occlusion(empty, empty, np.zeros(0, dtype=bool))
    return Occlusion(np.concatenate(ti), np.concatenate(pi), np.concatenate(vis))


def seen_faces(part: Part, standoff: float, intersector=None) -> np.ndarray:
    """(F,) True for the faces ``part.painted`` chose whose centroid sees a nozzle at
    ``standoff`` along the face's normal and beyond it, out of the part's bounding box
    (:func:`visible`): the gun reaches its standoff along its axis from outside the part, so a
    face behind another part, the inside of a box's far wall or of a drawer behind its front
    (whose standoff point lies inside the part) is not painted."""
    idx = np.flatnonzero(part.painted)
    centroid = part.vertices[part.faces[idx]].mean(axis=1)
    n = part.normals[idx]
    # beyond the box: a centroid lies in it, and its diagonal is at most √3 × its largest side
    reach = max(standoff, 2.0 * part.size)
    out = np.zeros(len(part.faces), dtype=bool)
    out[idx] = visible(part, centroid + reach * n, centroid, n, intersector)
    return out


def painted_part(part: Part, standoff: float, intersector=None) -> Part:
    """``part`` painting only the faces the gun can see (:func:`seen_faces`); a
    :class:`MeshError` line when none is left."""
    seen = seen_faces(part, standoff, intersector)
    if not seen.any():
        raise MeshError(f"{part.source}: all {int(part.painted.sum())} faces within "
                        f"{part.max_angle:.4g}° of facing are hidden from a gun at "
                        f"{standoff:.4g} m along their normals (behind other faces): turn "
                        "the part or change facing")
    seen.flags.writeable = False
    return replace(part, painted=seen)


def load_painted_part(job) -> Part:
    """The job's part (:func:`.workpiece.mesh.load_job_part`) painting the faces a gun at the
    job's standoff sees (:func:`painted_part`)."""
    return painted_part(load_job_part(job), job.standoff)


__all__ = ["OFFSET", "OFFSET_M", "Occlusion", "RATE_FLOOR", "SPOT_SIGMAS", "in_spot",
           "load_painted_part", "occlusion", "offset", "open_pairs", "painted_part",
           "seen_faces", "visible"]
