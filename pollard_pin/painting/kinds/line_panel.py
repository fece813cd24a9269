"""A panel on a moving line (docs/model.md §24): the program planned at the job's line speed
or the fastest, the film on the panel's grid at its t = 0 pose, paint.json's numbers with
the line table and the lines ``pollard-pin paint`` prints."""
from __future__ import annotations

import time

import numpy as np

from ...dynamics.motors import Actuators
from ...errors import say_less, without_asides
from ...version import __version__
from ..errors import LineReachError
from ..film.line import line_film, part_frame_positions
from ..film.stats import film_stats
from ..line.panel import LinePlan, line_speeds, max_line_speed, plan_line_job
from ..report import check_report, clearance_entries, line_table
from ..result import PaintFilm
from ..spray.deposition import Film
from ..summary import line_lines, motor_use_line
from .base import JobKind, Outputs, with_speeds


def line_plan(robot, job, act, options, part=None):
    """The plan at the job's line speed or at the fastest (a panel's or, with ``part``, a
    part's), and the planning time [s]."""
    t0 = time.perf_counter()
    try:
        if options.max_line_speed:
            _, plan = max_line_speed(robot, job, act, options.speed_resolution, part,
                                     policy=options.policy)
        else:
            plan = plan_line_job(robot, job, act, part, policy=options.policy)
    except LineReachError as exc:  # one robot's reach: a cell may paint it
        said, cell = str(exc), ", or a cell of robots (paint --robots N|auto)"
        raise LineReachError(say_less(said + cell, without_asides(said) + cell,
                                      said)) from None
    return plan, time.perf_counter() - t0


def paint(robot, job, act, options, res):
    """(plan, film, report) of a panel on the line."""
    plan, planning = line_plan(robot, job, act, options)
    t0 = time.perf_counter()
    U, V, pts, film = line_film(plan, res)
    rep = line_report(plan, film, act, {"nu": len(U), "nv": len(V), "resolution": res})
    rep.update(timings={"plan": planning, "film": time.perf_counter() - t0},
               pollard_pin=__version__)
    rep["line"]["searched"] = options.max_line_speed
    with_speeds(rep, options, lambda: line_speeds(robot, job, act, plan,
                                                   policy=options.policy))
    return plan, PaintFilm(pts, film, res, grid=(U, V)), rep


def line_report(plan: LinePlan, f: Film, act: Actuators, grid: dict) -> dict:
    """The numbers of ``paint.json`` for a panel on the line."""
    j = plan.job
    th = film_stats(f.thickness, j.thickness)
    seg = plan.segments
    rep = {
        "job": j.to_dict(),
        "thickness": th,
        "target": j.thickness,
        "cycle_time": plan.times.cycle,
        "program_time": plan.relative.total,  # a slow line's waits included
        "lower_bound": j.width * j.height * j.thickness / j.flow,
        "passes": len(plan.offsets),
        "spacing": plan.spacing,
        "speed": plan.pass_speed,
        "coats": 1,
        "direction": "horizontal" if plan.horizontal else "vertical",
        "turnarounds": [float(d) for d, k in zip(seg.duration, seg.kind) if k == "turn"],
        "samples": len(plan.trajectory),
        **clearance_entries(plan),
        "motors": plan.motor_use(act.names),
        "motors_source": act.source,
        "line": line_table(plan),
        "strokes": plan.strokes.to_dict(),
        "grid": grid,
        "integration": {"rule": "trapezoid over the sprayed path samples, in the part's "
                                "frame",
                        "error_estimate_max": float(np.nanmax(f.error_estimate))},
    }
    return check_report(rep, plan.job.source)


def summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a panel on the line."""
    th = rep["thickness"]
    return line_lines(rep) + [
        f"passes {rep['passes']} ({rep['direction']}), spacing {rep['spacing'] * 1e3:.2f} mm, "
        f"gun speed {rep['speed']:.4g} m/s relative to the part",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {rep['target'] * 1e6:.4g} µm), {100 * th['within_5pct']:.2f} % within ±5 %, "
        f"{100 * th['within_10pct']:.2f} % within ±10 %",
        motor_use_line(rep, names),
        f"planned in {rep['timings']['plan']:.2f} s, film map in {rep['timings']['film']:.2f} s "
        f"({rep['grid']['nu']} × {rep['grid']['nv']} points, {rep['samples']} path samples)",
    ]


# the film and the figure: the panel at its t = 0 pose, the tips seen from it
KIND = JobKind("line panel", paint, summary_lines,
               outputs=Outputs(part_frame=True, tips=part_frame_positions))

__all__ = ["KIND", "line_plan", "line_report", "paint", "summary_lines"]
