"""pollard-pin paint: plan a raster spray program over a panel (docs/model.md §20–§21) or
over a part's mesh (§23)."""
from __future__ import annotations

import sys
from pathlib import Path

from .common import (
    UsageError,
    as_flags,
    command,
    fraction,
    load_robot,
    model_args,
    name,
    nonnegative,
    number,
    numbers,
    positive,
    refuse_inputs,
    warnings_as_notes,
)
from .paint_files import say_written, spacing
from .paint_robots import (
    check_job,
    paint_layout,
    proposed_names,
    robot_count,
    robots_arg,
    write_layout,
)

# --strict's exit status when the film misses: distinct from 2 (a refusal, nothing written)
# and from 1 (an uncaught error): the outputs are written, for the paint engineer to look at
STRICT_STATUS = 3


def run(args) -> int:
    from ..dynamics.motors import as_actuators
    from ..io.atomic import all_or_nothing, check_outputs
    from ..outputs.result import paint
    from ..painting.api import film_spacing_of
    from ..painting.job import load_job
    from ..painting.kinds.base import output_files
    from ..painting.options import PaintOptions
    from ..painting.policy import PlannerPolicy

    out = Path(args.out)
    count = robot_count(args.robots)  # --robots N|auto: a proposed cell (§26.5)
    check_outputs(folders=(out,))  # the destination itself, before the job is read
    job = load_job(args.job)
    check_job(count, job)
    for flag in ("edge_room", "end_pitch"):
        if getattr(args, flag) is not None and count is None:
            raise UsageError(f"--{flag.replace('_', '-')}: only a proposed cell (--robots "
                             "N|auto) places its end robots")
    # the files, once: a cell writes a folder per robot (docs/model.md §26)
    files, stale = output_files(out, args.format, [r.name for r in job.robots]
                                or proposed_names(count))
    files = (*files, out / "robots.toml") if count is not None else files
    check_outputs(*files, folders=(out,))
    refuse_inputs(args, *files, *stale, also=[
        ("the job", args.job), ("the mesh", getattr(job, "mesh", None)),
        ("the actuators", job.actuators)])
    for flag in ("max_line_speed", "speeds"):
        if getattr(args, flag) and job.line is None:
            raise UsageError(f"--{flag.replace('_', '-')}: the job has no [line] table (speed, "
                             "direction)")
    res = spacing(film_spacing_of, job, args.resolution)
    # --actuators read before any planning; None: paint's own rule (the job's, else the
    # package's ratings)
    act = as_actuators(args.actuators)
    with as_flags("PlannerPolicy"):  # checked once; a refusal names the flag
        policy = PlannerPolicy(strokes=args.strokes, step_from=args.step_from,
                               seam_run=args.seam_run, smoothing=args.smoothing or 0.0,
                               seams=args.seams)
    options = PaintOptions(resolution=res, max_line_speed=args.max_line_speed,
                           speeds=args.speeds,
                           compliance=not args.no_compliance, policy=policy,
                           progress=True)  # bars when standard error is a terminal
    with warnings_as_notes(args):  # a mesh repaired (repeated or zero-area faces dropped)
        if count is None:
            result = paint(load_robot(args), job, act, options)
        else:
            robots, result = paint_layout(count, load_robot(args), job, act, options,
                                          args.edge_room or 0.0, args.end_pitch or 0.0)
    with all_or_nothing():
        name = result.write(out, args.format)
        if count is not None:
            write_layout(robots, out, count, job, result.options.policy.seams,
                         result.report.data.get("levers"))
    print("\n".join(result.summary_lines()))
    say_written(out, name, result.robot_folders)
    return _strict(args.strict, result.report.data["film_check"])


def _strict(share, check: dict) -> int:
    """--strict SHARE: STRICT_STATUS, said on stderr, when less than ``share`` of the area
    is within ±10 % of the target (True: the check's acceptance); else 0."""
    from ..painting.film.stats import misses

    if share is None or not misses(check, None if share is True else share):
        return 0
    need = check["acceptance"]["min_share"] if share is True else share
    print(f"pollard-pin paint: --strict: {100 * (1 - check['outside_10pct']):.2f} % of the "
          f"area within ±10 % of the target, under {100 * need:g} % (exit status "
          f"{STRICT_STATUS}; the outputs are written)", file=sys.stderr)
    return STRICT_STATUS


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
    p.add_argument("--speeds", action="store_true",
                   help="a job with [line]: also state the interval of line speeds that "
                        "paint the part, each end to 5 %% and planned in full (paint.json's "
                        "line.speeds; docs/model.md §24.3; ~10 more plans)")
    p.add_argument("--strokes", choices=("auto", "across", "along"), default="auto",
                   help="a job with [line]: the strokes across the travel or along it; auto "
                        "(default): of those that paint at the job's speed and keep the "
                        "gun's clearance, the shortest cycle (a cell: across; along, "
                        "forced, gives each robot whole passes) (docs/model.md §24.2)")
    p.add_argument("--step-from", choices=("leading", "trailing"), default="leading",
                   help="a job with [line]: the end of the part the strokes across the "
                        "travel step from (default: leading)")
    p.add_argument("--seam-run", type=nonnegative, default=None, metavar="M",
                   help="a cell: its strokes run M past a seam (default: R = 4σ; the trigger "
                        "still closes at the seam, docs/model.md §26.5)")
    p.add_argument("--smoothing", type=nonnegative, default=None, metavar="M",
                   help="a cell painting a part: every robot's passes average the surface "
                        "normal over at least M (default: 0, the least the gun can follow)")
    p.add_argument("--seams", type=numbers, default=None, metavar="W,...",
                   help="a cell: its seams [m along the split's axis], increasing, one fewer "
                        "than its robots (default: where the bands meet, docs/model.md §26.2)")
    p.add_argument("--edge-room", type=nonnegative, default=None, metavar="M",
                   help="with --robots: the end robots hold M more past the part's free "
                        "edges, room for the ramps there (default: 0, docs/model.md §26.5)")
    p.add_argument("--end-pitch", type=number, default=None, metavar="DEG",
                   help="with --robots: the top robot turned DEG about the line, away from the "
                        "wrist's singularity at a bevelled edge (default: 0, docs/model.md "
                        "§26.5)")
    p.add_argument("--strict", type=fraction, nargs="?", const=True, default=None,
                   metavar="SHARE",
                   help="exit with status 3 (after writing the outputs) when less than SHARE "
                        "of the painted area is within ±10 %% of the target (SHARE left "
                        "out: the acceptance paint.json's film_check states, 0.99; default: "
                        "off, the exit status says nothing of the film)")
    p.add_argument("--robots", type=robots_arg, default=None, metavar="N|auto",
                   help="a job with [line] and no [[robot]]: propose N robots (1..16) for the "
                        "part, stacked along the line (or auto: the fewest that paint it), "
                        "plan with them and write DIR/robots.toml (docs/model.md §26.5; "
                        "default: the job's robots, else one at the origin)")
