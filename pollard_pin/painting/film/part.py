"""The film a part's plan leaves (docs/model.md §23): film points on the painted faces and on
every face the gun lies in front of, the film with shadows and the trigger, the transfer
efficiency."""
from __future__ import annotations

import numpy as np

from ...analytic.taskspace import rotation
from ..plan.part import SurfacePlan
from ..spray.deposition import BLOCK_ELEMENTS, gun_of
from ..workpiece.mesh import Part
from .grid import film_spacing
from .mesh import MeshFilm, mesh_film
from .points import surface_points


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


def surface_film(plan: SurfacePlan, resolution: float | None = None):
    """(film points on the painted faces and on every face any tip lies in front of, their
    film :class:`.film.mesh.MeshFilm`, the painted mask over the points, the transfer
    efficiency): the film of the plan's path with shadows and the trigger. Faces behind every
    tip get exactly nothing (:func:`live_faces`), so the volume landed on the points is the
    volume landed on the part."""
    job = plan.job
    tr = plan.trajectory
    on = plan.spray > 0
    faces = live_faces(plan.part, tr.poses[on, :3]) | plan.part.painted
    pts = surface_points(plan.part, resolution, sigma=job.sigma, faces=faces)
    axes = rotation(tr.poses)  # the spot turns with the gun (docs/model.md §20)
    film: MeshFilm = mesh_film(gun_of(job), tr.t, tr.poses[:, :3], axes, pts, plan.part,
                               plan.spray)
    efficiency = film.landed / film.sprayed if film.sprayed > 0 else float("nan")
    return pts, film, plan.part.painted[pts.faces], efficiency


__all__ = ["live_faces", "part_resolution", "surface_film"]
