"""``pollard-pin`` command line: a thin layer over the public API."""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

from .io.atomic import atomic_open


def _progress(label: str, enabled: bool):
    if not enabled:
        return None
    state = {"last": -100}

    def report(done: int, total: int) -> None:
        pct = 100 * done // total
        if pct >= state["last"] + 5 or done == total:
            state["last"] = pct
            sys.stderr.write(f"\r{label}: {pct:3d}% ({done}/{total})")
            if done == total:
                sys.stderr.write("\n")
            sys.stderr.flush()

    return report


def _load_trajectory(args, params):
    from .io.trajectory import THESIS_DURATION, THESIS_SAMPLES, from_csv, thesis_trajectory

    if args.trajectory == "thesis":
        return thesis_trajectory(duration=args.duration or THESIS_DURATION,
                                 samples=args.samples or THESIS_SAMPLES,
                                 home_pose=params.home_pose)
    if args.duration is not None or args.samples is not None:
        print("note: --duration/--samples apply to the thesis trajectory only; "
              "the CSV file's own times are used", file=sys.stderr)
    traj = from_csv(args.trajectory)
    if traj.derivatives != "file columns":
        print(f"note: derivatives of {args.trajectory} come from a {traj.derivatives} "
              "(no d_*/dd_* columns in the file)", file=sys.stderr)
    return traj


def cmd_urdf(args) -> int:
    from .model.build import generate
    from .model.params import load_params

    params = load_params(args.params)
    urdf, srdf = generate(params)
    out = Path(args.out)
    srdf_out = out.with_suffix(".srdf")
    for path, text in ((out, urdf), (srdf_out, srdf)):
        with atomic_open(path) as f:
            f.write(text)
    print(f"wrote {out} and {srdf_out} from {params.source}")
    return 0


def cmd_info(args) -> int:
    import numpy as np

    from .model.build import constraint_residual, load

    robot = load(args.params)
    q = robot.home()
    r = constraint_residual(robot.model, robot.data, robot.constraint_models,
                            robot.constraint_datas, q)
    print(f"Pollard robot: nq = {robot.model.nq}, total mass {robot.params.total_mass:.4f} kg")
    for name, b in robot.params.bodies:
        print(f"  {name:9s} {b.mass:.3f} kg")
    print("home configuration (deg):")
    for name, val in robot.as_dict(q).items():
        print(f"  {name:10s} {np.degrees(val):10.4f}")
    print(f"closure residual at home: {np.abs(r).max():.3g} m")
    return 0


def cmd_run(args) -> int:
    from .io.results import summary, write_csv

    t0 = time.perf_counter()
    _, result = _solve(args, wrist_margin=args.wrist_margin,
                       singularity_margin=args.singularity_margin)
    wall = time.perf_counter() - t0  # model load included
    write_csv(result, args.out)
    print(summary(result, wall))
    print(f"wrote {len(result.ik)} rows to {args.out}")
    return 0


def cmd_sweep(args) -> int:
    from .sweep import load_grid, run_sweep, summary, write_csv

    sweep = load_grid(args.grid)
    where = (f"Dask cluster {args.dask}" if args.dask else
             "this process" if args.workers == 1 else
             f"{args.workers or os.cpu_count()} local processes")
    print(f"{sweep.source}: {len(sweep)} variants on {where}", file=sys.stderr)
    t0 = time.perf_counter()
    rows = run_sweep(sweep, workers=args.workers, dask=args.dask,
                     progress=_progress("sweep", not args.quiet))
    wall = time.perf_counter() - t0
    write_csv(rows, args.out, sweep.columns)
    print(summary(rows))
    print(f"wrote {len(rows)} rows to {args.out} (wall time {wall:.2f} s)")
    return 0


def _solve(args, dynamics: bool = True, **ik_options):
    """Load the model and the chosen trajectory, run the pipeline (run/view/plot/report)."""
    from .model.build import load
    from .io.results import run_pipeline

    robot = load(args.params)
    traj = _load_trajectory(args, robot.params)
    result = run_pipeline(robot, traj, dynamics=dynamics,
                          progress=_progress("solving", len(traj) >= 500 and not args.quiet),
                          **ik_options)
    return robot, result


def cmd_view(args) -> int:
    from .viz import viewer

    robot, result = _solve(args, dynamics=False)
    if args.html:
        path = viewer.write_html(args.html, robot, result.ik, frames=args.frames, fps=args.fps)
        print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB, {len(result.ik)} samples, "
              f"{result.ik.t[-1] - result.ik.t[0]:.4g} s): open it in a browser, no server "
              "needed; Open Controls → Animations to play and scrub")
        return 0
    viewer.serve(robot, result.ik, frames=args.frames, fps=args.fps)
    return 0


def cmd_plot(args) -> int:
    from .viz.plots import write_figures

    _, result = _solve(args)
    for path in write_figures(result, args.out, dpi=args.dpi):
        print(f"wrote {path}")
    return 0


def cmd_report(args) -> int:
    from .viz.report import report, to_json, to_markdown

    robot, result = _solve(args)
    rep = report(robot, result, cross_check=not args.no_cross_check)
    text = to_json(rep) + "\n" if args.format == "json" else to_markdown(rep)
    if args.out:
        with atomic_open(args.out) as f:
            f.write(text)
        print(f"wrote {args.out}", file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


def _positive(text: str) -> float:
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive, got {text}")
    return value


def _trajectory_args(p) -> None:
    p.add_argument("--trajectory", default="thesis", help="'thesis' or a CSV file")
    p.add_argument("--duration", type=float, default=None, help="thesis trajectory duration [s]")
    p.add_argument("--samples", type=int, default=None, help="thesis trajectory samples")
    p.add_argument("--params", help="parameter TOML")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def build_parser() -> argparse.ArgumentParser:
    from .kinematics.singularity import SINGULARITY_MARGIN, WRIST_MARGIN

    ap = argparse.ArgumentParser(prog="pollard-pin", description=__doc__)
    sub = ap.add_subparsers(dest="command", required=True)

    p = sub.add_parser("urdf", help="generate models/pollard.urdf (+ .srdf) from parameters")
    p.add_argument("--params", help="parameter TOML (default: the shipped models/pollard.toml)")
    p.add_argument("--out", default="models/pollard.urdf", help="output URDF path")
    p.set_defaults(func=cmd_urdf)

    p = sub.add_parser("info", help="load the model and print home configuration and masses")
    p.add_argument("--params", help="parameter TOML")
    p.set_defaults(func=cmd_info)

    p = sub.add_parser("run", help="solve a trajectory: kinematics and dynamics → CSV")
    p.add_argument("--trajectory", default="thesis", help="'thesis' or a CSV file")
    p.add_argument("--duration", type=float, default=None, help="thesis trajectory duration [s]")
    p.add_argument("--samples", type=int, default=None, help="thesis trajectory samples")
    p.add_argument("--out", default="run.csv", help="output CSV")
    p.add_argument("--params", help="parameter TOML")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--wrist-margin", type=float, default=WRIST_MARGIN,
                   help="fail where |sin θ1716| drops below this (default %(default)s)")
    p.add_argument("--singularity-margin", type=float, default=SINGULARITY_MARGIN,
                   help="fail where the parallel or serial σ_min drops below this "
                        "(default %(default)s)")
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("sweep", help="design sweep: parameter variants over a trajectory → CSV")
    p.add_argument("--grid", required=True, help="grid TOML file (see pollard_pin.sweep)")
    p.add_argument("--out", default="sweep.csv", help="output CSV")
    p.add_argument("--workers", type=int, default=None,
                   help="local processes (default: all cores; 1 = serial)")
    p.add_argument("--dask", metavar="ADDRESS", default=None,
                   help="run on this Dask scheduler (needs pollard-pin[cluster])")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_sweep)

    p = sub.add_parser("view", help="MeshCat 3D viewer: live on localhost, or --html FILE")
    _trajectory_args(p)
    p.add_argument("--html", metavar="FILE", help="write a self-contained static page instead "
                   "of serving")
    p.add_argument("--frames", action="store_true", help="also draw the tool and platform frames")
    p.add_argument("--fps", type=_positive, default=25.0,
                   help="animation key frames per second of trajectory time (default 25)")
    p.set_defaults(func=cmd_view)

    p = sub.add_parser("plot", help="chapter-4 style PNG figures of a trajectory")
    _trajectory_args(p)
    p.add_argument("--out", default="plots", help="output directory (default plots/)")
    p.add_argument("--dpi", type=int, default=100, help="PNG resolution")
    p.set_defaults(func=cmd_plot)

    p = sub.add_parser("report", help="actuator sizing table and engine cross-checks")
    _trajectory_args(p)
    p.add_argument("--format", choices=("md", "json"), default="md", help="output format")
    p.add_argument("--out", help="write to this file instead of stdout")
    p.add_argument("--no-cross-check", action="store_true",
                   help="sizing only: skip the thesis and MuJoCo comparisons")
    p.set_defaults(func=cmd_report)
    return ap


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    from .kinematics.errors import ClosureError, KinematicsError
    from .model.build import ModelFileError
    from .model.params import ParameterError
    from .sweep import SweepError
    from .io.trajectory import TrajectoryError

    try:
        return args.func(args)
    except (ParameterError, TrajectoryError, KinematicsError, ClosureError,
            ModelFileError, SweepError) as exc:
        print(f"pollard-pin {args.command}: error: {exc}", file=sys.stderr)
        out = getattr(args, "out", None)
        if out and args.command in ("run", "sweep"):
            print(f"pollard-pin {args.command}: nothing written to {out}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
