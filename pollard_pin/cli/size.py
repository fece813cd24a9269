"""pollard-pin size: motors and gearboxes."""
from __future__ import annotations

import sys
import time
from pathlib import Path

from ..io.atomic import all_or_nothing, atomic_open, check_outputs
from .common import (
    STDOUT,
    UsageError,
    command,
    log,
    name,
    refuse_inputs,
    solve,
    trajectory_args,
    wrote,
)


def run(args) -> int:
    from ..dynamics.motors import load_actuators
    from ..dynamics.sizing import actuator_sizing
    from ..io.retime import write_retimed
    from ..io.table import table_files
    from ..io.trajectory import carried_metadata
    from ..viz.torque_speed import to_json, to_markdown, write_torque_speed

    out = args.out or STDOUT
    if args.retime == STDOUT and out == STDOUT:
        raise UsageError("--retime - and the report both on standard output: give --out FILE "
                          "or --retime FILE.csv")
    retime = table_files(args.retime, "csv") if args.retime is not None else ()
    figure = Path(args.plot) / "torque_speed.png" if args.plot is not None else None
    check_outputs(*retime, figure, out, folders=(args.plot,))
    refuse_inputs(args, *retime, figure, out)
    actuators = load_actuators(args.actuators)
    robot, result = solve(args)
    t0 = time.perf_counter()
    sized = actuator_sizing(robot, result, actuators)
    log.info("sized in %.3f s (TOPP-RA solves: %d)", time.perf_counter() - t0,
             sized.timing.iterations if sized.timing else 0)
    text = to_json(sized.report) + "\n" if args.format == "json" else to_markdown(sized.report)
    written = []
    with all_or_nothing():  # every output or none; the report last (it may be a device)
        if args.retime is not None and sized.timing is not None:
            carried = ({} if args.trajectory == "thesis" else
                       carried_metadata(args.trajectory))  # its robot's gravity goes on
            retimed = write_retimed(result.trajectory, sized.timing, args.retime, carried)
            kept = ", the passes as planned" if sized.report.get("time_optimal_film") else ""
            written.append((args.retime, f" (time-optimal{kept}, "
                                         f"{sized.timing.duration:.4g} s, {len(retimed)} rows)"))
        if args.plot is not None:
            written.append((write_torque_speed(sized, args.plot), ""))
        with atomic_open(out) as f:
            f.write(text)
        written.append((out, ""))
    for path, what in written:
        wrote(path, what)
    if sized.timing is None:  # the rest of the report stands; say why in one line
        why = sized.report["time_optimal_error"]
        if args.retime:
            print(f"error: --retime {args.retime} not written: no time-optimal cycle: {why}",
                  file=sys.stderr)
            return 2
        print(f"note: no time-optimal cycle: {why}", file=sys.stderr)
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "size", "motors and gearboxes: ratings check, shortest uniform and "
                "time-optimal cycle of the path", run)
    trajectory_args(p)
    p.add_argument("--actuators", type=name, required=True, metavar="FILE.toml",
                   help="one table per actuator (see examples/actuators.toml)")
    p.add_argument("--format", choices=("md", "json"), default="md", help="output format")
    p.add_argument("--out", type=name, metavar="FILE", default=None,
                   help="write the table to this file (default: standard output)")
    p.add_argument("--retime", type=name, metavar="OUT.csv", default=None,
                   help="write the time-optimal traversal as a trajectory CSV (replay it with "
                        "run --trajectory OUT.csv; a paint program keeps its passes and its "
                        "spray column; default: not written)")
    p.add_argument("--plot", type=name, metavar="FOLDER", default=None,
                   help="write FOLDER/torque_speed.png, the motors' operating points and "
                        "ratings (default: no figure)")
