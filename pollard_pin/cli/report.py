"""pollard-pin report: sizing table and engine cross-checks."""
from __future__ import annotations

from ..io.atomic import atomic_open, check_outputs
from .common import (
    STDOUT,
    command,
    name,
    refuse_inputs,
    simulation_table,
    solve,
    trajectory_args,
    wrote,
)


def run(args) -> int:
    from ..viz.report import report, to_json, to_markdown

    out = args.out or STDOUT
    check_outputs(out)
    refuse_inputs(args, out)
    table = simulation_table(args.simulation) if args.simulation else None
    robot, result = solve(args)
    rep = report(robot, result, cross_check=not args.no_cross_check)
    if table is not None:
        from ..viz.simulation import simulation_summary

        rep["simulation"] = simulation_summary(table.columns, table.metadata)
    text = to_json(rep) + "\n" if args.format == "json" else to_markdown(rep)
    with atomic_open(out) as f:
        f.write(text)
    wrote(out)
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "report", "actuator sizing table and engine cross-checks", run)
    trajectory_args(p)
    p.add_argument("--format", choices=("md", "json"), default="md", help="output format")
    p.add_argument("--out", type=name, metavar="FILE", default=None,
                   help="write to this file (default: standard output)")
    p.add_argument("--no-cross-check", action="store_true",
                   help="sizing only: skip the thesis and MuJoCo comparisons")
    p.add_argument("--simulation", type=name, metavar="SIM.csv", default=None,
                   help="add this closed-loop simulation's tracking errors and torques "
                        "(pollard-pin simulate; default: none)")
