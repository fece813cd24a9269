"""Which surface points the spray reaches: paint travels in straight lines from the nozzle
(docs/model.md §20), so a point receives paint from a gun position only if the segment from
the nozzle to it crosses no face of the part.

Only pairs (gun sample, point) inside the spray spot are tested: h > 0, the point facing the
gun (−d·n > 0) and ρ < SPOT_SIGMAS·σ(h). Outside it the rate is below exp(−SPOT_SIGMAS²/2)
= 3.7e-6 of the spot's centre at that distance, and the pair counts as visible (shadows
there change the film by less than that share).

The ray starts at the point moved off its own face along the point's outward normal, by
OFFSET_M or OFFSET × the part's size if larger: well above Embree's float32 resolution (a
float32 step is 6e-8 m at 0.7 m) and trimesh's numpy intersector, which counts hits up to
1e-6 m behind a ray's origin; 10 µm is nothing beside the spray's millimetres. The ray runs
to the nozzle; the first face it
meets, if any, shades the pair when it lies closer than the nozzle. A face met within
2 × the offset is grazed (a point at the foot of a wall lies in the wall's plane) and the ray
goes on past it: into a closed part's material, where it meets the inside of another face.
The first hit comes from ``Part.mesh.ray`` (Embree through the optional ``embreex``
package when installed, else trimesh's numpy intersector) or any object with trimesh's
``intersects_first``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .deposition import BLOCK_ELEMENTS, Gun
from .mesh import Part

SPOT_SIGMAS = 5.0
OFFSET = 1e-5  # of the part's size (the largest side of its bounding box)
OFFSET_M = 1e-5  # m, at least
GRAZES = 4  # a ray restarts past at most this many grazed faces (corners where walls meet)
RAY_BLOCK = 500_000  # rays per intersector call (~100 MB of temporaries)


def spot_mask(gun: Gun, p, a, s, n, origin=None) -> np.ndarray:
    """(T, P) True where point s (P, 3) of outward normal n ((P, 3) or (3,)) lies in the
    spray spot of the gun at tip p (T, 3) with axis a (T, 3): h > 0, −d·n > 0 and
    ρ < SPOT_SIGMAS·σ(h). Matrix products as in deposition_rate, positions taken relative
    to ``origin`` (default: the points' mean)."""
    p, a, s = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, a, s))
    o = s.mean(axis=0) if origin is None else np.asarray(origin, dtype=float)
    p, s = p - o, s - o
    n = np.broadcast_to(np.asarray(n, dtype=float), s.shape)
    h = a @ s.T - np.einsum("ij,ij->i", p, a)[:, None]  # (T, P)
    d2 = (np.einsum("ij,ij->i", s, s)[None, :] + np.einsum("ij,ij->i", p, p)[:, None]
          - 2.0 * p @ s.T)
    dn = np.einsum("ij,ij->i", s, n)[None, :] - p @ n.T
    k = SPOT_SIGMAS * gun.sigma / gun.standoff
    return (h > 0) & (dn < 0) & (d2 - h * h < (k * h) ** 2)


def offset(part: Part) -> float:
    """How far [m] a ray's origin is moved off its point along the normal."""
    return max(OFFSET_M, OFFSET * part.size)


def visible(part: Part, p, s, n, intersector=None) -> np.ndarray:
    """(K,) True where the segment from nozzle p (K, 3) to point s (K, 3) of outward normal
    n (K, 3) crosses no face of ``part`` (the point moved :func:`offset` along n first)."""
    p, s, n = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, s, n))
    ray = part.mesh.ray if intersector is None else intersector
    out = np.ones(len(s), dtype=bool)
    eps = offset(part)
    for start in range(0, len(s), RAY_BLOCK):
        sl = slice(start, start + RAY_BLOCK)
        o = s[sl] + eps * n[sl]
        d = p[sl] - o
        length = np.linalg.norm(d, axis=1)
        out[sl] = ~_shaded(part, ray, o, d / length[:, None], length, eps)
    return out


def _shaded(part: Part, ray, o, u, length, eps) -> np.ndarray:
    """Rays o + λu, 0 < λ < length: does one meet a face? A face met within 2·eps of where
    the ray starts is grazed, not crossed (a point at the foot of a wall lies in the wall's
    plane): the ray starts again eps beyond it, up to GRAZES times (then it counts as
    shaded)."""
    tri0, fn = part.vertices[part.faces[:, 0]], part.normals
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
            dist = (np.einsum("ij,ij->i", fn[f], tri0[f] - oo[hit])
                    / np.einsum("ij,ij->i", fn[f], u[k]))
        graze = ~(dist >= 2 * eps)  # nan: a ray in a face's plane grazes it too
        shaded[k[~graze & (dist < length[k] - done[k])]] = True
        todo = k[graze]
        done[todo] += np.maximum(np.nan_to_num(dist[graze]), 0.0) + eps
    shaded[todo] = True
    return shaded


@dataclass(frozen=True)
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
    (:func:`spot_mask`) and its visibility (:func:`visible`), in blocks of samples."""
    p, a, s = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, a, s))
    n = np.broadcast_to(np.asarray(n, dtype=float), s.shape)
    block = max(1, BLOCK_ELEMENTS // max(len(s), 1))
    ti, pi, vis = [], [], []
    for start in range(0, len(p), block):
        sl = slice(start, start + block)
        t_k, p_k = np.nonzero(spot_mask(gun, p[sl], a[sl], s, n, origin))
        ti.append(t_k + start)
        pi.append(p_k)
        vis.append(visible(part, p[sl][t_k], s[p_k], n[p_k], intersector))
    if not ti:
        empty = np.zeros(0, dtype=int)
        return Occlusion(empty, empty, np.zeros(0, dtype=bool))
    return Occlusion(np.concatenate(ti), np.concatenate(pi), np.concatenate(vis))


__all__ = ["OFFSET", "OFFSET_M", "Occlusion", "SPOT_SIGMAS", "occlusion", "offset",
           "spot_mask", "visible"]
