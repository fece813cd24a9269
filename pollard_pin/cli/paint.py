"""pollard-pin paint: plan a raster spray program over a panel (docs/model.md §20–§21) or
over a part's mesh (§23)."""
from __future__ import annotations

from pathlib import Path

from .common import (
    UsageError,
    command,
    load_robot,
    model_args,
    name,
    positive,
    refuse_inputs,
    warnings_as_notes,
)
from .paint_files import motor_use_line, part_summary_lines, say_written, spacing
from .paint_robots import (
    check_job,
    paint_layout,
    proposed_names,
    robot_count,
    robots_arg,
    write_layout,
)


def _actuators(args, job):
    """--actuators, else the job's, else the package's (pollard_pin.paint's rule)."""
    from ..dynamics.motors import load_actuators
    from ..painting.api import default_actuators

    return load_actuators(args.actuators) if args.actuators else default_actuators(job)


def run(args) -> int:
    from ..io.atomic import all_or_nothing, check_outputs
    from ..io.paint_files import paint_outputs
    from ..painting.api import PaintOptions, film_spacing_of, job_kind, paint
    from ..painting.job import load_job

    out = Path(args.out)
    count = robot_count(args.robots)  # --robots N|auto: a proposed cell (§26.5)
    files, stale = paint_outputs(out, args.format)
    files = (*files, out / "robots.toml") if count is not None else files
    check_outputs(*files, folders=(out,))
    job = load_job(args.job)
    refuse_inputs(args, *files, *stale, also=[
        ("the job", args.job), ("the mesh", getattr(job, "mesh", None)),
        ("the actuators", job.actuators)])
    kind = job_kind(job)
    check_job(count, job)
    names = [r.name for r in job.robots] or proposed_names(count)
    if names:  # a cell writes a folder per robot (docs/model.md §26)
        from ..io.paint_cell_files import cell_outputs

        files, stale = cell_outputs(out, args.format, names)
        files = (*files, out / "robots.toml") if count is not None else files
        check_outputs(*files, folders=(out,))
        refuse_inputs(args, *files, *stale, also=[
            ("the job", args.job), ("the mesh", getattr(job, "mesh", None)),
            ("the actuators", job.actuators)])
    if args.max_line_speed and job.line is None:
        raise UsageError("--max-line-speed: the job has no [line] table (speed, direction)")
    res = spacing(film_spacing_of, job, args.resolution)
    act = _actuators(args, job)
    options = PaintOptions(resolution=res, max_line_speed=args.max_line_speed,
                           compliance=not args.no_compliance)
    with warnings_as_notes(args):  # a mesh repaired (repeated or zero-area faces dropped)
        if count is None:
            result = paint(load_robot(args), job, act, options)
        else:
            robots, result = paint_layout(count, load_robot(args), job, act, options)
    kind = result.kind
    with all_or_nothing():
        name = result.write(out, args.format)
        if count is not None:
            write_layout(robots, out, count, job)
    rep = result.report.to_dict()
    if kind == "panel":
        lines = summary_lines(rep, act.names)
    elif kind == "part":
        lines = part_summary_lines(rep, act.names)
    elif kind.startswith("cell"):
        from .paint_line import cell_lines

        lines = cell_lines(rep, act.names)
    else:
        from .paint_line import line_lines, line_summary_lines

        lines = (line_summary_lines(rep, act.names) if kind == "line panel" else
                 line_lines(rep) + part_summary_lines(rep, act.names))
    if "min_clearance_m" in rep:  # docs/model.md §25
        c = rep["clearance"]
        lines.append(f"gun body {rep['min_clearance_m'] * 1e3:.1f} mm from the part at its "
                     f"closest (± {c['between_samples_m'] * 1e3:.1f} mm between samples; "
                     f"clearance {c['required_m'] * 1e3:.3g} mm)")
    if "compliance" in rep:  # docs/model.md §27.7
        lines.append(compliance_line(rep["compliance"]))
    print("\n".join(lines))
    say_written(out, name, [r.robot.name for r in result.plan.robots]
                if kind.startswith("cell") else ())
    return 0


def compliance_line(c: dict) -> str:
    """paint.json's ``compliance`` in one line (docs/model.md §27.7)."""
    if not c["stiffness"]:
        return f"compliance {c['note']}"
    who = f" (robot '{c['standoff_error_robot']}')" if "standoff_error_robot" in c else ""
    return (f"compliance (weight, recoil {c['recoil_n']:.3g} N): standoff error "
            f"{c['standoff_error_m'] * 1e6:.3g} µm{who}, lateral "
            f"{c['lateral_error_m'] * 1e6:.3g} µm, "
            f"tilt {c['tilt_rad'] * 1e3:.3g} mrad; film changes by at most "
            f"{100 * c['film_error']:.2g} % of the target")


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


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "paint", "plan a spray program over a panel or a part's mesh: "
                "path, film map, motors (docs/model.md §20–§21, §23)", run)
    model_args(p)
    p.add_argument("--job", type=name, required=True, metavar="JOB.toml",
                   help="the paint job (see examples/paint.toml; a part's mesh: "
                        "examples/parts/*.toml; a panel on a moving line: "
                        "examples/line.toml, a part: examples/line_part.toml; a cell of "
                        "robots: examples/cell.toml)")
    p.add_argument("--actuators", type=name, metavar="FILE.toml", default=None,
                   help="motor ratings (default: the job's actuators, else the ratings of "
                        "examples/actuators.toml, shipped in the package)")
    p.add_argument("--out", type=name, default="paint", metavar="DIR",
                   help="output folder: path.csv, thickness.csv|parquet, paint.json, "
                        "thickness.png (and film.ply for a part); a cell: NAME/path.csv per "
                        "robot")
    p.add_argument("--format", choices=("csv", "parquet"), default="csv",
                   help="thickness table format")
    p.add_argument("--resolution", type=positive, default=None, metavar="M",
                   help="film grid (a part: film point) spacing [m], at most σ (default: "
                        "σ/3)")
    p.add_argument("--no-compliance", action="store_true",
                   help="skip what the drives' compliance does to the gun and the film "
                        "(docs/model.md §27.7: a second film integration)")
    p.add_argument("--max-line-speed", action="store_true",
                   help="a job with [line]: plan at the fastest line speed that paints the "
                        "part (bisection to 1 %%) instead of the job's speed (docs/model.md "
                        "§24)")
    p.add_argument("--robots", type=robots_arg, default=None, metavar="N|auto",
                   help="a job with [line] and no [[robot]]: propose N robots (1..16) for the "
                        "part, stacked along the line (or auto: the fewest that paint it), "
                        "plan with them and write DIR/robots.toml (docs/model.md §26.5; "
                        "default: the job's robots, else one at the origin)")
