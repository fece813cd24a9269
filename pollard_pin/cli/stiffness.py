"""pollard-pin stiffness: how far the gun gives under its weight and a wrench, and how low the
modes are, along a trajectory (docs/model.md §27), streamed into a table."""
from __future__ import annotations

import argparse
import os
import sys

from ..io.atomic import check_outputs
from ..version import __version__
from .common import (
    STDOUT,
    UsageError,
    command,
    count,
    load_robot,
    load_trajectory,
    log,
    margin_args,
    margins_of,
    name,
    number,
    progress,
    refuse_inputs,
    robot_for_trajectory,
    trajectory_args,
    wrote,
)

MAX_WORKERS = 4  # IK threads by default, as run
STREAM_WINDOW = 4096  # = pollard_pin.run.STREAM_CHUNK (not imported: --help stays fast)
HELP = ("stiffness and vibration along a trajectory: the tool's deflection under its weight and "
        "a wrench, the six natural frequencies, kmin → CSV or Parquet")


def wrench(text: str) -> tuple[float, ...]:
    """"FX,FY,FZ,MX,MY,MZ" [N, N·m]: six finite numbers."""
    parts = text.split(",")
    if len(parts) != 6:
        raise argparse.ArgumentTypeError(f"expected six numbers FX,FY,FZ,MX,MY,MZ (N, N·m), "
                                         f"got {len(parts)}: {text[:60]!r}")
    values = []
    for axis, part in zip(("FX", "FY", "FZ", "MX", "MY", "MZ"), parts):
        try:
            values.append(number(part))
        except argparse.ArgumentTypeError as exc:
            raise argparse.ArgumentTypeError(f"{axis}: {exc}") from None
    return tuple(values)


def run(args) -> int:
    from ..dynamics.drives.stiffness import UNITS, StiffnessError, StiffnessOptions
    from ..dynamics.motors import load_actuators
    from ..io.table import table_files
    from ..run import StreamOptions
    from ..run.stiffness import drive_stiffness, stream_stiffness

    check_outputs(*table_files(args.out))
    refuse_inputs(args, *table_files(args.out))
    try:
        options = StiffnessOptions(*(() if args.wrench is None else (args.wrench,)))
    except StiffnessError as exc:  # the library speaks of the value; name the flag
        raise UsageError(f"--wrench: {exc}") from None
    margins = margins_of(args)
    k = drive_stiffness(load_actuators(args.actuators))
    robot = load_robot(args)
    traj = load_trajectory(args, robot.params, lazy=True)
    robot = robot_for_trajectory(args, robot)
    n = len(traj)
    log.info("trajectory %s: %d samples", traj.name, n)
    metadata = {"pollard_pin": __version__, "command": "stiffness",
                "parameters_source": str(robot.params.source),
                "parameters": robot.params.to_toml_dict(),
                "trajectory": {"name": traj.name, "source": args.trajectory, "samples": n},
                "actuators": {"source": args.actuators,
                              "stiffness": dict(zip(robot.actuated, k.tolist()))},
                "options": {**margins.as_dict(), "wrench": list(options.wrench),
                            "joint_limits": not args.ignore_limits,
                            "gravity": [float(c) for c in robot.model.gravity.linear]},
                "units": UNITS}
    timings: dict = {}
    workers = args.workers or min(os.cpu_count() or 1, MAX_WORKERS,
                                  -(-n // (STREAM_WINDOW - 1)))  # no idle threads
    stats = stream_stiffness(robot, traj, k, args.out, options, StreamOptions(workers=workers),
                             metadata=metadata,
                             timings=timings,
                             progress=progress("solving", n >= 500 and not args.quiet),
                             margins=margins, joint_limits=not args.ignore_limits)
    wall = timings["wall"]
    text = stats.summary() + (f"\nsolved and written in {wall:.3f} s ({1e6 * wall / n:.2f} "
                              f"µs/sample, model loading not included): the IK in {workers} "
                              "thread(s), the stiffness and the writing in the main thread")
    print(text, file=sys.stderr if args.out == STDOUT else sys.stdout)
    wrote(args.out, f" ({stats.samples} rows)")
    from ..timing import peak_memory_mb

    mb = peak_memory_mb()
    log.info("peak resident memory %s MB", "unknown" if mb is None else f"{mb:.0f}")
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "stiffness", HELP, run)
    trajectory_args(p)
    p.add_argument("--actuators", type=name, required=True, metavar="FILE.toml",
                   help="actuator file with a 'stiffness' [N·m/rad, joint side] per actuator "
                        "(see examples/actuators.toml)")
    p.add_argument("--wrench", type=wrench, default=None, metavar="FX,FY,FZ,MX,MY,MZ",
                   help="wrench on the tool [N, N·m], force at the tip and moment about it, "
                        "world axes, besides the weight, e.g. -5,0,0,0,0,0 (default: none)")
    p.add_argument("--out", type=name, default="stiffness.csv",
                   metavar="FILE.csv|FILE.parquet",
                   help="output table: t, dx, dy, dz [m], rx, ry, rz [rad], f1…f6 [Hz], kmin "
                        "[N/m]; CSV with a NAME.units.json sidecar, or Parquet; '-': CSV on "
                        "standard output")
    margin_args(p)
    p.add_argument("--workers", type=count(1, 64), default=None,
                   help=f"IK threads, one window of {STREAM_WINDOW} samples each (default: the "
                        f"cores, at most {MAX_WORKERS}; 1 = no threads)")
