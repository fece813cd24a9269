"""What compliance does to a paint cell (docs/model.md §27.7, §26.6): each robot's program in
its base frame deflected by the drives under its weight (gravity Rᵀg in that frame,
:func:`.cell.frames.robot_model_in_base`) and the spray's recoil; the deflected poses seen
from the part in the world (:func:`.film.cell.world_gun`) and the film of all robots with
their deflected programs, integrated at the rigid film's points by the cell's film code.
The films add over the robots, so the cell's film change is the sum of each robot's."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...dynamics.drives.stiffness import StiffnessError
from ...dynamics.motors import Actuators
from ...paths.trajectory import Trajectory
from ..cell.frames import robot_model_in_base
from ..film.cell import weighted_film, world_gun
from ..film.edge_points import moved_shade
from ..film.mesh import mesh_film
from ..spray.deposition import gun_of
from .compliance import (
    ProgramDeflection,
    beyond_linear,
    deflected_poses,
    drive_stiffness,
    film_error,
    film_points,
    program_deflection,
    sprayed_errors,
)


@dataclass(frozen=True)
class FilmSite:
    """Where a cell's film is integrated: the film ``points`` (a panel's grid (…, 3) or a
    part's :class:`.film.points.SurfacePoints`) and, for a panel, its ``frame`` (normal n,
    centre c); for a part, the world ``part`` at t = 0 (its shadows)."""

    points: object
    frame: object = None
    part: object = None


def robot_deflection(robot, rp, stiffness, recoil: float) -> ProgramDeflection:
    """The deflection (base frame) along one cell robot's program (:class:`.cell.plan.
    RobotPlan`), its model carrying its base-frame gravity Rᵀg."""
    model = robot_model_in_base(robot, rp.robot)
    return program_deflection(model, rp.plan.trajectory, stiffness, rp.plan.spray, recoil)


def deflected_robot(rp, d: ProgramDeflection):
    """The robot's plan with its program's poses moved by the deflection ``d`` (base frame;
    times, rates and trigger unchanged)."""
    tr = rp.plan.trajectory
    moved = Trajectory(tr.t, deflected_poses(tr.poses, d.deflection), tr.d_poses,
                       tr.dd_poses, name=tr.name + ", deflected")
    return replace(rp, plan=replace(rp.plan, trajectory=moved))


def robot_film(job, rp, site: FilmSite, shade=None) -> np.ndarray:
    """The film [m] one robot's program leaves at the site's points, as the cell's film
    integrates it (:func:`.film.cell.cell_panel_film`, :func:`.film.cell.cell_part_film`);
    on a part, given ``shade`` (the robot's rigid film's, :class:`.film.mesh.Shade`), its
    shadows reused but beside their edges (:func:`.film.edge_points.moved_shade`)."""
    t, p, a, spray = world_gun(rp)
    if site.part is not None:
        if shade is not None:
            shade = moved_shade(gun_of(job), t, p, a, spray, site.points, site.part, shade)[0]
        return mesh_film(gun_of(job), t, p, a, site.points, site.part, spray,
                         shade=shade).thickness
    flat = np.asarray(site.points).reshape(-1, 3)
    return weighted_film(gun_of(job), t, p, a, spray, flat, site.frame.n,
                         site.frame.c).thickness


def film_site(cell, points) -> FilmSite:
    """The cell's film site: the panel's frame, or the world part at t = 0."""
    if cell.part is not None:
        return FilmSite(points, part=cell.part)
    from ..workpiece.panel import panel_frame

    return FilmSite(points, frame=panel_frame(cell.job))


def _robot_entry(rp, d: ProgramDeflection, change, target: float, pts, painted) -> dict:
    """A robot's ``compliance``: its sprayed samples' worst standoff, lateral and tilt
    errors, and the largest film change its deflection alone makes."""
    if not (rp.plan.spray > 0).any():
        return {"sprayed": False}
    err, where = film_error(np.zeros_like(change), change, target, painted)
    return {**sprayed_errors(d, rp.plan.spray, rp.plan.trajectory.t),
            "film_error": err, "film_error_at": [float(c) for c in pts[where]]}


def cell_compliance(robot, cell, points, thickness, act: Actuators, painted=None,
                    films=()) -> tuple[dict, list]:
    """(paint.json's ``compliance`` for the cell, each robot's entry for ``robots[i]``)
    (docs/model.md §26.6): the worst standoff, lateral and tilt errors over the robots
    (naming the robot), and the film change of all robots deflected together relative to
    the target over the painted points; without ``stiffness``, or with a drive turned beyond
    the linear model's bound (docs/model.md §27.2), entries that say so. ``films``: the
    cell's per-robot rigid films (a part's :class:`.film.mesh.MeshFilm`, a panel's
    :class:`.spray.deposition.Film`), whose thickness (and a part's shadows) the deflected
    films reuse (default: integrated again)."""
    job = cell.job
    recoil, k, note = drive_stiffness(job, act)
    if k is None:
        return note, [note] * len(cell.robots)
    entry = {"recoil_n": recoil}
    site = film_site(cell, points)
    pts = film_points(points)
    deflected = np.zeros(len(pts))
    per, ds = [], []
    for rp in cell.robots:
        try:
            ds.append(robot_deflection(robot, rp, k, recoil))
        except StiffnessError as exc:  # beyond the linear model: flagged, the plan stands
            out = beyond_linear(entry, StiffnessError(f"robot '{rp.robot.name}': {exc}"))
            return out, [out] * len(cell.robots)
    rigid = list(films) if len(films) == len(cell.robots) else [None] * len(cell.robots)
    for rp, d, own in zip(cell.robots, ds, rigid):
        shade = getattr(own, "shade", None)  # a part's; a panel has none
        mine = robot_film(job, deflected_robot(rp, d), site, shade)
        change = mine - (robot_film(job, rp, site) if own is None else own.thickness)
        deflected += mine
        per.append({**entry, "stiffness": True,
                    **_robot_entry(rp, d, change, job.thickness, pts, painted)})
    err, where = film_error(thickness, deflected, job.thickness, painted)
    live = [(e, rp.robot.name) for e, rp in zip(per, cell.robots) if "standoff_error_m" in e]
    if not live:
        return {**entry, "stiffness": True, "note": "no robot sprays"}, per
    worst = max(live, key=lambda x: x[0]["standoff_error_m"])
    out = {**entry, "stiffness": True,
           "standoff_error_m": worst[0]["standoff_error_m"],
           "standoff_error_at_t": worst[0]["standoff_error_at_t"],
           "standoff_error_robot": worst[1],
           "lateral_error_m": max(e["lateral_error_m"] for e, _ in live),
           "tilt_rad": max(e["tilt_rad"] for e, _ in live),
           "film_error": err, "film_error_at": [float(c) for c in pts[where]],
           "drive_stiffness": [float(x) for x in k]}
    return out, per


__all__ = ["FilmSite", "cell_compliance", "deflected_robot",
           "film_site", "robot_deflection", "robot_film"]
