"""The painted mesh refined to its film points (``film.ply``): each painted face cut into the
n² sub-triangles whose corners are :mod:`.film.points`' lattice, wound as the face, their
corners the film points themselves (a point shared by faces of one normal is one vertex)."""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from ..errors import MeshError
from ..workpiece.mesh import Part
from .points import SurfacePoints, lattice


def _sub_triangles(n: int) -> np.ndarray:
    """Index triples (n², 3) into :func:`.film.points.lattice`'s points of a face cut in n²."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    keep = i + j <= n
    index = -np.ones((n + 1, n + 1), dtype=int)
    index[i[keep], j[keep]] = np.arange(int(keep.sum()))
    tris = []
    for a in range(n):
        for b in range(n - a):
            tris.append((index[a, b], index[a + 1, b], index[a, b + 1]))
            if a + b <= n - 2:
                tris.append((index[a + 1, b], index[a + 1, b + 1], index[a, b + 1]))
    return np.array(tris, dtype=int)


def refined_mesh(part: Part, points: SurfacePoints, faces=None):
    """(vertex indices into ``points`` (V,), triangles (M, 3) indexing those vertices) of the
    ``faces`` (default: the painted ones) cut at ``points.resolution``, each triangle wound
    counter-clockwise about its face's outward normal."""
    idx = np.flatnonzero(part.painted) if faces is None else np.asarray(faces)
    tri = part.vertices[part.faces[idx]]
    edges = np.linalg.norm(tri - np.roll(tri, -1, axis=1), axis=2).max(axis=1)
    n = np.maximum(1, np.ceil(edges / points.resolution - 1e-9)).astype(int)
    tree = cKDTree(np.hstack([points.points, points.normals]))
    out, offset, keys = [], 0, []
    for m in np.unique(n):
        sel = n == m
        bary, _ = lattice(int(m))
        pts = np.einsum("kc,fcx->fkx", bary, tri[sel])  # (F, K, 3)
        nrm = np.repeat(part.normals[idx[sel]][:, None, :], len(bary), axis=1)
        sub = _sub_triangles(int(m))
        out.append((sub[None, :, :] + offset + len(bary) * np.arange(int(sel.sum()))[:, None,
                                                                                      None]
                    ).reshape(-1, 3))
        keys.append(np.concatenate([pts, nrm], axis=2).reshape(-1, 6))
        offset += int(sel.sum()) * len(bary)
    dist, which = tree.query(np.concatenate(keys))
    if dist.max() > 1e-9:
        raise MeshError(f"{part.source}: the film points do not cover the faces to refine "
                        f"(a lattice point {dist.max():.3g} m from the nearest)")
    triangles = which[np.concatenate(out)]
    # wind each as its face: flip those whose right-hand normal opposes the point's
    p = points.points[triangles]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    flip = np.einsum("ij,ij->i", cross, points.normals[triangles[:, 0]]) < 0
    triangles[flip] = triangles[flip][:, ::-1]
    used, compact = np.unique(triangles, return_inverse=True)
    return used, compact.reshape(-1, 3)



def grid_mesh(points, normal):
    """Triangles (2(nv−1)(nu−1), 3) over a film grid ``points`` (nv, nu, 3), row-major
    vertex indices, each cell cut in two and wound counter-clockwise about the surface's
    outward ``normal`` (3,): a flat panel's film mesh (``film.ply``)."""
    pts = np.asarray(points, dtype=float)
    nv, nu = pts.shape[:2]
    i, j = np.meshgrid(np.arange(nv - 1), np.arange(nu - 1), indexing="ij")
    a = (i * nu + j).ravel()
    b, c, d = a + 1, a + nu + 1, a + nu
    tris = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    flat = pts.reshape(-1, 3)
    p = flat[tris]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    flip = cross @ np.asarray(normal, dtype=float) < 0
    tris[flip] = tris[flip][:, ::-1]
    return tris


__all__ = ["grid_mesh", "refined_mesh"]
