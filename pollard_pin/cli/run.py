"""pollard-pin run: solve a trajectory (streamed, window by window) into a table."""
from __future__ import annotations

import os
import sys

from ..io.atomic import check_outputs
from ..version import __version__
from .common import (
    STDOUT,
    command,
    count,
    load_robot,
    load_trajectory,
    log,
    margin_args,
    margins_of,
    name,
    progress,
    refuse_inputs,
    robot_for_trajectory,
    trajectory_args,
    wrote,
)

MAX_RUN_WORKERS = 4  # solver threads by default (each holds one window in memory)
STREAM_WINDOW = 4096  # = pollard_pin.run.STREAM_CHUNK (not imported: --help stays fast)


def run(args) -> int:
    from ..io.table import table_files
    from ..run import StreamOptions, stream_run
    from ..run.stats import summary

    check_outputs(*table_files(args.out))  # the table and its units sidecar
    refuse_inputs(args, *table_files(args.out))
    margins = margins_of(args)
    robot = load_robot(args)
    traj = load_trajectory(args, robot.params, lazy=True)
    robot = robot_for_trajectory(args, robot)
    n = len(traj)
    log.info("trajectory %s: %d samples (derivatives: %s)", traj.name, n, traj.derivatives)
    metadata = {"pollard_pin": __version__, "command": "run",
                "parameters_source": str(robot.params.source),
                "parameters": robot.params.to_toml_dict(),
                "trajectory": {"name": traj.name, "source": args.trajectory, "samples": n,
                               "derivatives": traj.derivatives},
                "options": {**margins.as_dict(), "loads": args.loads,
                            "joint_limits": not args.ignore_limits,
                            "gravity": [float(c) for c in robot.model.gravity.linear]}}
    timings: dict = {}
    workers = args.workers or min(os.cpu_count() or 1, MAX_RUN_WORKERS,
                                  -(-n // (STREAM_WINDOW - 1)))  # no idle threads
    stats = stream_run(robot, traj, args.out, StreamOptions(workers=workers),
                       metadata=metadata, timings=timings,
                       progress=progress("solving", n >= 500 and not args.quiet),
                       margins=margins, loads=args.loads,
                       joint_limits=not args.ignore_limits)
    wall, write = timings["wall"], timings["write"]
    text = summary(stats) + (
        f"\nsolved and written in {wall:.3f} s ({1e6 * wall / n:.2f} µs/sample, the first "
        f"window's one-off set-up included; model loading not): {workers} solver thread(s), "
        f"writing {write:.3f} s ({1e6 * write / n:.2f} µs/sample) in the main thread meanwhile")
    print(text, file=sys.stderr if args.out == STDOUT else sys.stdout)
    wrote(args.out, f" ({stats.samples} rows)")
    from ..timing import peak_memory_mb

    log.info("peak resident memory %s MB", _fmt_mb(peak_memory_mb()))
    return 0


def _fmt_mb(mb: float | None) -> str:
    return "unknown" if mb is None else f"{mb:.0f}"


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "run",
                "solve a trajectory: kinematics and dynamics → CSV or Parquet", run)
    trajectory_args(p)
    p.add_argument("--out", type=name, default="run.csv", metavar="FILE.csv|FILE.parquet",
                   help="output table: CSV with a NAME.units.json sidecar, or Parquet (zstd, "
                        "units and metadata inside) for a .parquet name; '-': CSV on standard "
                        "output")
    margin_args(p)
    p.add_argument("--loads", action="store_true",
                   help="also write the load of every tree joint: F_<joint>_x/y/z [N] and "
                        "M_<joint>_x/y/z [N·m], world axes (docs/model.md §17)")
    p.add_argument("--workers", type=count(1, 64), default=None,
                   help=f"solver threads, one window of {STREAM_WINDOW} samples each (default: "
                        f"the cores, at most {MAX_RUN_WORKERS}; 1 = no threads)")
