"""pollard-pin paint of a job with a [line]: the panel rides a conveyor (docs/model.md §24)."""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from .. import __version__
from ..io.atomic import all_or_nothing, atomic_open, make_folder, remove_stale
from .common import UsageError, load_robot


def run_line(args, job, out: Path, actuators, stale) -> int:
    """``paint`` of a panel on the line at the job's speed, or at the fastest with
    ``--max-line-speed``. ``actuators``: the motor ratings (cli/paint.py's rule)."""
    import numpy as np

    from ..io.table import write_table
    from ..io.trajectory import to_csv
    from ..paint.errors import PlanError
    from ..paint.film import film_resolution
    from ..paint.job import PartJob
    from ..paint.line import max_line_speed, plan_line_job
    from ..paint.line_report import line_film, line_report, part_frame_positions
    from ..viz.paint import write_thickness_png

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
    UU, VV = np.meshgrid(U, V)
    flat = pts.reshape(-1, 3)
    table = {"x": flat[:, 0], "y": flat[:, 1], "z": flat[:, 2], "u": UU.ravel(),
             "v": VV.ravel(), "thickness": film.thickness}
    name = out / f"thickness.{args.format}"
    with all_or_nothing():  # everything is computed: now write every output, or none
        make_folder(out)
        to_csv(plan.trajectory, out / "path.csv", spray=plan.spray)
        write_table(name, table, {"command": "paint", "job": rep["job"],
                                  "frame": "the part at its t = 0 pose, world coordinates"},
                    fmt=args.format)
        with atomic_open(out / "paint.json") as f:
            f.write(json.dumps(rep, indent=2) + "\n")
        write_thickness_png(out / "thickness.png", U, V,
                            film.thickness.reshape(len(V), len(U)), j.thickness,
                            np.array([rel @ fr.u, rel @ fr.v]), j.width, j.height)
        remove_stale(*stale)
    print("\n".join(line_summary_lines(rep, actuators.names)))
    print(f"wrote {out}/path.csv, {name.name}, paint.json, thickness.png", file=sys.stderr)
    return 0


def line_summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a panel on the line."""
    th, ln = rep["thickness"], rep["line"]
    motors = ", ".join(f"{n} {100 * rep['motors'][n]['peak_torque']:.0f}/"
                       f"{100 * rep['motors'][n]['speed']:.0f}/"
                       f"{100 * rep['motors'][n]['rms_torque']:.0f}" for n in names)
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
        f"motor peak torque/speed/RMS use [%]: {motors}",
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
