"""Film sample points on a part's faces (docs/model.md §20: the film is evaluated at points
of the surface, each with its normal and the area it stands for).

Each face is cut into n² congruent triangles, n = ⌈longest edge / h⌉, so no sub-triangle edge
exceeds h; the points are the corners of the sub-triangles: the barycentric lattice
(i, j, n − i − j)/n. A point takes a third of each sub-triangle it is a corner of, so its
area share is A/n² × (2 inside, 1 on an edge, 1/3 at a corner of the face) and a face's shares
sum to its area A exactly (the trapezoid-like rule, second order in h for a smooth film).

A point on an edge shared by faces of the same normal (the two triangles of a flat quad) is
one point carrying both shares; where the normals differ (a crease, a facet of a curved
part) it stays one point per face, each with its face's normal. Normals are the flat faces'
own (no vertex interpolation): a curved part is painted as the facets its mesh gives.

Faces whose film only the volume landed needs (not painted) may take :func:`strips` instead,
whose points grow with a face's area rather than with its longest edge squared.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ..errors import MeshError
from ..workpiece.mesh import Part

# The planner's film grid spacing is σ/3 (film.film_resolution): fine enough for the ripple
# between passes some 2σ apart (docs/model.md §21).
SIGMA_FRACTION = 1.0 / 3.0
MAX_POINTS = 5_000_000  # ~0.5 GB of arrays: a finer request is a unit slip


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class SurfacePoints:
    """Film points (P, 3) [m] with unit outward ``normals`` (P, 3), ``areas`` (P,) [m²] and
    ``faces`` (P,) the index of a part's face each lies on; ``covered`` the indices of the
    faces the points stand for; ``resolution`` h [m]."""

    points: np.ndarray
    normals: np.ndarray
    areas: np.ndarray
    faces: np.ndarray
    covered: np.ndarray
    resolution: float

    @property
    def area(self) -> float:
        return float(self.areas.sum())

    def __len__(self) -> int:
        return len(self.points)


def lattice(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric coordinates (K, 3) of the lattice of a triangle cut into n² and each
    point's share of the triangle's area (K,), summing to 1."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    keep = i + j <= n
    i, j = i[keep], j[keep]
    k = n - i - j
    bary = np.column_stack([i, j, k]) / n
    zeros = (i == 0).astype(int) + (j == 0) + (k == 0)  # 0 inside, 1 on an edge, 2 a corner
    share = np.choose(zeros, [2.0, 1.0, 1.0 / 3.0]) / n ** 2
    return bary, share


def _subdivisions(part: Part, tri, resolution: float) -> np.ndarray:
    """Each face's lattice subdivisions (F,) as floats, or :class:`MeshError` when their
    points exceed MAX_POINTS."""
    edges = np.linalg.norm(tri - np.roll(tri, -1, axis=1), axis=2).max(axis=1)
    # counted in floats: at a resolution of 1e-300 the subdivisions overflow an int
    with np.errstate(over="ignore"):  # inf points: refused below
        n = np.maximum(1.0, np.ceil(edges / resolution - 1e-9))
        total = float(((n + 1) * (n + 2) / 2).sum())
    if not total <= MAX_POINTS:
        raise MeshError(f"{part.source}: {total:.4g} film points at resolution "
                        f"{resolution:.4g} m, more than {MAX_POINTS:.4g}: coarsen the "
                        "resolution")
    return n


def strips(tri, spacing: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(points (K, 3), owner (K,), share (K,)) of the triangles ``tri`` (F, 3, 3) cut in
    strips across their longest side (docs/model.md §23): with A the corner facing the
    shortest edge BC, x(u, v) = A + u·(B − A) + u·v·(C − B) over the unit square, whose area
    element is 2u du dv of the triangle's; the midpoint rule in u (m = ⌈longest of AB, AC /
    spacing⌉ cells) and in v (k = ⌈BC / spacing⌉): each point the centre of its cell (none
    on an edge of the triangle), no point of the triangle further than ``spacing`` from one,
    a sliver L long taking m·k points where the lattice takes (m + 1)(m + 2)/2; each point's
    ``share`` of its triangle's area, summing to 1 (the rule is exact for 2u), second order
    in the spacing for a smooth film."""
    tri = np.asarray(tri, dtype=float)
    edge = np.linalg.norm(np.roll(tri, -1, axis=1) - tri, axis=2)  # edge i: corner i → i+1
    a = (np.argmin(edge, axis=1) + 2) % 3  # the corner facing the shortest edge
    f = np.arange(len(tri))
    A, B, C = tri[f, a], tri[f, (a + 1) % 3], tri[f, (a + 2) % 3]
    with np.errstate(over="ignore"):
        m = np.maximum(1.0, np.ceil(np.maximum(edge[f, a], edge[f, (a + 2) % 3]) / spacing
                                    - 1e-9)).astype(int)
        k = np.maximum(1.0, np.ceil(edge[f, (a + 1) % 3] / spacing - 1e-9)).astype(int)
    pts, owner, share = [], [], []
    for mm, kk in np.unique(np.column_stack([m, k]), axis=0):
        sel = np.flatnonzero((m == mm) & (k == kk))
        u, v = (np.arange(mm) + 0.5) / mm, (np.arange(kk) + 0.5) / kk
        wu, wv = np.full(mm, 1.0 / mm), np.full(kk, 1.0 / kk)
        uu, vv = (x.ravel() for x in np.meshgrid(u, v, indexing="ij"))
        w = (2.0 * u * wu)[:, None] * wv[None, :]
        pts.append((A[sel, None] + uu[None, :, None] * (B - A)[sel, None]
                    + (uu * vv)[None, :, None] * (C - B)[sel, None]).reshape(-1, 3))
        owner.append(np.repeat(sel, len(uu)))
        share.append(np.tile(w.ravel(), len(sel)))
    return np.concatenate(pts), np.concatenate(owner), np.concatenate(share)


def check_film_points(part: Part, resolution: float) -> None:
    """:class:`MeshError` if the painted faces alone need more than MAX_POINTS film points
    at ``resolution`` [m]: the budget checked before a plan is made (the film also takes the
    faces the gun faces, known after it)."""
    _subdivisions(part, part.vertices[part.faces[part.painted]], resolution)


def surface_points(part: Part, resolution: float | None = None, sigma: float | None = None,
                   faces="painted", coarse=None) -> SurfacePoints:
    """Film points on ``part`` no further apart than ``resolution`` [m] (default
    SIGMA_FRACTION × ``sigma``, the spray spot's σ) along any face's lattice, on the
    ``faces``: "painted" (the part's painted faces), "all" (every face: for the transfer
    efficiency) or a boolean mask / index array. ``coarse``: None, or (a mask (F,) of faces,
    a spacing [m] ≥ ``resolution``): those of ``faces`` take instead the points of their
    :func:`strips` at that spacing (faces whose film only the transfer efficiency needs,
    docs/model.md §23)."""
    if resolution is None:
        if sigma is None:
            raise MeshError("film points need a resolution [m] or the spray spot's σ")
        resolution = SIGMA_FRACTION * sigma
    if (isinstance(resolution, bool) or not isinstance(resolution, numbers.Real)
            or not (math.isfinite(resolution) and resolution > 0)):
        raise MeshError(f"film point resolution {resolution!r} m must be a number > 0")
    if isinstance(faces, str):
        if faces not in ("painted", "all"):
            raise MeshError(f"faces = {faces!r} must be 'painted', 'all' or a face mask")
        idx = np.flatnonzero(part.painted) if faces == "painted" else np.arange(len(part.faces))
    else:
        sel = np.asarray(faces)
        idx = np.flatnonzero(sel) if sel.dtype == bool else np.unique(sel.astype(int))
    tri = part.vertices[part.faces[idx]]  # (F, 3, 3)
    n = _subdivisions(part, tri, resolution).astype(int)
    pts, nrm, area, face = [], [], [], []
    if coarse is not None:
        mask, spacing = coarse
        if not (math.isfinite(spacing) and spacing >= resolution):
            raise MeshError(f"coarse film point spacing {spacing!r} m must be at least the "
                            f"resolution {resolution:.4g} m")
        few = np.asarray(mask, dtype=bool)[idx]
        if few.any():
            at, owner, share = strips(tri[few], spacing)
            k = idx[few][owner]
            pts.append(at)
            nrm.append(part.normals[k])
            area.append(part.areas[k] * share)
            face.append(k)
        n = np.where(few, 0, n)
    for m in np.unique(n[n > 0]):
        sel = n == m
        bary, share = lattice(int(m))
        t = tri[sel]
        pts.append(np.einsum("kc,fcx->fkx", bary, t).reshape(-1, 3))
        nrm.append(np.repeat(part.normals[idx[sel]], len(bary), axis=0))
        area.append((part.areas[idx[sel]][:, None] * share[None, :]).ravel())
        face.append(np.repeat(idx[sel], len(bary)))
    if not pts:
        raise MeshError(f"{part.source}: no faces selected for film points")
    pts, nrm, area, face = (np.concatenate(x) for x in (pts, nrm, area, face))
    # one point where faces of the same normal share it (keys: 1e-10 m, 1e-9 in the normal)
    key = np.column_stack([np.round(pts / 1e-10), np.round(nrm / 1e-9)]).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    merged = np.bincount(inverse.ravel(), weights=area, minlength=len(first))
    arrays = [pts[first], nrm[first], merged, face[first], idx]
    for a in arrays:
        a.flags.writeable = False
    return SurfacePoints(*arrays, float(resolution))


__all__ = ["MAX_POINTS", "SIGMA_FRACTION", "SurfacePoints", "check_film_points",
           "lattice", "strips", "surface_points"]
