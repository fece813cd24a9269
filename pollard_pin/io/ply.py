"""A film on a mesh as PLY (``paint``'s ``film.ply``): binary little-endian, vertices x, y, z
(float32, as MeshLab and ParaView read them), RGBA colours (uchar) and a per-vertex
``thickness`` property (float64, m), triangles as vertex index lists; written through trimesh's
exporter, atomically."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def write_film_ply(path: str | Path, vertices, faces, thickness, colours) -> None:
    """Write the mesh ``vertices`` (V, 3) [m], ``faces`` (M, 3) with per-vertex ``thickness``
    (V,) [m] and ``colours`` (V, 4) RGBA bytes to ``path``."""
    import trimesh

    from .atomic import atomic_open

    mesh = trimesh.Trimesh(np.asarray(vertices, float), np.asarray(faces, int), process=False)
    mesh.visual.vertex_colors = np.asarray(colours, dtype=np.uint8)
    mesh.vertex_attributes["thickness"] = np.asarray(thickness, dtype=np.float64)
    data = mesh.export(file_type="ply", encoding="binary")
    with atomic_open(path, binary=True) as f:
        f.write(data)


__all__ = ["write_film_ply"]
