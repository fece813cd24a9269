"""pollard-pin paint of a job with a [line]: the panel rides a conveyor (docs/model.md §24)."""
from __future__ import annotations

import sys
import time
from pathlib import Path

from .. import __version__
from .common import UsageError, load_robot
from .paint_files import motor_use_line, write_panel_outputs


def run_line(args, job, out: Path, actuators, stale) -> int:
    """``paint`` of a panel on the line at the job's speed, or at the fastest with
    ``--max-line-speed``. ``actuators``: the motor ratings (cli/paint.py's rule)."""
    import numpy as np

    from ..paint.errors import PlanError
    from ..paint.film import film_resolution
    from ..paint.job import PartJob
    from ..paint.line import max_line_speed, plan_line_job
    from ..paint.line_report import line_film, line_report, part_frame_positions

    if job.line is None:
        raise UsageError("--max-line-speed: the job has no [line] table (speed, direction)")
    if isinstance(job, PartJob):
        raise UsageError(f"{job.source}: a [part] on a [line] is not planned yet; give the "
                         "strip as a [panel]")
    try:
        res = film_resolution(job, args.resolution)
    except PlanError as exc:
        raise UsageError(f"--resolution: {exc}") from None
    robot = load_robot(args)
    t0 = time.perf_counter()
    if args.max_line_speed:
        _, plan = max_line_speed(robot, job, actuators)
    else:
        plan = plan_line_job(robot, job, actuators)
    t1 = time.perf_counter()
    U, V, pts, film = line_film(plan, res)
    t2 = time.perf_counter()
    rep = line_report(plan, film, actuators, {"nu": len(U), "nv": len(V), "resolution": res})
    rep.update(timings={"plan": t1 - t0, "film": t2 - t1}, pollard_pin=__version__)
    rep["line"]["searched"] = bool(args.max_line_speed)
    fr, j = plan.frame, plan.job
    rel = part_frame_positions(plan)[plan.spray > 0] - fr.c - j.standoff * fr.n
    name = write_panel_outputs(out, args.format, plan.trajectory, plan.spray, U, V, pts,
                               film.thickness, fr, j, rep,
                               {"command": "paint", "job": rep["job"],
                                "frame": "the part at its t = 0 pose, world coordinates"},
                               np.array([rel @ fr.u, rel @ fr.v]), stale)
    print("\n".join(line_summary_lines(rep, actuators.names)))
    print(f"wrote {out}/path.csv, {name.name}, film.ply, paint.json, thickness.png",
          file=sys.stderr)
    return 0


def line_summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a panel on the line."""
    th, ln = rep["thickness"], rep["line"]
    return [
        f"line speed {ln['speed']:.4g} m/s{' (the fastest)' if ln['searched'] else ''}, "
        f"upper bound {ln['upper_bound']:.4g} m/s (part length + window over area × target / "
        "flow)",
        f"start delay {ln['start_delay']:.3f} s, window {ln['window'][0]:.3f}–"
        f"{ln['window'][1]:.3f} m along the line, cycle {ln['cycle']:.3f} s, pitch "
        f"{ln['min_pitch']:.3f} m, {ln['parts_per_hour']:.1f} parts per hour",
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
    """The viewer's moving nodes of a line's paint folder: the film panel carried by the line
    (translation speed·t·direction at path time t, docs/model.md §24)."""
    import math

    import numpy as np

    from ..io.table import ResultFileError
    from ..viz.viewer import ROOT

    try:
        speed, e = line["speed"], line["direction"]
        ok = (type(speed) in (int, float) and 0 <= speed < math.inf and len(e) == 3
              and all(type(c) in (int, float) and math.isfinite(c) for c in e))
    except (KeyError, TypeError):
        ok = False
    if not ok:
        raise ResultFileError(f"{folder / 'paint.json'}: line = {line!r}: expected speed >= 0 "
                              "[m/s] and a direction [x, y, z]")
    e = np.asarray(e, dtype=float)

    def place(t: float) -> np.ndarray:
        T = np.eye(4)
        T[:3, 3] = speed * t * e
        return T

    return {f"{ROOT}/paint": place}
