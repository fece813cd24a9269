"""pollard-pin sweep: design sweeps."""
from __future__ import annotations

import os
import sys
import time

from ..io.atomic import check_outputs
from .common import (
    STDOUT,
    command,
    count,
    log,
    name,
    progress,
    refuse_inputs,
    scheduler_address,
    warnings_as_notes,
    wrote,
)


def run(args) -> int:
    from ..sweep import load_grid, run_sweep, summary, write_sweep_table

    check_outputs(args.out)
    refuse_inputs(args, args.out)
    if args.dask:  # the extra, before the banner: a missing one is then the only line
        from ..sweep.backends import require_distributed

        require_distributed()
    with warnings_as_notes(args):  # a trajectory CSV without derivatives
        sweep = load_grid(args.grid)
    where = (f"Dask cluster {args.dask}" if args.dask else
             "this process" if args.workers == 1 else
             f"{args.workers or os.cpu_count()} local processes")
    # said beside the bar, on a terminal only: an error is then the only line
    banner = f"{sweep.source}: {len(sweep)} variants on {where}"
    log.info(banner)
    t0 = time.perf_counter()
    with warnings_as_notes(args):
        rows = run_sweep(sweep, workers=args.workers, dask=args.dask,
                         progress=progress(banner, not args.quiet))
    wall = time.perf_counter() - t0
    write_sweep_table(rows, args.out, sweep.columns)
    print(summary(rows), file=sys.stderr if args.out == STDOUT else sys.stdout)
    wrote(args.out, f" ({len(rows)} rows, wall time {wall:.2f} s)")
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "sweep",
                "design sweep: parameter variants over a trajectory → CSV", run)
    p.add_argument("--grid", type=name, required=True, metavar="FILE.toml",
                   help="grid file (see examples/sweep.toml)")
    p.add_argument("--out", type=name, default="sweep.csv", metavar="FILE.csv",
                   help="output CSV ('-': standard output)")
    p.add_argument("--workers", type=count(1), default=None,
                   help="local processes (1 = serial; default: all cores)")
    p.add_argument("--dask", type=scheduler_address, metavar="ADDRESS", default=None,
                   help="run on this Dask scheduler (needs pollard-pin[cluster]; default: "
                        "local processes)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
