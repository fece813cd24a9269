"""The gun's clearance from the part along a planned path (docs/model.md §25).

At every sample of the path (the part at rest: a line's path less the line's displacement),
the gun's body (:class:`.spray.gun_body.GunBody`: capsules along the spray axis behind the
tip) must stay ``clearance`` from the part's mesh. The distance is that of the capsules'
sampled axis points to the mesh, less each capsule's radius, the least over all samples:

1. the mesh's faces are sampled on barycentric grids (:func:`surface_samples`) whose every
   sub-triangle's longest edge is at most δ, so any point of the mesh lies within δ of a
   sample, and a k-d tree gives each axis point's distance d̃ to the samples:
   d − δ ≤ ... ≤ d̃ − r bounds the point's clearance d − r (d its distance to the mesh);
2. only the axis points whose lower bound d̃ − δ − r lies below the least upper bound can
   hold the least distance: their exact closest points on the faces whose centroid lies
   within d̃ + the faces' largest centroid-to-vertex distance (a k-d tree of centroids;
   ``trimesh.triangles.closest_point`` on each pair), lowest bound first, stopping when no
   lower bound is below the least exact distance found less δ: the least found is within δ
   above the least over the sampled points.

What lies between the samples may come closer, by at most ``between`` (stated in the
result): δ, plus half the largest spacing of the axis points, plus half the largest chord
any body point travels in one time step (|Δtip| + reach·|Δaxis|). A path refused is one line naming
the sample's time, what the gun is doing there, the point on the part [mm] and the distance
found against the clearance.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import trimesh
from scipy.spatial import cKDTree

from ...analytic.taskspace import rotation
from ..errors import PlanError
from ..spray.gun_body import CLEARANCE, GunBody

SURFACE_STEP = 0.004  # m: the surface samples' sub-triangle edges, at most (δ)
MAX_SURFACE_POINTS = 400_000  # δ grows until the samples fit (≈ 10 MB of k-d tree)
EXACT_POINTS = 512  # the axis points of lowest bound whose exact distance is computed


class ClearanceError(PlanError):
    """The gun's body comes closer to the part than the clearance (one line: where)."""


@dataclass(frozen=True)
class Clearance:
    """The least distance [m] between the gun's body and the part over a path's samples
    (negative: the body cuts into the part), at ``sample`` (time ``time`` [s]), the part's
    ``point`` nearest the body there and the ``tip``; ``between`` [m] how much closer the
    body may come between samples; ``required`` the clearance asked for."""

    distance: float
    between: float
    required: float
    sample: int
    time: float
    point: tuple[float, float, float]
    tip: tuple[float, float, float]

    def to_dict(self) -> dict:
        return {"min_m": self.distance, "between_samples_m": self.between,
                "required_m": self.required, "time": self.time,
                "point": list(self.point), "tip": list(self.tip)}


def surface_samples(vertices, faces, step: float = SURFACE_STEP):
    """Points on every face (barycentric grids), the face of each, and δ [m]: every point
    of the mesh lies within δ of one of its face's points (a sub-triangle's diameter is its
    longest edge)."""
    tri = np.asarray(vertices, float)[np.asarray(faces)]
    longest = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)
    while True:
        n = np.maximum(1, np.ceil(longest / step)).astype(int)
        if ((n + 1) * (n + 2) // 2).sum() <= MAX_SURFACE_POINTS:
            break
        step *= 1.5
    points, owner = [], []
    for k in np.unique(n):
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
        keep = i + j <= k
        w = np.stack([k - i[keep] - j[keep], i[keep], j[keep]], axis=1) / k  # (G, 3)
        these = np.flatnonzero(n == k)
        points.append(np.einsum("gc,fcx->fgx", w, tri[these]).reshape(-1, 3))
        owner.append(np.repeat(these, len(w)))
    return np.concatenate(points), np.concatenate(owner), float((longest / n).max())


def body_points(poses, body: GunBody):
    """The body's sampled axis points (N, K, 3) for tool poses (N, 6), their radii (K,)."""
    poses = np.asarray(poses, float)
    axis = rotation(poses)[:, :, 0]  # the spray axis a = R·e_x (docs/model.md §20)
    offs, radii = body.axis_points()
    return poses[:, None, :3] - offs[None, :, None] * axis[:, None, :], radii


def least_distance(mesh: trimesh.Trimesh, centres, radii):
    """The least of |c − mesh| − r found over axis points ``centres`` (M, 3) of radii (M,)
    (module notes 1–2): (that distance, its index, the mesh's closest point there, how much
    less the least over all of them may be)."""
    tri = np.asarray(mesh.triangles, float)
    samples, owner, delta = surface_samples(mesh.vertices, mesh.faces)
    tree = cKDTree(samples, balanced_tree=False, compact_nodes=False)  # faster far queries
    approx, _ = tree.query(centres)
    lower = approx - delta - radii
    order = np.argsort(lower)[:EXACT_POINTS]
    # a face within d ≤ d̃ of c has one of its samples within d̃ + δ
    near = tree.query_ball_point(centres[order], approx[order] + delta)
    pair = np.unique(np.concatenate([
        i * len(tri) + np.unique(owner[np.asarray(f, int)]) for i, f in enumerate(near)]))
    who, face = order[pair // len(tri)], pair % len(tri)
    closest = trimesh.triangles.closest_point(tri[face], centres[who])
    dist = np.linalg.norm(closest - centres[who], axis=1) - radii[who]
    j = int(np.argmin(dist))
    best = float(dist[j])
    rest = np.argsort(lower)[EXACT_POINTS:EXACT_POINTS + 1]
    floor = min(best, float(lower[rest[0]])) if len(rest) else best
    return best, int(who[j]), closest[j], best - floor


def between_samples(poses, body: GunBody) -> float:
    """How much closer than the samples the body may come [m] (module notes)."""
    poses = np.asarray(poses, float)
    if len(poses) < 2:
        return body.axis_gap
    axis = rotation(poses)[:, :, 0]
    chord = (np.linalg.norm(np.diff(poses[:, :3], axis=0), axis=1)
             + body.reach * np.linalg.norm(np.diff(axis, axis=0), axis=1))
    return body.axis_gap + float(chord.max()) / 2


def clearance_of(mesh: trimesh.Trimesh, poses, t, body: GunBody | None = None,
                 required: float = CLEARANCE) -> Clearance:
    """The :class:`Clearance` of tool poses (N, 6) at times ``t`` (N,) from the mesh (in
    the same frame), not checked against ``required``."""
    body = GunBody() if body is None else body
    poses = np.asarray(poses, float)
    centres, radii = body_points(poses, body)
    n, k = centres.shape[:2]
    best, idx, point, less = least_distance(mesh, centres.reshape(-1, 3), np.tile(radii, n))
    i = idx // k
    return Clearance(best, less + between_samples(poses, body), float(required), i, float(t[i]),
                     tuple(float(c) for c in point), tuple(float(c) for c in poses[i, :3]))


def check_clearance(mesh: trimesh.Trimesh, poses, t, body: GunBody | None = None,
                    required: float = CLEARANCE,
                    where: Callable[[int], str] | None = None) -> Clearance:
    """:func:`clearance_of`, refused as a :class:`ClearanceError` naming the place (``where``
    of the sample: what the gun does there) when the body comes closer than ``required``
    less what may lie between samples."""
    c = clearance_of(mesh, poses, t, body, required)
    if c.distance - c.between < required:
        x = np.asarray(c.point) * 1e3
        place = f" {where(c.sample)}" if where is not None else ""
        gap = (f"comes {c.distance * 1e3:.1f} mm from" if c.distance >= 0 else
               f"cuts {-c.distance * 1e3:.1f} mm into")
        raise ClearanceError(
            f"the gun's body {gap} the part at ({x[0]:.0f}, {x[1]:.0f}, {x[2]:.0f}) mm, t = "
            f"{c.time:.3f} s{place}; clearance {required * 1e3:.3g} mm (± "
            f"{c.between * 1e3:.1f} mm between samples): a larger standoff, or turn the part "
            "so nothing stands taller than it")
    return c


def job_clearance(robot, job, mesh, poses, t, where=None) -> Clearance:
    """:func:`check_clearance` of a planned path (poses in the part's frame) with the
    robot's gun body and the job's ``gun.clearance`` (default CLEARANCE)."""
    from ..spray.gun_body import gun_body

    required = CLEARANCE if getattr(job, "clearance", None) is None else job.clearance
    return check_clearance(mesh, poses, t, gun_body(getattr(robot, "params", None)),
                           required, where)


def panel_mesh(frame) -> trimesh.Trimesh:
    """A panel (:class:`.target.panel.PanelFrame`) as two triangles."""
    corners = frame.world(np.array([-1, 1, 1, -1]) * frame.width / 2,
                          np.array([-1, -1, 1, 1]) * frame.height / 2)
    return trimesh.Trimesh(corners, np.array([[0, 1, 2], [0, 2, 3]]), process=False)


__all__ = ["Clearance", "ClearanceError", "between_samples", "body_points", "check_clearance",
           "clearance_of", "job_clearance", "least_distance", "panel_mesh", "surface_samples"]
