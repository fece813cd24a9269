"""The numbers of a cell's ``paint.json`` (docs/model.md §26): the job, the film of all robots
on the part at t = 0, the cell's ``line`` table (its slowest robot's cycle), each robot's
start, program time, zone and motor use, the seams' film and the clearances."""
from __future__ import annotations

import math

import numpy as np

from ...dynamics.motors import Actuators
from ..film.stats import film_stats
from ..report import check_report
from .frames import gravity_in_base


def _zone_mask(x, n, zone, job_facing, split) -> np.ndarray:
    """The film points in a robot's zone: along the axis within [lo, hi] and, with normals
    ``n``, on the faces of its facing."""
    inside = (x >= zone.lo) & (x <= zone.hi)
    if n is None:
        return inside
    f = np.asarray(job_facing if zone.facing is None else zone.facing, float)
    return inside & (n @ f > 0)


def _robot_entry(rp, act: Actuators, area: float, job, axis) -> dict:
    plan, cr = rp.plan, rp.robot
    tr = plan.trajectory
    on = plan.spray > 0
    along = tr.poses[on, :3] @ plan.direction
    window = [float(along.min()), float(along.max())] if on.any() else [0.0, 0.0]
    z = rp.zone
    c = plan.clearance
    bound = area * job.thickness / job.flow
    return {"name": cr.name, "base": list(cr.base), "rotation": list(cr.rotation),
            "gravity_base": [float(g) for g in gravity_in_base(cr)],
            "start": plan.times.delay, "program_time": plan.times.end - plan.times.delay,
            "cycle": plan.times.cycle, "path_time": float(tr.t[-1]), "samples": len(tr),
            "window": window,
            "zone": {"lo": None if math.isinf(z.lo) else z.lo,
                     "hi": None if math.isinf(z.hi) else z.hi, "axis": list(axis),
                     "facing": None if z.facing is None else list(z.facing),
                     "area": area},
            "painting_bound": bound,
            "upper_bound": float((plan.length + window[1] - window[0]) / bound) if bound > 0
            else math.inf,
            "motors": plan.motor_use(act.names),
            "to_part_m": None if c is None else c.distance,
            "to_part_at_s": None if c is None else c.time}


def seam_entries(split, x, th, areas, target: float) -> list:
    """Each seam's film: min and max over the points within the run-on R of it, relative to
    the target, and the mean."""
    out = []
    for w in split.seams():
        band = np.abs(x - w) <= split.runout
        if not band.any():
            continue
        t = th[band] / target
        a = areas[band]
        out.append({"at": w, "band_m": split.runout, "min": float(t.min()),
                    "max": float(t.max()), "mean": float(a @ t / a.sum())})
    return out


def _clearance(cell, near) -> dict:
    """paint.json's ``clearance``: the cell's (robot pairs, robots' links to the part) and
    the gun body's nearest approach to the part (today's check, per robot)."""
    out = {} if cell.clearance is None else cell.clearance.to_dict()
    if near is not None:
        out.update(gun_to_part_m=near["to_part_m"], gun_robot=near["name"],
                   gun_at_s=near["to_part_at_s"])
    return out


def _motors(robots, names) -> dict:
    """Each motor's worst use over the robots."""
    return {n: {k: max(r["motors"][n][k] for r in robots) for k in robots[0]["motors"][n]}
            for n in names}


def cell_report(cell, film_points, normals, thickness, areas, act: Actuators,
                extra: dict | None = None) -> dict:
    """paint.json for a cell: ``film_points`` (P, 3) world at t = 0 with their ``normals``
    (P, 3; None for a panel), ``thickness`` and ``areas`` (P,) over the painted points."""
    job, split = cell.job, cell.split
    axis = np.asarray(split.axis, float)
    x = film_points @ axis
    facing = job.normal if cell.part is None else cell.part.facing
    robots = []
    for rp in cell.robots:
        area = float(areas[_zone_mask(x, normals, rp.zone, facing, split)].sum())
        robots.append(_robot_entry(rp, act, area, job, split.axis))
    slow = max(robots, key=lambda r: r["cycle"])
    cycle = slow["cycle"]
    e = np.asarray(job.line.direction, float)
    clear = [r for r in robots if r["to_part_m"] is not None]
    near = min(clear, key=lambda r: r["to_part_m"]) if clear else None
    rep = {
        "job": job.to_dict(),
        "kind": "cell panel" if cell.part is None else "cell part",
        "thickness": film_stats(thickness, job.thickness, areas),
        "target": job.thickness,
        "cycle_time": cycle,
        "lower_bound": max(r["painting_bound"] for r in robots),
        "line": {"speed": cell.speed, "direction": [float(c) for c in e], "cycle": cycle,
                 "slowest_robot": slow["name"], "min_pitch": cell.speed * cycle,
                 "parts_per_hour": 3600.0 / cycle,
                 "upper_bound": min(r["upper_bound"] for r in robots),
                 "frames": "thickness table and film.ply: the part at its t = 0 pose, world "
                           "coordinates; DIR/<robot>/path.csv: each robot's base frame"},
        "split": {"axis": list(split.axis), "runout": split.runout, "seams": split.seams()},
        "seams": seam_entries(split, x, thickness, areas, job.thickness),
        "robots": robots,
        "clearance": _clearance(cell, near),
        "motors": _motors(robots, act.names),
        "motors_source": act.source,
        **(extra or {}),
    }
    return check_report(rep, job.source)


__all__ = ["cell_report", "seam_entries"]
