"""pollard-pin plot: PNG figures."""
from __future__ import annotations

from pathlib import Path

from ..io.atomic import all_or_nothing, check_outputs
from .common import command, count, name, simulation_table, solve, trajectory_args


def run(args) -> int:
    from ..viz.plots import FIGURES, LOAD_FIGURES, write_figures
    from ..viz.simulation import FLEXIBLE_FIGURES, SIMULATION_FIGURES, write_simulation_figures

    names = SIMULATION_FIGURES + FLEXIBLE_FIGURES if args.simulation else FIGURES + LOAD_FIGURES
    check_outputs(*(Path(args.out) / f"{n}.png" for n in names), folders=(args.out,))
    if args.simulation:  # the simulation's figures only (docs/model.md §18)
        table = simulation_table(args.simulation)
        name = f"{table.metadata.get('controller', 'simulation')}, {Path(args.simulation).name}"
        with all_or_nothing():  # every figure or none
            paths = write_simulation_figures(table.columns, args.out, dpi=args.dpi, name=name)
    else:
        _, result = solve(args, loads=True)  # joint-loads figure, docs/model.md §17
        with all_or_nothing():
            paths = write_figures(result, args.out, dpi=args.dpi)
    for path in paths:
        print(f"wrote {path}")
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "plot", "chapter-4 style PNG figures of a trajectory", run)
    trajectory_args(p)
    p.add_argument("--out", type=name, default="plots", metavar="FOLDER", help="output folder")
    p.add_argument("--dpi", type=count(10, 1200), default=100, help="PNG resolution")
    p.add_argument("--simulation", type=name, metavar="SIM.csv", default=None,
                   help="plot this closed-loop simulation (pollard-pin simulate) instead: "
                        "tracking errors, torques, desired vs actual path, and the drives' "
                        "deflections of a --flexible one (default: plot the trajectory)")
