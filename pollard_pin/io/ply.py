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


# a film thicker than this many times the target is a damaged file, not a film
ABSURD_FILM = 1000.0


def read_film_ply(path: str | Path, target: float | None = None):
    """(vertices (V, 3) [m], faces (M, 3), thickness (V,) [m]) of a ``film.ply``. A file that
    is not one, a face index outside the vertices, a non-finite or negative thickness, or (with
    the film's ``target`` [m]) one over :data:`ABSURD_FILM` × target is a
    :class:`~pollard_pin.io.table.ResultFileError` line naming the element and the value."""
    from trimesh.exchange.ply import load_ply

    from .table import ResultFileError

    try:  # the raw arrays: a Trimesh would index (or wrap) bad faces before we look
        with open(path, "rb") as fh:
            raw = load_ply(fh)
        th = np.asarray(raw["metadata"]["_ply_raw"]["vertex"]["data"]["thickness"], float)
        v, f = np.asarray(raw["vertices"], float), np.asarray(raw["faces"])
    except Exception as exc:  # any reader failure is the file's fault
        why = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ResultFileError(f"{path}: not a film PLY with a per-vertex thickness ({why})"
                              ) from None
    if (f.ndim != 2 or f.shape[1:] != (3,) or len(f) == 0 or v.ndim != 2
            or v.shape[1:] != (3,) or len(th) != len(v) or f.dtype.kind not in "iu"):
        raise ResultFileError(f"{path}: not a film PLY (no triangles, or not one thickness "
                              "per vertex)")
    _check_film(path, v, f, th, target)
    return v, f, th


def _check_film(path, v, f, th, target) -> None:
    from .table import ResultFileError

    n = len(v)
    bad = (f < 0) | (f >= n)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        raise ResultFileError(f"{path}: face {k} (from 0): vertex index {f[k, j]}, outside "
                              f"0 … {n - 1} (the file's {n} vertices)")
    if not np.isfinite(v).all():
        k = int(np.argwhere(~np.isfinite(v))[0][0])
        raise ResultFileError(f"{path}: vertex {k} (from 0): position {v[k].tolist()} m, "
                              "not finite")
    check_film_values(path, th, target)


def check_film_values(where, th, target: float | None, what: str = "vertex",
                      first: int = 0) -> None:
    """A :class:`~pollard_pin.io.table.ResultFileError` line for the first film ``th`` [m]
    that no spray lays: not finite, below 0, or over :data:`ABSURD_FILM` × ``target`` [m]
    (when given); ``where`` names the file, ``what`` its elements, numbered from ``first``."""
    from .table import ResultFileError

    th = np.asarray(th, float).ravel()
    odd = ~np.isfinite(th) | (th < 0)
    if target is not None:
        odd |= th > ABSURD_FILM * target
    if odd.any():
        k = int(np.argmax(odd))
        at = f"{where}: {what} {k + first}" + (" (from 0)" if first == 0 else "")
        if not np.isfinite(th[k]):
            raise ResultFileError(f"{at}: thickness not finite ({th[k]})")
        why = ("below 0 (a film is at least 0 m thick)" if th[k] < 0 else
               f"over {ABSURD_FILM:g} × the target {target:.4g} m: a damaged file?")
        raise ResultFileError(f"{at}: thickness = {th[k]:.4g} m, {why}")


__all__ = ["ABSURD_FILM", "check_film_values", "read_film_ply", "write_film_ply"]
