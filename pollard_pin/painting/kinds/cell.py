"""A cell of robots on one line (docs/model.md §26), a panel or a part: every robot's program
in its own base frame on the cell's clock, the film of all on the part; the numbers of its
``paint.json`` (the job, the film of all robots on the part at t = 0, the cell's ``line``
table (its slowest robot's cycle), each robot's start, program time, zone and motor use, the
seams' film and the clearances) and the lines ``pollard-pin paint`` prints."""
from __future__ import annotations

import math
import time

import numpy as np

from ...dynamics.motors import Actuators
from ...version import __version__
from ..cell.frames import gravity_in_base
from ..cell.plan import cell_speeds, max_cell_speed, plan_cell_job
from ..film.cell import cell_panel_film, cell_part_film
from ..film.grid import grid_areas
from ..film.stats import film_stats
from ..job import PartJob
from ..report import check_report
from ..result import PaintFilm
from ..summary import speeds_lines, strokes_line
from .base import JobKind, Outputs, checked_part, with_speeds


def paint(robot, job, act, options, res):
    """(plan, film, report) of a cell: every robot's program, the film of all on the part."""
    part = checked_part(job, res) if isinstance(job, PartJob) else None
    t0 = time.perf_counter()
    if options.max_line_speed:
        _, plan = max_cell_speed(robot, job, act, options.speed_resolution, part,
                                 policy=options.policy)
    else:
        plan = plan_cell_job(robot, job, act, part, policy=options.policy)
    t1 = time.perf_counter()
    if part is None:
        U, V, pts, film = cell_panel_film(plan, res)
        flat = pts.reshape(-1, 3)
        areas = grid_areas(U, V)  # each point's share
        rep = cell_report(plan, flat, None, film.thickness, areas, act,
                          {"grid": {"nu": len(U), "nv": len(V), "resolution": res}})
        pf = PaintFilm(pts, film, res, grid=(U, V))
    else:
        pts, film, painted, efficiency = cell_part_film(plan, res)
        rep = cell_report(plan, pts.points[painted], pts.normals[painted],
                          film.thickness[painted], pts.areas[painted], act,
                          {"transfer_efficiency": efficiency,
                           "film_points": {"painted": int(np.count_nonzero(painted)),
                                           "total": len(pts), "resolution": res}})
        pf = PaintFilm(pts, film, res, painted=painted, efficiency=efficiency)
    rep.update(timings={"plan": t1 - t0, "film": time.perf_counter() - t1},
               pollard_pin=__version__)
    rep["line"]["searched"] = options.max_line_speed
    with_speeds(rep, options, lambda: cell_speeds(robot, job, act, plan, part,
                                                   policy=options.policy))
    return plan, pf, rep


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
            "strokes": plan.strokes.to_dict(),
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


def summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a cell (docs/model.md §26): the line, the film, the
    seams, each robot's zone, start, program and motors, the clearances."""
    ln, th = rep["line"], rep["thickness"]
    lines = [
        f"line speed {ln['speed']:.4g} m/s{' (the fastest)' if ln['searched'] else ''}, "
        f"cycle {ln['cycle']:.3f} s (robot {ln['slowest_robot']!r}, the slowest), pitch "
        f"{ln['min_pitch']:.3f} m, {ln['parts_per_hour']:.1f} parts per hour; upper bound "
        f"{ln['upper_bound']:.4g} m/s", *speeds_lines(rep),
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {rep['target'] * 1e6:.4g} µm), {100 * th['within_5pct']:.2f} % of the area "
        f"within ±5 %, {100 * th['within_10pct']:.2f} % within ±10 %"]
    lines += [f"seam at {s['at']:.4f} m: film {s['min']:.4f}–{s['max']:.4f} of the target "
              f"within ±{s['band_m'] * 1e3:.0f} mm" for s in rep["seams"]]
    waits = ", ".join(f"{r['name']!r} {r['strokes']['dwell_s']:.3f} s" for r in rep["robots"])
    lines.append(strokes_line(rep["robots"][0]["strokes"], waits))
    for r in rep["robots"]:
        z = r["zone"]
        lo = "edge" if z["lo"] is None else f"{z['lo']:.4f}"
        hi = "edge" if z["hi"] is None else f"{z['hi']:.4f}"
        use = r["motors"]
        peak = max(use[n]["peak_torque"] for n in names)
        rms = max(use[n]["rms_torque"] for n in names)
        lines.append(f"robot {r['name']!r}: zone {lo}..{hi} m, starts {r['start']:.3f} s, "
                     f"program {r['program_time']:.3f} s, cycle {r['cycle']:.3f} s, motors "
                     f"≤ {100 * peak:.0f} % of peak torque, ≤ {100 * rms:.0f} % RMS")
    c = rep["clearance"]
    if c.get("gun_to_part_m") is not None:
        lines.append(f"gun body {c['gun_to_part_m'] * 1e3:.1f} mm from the part at its "
                     f"closest (robot {c['gun_robot']!r})")
    if c.get("to_part_m") is not None:
        lines.append(f"the links of robot {c['robot']!r} {c['to_part_m'] * 1e3:.1f} mm from the "
                     f"part at their closest (t = {c['robot_at_s']:.2f} s)")
    if c.get("between_robots_m") is not None:
        lines.append(f"robots {c['pair'][0]!r} and {c['pair'][1]!r} "
                     f"{c['between_robots_m'] * 1e3:.1f} mm apart at their closest "
                     f"(t = {c['pair_at_s']:.2f} s)")
    lines.append(f"planned in {rep['timings']['plan']:.2f} s, film in "
                 f"{rep['timings']['film']:.2f} s")
    return lines


# a folder per robot for its path.csv; the film: the part at its t = 0 pose, all robots
OUTPUTS = Outputs(per_robot=True, part_frame=True)


def compliance(robot, plan, film, act, rep: dict) -> None:
    """``rep``'s ``compliance``, the worst over the cell's robots, and each robot's own in its
    entry (docs/model.md §27.7)."""
    from ..checks.cell_compliance import cell_compliance

    rep["compliance"], per = cell_compliance(robot, plan, film.points, film.thickness, act,
                                             film.painted, film.film.robots)
    for r, c in zip(rep["robots"], per):
        r["compliance"] = c


PANEL = JobKind("cell panel", paint, summary_lines, compliance, outputs=OUTPUTS)
PART = JobKind("cell part", paint, summary_lines, compliance, outputs=OUTPUTS)

__all__ = ["OUTPUTS", "PANEL", "PART", "cell_report", "compliance", "paint", "seam_entries",
           "summary_lines"]
