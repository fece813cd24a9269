"""pollard-pin paint: plan a raster spray program over a panel (docs/model.md §20–§21) or
over a part's mesh (§23)."""
from __future__ import annotations

import json
import math
from pathlib import Path

from .common import UsageError, command, load_robot, model_args, name, positive
from .paint_files import motor_use_line, part_summary_lines, say_written, spacing


def _actuators(args, job):
    """--actuators, else the job's, else the package's (pollard_pin.paint's rule)."""
    from ..dynamics.motors import load_actuators
    from ..paint.api import default_actuators

    return load_actuators(args.actuators) if args.actuators else default_actuators(job)


def run(args) -> int:
    from ..io.atomic import check_outputs
    from ..io.paint_files import paint_outputs
    from ..paint.api import PaintOptions, film_spacing_of, job_kind, paint
    from ..paint.job import load_job

    out = Path(args.out)
    check_outputs(*paint_outputs(out, args.format)[0], folders=(out,))
    job = load_job(args.job)
    kind = job_kind(job)
    if args.max_line_speed and job.line is None:
        raise UsageError("--max-line-speed: the job has no [line] table (speed, direction)")
    res = spacing(film_spacing_of, job, args.resolution)
    act = _actuators(args, job)
    result = paint(load_robot(args), job, act,
                   PaintOptions(resolution=res, max_line_speed=args.max_line_speed))
    name = result.write(out, args.format)
    rep = result.report.to_dict()
    if kind == "panel":
        lines = summary_lines(rep, act.names)
    elif kind == "part":
        lines = part_summary_lines(rep, act.names)
    else:
        from .paint_line import line_lines, line_summary_lines

        lines = (line_summary_lines(rep, act.names) if kind == "line panel" else
                 line_lines(rep) + part_summary_lines(rep, act.names))
    print("\n".join(lines))
    say_written(out, name)
    return 0


def summary_lines(rep: dict, names) -> list[str]:
    """The report-style lines ``paint`` prints."""
    th, target = rep["thickness"], rep["target"]
    return [
        f"passes {rep['passes']} ({rep['direction']}), spacing {rep['spacing'] * 1e3:.2f} mm, "
        f"speed {rep['speed']:.4g} m/s, coats {rep['coats']}",
        f"cycle {rep['cycle_time']:.3f} s; painting-only lower bound {rep['lower_bound']:.3f} s "
        f"(panel area × target / flow), {rep['swept_lower_bound']:.3f} s over the swept passes",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {target * 1e6:.4g} µm: {100 * th['deviation_min']:+.2f} % / "
        f"{100 * th['deviation_max']:+.2f} %), {100 * th['within_10pct']:.0f} % within ±10 %",
        motor_use_line(rep, names),
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
    from ..viz.viewer import ViewerError, check_scene_points, film_panel

    found = [p for p in (folder / "thickness.csv", folder / "thickness.parquet") if p.is_file()]
    if not (folder / "path.csv").is_file() or not found or not (folder / "paint.json").is_file():
        raise UsageError(f"--paint {folder}: not a paint output folder (expected path.csv, "
                         "thickness.csv or .parquet and paint.json from pollard-pin paint)")
    try:
        report = json.loads((folder / "paint.json").read_text(encoding="utf-8"))
        if isinstance(report, dict) and "part" in report.get("job", {}):
            return _part_overlay(folder, report)
        nu, nv, target = report["grid"]["nu"], report["grid"]["nv"], report["target"]
    except (OSError, ValueError, KeyError, TypeError, RecursionError) as exc:  # deep nesting
        raise ResultFileError(f"{folder / 'paint.json'}: not a paint report "
                              f"({clip(exc, 100)})") from None
    counts_ok = all(type(n) is int and n >= 1 for n in (nu, nv))
    if not (counts_ok and type(target) in (int, float) and 0 < target < math.inf):
        raise ResultFileError(f"{folder / 'paint.json'}: not a paint report (grid nu = "
                              f"{shorten(nu)}, nv = {shorten(nv)}, target = {shorten(target)}: "
                              "expected point counts >= 1 and a film thickness > 0 [m])")
    if len(found) > 1:  # pollard-pin paint never leaves both: which film is meant?
        raise UsageError(f"--paint {folder}: holds both thickness.csv and thickness.parquet, "
                         "two different films perhaps: remove the one not meant")
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
    if (th < 0).any():
        k = int(np.argmax(th.ravel() < 0))
        raise ResultFileError(f"{found[0]}: row {k + 1}: thickness = {th.ravel()[k]:.4g} m, "
                              "below 0 (a film is at least 0 m thick)")
    try:
        check_scene_points(pts, str(found[0]))
    except ViewerError as exc:
        raise ResultFileError(str(exc)) from None

    def draw(vis):
        film_panel(vis, pts, th, target * (1 - BAND), target * (1 + BAND))

    if "line" in report:  # the panel rides the line with the path (docs/model.md §24)
        from .paint_line import riding

        draw.moving = riding(report["line"], folder)
    return draw


def _part_overlay(folder: Path, report: dict):
    """The film of a part's ``paint`` folder (film.ply) as a viewer overlay."""
    from ..io.ply import read_film_ply
    from ..io.table import ResultFileError
    from ..viz.paint import BAND
    from ..viz.viewer import ViewerError, check_scene_points, film_mesh

    target = report.get("target")
    if not (type(target) in (int, float) and 0 < target < math.inf):
        raise ResultFileError(f"{folder / 'paint.json'}: target = {target!r}: expected a film "
                              "thickness > 0 [m]")
    if not (folder / "film.ply").is_file():
        raise UsageError(f"--paint {folder}: a part's paint folder without film.ply")
    v, f, th = read_film_ply(folder / "film.ply")
    try:
        check_scene_points(v, str(folder / "film.ply"))
    except ViewerError as exc:
        raise ResultFileError(str(exc)) from None

    def draw(vis):
        film_mesh(vis, v, f, th, target * (1 - BAND), target * (1 + BAND))

    if "line" in report:  # the part rides the line with the path (docs/model.md §24)
        from .paint_line import riding

        draw.moving = riding(report["line"], folder)
    return draw


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "paint", "plan a spray program over a panel or a part's mesh: "
                "path, film map, motors (docs/model.md §20–§21, §23)", run)
    model_args(p)
    p.add_argument("--job", type=name, required=True, metavar="JOB.toml",
                   help="the paint job (see examples/paint.toml; a part's mesh: "
                        "examples/parts/*.toml; a panel on a moving line: "
                        "examples/line.toml, a part: examples/line_part.toml)")
    p.add_argument("--actuators", type=name, metavar="FILE.toml", default=None,
                   help="motor ratings (default: the job's actuators, else the ratings of "
                        "examples/actuators.toml, shipped in the package)")
    p.add_argument("--out", type=name, default="paint", metavar="DIR",
                   help="output folder: path.csv, thickness.csv|parquet, paint.json, "
                        "thickness.png (and film.ply for a part)")
    p.add_argument("--format", choices=("csv", "parquet"), default="csv",
                   help="thickness table format")
    p.add_argument("--resolution", type=positive, default=None, metavar="M",
                   help="film grid (a part: film point) spacing [m], at most σ (default: "
                        "σ/3)")
    p.add_argument("--max-line-speed", action="store_true",
                   help="a job with [line]: plan at the fastest line speed that paints the "
                        "part (bisection to 1 %%) instead of the job's speed (docs/model.md "
                        "§24)")
