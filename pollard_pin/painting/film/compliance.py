"""What compliance does to the paint (docs/model.md §27.7): the film of the deflected program
(the same planned path, each sample's pose moved by the drives' deflection under the weight
and the spray's recoil, :mod:`.plan.compliance`) against the rigid film, at the same film
points, by the same integration; and paint.json's ``compliance`` entry."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...analytic.taskspace import rotation
from ...dynamics.motors import ActuatorError, Actuators
from ...paths.trajectory import Trajectory
from ..errors import JobKindError
from ..line.panel import LinePlan
from ..line.part import LinePartPlan
from ..plan.compliance import ProgramDeflection, deflected_poses, program_deflection
from ..plan.panel import PaintPlan
from ..plan.part import SurfacePlan
from ..spray.deposition import film, gun_of
from .line import part_frame_positions
from .mesh import mesh_film


def _moved(plan, poses):
    """The plan with its trajectory's poses replaced (rates and timing unchanged)."""
    tr = plan.trajectory
    return replace(plan, trajectory=Trajectory(tr.t, poses, tr.d_poses, tr.dd_poses,
                                               name=tr.name + ", deflected"))


def program_film(plan, points, poses) -> np.ndarray:
    """The film thickness [m] that ``plan``'s program leaves at ``points`` (a panel's grid
    (nv, nu, 3), a part's :class:`.film.points.SurfacePoints`) when the gun follows ``poses``
    (N, 6, world) at the plan's times and trigger: the integration the plan's own film uses
    (:func:`.film.grid.plan_film`, :func:`.film.line.line_film`,
    :func:`.film.part.surface_film`), flattened as its thickness."""
    moved = _moved(plan, poses)
    if isinstance(moved, LinePartPlan):
        moved = moved.in_part_frame()
    tr = moved.trajectory
    gun = gun_of(plan.job)
    if isinstance(moved, SurfacePlan):
        return mesh_film(gun, tr.t, tr.poses[:, :3], rotation(tr.poses)[:, :, 0], points,
                         moved.part, moved.spray).thickness
    pts = np.asarray(points).reshape(-1, 3)
    if isinstance(moved, LinePlan):
        on = moved.spray > 0
        return film(gun, tr.t[on], part_frame_positions(moved)[on],
                    rotation(tr.poses[on])[:, :, 0], pts, moved.frame.n,
                    origin=moved.frame.c).thickness
    if isinstance(moved, PaintPlan):
        return film(gun, tr.t, tr.poses[:, :3], rotation(tr.poses)[:, :, 0], pts,
                    moved.frame.n, origin=moved.frame.c).thickness
    raise JobKindError(f"no film of a deflected program for a {type(plan).__name__}: a "
                       "panel's or a part's plan, still or on a line")


def film_error(thickness, deflected, target: float, painted=None) -> tuple[float, int]:
    """(max |T' − T| / target over the painted points, the index of that point)."""
    change = np.abs(np.asarray(deflected) - np.asarray(thickness).ravel()) / target
    if painted is not None:
        change = np.where(painted, change, -np.inf)
    k = int(np.argmax(change))
    return float(change[k]), k


def drive_stiffness(job, act: Actuators) -> tuple[float, np.ndarray | None, dict]:
    """(the job's recoil [N], the drives' stiffnesses or None, the report entry that says
    why nothing was computed): an actuators file without ``stiffness`` is not an error for
    paint, only a note (docs/model.md §27.7)."""
    recoil = float(getattr(job, "recoil", None) or 0.0)
    try:
        return recoil, act.stiffness(), {}
    except ActuatorError as exc:
        return recoil, None, {"recoil_n": recoil, "stiffness": False,
                              "note": f"not computed: {exc}"}


def compliance_entry(robot, plan, points, thickness, act: Actuators, painted=None) -> dict:
    """paint.json's ``compliance`` (docs/model.md §27.7): what the drives' springs do to the
    paint under the weight and the job's recoil.

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    plan : object
        A single robot's plan (``PaintResult.plan``): its program, trigger and job.
    points : object
        The film points (a panel's grid (nv, nu, 3) or a part's surface points) [m].
    thickness : numpy.ndarray
        The rigid film there [m].
    act : Actuators
        The motor ratings; their ``stiffness`` gives the springs.
    painted : numpy.ndarray or None, optional
        The mask of points whose film counts (default all).

    Returns
    -------
    dict
        ``recoil_n`` [N]; ``stiffness`` (False, with a ``note``, when the actuators have
        none); over the sprayed samples ``standoff_error_m`` [m] (at
        ``standoff_error_at_t`` [s]), ``lateral_error_m`` [m], ``tilt_rad`` [rad]; over the
        painted points ``film_error``, the largest film change relative to the target, at
        ``film_error_at`` [m]; ``drive_stiffness`` [N·m/rad].
    """
    recoil, k, note = drive_stiffness(plan.job, act)
    if k is None:
        return note
    entry = {"recoil_n": recoil}
    d: ProgramDeflection = program_deflection(robot, plan.trajectory, k, plan.spray, recoil)
    on = plan.spray > 0
    T = program_film(plan, points, deflected_poses(plan.trajectory.poses, d.deflection))
    err, where = film_error(thickness, T, plan.job.thickness, painted)
    pts = points.points if hasattr(points, "points") else np.asarray(points).reshape(-1, 3)
    i = int(np.flatnonzero(on)[np.argmax(np.abs(d.standoff[on]))])
    return {**entry, "stiffness": True,
            "standoff_error_m": float(np.abs(d.standoff[on]).max()),
            "standoff_error_at_t": float(plan.trajectory.t[i]),
            "lateral_error_m": float(d.lateral[on].max()),
            "tilt_rad": float(d.tilt[on].max()),
            "film_error": err,
            "film_error_at": [float(c) for c in pts[where]],
            "drive_stiffness": [float(x) for x in k]}


__all__ = ["compliance_entry", "drive_stiffness", "film_error", "program_film"]
