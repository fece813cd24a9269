"""pollard-pin paint of a job with a [line]: the panel or part rides a conveyor
(docs/model.md §24)."""
from __future__ import annotations

import time
from pathlib import Path

from .. import __version__
from .common import UsageError, load_robot
from .paint_files import (
    motor_use_line,
    part_summary_lines,
    say_written,
    spacing,
    write_panel_outputs,
    write_part_outputs,
)

FRAME = "the part at its t = 0 pose, world coordinates"


def run_line(args, job, out: Path, actuators, stale) -> int:
    """``paint`` of a panel or part on the line at the job's speed, or at the fastest with
    ``--max-line-speed``. ``actuators``: the motor ratings (cli/paint.py's rule)."""
    import numpy as np

    from ..paint.film import film_resolution
    from ..paint.job import PartJob
    from ..paint.line_report import line_film, line_report, part_frame_positions
    from ..viz.paint_part import ply_colours

    if job.line is None:
        raise UsageError("--max-line-speed: the job has no [line] table (speed, direction)")
    if isinstance(job, PartJob):
        return _run_line_part(args, job, out, actuators, stale)
    res = spacing(film_resolution, job, args.resolution)
    plan, planning = _planned(args, job, actuators)
    t0 = time.perf_counter()
    U, V, pts, film = line_film(plan, res)
    rep = line_report(plan, film, actuators, {"nu": len(U), "nv": len(V), "resolution": res})
    rep.update(timings={"plan": planning, "film": time.perf_counter() - t0},
               film_ply=ply_colours(job.thickness), pollard_pin=__version__)
    rep["line"]["searched"] = bool(args.max_line_speed)
    fr, j = plan.frame, plan.job
    rel = part_frame_positions(plan)[plan.spray > 0] - fr.c - j.standoff * fr.n
    name = write_panel_outputs(out, args.format, plan.trajectory, plan.spray, U, V, pts,
                               film.thickness, fr, j, rep,
                               {"command": "paint", "job": rep["job"], "frame": FRAME},
                               np.array([rel @ fr.u, rel @ fr.v]), stale, f"film: {FRAME}")
    print("\n".join(line_summary_lines(rep, actuators.names)))
    say_written(out, name)
    return 0


def _planned(args, job, actuators, part=None):
    """The plan at the job's speed or at the fastest (--max-line-speed), and the planning
    time [s]; ``part``: a [part] job's mesh, read by the caller."""
    from ..paint.line import SPEED_RESOLUTION, max_line_speed, plan_line_job

    robot = load_robot(args)
    t0 = time.perf_counter()
    if args.max_line_speed:
        _, plan = max_line_speed(robot, job, actuators, SPEED_RESOLUTION, part)
    else:
        plan = plan_line_job(robot, job, actuators, part)
    return plan, time.perf_counter() - t0


def _run_line_part(args, job, out: Path, actuators, stale) -> int:
    """``paint`` of a [part] on the line (the surface planner's passes, docs/model.md §23)."""
    from dataclasses import replace

    from ..paint.film_points import check_film_points
    from ..paint.line_report import line_part_report
    from ..paint.surface_plan import load_job_part, part_resolution, surface_film
    from ..viz.paint_part import ply_colours

    res = spacing(part_resolution, job, args.resolution)
    part = load_job_part(job)
    check_film_points(part, res)  # before planning: the budget of the film's points
    plan, planning = _planned(args, job, actuators, part)
    t0 = time.perf_counter()
    seen = plan.in_part_frame()
    pts, film, painted, efficiency = surface_film(seen, res)
    rep = line_part_report(plan, pts, film, painted, efficiency, actuators)
    rep.update(timings={"plan": planning, "film": time.perf_counter() - t0},
               film_ply=ply_colours(job.thickness), pollard_pin=__version__)
    rep["line"]["searched"] = bool(args.max_line_speed)
    # the world path and its trigger; the film on the part at its t = 0 pose
    world = replace(seen, trajectory=plan.trajectory)
    name = write_part_outputs(out, args.format, world, pts, film, painted, rep,
                              {"command": "paint", "job": rep["job"], "frame": FRAME}, stale,
                              f"film: {FRAME}")
    print("\n".join(line_lines(rep) + part_summary_lines(rep, actuators.names)))
    say_written(out, name)
    return 0


def line_lines(rep: dict) -> list[str]:
    """The two lines ``paint`` prints of the line (a panel's or a part's)."""
    ln = rep["line"]
    return [
        f"line speed {ln['speed']:.4g} m/s{' (the fastest)' if ln['searched'] else ''}, "
        f"upper bound {ln['upper_bound']:.4g} m/s (part length + window over area × target / "
        "flow)",
        f"start delay {ln['start_delay']:.3f} s, window {ln['window'][0]:.3f}–"
        f"{ln['window'][1]:.3f} m along the line, cycle {ln['cycle']:.3f} s, pitch "
        f"{ln['min_pitch']:.3f} m, {ln['parts_per_hour']:.1f} parts per hour",
    ]


def line_summary_lines(rep: dict, names) -> list[str]:
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


def riding(line, folder: Path) -> dict:
    """The viewer's moving nodes of a line's paint folder: the film (a panel's or a part's)
    carried by the line (translation speed·t·direction at path time t, docs/model.md §24),
    the line read by the job's rule (paint.line_job: 0 < speed ≤ 2 m/s, a direction)."""
    from collections.abc import Mapping

    import numpy as np

    from ..io.table import ResultFileError
    from ..paint.line_job import LINE_KEYS, line_from_table
    from ..viz.viewer import ROOT

    table = {k: line[k] for k in LINE_KEYS if k in line} if isinstance(line, Mapping) else line
    conveyor = line_from_table(str(folder / "paint.json"), table, ResultFileError)
    speed, e = conveyor.speed, np.asarray(conveyor.direction)

    def place(t: float) -> np.ndarray:
        T = np.eye(4)
        T[:3, 3] = speed * t * e
        return T

    return {f"{ROOT}/paint": place}
