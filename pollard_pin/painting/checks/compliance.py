"""How far the gun gives along a paint program (docs/model.md §27.7): the compliant drives'
deflection d = J K⁻¹ (Jᵀ W − τ_g) of :mod:`pollard_pin.dynamics.drives.stiffness` at every sample
of the program, under the robot's weight and the spray's recoil, split along the gun's axis.

The recoil is a force of ``recoil`` [N] × the trigger at the tip along −a (a = R e_x the
spray axis): the jet's momentum leaves the nozzle along a and pushes the gun back. A round jet
has no moment about its axis and no side force, so one number states it.

What that does to the paint: the film of the deflected program (the same planned path, each
sample's pose moved by the deflection) against the rigid film, at the same film points, by
the same integration; and paint.json's ``compliance`` entry.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...analytic.taskspace import angles_from_rotation, rotation
from ...dynamics.drives.stiffness import (
    StiffnessError,
    check_linear,
    check_stiffness,
    loaded_deflection,
)
from ...dynamics.motors import ActuatorError, Actuators
from ...errors import InputError
from ...paths.trajectory import Trajectory
from ..errors import JobKindError, ReachError
from ..film.cell import weighted_film
from ..film.edge_points import moved_shade
from ..film.line import part_frame_positions
from ..film.mesh import mesh_film
from ..job import MAX_RECOIL
from ..line.panel import LinePlan
from ..line.part import LinePartPlan
from ..plan.panel import PaintPlan
from ..plan.part import SurfacePlan
from ..progress import bar
from ..spray.deposition import film, gun_of
from .motion import reach

CHUNK = 4096  # samples per block: the IK's and the maps' arrays stay some 50 MB
# a point whose edge film (film.edge_points) exceeds this share of the target is reported
# apart, beside a shadow's edge (docs/model.md §27.7)
EDGE_FLOOR = 1e-4


@dataclass(frozen=True)
class ProgramDeflection:
    """Per sample of a program (N samples, the robot's base frame): ``deflection`` (N, 6) the
    tip's translation dx, dy, dz [m] and the gun's rotation vector rx, ry, rz [rad];
    ``axis`` (N, 3) the rigid spray axis; ``standoff`` (N,) the tip's translation along the
    axis [m] (> 0: towards the surface, the standoff shrinks by it); ``lateral`` (N,) the
    translation across the axis [m]; ``tilt`` (N,) the rotation's part perpendicular to the
    axis [rad] (the part about it does not move the spray)."""

    deflection: np.ndarray
    axis: np.ndarray
    standoff: np.ndarray
    lateral: np.ndarray
    tilt: np.ndarray


def recoil_wrench(axes, spray, recoil: float) -> np.ndarray:
    """The recoil wrench (N, 6) on the tool (force at the tip, world axes; no moment):
    −recoil × trigger × a."""
    w = np.zeros((len(axes), 6))
    w[:, :3] = -recoil * np.asarray(spray, dtype=float)[:, None] * axes
    return w


def program_deflection(robot, trajectory: Trajectory, stiffness, spray=None,
                       recoil: float = 0.0) -> ProgramDeflection:
    """The gun's deflection at every sample of a paint program under the weight and the
    spray's recoil along −a, the spray axis (docs/model.md §27.2, §27.7).

    Parameters
    ----------
    robot : Robot
        The model (:func:`pollard_pin.load`).
    trajectory : Trajectory
        The program, in the robot's base frame.
    stiffness : ArrayLike
        The six drives' stiffnesses [N·m/rad].
    spray : ArrayLike or None, optional
        The trigger per sample, 0…1 (default 1 throughout).
    recoil : float, optional
        The spray's push back on the gun [N] while the trigger is on (default 0).

    Returns
    -------
    ProgramDeflection
        Per sample the ``deflection`` (N, 6) [m, rad], the rigid spray ``axis`` (N, 3), the
        ``standoff`` (N,) [m] change along it (> 0: towards the surface), the ``lateral``
        (N,) [m] translation across it and the ``tilt`` (N,) [rad].

    Raises
    ------
    KinematicsError
        A pose out of reach or singular, naming the sample (the IK is ``run``'s).
    StiffnessError
        A stiffness missing or invalid; a drive turned beyond the linear model's bound
        (docs/model.md §27.2), naming the sample.
    """
    k = check_stiffness(stiffness)
    poses = np.asarray(trajectory.poses, dtype=float)
    n = len(poses)
    spray = np.ones(n) if spray is None else np.asarray(spray, dtype=float)
    if spray.shape != (n,) or not np.all((spray >= 0) & (spray <= 1)):
        raise InputError(f"spray: one trigger fraction in [0, 1] per sample ({n}), got shape "
                         f"{spray.shape}")
    if isinstance(recoil, bool) or not 0 <= recoil <= MAX_RECOIL:  # NaN fails too
        raise InputError(f"recoil = {recoil!r}: expected a force of 0 to {MAX_RECOIL:g} N")
    axes = rotation(poses)[:, :, 0]
    d = np.empty((n, 6))
    for start in bar(range(0, n, CHUNK), "compliance"):
        sl = slice(start, start + CHUNK)
        try:
            q = reach(robot, poses[sl]).q
        except ReachError as exc:  # the sample counted from the program's start
            raise ReachError(str(exc), start + exc.sample, exc.pose) from None
        d[sl], turn = loaded_deflection(robot, q, k, recoil_wrench(axes[sl], spray[sl], recoil))
        check_linear(turn, np.asarray(trajectory.t)[sl], start)  # the sample from the start
    along = np.einsum("ij,ij->i", d[:, :3], axes)
    turn = np.einsum("ij,ij->i", d[:, 3:], axes)
    lateral = np.linalg.norm(d[:, :3] - along[:, None] * axes, axis=1)
    tilt = np.linalg.norm(d[:, 3:] - turn[:, None] * axes, axis=1)
    return ProgramDeflection(d, axes, along, lateral, tilt)


def deflected_poses(poses, deflection) -> np.ndarray:
    """The poses (N, 6) moved by the deflection (N, 6): the tip by (dx, dy, dz), the
    orientation turned by the rotation vector (rx, ry, rz), world axes: R' = exp(r) R."""
    poses = np.asarray(poses, dtype=float)
    d = np.asarray(deflection, dtype=float)
    r = d[:, 3:]
    angle = np.linalg.norm(r, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where(angle[:, None] > 0, r / angle[:, None], 0.0)
    c, s = np.cos(angle)[:, None, None], np.sin(angle)[:, None, None]
    ux = np.zeros((len(r), 3, 3))
    ux[:, 0, 1], ux[:, 0, 2], ux[:, 1, 2] = -u[:, 2], u[:, 1], -u[:, 0]
    ux -= np.swapaxes(ux, 1, 2)
    # Rodrigues: exp(r) = I + sin θ [u]× + (1 − cos θ) [u]×²
    E = np.eye(3) + s * ux + (1 - c) * (ux @ ux)
    out = poses.copy()
    out[:, :3] += d[:, :3]
    out[:, 3:] = angles_from_rotation(E @ rotation(poses))
    return out


def _moved(plan, poses):
    """The plan with its trajectory's poses replaced (rates and timing unchanged)."""
    tr = plan.trajectory
    return replace(plan, trajectory=Trajectory(tr.t, poses, tr.d_poses, tr.dd_poses,
                                               name=tr.name + ", deflected"))


def _part_path(plan, poses) -> tuple:
    """(gun, t, tips, rotations, spray, part) of a part's plan (still or on a line) whose gun
    follows ``poses`` (N, 6, world), as its film sees them (a line part: from the part)."""
    moved = _moved(plan, poses)
    if isinstance(moved, LinePartPlan):
        moved = moved.in_part_frame()
    tr = moved.trajectory
    return (gun_of(plan.job), tr.t, tr.poses[:, :3], rotation(tr.poses), moved.spray,
            moved.part)


def program_film(plan, points, poses, shade=None) -> np.ndarray:
    """The film thickness [m] that ``plan``'s program leaves at ``points`` (a panel's grid
    (nv, nu, 3), a part's :class:`.film.points.SurfacePoints`) when the gun follows ``poses``
    (N, 6, world) at the plan's times and trigger: the integration the plan's own film uses
    (:func:`.film.grid.plan_film`, :func:`.film.line.line_film`,
    :func:`.film.part.surface_film`), flattened as its thickness. ``shade``: a part's rigid
    film's :class:`.film.mesh.Shade`, whose shadows the deflected film takes as they are
    (docs/model.md §27.7: a deflection of tenths of a millimetre moves a shadow's edge by no
    more; no ray is cast)."""
    if isinstance(plan, (SurfacePlan, LinePartPlan)):
        gun, t, p, a, spray, part = _part_path(plan, poses)
        return mesh_film(gun, t, p, a, points, part, spray, shade=shade).thickness
    moved = _moved(plan, poses)
    tr = moved.trajectory
    gun = gun_of(plan.job)
    pts = np.asarray(points).reshape(-1, 3)
    if isinstance(moved, LinePlan):
        return weighted_film(gun, tr.t, part_frame_positions(moved), rotation(tr.poses),
                             moved.spray, pts, moved.frame.n, moved.frame.c).thickness
    if isinstance(moved, PaintPlan):
        return film(gun, tr.t, tr.poses[:, :3], rotation(tr.poses), pts,
                    moved.frame.n, origin=moved.frame.c).thickness
    raise JobKindError(f"no film of a deflected program for a {type(plan).__name__}: a "
                       "panel's or a part's plan, still or on a line")


def shadow_edge_entry(plan, points, thickness, shade, poses, painted=None) -> tuple:
    """(the film of the program moved to ``poses``, the mask of points off every shadow's
    edge, paint.json's ``shadow_edges``) (docs/model.md §27.7): the rigid film's ``shade``
    reused, but for the pairs beside a shadow's edge, tested again
    (:func:`.film.edge_points.moved_shade`); the painted points whose edge film exceeds
    EDGE_FLOOR × target said apart from the rest: their number ``points`` and largest film
    change ``film_error`` (relative to the target) at ``film_error_at`` [m]."""
    gun, t, p, a, spray, part = _part_path(plan, poses)
    target = plan.job.thickness
    moved, E = moved_shade(gun, t, p, a, spray, points, part, shade)
    full = mesh_film(gun, t, p, a, points, part, spray, shade=moved).thickness
    edge = E > EDGE_FLOOR * target
    mine = edge if painted is None else edge & painted
    if not mine.any():
        return full, ~edge, {"points": 0}
    err, k = film_error(thickness, full, target, mine)
    return full, ~edge, {"points": int(mine.sum()), "film_error": err,
                         "film_error_at": [float(c) for c in film_points(points)[k]]}


def film_points(points) -> np.ndarray:
    """The film points (P, 3) of a panel's grid (…, 3) or a part's surface points."""
    return points.points if hasattr(points, "points") else np.asarray(points).reshape(-1, 3)


def sprayed_errors(d: ProgramDeflection, spray, t) -> dict:
    """The worst deflection over the sprayed samples (``spray`` > 0, at least one): the
    ``standoff_error_m`` [m] (at ``standoff_error_at_t``, ``t`` the program's times [s]),
    ``lateral_error_m`` [m] and ``tilt_rad`` [rad]."""
    on = np.asarray(spray) > 0
    i = int(np.flatnonzero(on)[np.argmax(np.abs(d.standoff[on]))])
    return {"standoff_error_m": float(np.abs(d.standoff[on]).max()),
            "standoff_error_at_t": float(t[i]),
            "lateral_error_m": float(d.lateral[on].max()),
            "tilt_rad": float(d.tilt[on].max())}


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


def beyond_linear(entry: dict, exc: StiffnessError) -> dict:
    """The report entry of a program whose drives turn beyond the linear model's bound
    (docs/model.md §27.2): no figures, a ``note`` saying why."""
    return {**entry, "stiffness": True, "note": f"not computed: {exc}"}


def compliance_entry(robot, plan, points, thickness, act: Actuators, painted=None,
                     shade=None) -> dict:
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
    shade : pollard_pin.painting.film.mesh.Shade or None, optional
        A part's rigid film's shadows, reused by the deflected film (default: cast again).

    Returns
    -------
    dict
        ``recoil_n`` [N]; ``stiffness`` (False, with a ``note``, when the actuators have
        none; True with a ``note`` and no figures when a drive turns beyond the linear
        model's bound); over the sprayed samples ``standoff_error_m`` [m] (at
        ``standoff_error_at_t`` [s]), ``lateral_error_m`` [m], ``tilt_rad`` [rad]; over the
        painted points ``film_error``, the largest film change relative to the target, at
        ``film_error_at`` [m] (given ``shade``: off the shadows' edges, which
        ``shadow_edges`` reports apart where there are any, :func:`shadow_edge_entry`);
        ``drive_stiffness`` [N·m/rad].
    """
    recoil, k, note = drive_stiffness(plan.job, act)
    if k is None:
        return note
    entry = {"recoil_n": recoil}
    try:
        d: ProgramDeflection = program_deflection(robot, plan.trajectory, k, plan.spray, recoil)
    except StiffnessError as exc:  # beyond the linear model: flagged, the plan stands
        return beyond_linear(entry, exc)
    moved = deflected_poses(plan.trajectory.poses, d.deflection)
    edges = {}
    if shade is not None:  # the points beside a shadow's edge apart (docs/model.md §27.7)
        T, rest, edges = shadow_edge_entry(plan, points, thickness, shade, moved, painted)
        painted = rest if painted is None else painted & rest
    else:
        T = program_film(plan, points, moved)
    err, where = film_error(thickness, T, plan.job.thickness, painted)
    return {**entry, "stiffness": True,
            **sprayed_errors(d, plan.spray, plan.trajectory.t),
            "film_error": err,
            "film_error_at": [float(c) for c in film_points(points)[where]],
            **({"shadow_edges": edges} if edges.get("points") else {}),
            "drive_stiffness": [float(x) for x in k]}


__all__ = ["CHUNK", "EDGE_FLOOR", "ProgramDeflection", "beyond_linear", "compliance_entry",
           "deflected_poses", "drive_stiffness", "film_error", "film_points",
           "program_deflection", "program_film", "recoil_wrench", "shadow_edge_entry",
           "sprayed_errors"]
