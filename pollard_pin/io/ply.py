"""A film on a mesh as PLY (``paint``'s ``film.ply``): binary little-endian, vertices x, y, z
(float32, as MeshLab and ParaView read them), RGBA colours (uchar) and a per-vertex
``thickness`` property (float64, m), triangles as vertex index lists; written through trimesh's
exporter, atomically."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def write_film_ply(path: str | Path, vertices, faces, thickness, colours,
                   comment: str | None = None) -> None:
    """Write the mesh ``vertices`` (V, 3) [m], ``faces`` (M, 3) with per-vertex ``thickness``
    (V,) [m] and ``colours`` (V, 4) RGBA bytes to ``path``; ``comment`` (one line) goes in
    the header after the format line (a PLY ``comment``)."""
    import trimesh

    from .atomic import atomic_open

    mesh = trimesh.Trimesh(np.asarray(vertices, float), np.asarray(faces, int), process=False)
    mesh.visual.vertex_colors = np.asarray(colours, dtype=np.uint8)
    mesh.vertex_attributes["thickness"] = np.asarray(thickness, dtype=np.float64)
    data = mesh.export(file_type="ply", encoding="binary")
    if comment:
        k = data.index(b"\n", data.index(b"\nformat ") + 1) + 1
        line = " ".join(str(comment).split()).encode("ascii", "replace")
        data = data[:k] + b"comment " + line + b"\n" + data[k:]
    with atomic_open(path, binary=True) as f:
        f.write(data)


def read_film_ply(path: str | Path):
    """(vertices (V, 3) [m], faces (M, 3), thickness (V,) [m]) of a ``film.ply``; a file that
    is not one is a :class:`~pollard_pin.io.table.ResultFileError` line."""
    import trimesh

    from .table import ResultFileError

    try:
        mesh = trimesh.load(str(path), file_type="ply", process=False, force="mesh")
        th = np.asarray(mesh.metadata["_ply_raw"]["vertex"]["data"]["thickness"], float)
    except Exception as exc:  # any reader failure is the file's fault
        why = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ResultFileError(f"{path}: not a film PLY with a per-vertex thickness ({why})"
                              ) from None
    v, f = np.asarray(mesh.vertices, float), np.asarray(mesh.faces)
    if len(f) == 0 or len(th) != len(v) or not (np.isfinite(v).all() and np.isfinite(th).all()):
        raise ResultFileError(f"{path}: not a film PLY (no faces, or non-finite vertices or "
                              "thickness)")
    return v, f, th


__all__ = ["read_film_ply", "write_film_ply"]
