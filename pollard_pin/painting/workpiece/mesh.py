"""A part to paint, from its triangle mesh (STL binary or ASCII, OBJ, PLY), placed in the
world frame (docs/model.md §2: x forward from the robot's base towards the work, z up).

Faces keep the file's winding: counter-clockwise seen from outside, so the right-hand normal
(v1 − v0) × (v2 − v0) points outwards. A closed mesh whose signed volume is negative is wound
the other way throughout and is turned over once; an open sheet is taken as given. Faces of
zero area (below 1e-12 of the part's size squared) are dropped: they receive no paint.

Ray queries (:mod:`..spray.occlusion`) go through ``Part.mesh.ray``: Embree (``embreex``,
installed with the package where it has wheels), else trimesh's own numpy intersector on
``rtree``: the same verdicts (up to Embree's float32 arithmetic), only slower.
"""
from __future__ import annotations

import io
import math
import warnings
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from ...analytic.taskspace import turn
from ...model.values import read_bytes
from ..errors import MeshError, MeshFileError
from ..job import UNITS, PaintJob
from .mesh_check import (
    check_indices,
    obj_absolute,
    ply_counts,
    stl_ascii,
    stl_count,
    unique_faces,
)
from .panel import panel_frame

if TYPE_CHECKING:  # trimesh (with scipy, networkx) loads where a mesh is made: not for `run`
    import trimesh

FORMATS = ("stl", "obj", "ply")
# Faces beyond this make the film (≥ 3 points a face) and the shadows slow for no gain: the
# film grid is ~σ/3 = 3 mm, so a 0.3 m part needs ~1e4 faces, a 1 m² part ~1e5.
MAX_FACES = 200_000
# bytes of a mesh file: an ASCII STL of MAX_FACES triangles takes about 50 MB
MAX_MESH_BYTES = 128 * 2**20
# A part larger than this is a unit slip: the robot reaches ~0.5 m (mm read as m).
MAX_EXTENT = 5.0
# Faces whose outward normal lies within this of ``facing`` are painted, unless told: the
# gun stays normal to the surface, and it keeps most of the workspace up to ~35° of yaw.
MAX_ANGLE = 45.0
# The robot stands at the origin, the work in front along +x: a face towards it faces −x
# (examples/paint.toml's panel normal).
FACING = (-1.0, 0.0, 0.0)
DEGENERATE = 1e-12  # of the part's size squared: faces of smaller area are dropped
RISE_PRODUCTS = 50_000_000  # faces × hull vertices for Part.rise (~0.2 s): beyond, not computed


def _frozen(x, dtype=float) -> np.ndarray:
    a = np.array(x, dtype=dtype)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class Part:
    """A part in the world frame [m]: ``vertices`` (V, 3), ``faces`` (F, 3) indices wound
    counter-clockwise seen from outside, unit outward ``normals`` (F, 3), ``areas`` (F,)
    [m²], ``painted`` (F,) the faces to paint (normal within ``max_angle`` degrees of the
    unit ``facing``), ``mesh`` the same triangles as a trimesh for ray queries."""

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    areas: np.ndarray
    painted: np.ndarray
    facing: tuple[float, float, float]
    max_angle: float
    mesh: trimesh.Trimesh
    source: str = "<python>"

    @property
    def painted_area(self) -> float:
        return float(self.areas[self.painted].sum())

    @cached_property  # asked by every block of the film's ray tests
    def size(self) -> float:
        """The largest side of the bounding box [m]."""
        return float(np.ptp(self.vertices, axis=0).max())

    @cached_property  # asked by every block of the film's ray tests
    def rise(self) -> np.ndarray:
        """(F,) how far [m] the part rises above each face's plane, along its outward normal:
        the largest (v − v₀)·n over the vertices of its convex hull (all vertices of a flat
        part), ≥ 0 up to round-off; 0 where the plane supports the whole part (a convex
        part's faces, the back of a plate, a rib's top), inf where not computed (more than
        RISE_PRODUCTS face × hull vertex products)."""
        v = self.vertices[np.unique(self.faces)]
        try:
            v = v[ConvexHull(v).vertices]
        except (QhullError, ValueError):  # a flat part: every vertex counts
            pass
        out = np.full(len(self.faces), np.inf)
        if len(self.faces) * len(v) <= RISE_PRODUCTS:
            base = np.einsum("ij,ij->i", self.vertices[self.faces[:, 0]], self.normals)
            block = max(1, 1_000_000 // len(v))  # (block × hull) products: ~8 MB each
            for start in range(0, len(self.faces), block):
                sl = slice(start, start + block)
                out[sl] = (self.normals[sl] @ v.T).max(axis=1) - base[sl]
        out.flags.writeable = False
        return out


def _vector(source: str, name: str, value, unit: str) -> np.ndarray:
    v = np.asarray(value, dtype=float) if value is not None else None
    if v is None or v.shape != (3,) or not np.all(np.isfinite(v)):
        raise MeshError(f"{source}: {name} = {value!r} must be 3 finite numbers [{unit}]")
    return v


def placement(position=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0), source: str = "<python>"):
    """(R (3, 3), position (3,)) of a part: ``rotation`` = (rx, ry, rz) degrees about the world
    axes, composed like the tool pose (docs/model.md §2) R = Rx(rx)·Ry(ry)·Rz(rz): the part
    turns about world z first, then world y, then world x (extrinsic z–y–x, intrinsic
    x–y′–z″), about its own origin, which then goes to ``position`` [m]."""
    angles = _vector(source, "rotation", rotation, "deg")
    p = _vector(source, "position", position, "m")
    return turn(*angles), p


def make_part(vertices, faces, facing=None, max_angle: float = MAX_ANGLE,
              source: str = "<python>", units: str | float = "m") -> Part:
    """Check world ``vertices`` (V, 3) [m] and ``faces`` (F, 3) and build the :class:`Part`
    (see :func:`load_part` for the rules)."""
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3 or len(f) == 0:
        raise MeshError(f"{source}: no triangles in the mesh (is it a triangle mesh in STL, "
                        "OBJ or PLY?)")
    if not np.issubdtype(f.dtype, np.integer) or f.min() < 0 or f.max() >= len(v):
        raise MeshError(f"{source}: face indices must lie in 0..{len(v) - 1}")
    if len(f) > MAX_FACES:
        raise MeshError(f"{source}: {len(f)} faces, more than the {MAX_FACES} the film and "
                        "shadow computations take: decimate the mesh (faces need not be "
                        "smaller than the film resolution, ~σ/3)")
    bad = ~np.all(np.isfinite(v), axis=1)
    if bad.any():
        k = int(np.argmax(bad))
        raise MeshError(f"{source}: vertex {k} = {tuple(float(c) for c in v[k])} is not "
                        f"finite ({int(bad.sum())} such vertices)")
    used = v[np.unique(f)]
    extent = float(np.ptp(used, axis=0).max())
    if extent > MAX_EXTENT:
        hint = ("1000x too large: units = 'mm'?" if units in ("m", 1.0) else
                "far beyond this robot's reach: a smaller part.scale?")
        raise MeshError(f"{source}: the part is {extent:.4g} m across, more than "
                        f"{MAX_EXTENT:g} m: {hint}")
    tri = v[f]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area2 = np.linalg.norm(cross, axis=1)
    keep = area2 > 2 * DEGENERATE * max(extent, 1e-300) ** 2
    if not keep.any():
        raise MeshError(f"{source}: all {len(f)} faces have zero area (the part is "
                        f"{extent:.4g} m across)")
    if not keep.all():
        warnings.warn(f"{source}: dropped {int((~keep).sum())} faces of zero area (below "
                      f"{DEGENERATE:g} of the part's size squared): they take no paint",
                      stacklevel=3)
    f, cross, area2 = f[keep], cross[keep], area2[keep]
    normals = cross / area2[:, None]
    import trimesh

    mesh = trimesh.Trimesh(v, f, process=False)
    if mesh.is_watertight and mesh.is_winding_consistent and mesh.volume < 0:
        f, normals = f[:, ::-1], -normals  # wound clockwise seen from outside: turn over
        mesh = trimesh.Trimesh(v, f, process=False)
    facing = np.asarray(FACING if facing is None else _vector(source, "facing", facing, "-"))
    length = float(np.linalg.norm(facing))
    if not length > 1e-12:
        raise MeshError(f"{source}: facing = {tuple(float(c) for c in facing)} has zero "
                        "length")
    facing = facing / length
    max_angle = float(max_angle)
    if not 0 < max_angle < 90:  # a face at 90° or more is edge-on or turned away
        raise MeshError(f"{source}: max_angle = {max_angle:.4g}° must be in (0, 90): a face "
                        "at 90° or more is seen edge-on or from behind")
    painted = normals @ facing >= math.cos(math.radians(max_angle)) - 1e-12
    if not painted.any():
        best = math.degrees(math.acos(float(np.clip((normals @ facing).max(), -1, 1))))
        raise MeshError(f"{source}: no face has its outward normal within {max_angle:.4g}° of "
                        f"facing {tuple(round(float(c), 4) for c in facing)} (the closest is "
                        f"{best:.4g}° off): turn the part or raise max_angle")
    return Part(_frozen(v), _frozen(f, int), _frozen(normals), _frozen(area2 / 2),
                _frozen(painted, bool), tuple(float(c) for c in facing), max_angle, mesh,
                source)


def _read_mesh(data: bytes, ext: str, src: str):
    """(vertices, faces) of a mesh file's bytes, checked against what the file says
    (:mod:`.mesh_check`): indices, PLY and binary STL counts; repeated faces dropped with a
    warning."""
    if ext == "obj":
        data = obj_absolute(data, src)
    elif ext == "ply":
        ply_counts(data, src)
    elif stl_count(data, src) is None:
        stl_ascii(data, src)
    import trimesh

    try:
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            loaded = trimesh.load(io.BytesIO(data), file_type=ext, force="mesh",
                                  process=False)
            if len(getattr(loaded, "faces", ())):
                check_indices(loaded.vertices, loaded.faces, src)
                # one vertex per position (an STL repeats each corner per face), so that a
                # closed part is seen to be closed
                loaded.merge_vertices(merge_tex=True, merge_norm=True)
    except MeshFileError:
        raise
    except Exception as exc:  # any reader failure is the file's fault
        raise MeshError(f"{src}: not a readable {ext.upper()} mesh "
                        f"({str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__})"
                        ) from None
    v = np.asarray(getattr(loaded, "vertices", np.empty((0, 3))), dtype=float)
    f = np.asarray(getattr(loaded, "faces", np.empty((0, 3), int)))
    if len(f) == 0:
        raise MeshError(f"{src}: no triangles in the file (is it a triangle mesh in {ext.upper()} "
                        "format?)")
    f, repeated = unique_faces(f)
    if repeated:
        warnings.warn(f"{src}: dropped {repeated} repeated faces (the same three corners as "
                      "another face): each is painted once", stacklevel=3)
    return v, f


def unit_length(units: str | float, source: str = "<python>") -> float:
    """The mesh file's length unit [m]: a name of UNITS or a number > 0 (a job's scale)."""
    if isinstance(units, str) and units in UNITS:
        return UNITS[units]
    if (not isinstance(units, (str, bool)) and isinstance(units, (int, float))
            and math.isfinite(units) and units > 0):
        return float(units)
    raise MeshError(f"{source}: units = {units!r} must be one of "
                    f"{', '.join(repr(k) for k in UNITS)} or a length in m > 0")


def load_part(path, units: str | float = "m", position=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0),
              facing=None, max_angle: float = MAX_ANGLE) -> Part:
    """Read a part's mesh (STL, OBJ or PLY by its extension) and place it: file coordinates
    in ``units`` (a name of UNITS, or the unit's length in m: :func:`unit_length`), turned
    by ``rotation`` (degrees, :func:`placement`) about the file's origin and moved to
    ``position`` [m]. Painted faces: outward normal within
    ``max_angle`` degrees of ``facing`` (default −x, towards the robot).

    One :class:`MeshError` line for: a file that is missing, unreadable or of another format;
    no triangles; non-finite vertices; only zero-area faces; more than MAX_FACES faces; a part
    over MAX_EXTENT across (mm read as m); no face within ``max_angle``."""
    path = Path(path)
    src = str(path)
    unit = unit_length(units, src)
    ext = path.suffix.lower().lstrip(".")
    if ext not in FORMATS:  # the format is the name's: a name without one says so
        what = f"format '.{ext}' is" if ext else "a name without an extension is"
        raise MeshError(f"{src}: {what} not a mesh this reads (STL, OBJ or PLY)")
    # the one reading rule: a regular file (a FIFO would block), within a size budget
    data = read_bytes(path, "mesh file", MeshError, MAX_MESH_BYTES)
    R, p = placement(position, rotation, src)
    v, f = _read_mesh(data, ext, src)
    v = v * unit
    if not np.all(np.isfinite(v)):
        return make_part(v, f, facing, max_angle, src, units)  # names the vertex
    return make_part(v @ R.T + p, f, facing, max_angle, src, units)


def panel_part(job: PaintJob) -> Part:
    """The job's flat panel as two triangles (the panel planner's frame, :mod:`.passes.raster`):
    corners c ± width/2·u ± height/2·v, outward normal the job's normal, all painted."""
    fr = panel_frame(job)
    w, h = job.width / 2, job.height / 2
    corners = [fr.c - w * fr.u - h * fr.v, fr.c + w * fr.u - h * fr.v,
               fr.c + w * fr.u + h * fr.v, fr.c - w * fr.u + h * fr.v]
    # u × v = −n: counter-clockwise about n runs against (u, v)
    faces = [[0, 2, 1], [0, 3, 2]]
    return make_part(np.array(corners), np.array(faces), facing=fr.n, max_angle=MAX_ANGLE,
                     source=job.source)


def load_job_part(job) -> Part:
    """The job's part, read and placed (:func:`.workpiece.mesh.load_part`)."""
    return load_part(job.mesh, job.unit, job.position, job.rotation, job.facing,
                     MAX_ANGLE if job.max_angle is None else job.max_angle)


__all__ = ["FACING", "FORMATS", "MAX_ANGLE", "MAX_EXTENT", "MAX_FACES", "Part",
           "RISE_PRODUCTS", "UNITS", "load_job_part", "load_part", "make_part", "panel_part",
           "placement", "unit_length"]
