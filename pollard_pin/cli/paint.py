"""pollard-pin paint: plan a raster spray program over a panel (docs/model.md §20–§21)."""
from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

from .. import __version__
from ..io.atomic import atomic_open, check_destination, make_folder
from .common import UsageError, command, load_robot, model_args, name, positive

MAX_FILM_POINTS = 2_000_000  # film grid points: ~0.3 s per 3,000 points × 5,000 samples


def _actuators(args, job):
    """--actuators, else the job's ``actuators``, else the package default (the ratings of
    examples/actuators.toml, shipped as models/actuators.toml)."""
    from ..dynamics.motors import load_actuators
    from ..model.paths import models_dir

    return load_actuators(args.actuators or job.actuators or models_dir() / "actuators.toml")


def run(args) -> int:
    import numpy as np

    from ..io.table import write_table
    from ..io.trajectory import to_csv
    from ..paint.job import load_job
    from ..paint.motion import PlanError
    from ..paint.plan import film_resolution, paint_report, plan_film, plan_paint
    from ..viz.paint import write_thickness_png

    out = Path(args.out)
    check_destination(out, folder=True)
    job = load_job(args.job)
    try:
        res = film_resolution(job, args.resolution)
    except PlanError as exc:
        raise UsageError(f"--resolution: {exc}") from None
    points = (math.ceil(job.width / res) + 1) * (math.ceil(job.height / res) + 1)
    if points > MAX_FILM_POINTS:
        raise UsageError(f"--resolution {res:g} m makes {points} film points on the "
                         f"{job.width:g} × {job.height:g} m panel, more than "
                         f"{MAX_FILM_POINTS}: give a coarser resolution")
    act = _actuators(args, job)
    robot = load_robot(args)
    t0 = time.perf_counter()
    plan = plan_paint(robot, job, act)
    t1 = time.perf_counter()
    U, V, pts, film = plan_film(plan, res)
    t2 = time.perf_counter()
    rep = paint_report(plan, film, act)
    rep.update(timings={"plan": t1 - t0, "film": t2 - t1},
               grid={"nu": len(U), "nv": len(V), "resolution": res}, pollard_pin=__version__)
    tr, fr = plan.trajectory, plan.frame
    rel = tr.poses[:, :3] - fr.c - job.standoff * fr.n
    UU, VV = np.meshgrid(U, V)
    flat = pts.reshape(-1, 3)
    table = {"x": flat[:, 0], "y": flat[:, 1], "z": flat[:, 2], "u": UU.ravel(),
             "v": VV.ravel(), "thickness": film.thickness}
    # everything is computed: now write
    make_folder(out)
    to_csv(tr, out / "path.csv")
    name = out / f"thickness.{args.format}"
    write_table(name, table, {"command": "paint", "job": rep["job"]}, fmt=args.format)
    with atomic_open(out / "paint.json") as f:
        f.write(json.dumps(rep, indent=2) + "\n")
    write_thickness_png(out / "thickness.png", U, V, film.thickness.reshape(len(V), len(U)),
                        job.thickness, np.array([rel @ fr.u, rel @ fr.v]), job.width,
                        job.height)
    print("\n".join(summary_lines(rep, act.names)))
    print(f"wrote {out}/path.csv, {name.name}, paint.json, thickness.png", file=sys.stderr)
    return 0


def summary_lines(rep: dict, names) -> list[str]:
    """The report-style lines ``paint`` prints."""
    th, target = rep["thickness"], rep["target"]
    motors = ", ".join(f"{n} {100 * rep['motors'][n]['peak_torque']:.0f}/"
                       f"{100 * rep['motors'][n]['speed']:.0f}" for n in names)
    return [
        f"passes {rep['passes']} ({rep['direction']}), spacing {rep['spacing'] * 1e3:.2f} mm, "
        f"speed {rep['speed']:.4g} m/s, coats {rep['coats']}",
        f"cycle {rep['cycle_time']:.3f} s; painting-only lower bound {rep['lower_bound']:.3f} s "
        f"(panel area × target / flow), {rep['swept_lower_bound']:.3f} s over the swept passes",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {target * 1e6:.4g} µm: {100 * th['deviation_min']:+.2f} % / "
        f"{100 * th['deviation_max']:+.2f} %), {100 * th['within_10pct']:.0f} % within ±10 %",
        f"motor peak torque/speed use [%]: {motors}",
        f"planned in {rep['timings']['plan']:.2f} s, film map in {rep['timings']['film']:.2f} s "
        f"({rep['grid']['nu']} × {rep['grid']['nv']} points, {rep['samples']} path samples)",
    ]


def paint_overlay(folder: Path):
    """The film of a ``paint`` output folder as a viewer overlay (``view --paint``): the panel
    coloured by thickness over the target ± 2 %."""
    import numpy as np

    from ..io.table import ResultFileError, read_result
    from ..model.values import clip, shorten
    from ..viz.paint import BAND
    from ..viz.viewer import film_panel

    found = [p for p in (folder / "thickness.csv", folder / "thickness.parquet") if p.is_file()]
    if not (folder / "path.csv").is_file() or not found or not (folder / "paint.json").is_file():
        raise UsageError(f"--paint {folder}: not a paint output folder (expected path.csv, "
                         "thickness.csv or .parquet and paint.json from pollard-pin paint)")
    try:
        report = json.loads((folder / "paint.json").read_text(encoding="utf-8"))
        nu, nv, target = report["grid"]["nu"], report["grid"]["nv"], report["target"]
    except (OSError, ValueError, KeyError, TypeError, RecursionError) as exc:  # deep nesting
        raise ResultFileError(f"{folder / 'paint.json'}: not a paint report "
                              f"({clip(exc, 100)})") from None
    counts_ok = all(type(n) is int and n >= 1 for n in (nu, nv))
    if not (counts_ok and type(target) in (int, float) and 0 < target < math.inf):
        raise ResultFileError(f"{folder / 'paint.json'}: not a paint report (grid nu = "
                              f"{shorten(nu)}, nv = {shorten(nv)}, target = {shorten(target)}: "
                              "expected point counts >= 1 and a film thickness > 0 [m])")
    table = read_result(found[0])
    try:
        pts = np.column_stack([table["x"], table["y"], table["z"]]).reshape(nv, nu, 3)
        th = table["thickness"].reshape(nv, nu)
    except (KeyError, ValueError, OverflowError) as exc:
        raise ResultFileError(f"{found[0]}: not the film of paint.json's {shorten(nu)} × "
                              f"{shorten(nv)} grid ({clip(exc, 100)})") from None
    for what, values in (("x, y, z", pts), ("thickness", th)):
        if not np.isfinite(values).all():
            k = int(np.argwhere(~np.isfinite(values).reshape(nv * nu, -1))[0][0])
            raise ResultFileError(f"{found[0]}: row {k + 1}: {what} not finite")

    def draw(vis):
        film_panel(vis, pts, th, target * (1 - BAND), target * (1 + BAND))

    return draw


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "paint", "plan a raster spray program over a panel: path, film "
                "map, motors (docs/model.md §20–§21)", run)
    model_args(p)
    p.add_argument("--job", type=name, required=True, metavar="JOB.toml",
                   help="the paint job (see examples/paint.toml)")
    p.add_argument("--actuators", type=name, metavar="FILE.toml", default=None,
                   help="motor ratings (default: the job's actuators, else the ratings of "
                        "examples/actuators.toml, shipped in the package)")
    p.add_argument("--out", type=name, default="paint", metavar="DIR",
                   help="output folder: path.csv, thickness.csv|parquet, paint.json, "
                        "thickness.png")
    p.add_argument("--format", choices=("csv", "parquet"), default="csv",
                   help="thickness table format")
    p.add_argument("--resolution", type=positive, default=None, metavar="M",
                   help="film grid spacing [m], at most σ (default: σ/3)")
