"""The pollard-pin command: a thin layer over the public API.

Every command loads the model (the shipped one, or --params FILE.toml and --set KEY=VALUE),
solves, and writes its output only when all went well. Errors are one line on standard error
with exit status 2; outputs are checked for writability before the work starts.
"""
from __future__ import annotations

import argparse
import contextlib
import errno
import logging
import math
import os
import signal
import sys
import threading
import time
import warnings
from pathlib import Path

from . import __version__
from .io.atomic import STDOUT, atomic_open, check_destination

log = logging.getLogger("pollard_pin")

DESCRIPTION = """\
Verified multibody model of the Pollard spray-painting parallel robot (Pinocchio).

Solve a painting trajectory for every joint's motion and every actuator's torque, view it in
a browser, plot it, size the actuators, and sweep the design. See docs/model.md for the model
and its conventions.
"""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage block): ``pollard-pin run: error: ...``."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}\n")


class _Help(argparse.ArgumentDefaultsHelpFormatter, argparse.RawDescriptionHelpFormatter):
    """Every default in --help: shown by argparse, or said in the help text where the default
    is "none given" (then the text says what happens)."""

    def _get_help_string(self, action):
        if action.default in (None, [], False, argparse.SUPPRESS):
            return action.help
        return super()._get_help_string(action)


# --- argument types: each rejects what the API would reject, before any work ----------------
def _float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text}")
    return value


def _positive(text: str) -> float:
    value = _float(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"must be positive, got {text}")
    return value


def _nonnegative(text: str) -> float:
    value = _float(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {text}")
    return value


def _count(minimum: int, maximum: int | None = None):
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
        if value < minimum or (maximum is not None and value > maximum):
            bound = f"between {minimum} and {maximum}" if maximum else f">= {minimum}"
            raise argparse.ArgumentTypeError(f"must be {bound}, got {text}")
        return value

    return parse


# --- shared steps ---------------------------------------------------------------------------
def _progress(label: str, enabled: bool):
    """A tqdm bar fed by the pipeline's ``progress(done, total)`` calls; silent when not on a
    terminal (tqdm's ``disable=None``) or with --quiet."""
    if not enabled:
        return None
    from tqdm import tqdm

    state = {}

    def report(done: int, total: int) -> None:
        bar = state.get("bar")
        if bar is None:
            bar = state["bar"] = tqdm(total=total, desc=label, unit="sample", disable=None,
                                      leave=False, file=sys.stderr)
        bar.update(done - bar.n)
        if done >= total:
            bar.close()

    return report


def _params(args):
    """The parameters of --params (a file, possibly partial) and --set, or None (shipped)."""
    from .model.params import load_params, parse_assignment

    sets = dict(parse_assignment(s) for s in getattr(args, "set", None) or ())
    if args.params is None and not sets:
        return None
    return load_params(args.params, overrides=sets)


def _robot(args):
    from .model.build import load

    t0 = time.perf_counter()
    robot = load(_params(args))
    log.info("model %s loaded in %.1f ms", robot.params.source, 1e3 * (time.perf_counter() - t0))
    return robot


def _load_trajectory(args, params, lazy: bool = False):
    """The chosen trajectory; ``lazy``: the thesis curve evaluated window by window (run)."""
    from .io.trajectory import (THESIS_DURATION, THESIS_SAMPLES, ThesisTrajectory, from_csv,
                                thesis_trajectory)

    if args.trajectory == "thesis":
        duration = THESIS_DURATION if args.duration is None else args.duration
        samples = THESIS_SAMPLES if args.samples is None else args.samples
        make = ThesisTrajectory if lazy else thesis_trajectory
        return make(duration=duration, samples=samples, home_pose=params.home_pose)
    if args.duration is not None or args.samples is not None:
        print("note: --duration/--samples apply to the thesis trajectory only; "
              "the CSV file's own times are used", file=sys.stderr)
    with warnings.catch_warnings(record=True) as caught:  # said once, below, as a note
        warnings.simplefilter("always")
        traj = from_csv(args.trajectory)
    for w in caught:
        print(f"note: {w.message}", file=sys.stderr)
    return traj


def _solve(args, dynamics: bool = True, **ik_options):
    """Load the model and the chosen trajectory, run the pipeline (run/view/plot/report)."""
    from .run import run_pipeline

    robot = _robot(args)
    traj = _load_trajectory(args, robot.params)
    log.info("trajectory %s: %d samples over %.4g s (derivatives: %s)", traj.name, len(traj),
             traj.t[-1] - traj.t[0], traj.derivatives)
    t0 = time.perf_counter()
    result = run_pipeline(robot, traj, dynamics=dynamics,
                          progress=_progress("solving", len(traj) >= 500 and not args.quiet),
                          **ik_options)
    log.info("solved in %.3f s", time.perf_counter() - t0)
    return robot, result


def _wrote(path, what: str = "") -> None:
    if str(path) != STDOUT:
        print(f"wrote {path}{what}", file=sys.stderr)


# --- commands -------------------------------------------------------------------------------
def cmd_urdf(args) -> int:
    from .model.build import generate

    out = Path(args.out) if args.out != STDOUT else None
    if out is not None:
        installed = Path(__file__).resolve().parent
        if installed in out.resolve().parents:
            raise _UsageError(f"--out {out}: refusing to write inside the installed package "
                              f"({installed}); write elsewhere and load it with --params")
        check_destination(out)
        check_destination(out.with_suffix(".srdf"))
    params = _params(args)
    if params is None:
        from .model.params import load_params

        params = load_params()
    urdf, srdf = generate(params)
    if out is None:
        sys.stdout.write(urdf)
        return 0
    for path, text in ((out, urdf), (out.with_suffix(".srdf"), srdf)):
        with atomic_open(path) as f:
            f.write(text)
    print(f"wrote {out} and {out.with_suffix('.srdf')} from {params.source}")
    return 0


def cmd_info(args) -> int:
    import numpy as np

    from .model.build import constraint_residual

    robot = _robot(args)
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
    from .run import stream_run, summary

    check_destination(args.out)
    robot = _robot(args)
    traj = _load_trajectory(args, robot.params, lazy=True)
    n = len(traj)
    log.info("trajectory %s: %d samples (derivatives: %s)", traj.name, n, traj.derivatives)
    metadata = {"pollard_pin": __version__, "command": "run",
                "parameters_source": str(robot.params.source),
                "parameters": robot.params.to_toml_dict(),
                "trajectory": {"name": traj.name, "source": args.trajectory, "samples": n,
                               "derivatives": traj.derivatives},
                "options": {"wrist_margin": args.wrist_margin,
                            "singularity_margin": args.singularity_margin,
                            "loads": args.loads}}
    timings: dict = {}
    workers = args.workers or min(os.cpu_count() or 1, MAX_RUN_WORKERS,
                                  -(-n // (STREAM_WINDOW - 1)))  # no idle threads
    stats = stream_run(robot, traj, args.out, metadata=metadata, timings=timings,
                       workers=workers,
                       progress=_progress("solving", n >= 500 and not args.quiet),
                       wrist_margin=args.wrist_margin,
                       singularity_margin=args.singularity_margin, loads=args.loads)
    wall, write = timings["wall"], timings["write"]
    text = summary(stats) + (
        f"\nsolved and written in {wall:.3f} s ({1e6 * wall / n:.2f} µs/sample; model loading "
        f"and imports not included): {workers} solver thread(s), writing {write:.3f} s "
        f"({1e6 * write / n:.2f} µs/sample) in the main thread meanwhile")
    print(text, file=sys.stderr if args.out == STDOUT else sys.stdout)
    _wrote(args.out, f" ({stats.samples} rows)")
    from .timing import peak_memory_mb

    log.info("peak resident memory %s MB", _fmt_mb(peak_memory_mb()))
    return 0


def _fmt_mb(mb: float | None) -> str:
    return "unknown" if mb is None else f"{mb:.0f}"


def cmd_sweep(args) -> int:
    from .sweep import load_grid, run_sweep, summary, write_csv

    check_destination(args.out)
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
    print(summary(rows), file=sys.stderr if args.out == STDOUT else sys.stdout)
    _wrote(args.out, f" ({len(rows)} rows, wall time {wall:.2f} s)")
    return 0


def cmd_view(args) -> int:
    from .viz import viewer

    if args.html:
        check_destination(args.html)
    robot, result = _solve(args, dynamics=False)
    if args.html:
        path = viewer.write_html(args.html, robot, result.ik, frames=args.frames, fps=args.fps)
        if args.html != STDOUT:
            print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB, {len(result.ik)} samples,"
                  f" {result.ik.t[-1] - result.ik.t[0]:.4g} s): open it in a browser, no server "
                  "needed; Open Controls → Animations to play and scrub", file=sys.stderr)
        return 0
    viewer.serve(robot, result.ik, frames=args.frames, fps=args.fps)
    return 0


def _simulation_table(path):
    """The columns and metadata of a ``simulate`` table (one-line error otherwise)."""
    from .io.table import read_result
    from .viz.simulation import check_simulation_columns

    table = read_result(path)
    check_simulation_columns(table.columns, str(path))
    return table


def cmd_plot(args) -> int:
    from .viz.plots import write_figures

    check_destination(args.out, folder=True)
    if args.simulation:  # the simulation's figures only (docs/model.md §18)
        from .viz.simulation import write_simulation_figures

        table = _simulation_table(args.simulation)
        name = f"{table.metadata.get('controller', 'simulation')}, {Path(args.simulation).name}"
        for path in write_simulation_figures(table.columns, args.out, dpi=args.dpi, name=name):
            print(f"wrote {path}")
        return 0
    _, result = _solve(args, loads=True)  # joint-loads figure, docs/model.md §17
    for path in write_figures(result, args.out, dpi=args.dpi):
        print(f"wrote {path}")
    return 0


def cmd_report(args) -> int:
    from .viz.report import report, to_json, to_markdown

    out = args.out or STDOUT
    check_destination(out)
    table = _simulation_table(args.simulation) if args.simulation else None
    robot, result = _solve(args)
    rep = report(robot, result, cross_check=not args.no_cross_check)
    if table is not None:
        from .viz.simulation import simulation_summary

        rep["simulation"] = simulation_summary(table.columns, table.metadata)
    text = to_json(rep) + "\n" if args.format == "json" else to_markdown(rep)
    with atomic_open(out) as f:
        f.write(text)
    _wrote(out)
    return 0


def cmd_size(args) -> int:
    from .dynamics.actuators import load_actuators
    from .io.trajectory import to_csv
    from .viz.sizing import actuator_sizing, to_json, to_markdown, write_torque_speed

    out = args.out or STDOUT
    if args.retime == STDOUT and out == STDOUT:
        raise _UsageError("--retime - and the report both on standard output: give --out FILE "
                          "or --retime FILE.csv")
    for path in (out, args.retime):
        if path is not None:
            check_destination(path)
    if args.plot is not None:
        check_destination(args.plot, folder=True)
    actuators = load_actuators(args.actuators)
    robot, result = _solve(args)
    t0 = time.perf_counter()
    sized = actuator_sizing(robot, result, actuators)
    log.info("sized in %.3f s (TOPP-RA solves: %d)", time.perf_counter() - t0,
             sized.timing.iterations)
    if args.retime is not None:
        to_csv(sized.retimed, args.retime)
        _wrote(args.retime, f" (time-optimal, {sized.timing.duration:.4g} s, "
                            f"{len(sized.retimed)} rows)")
    if args.plot is not None:
        _wrote(write_torque_speed(sized, args.plot))
    text = to_json(sized.report) + "\n" if args.format == "json" else to_markdown(sized.report)
    with atomic_open(out) as f:
        f.write(text)
    _wrote(out)
    return 0


def cmd_export(args) -> int:
    check_destination(args.out)
    from .io.mjcf import export_mjcf

    robot = _robot(args)
    path = export_mjcf(args.out, urdf=robot.urdf)
    _wrote(path, f" (MJCF: {len(robot.joint_names)} joints, {len(robot.closures)} connect "
                 "equalities)")
    return 0


def cmd_simulate(args) -> int:
    import numpy as np

    from .dynamics.control import Gains, MeasurementNoise, simulate_tracking
    from .dynamics.inverse import JointLosses
    from .dynamics.plant import PlantErrors
    from .io.table import write_table

    check_destination(args.out)
    gains = Gains(args.wn, args.zeta)
    noise = (MeasurementNoise(args.noise, args.velocity_noise, args.seed)
             if args.noise or args.velocity_noise else None)
    if args.torque_limit is not None and len(args.torque_limit) not in (1, 6):
        raise _UsageError(f"--torque-limit takes 1 value (all actuators) or 6, got "
                          f"{len(args.torque_limit)}")
    robot = _robot(args)
    losses = known = None
    limit = args.torque_limit
    if args.actuators:  # motors known to the controller (docs/model.md §18, §19)
        from .dynamics.actuators import load_actuators

        if args.armature or args.viscous or args.coulomb:
            raise _UsageError("--actuators gives the rotor inertia and friction; do not "
                              "combine it with --armature/--viscous/--coulomb")
        motors = load_actuators(args.actuators)
        losses = known = motors.joint_losses(robot.joint_names)
        if limit is None:
            limit = motors.column("gear_ratio") * motors.column("peak_torque")
    elif args.armature or args.viscous or args.coulomb:  # on the six actuated joints
        per_joint = {}
        for name, value in (("armature", args.armature), ("viscous", args.viscous),
                            ("coulomb", args.coulomb)):
            per_joint[name] = np.zeros(robot.model.nv)
            per_joint[name][robot.actuated_v] = value
        losses = JointLosses(**per_joint)
    errors = PlantErrors(args.payload, args.mass_error, losses)
    traj = _load_trajectory(args, robot.params)
    start = None if args.start == "path" else robot.home()
    t0 = time.perf_counter()
    result = simulate_tracking(
        robot, traj, args.controller, errors, gains=gains, dt=args.dt,
        control_period=args.control_period, torque_limit=limit, noise=noise,
        start=start, known_losses=known, progress=_progress("simulating", len(traj) >= 500 and not args.quiet))
    wall = time.perf_counter() - t0
    meta = {"command": "simulate", "trajectory": traj.name, "actuators": args.actuators,
            "armature": args.armature, "viscous": args.viscous, "coulomb": args.coulomb,
            **result.settings,
            "summary": result.summary()}
    rows = write_table(args.out, result.columns(), metadata=meta)
    lines = [f"{args.controller} on {traj.name}: {len(traj)} samples over "
             f"{traj.t[-1] - traj.t[0]:.4g} s, dt {args.dt:g} s, control period "
             f"{args.control_period:g} s, ω {args.wn:g} rad/s, ζ {args.zeta:g}",
             *result.summary_lines(), f"wall time {wall:.2f} s (desired trajectory included)"]
    print("\n".join(lines), file=sys.stderr if args.out == STDOUT else sys.stdout)
    _wrote(args.out, f" ({rows} rows)")
    return 0


MAX_RUN_WORKERS = 4  # run: solver threads by default (each holds one window in memory)
STREAM_WINDOW = 4096  # = pollard_pin.run.STREAM_CHUNK (not imported: --help stays fast)


class _UsageError(ValueError):
    """A command-line value the command cannot use (one line)."""


# --- parser ---------------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    from .kinematics.singularity import SINGULARITY_MARGIN, WRIST_MARGIN

    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-v", "--verbose", action="count", default=argparse.SUPPRESS,
                        help="log what happens (-vv: debug)")
    ap = _Parser(prog="pollard-pin", description=DESCRIPTION, formatter_class=_Help)
    ap.add_argument("--version", action="version", version=f"pollard-pin {__version__}")
    ap.add_argument("-v", "--verbose", action="count", default=0,
                    help="log what happens (-vv: debug)")
    sub = ap.add_subparsers(dest="command", required=True, metavar="COMMAND",
                            parser_class=_Parser)

    def command(name, help, func):
        p = sub.add_parser(name, help=help, description=help, parents=[common],
                           formatter_class=_Help)
        p.set_defaults(func=func)
        return p

    def model_args(p):
        p.add_argument("--params", metavar="FILE.toml", default=None,
                       help="parameter file; may list only the values that differ from the "
                            "shipped models/pollard.toml (default: the shipped parameters)")
        p.add_argument("--set", metavar="KEY=VALUE", action="append", default=[],
                       help="override one parameter, e.g. chain0.x32=0.35 (repeatable; "
                            "units as in the parameter file; default: none)")

    def trajectory_args(p):
        model_args(p)
        p.add_argument("--trajectory", metavar="thesis|FILE.csv", default="thesis",
                       help="the thesis painting curve or a trajectory CSV")
        p.add_argument("--duration", type=_positive, default=None, metavar="S",
                       help="thesis trajectory duration [s] (default: 20)")
        p.add_argument("--samples", type=_count(2), default=None, metavar="N",
                       help="thesis trajectory samples (default: 2001)")
        p.add_argument("--quiet", action="store_true", help="no progress bar")

    p = command("urdf", "generate the URDF (and the SRDF beside it) from parameters", cmd_urdf)
    model_args(p)
    p.add_argument("--out", default="pollard.urdf", metavar="FILE.urdf",
                   help="output URDF ('-': the URDF on standard output); the shipped "
                        "model is regenerated with --out models/pollard.urdf")

    p = command("info", "load the model and print home configuration and masses", cmd_info)
    model_args(p)

    p = command("run", "solve a trajectory: kinematics and dynamics → CSV or Parquet", cmd_run)
    trajectory_args(p)
    p.add_argument("--out", default="run.csv", metavar="FILE.csv|FILE.parquet",
                   help="output table: CSV with a NAME.units.json sidecar, or Parquet (zstd, "
                        "units and metadata inside) for a .parquet name; '-': CSV on standard "
                        "output")
    p.add_argument("--wrist-margin", type=_nonnegative, default=WRIST_MARGIN,
                   help="fail where |sin θ1716| drops below this")
    p.add_argument("--singularity-margin", type=_nonnegative, default=SINGULARITY_MARGIN,
                   help="fail where the parallel or serial σ_min drops below this")
    p.add_argument("--loads", action="store_true",
                   help="also write the load of every tree joint: F_<joint>_x/y/z [N] and "
                        "M_<joint>_x/y/z [N·m], world axes (docs/model.md §17)")
    p.add_argument("--workers", type=_count(1, 64), default=None,
                   help=f"solver threads, one window of {STREAM_WINDOW} samples each (default: "
                        f"the cores, at most {MAX_RUN_WORKERS}; 1 = no threads)")

    p = command("sweep", "design sweep: parameter variants over a trajectory → CSV", cmd_sweep)
    p.add_argument("--grid", required=True, metavar="FILE.toml",
                   help="grid file (see examples/sweep.toml)")
    p.add_argument("--out", default="sweep.csv", metavar="FILE.csv",
                   help="output CSV ('-': standard output)")
    p.add_argument("--workers", type=_count(1), default=None,
                   help="local processes (1 = serial; default: all cores)")
    p.add_argument("--dask", metavar="ADDRESS", default=None,
                   help="run on this Dask scheduler (needs pollard-pin[cluster]; default: "
                        "local processes)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")

    p = command("view", "MeshCat 3D viewer: live on localhost, or --html FILE", cmd_view)
    trajectory_args(p)
    p.add_argument("--html", metavar="FILE", default=None,
                   help="write a self-contained static page instead of serving (default: "
                        "serve on localhost)")
    p.add_argument("--frames", action="store_true", help="also draw the tool and platform frames")
    p.add_argument("--fps", type=_positive, default=25.0,
                   help="animation key frames per second of trajectory time")

    p = command("plot", "chapter-4 style PNG figures of a trajectory", cmd_plot)
    trajectory_args(p)
    p.add_argument("--out", default="plots", metavar="FOLDER", help="output folder")
    p.add_argument("--dpi", type=_count(10, 1200), default=100, help="PNG resolution")
    p.add_argument("--simulation", metavar="SIM.csv", default=None,
                   help="plot this closed-loop simulation (pollard-pin simulate) instead: "
                        "tracking errors, torques, desired vs actual path (default: plot the "
                        "trajectory)")

    p = command("report", "actuator sizing table and engine cross-checks", cmd_report)
    trajectory_args(p)
    p.add_argument("--format", choices=("md", "json"), default="md", help="output format")
    p.add_argument("--out", metavar="FILE", default=None,
                   help="write to this file (default: standard output)")
    p.add_argument("--no-cross-check", action="store_true",
                   help="sizing only: skip the thesis and MuJoCo comparisons")
    p.add_argument("--simulation", metavar="SIM.csv", default=None,
                   help="add this closed-loop simulation's tracking errors and torques "
                        "(pollard-pin simulate; default: none)")

    p = command("size", "motors and gearboxes: ratings check, shortest uniform and "
                "time-optimal cycle of the path", cmd_size)
    trajectory_args(p)
    p.add_argument("--actuators", required=True, metavar="FILE.toml",
                   help="one table per actuator (see examples/actuators.toml)")
    p.add_argument("--format", choices=("md", "json"), default="md", help="output format")
    p.add_argument("--out", metavar="FILE", default=None,
                   help="write the table to this file (default: standard output)")
    p.add_argument("--retime", metavar="OUT.csv", default=None,
                   help="write the time-optimal traversal as a trajectory CSV (replay it with "
                        "run --trajectory OUT.csv; default: not written)")
    p.add_argument("--plot", metavar="FOLDER", default=None,
                   help="write FOLDER/torque_speed.png, the motors' operating points and "
                        "ratings (default: no figure)")

    p = command("simulate", "closed-loop simulation: a controller tracking a trajectory on a "
                "(perturbed) plant → CSV or Parquet", cmd_simulate)
    trajectory_args(p)
    p.add_argument("--controller", choices=("computed-torque", "pd"), default="computed-torque",
                   help="computed-torque (nominal feedforward + inertia-scaled PD) or pd (PD + "
                        "gravity compensation)")
    p.add_argument("--wn", type=_nonnegative, default=60.0, metavar="RAD/S",
                   help="natural frequency ω of the actuator error dynamics")
    p.add_argument("--zeta", type=_nonnegative, default=1.0, metavar="Z",
                   help="damping ratio ζ of the actuator error dynamics")
    p.add_argument("--dt", type=_positive, default=1e-3, metavar="S", help="RK4 step")
    p.add_argument("--control-period", type=_positive, default=1e-3, metavar="S",
                   help="controller period (torque held in between)")
    p.add_argument("--torque-limit", type=_positive, nargs="+", default=None, metavar="N·M",
                   help="|τ| limit: one value for all actuators or six (default: none)")
    p.add_argument("--payload", type=_nonnegative, default=0.0, metavar="KG",
                   help="point mass at the tool tip, unknown to the controller (default: 0)")
    p.add_argument("--mass-error", type=_float, default=0.0, metavar="FRACTION",
                   help="plant link masses and inertias × (1 + FRACTION) (default: 0, exact)")
    p.add_argument("--actuators", metavar="FILE.toml", default=None,
                   help="motors and gearboxes (format of examples/actuators.toml): their "
                        "reflected rotor inertia N²·Jm and friction act in the plant and are "
                        "known to the controller; --torque-limit defaults to N × peak motor "
                        "torque (default: ideal joints)")
    p.add_argument("--armature", type=_nonnegative, default=0.0, metavar="KG·M²",
                   help="rotor inertia on each actuated joint (plant only; default: 0)")
    p.add_argument("--viscous", type=_nonnegative, default=0.0, metavar="N·M·S",
                   help="viscous friction on each actuated joint (plant only; default: 0)")
    p.add_argument("--coulomb", type=_nonnegative, default=0.0, metavar="N·M",
                   help="Coulomb friction on each actuated joint (plant only; default: 0)")
    p.add_argument("--noise", type=_nonnegative, default=0.0, metavar="RAD",
                   help="standard deviation of the measured actuator angles (default: 0, exact)")
    p.add_argument("--velocity-noise", type=_nonnegative, default=0.0, metavar="RAD/S",
                   help="standard deviation of the measured actuator rates (default: 0, exact)")
    p.add_argument("--seed", type=_count(0), default=0, help="noise seed (default: 0)")
    p.add_argument("--start", choices=("path", "home"), default="path",
                   help="plant start: on the path (the reference's first state) or at rest at "
                        "home (the trajectory must then start at the home pose, at rest)")
    p.add_argument("--out", default="sim.csv", metavar="FILE.csv|FILE.parquet",
                   help="output table ('-': CSV on standard output)")

    p = command("export", "write the model for another engine (MuJoCo MJCF)", cmd_export)
    model_args(p)
    p.add_argument("--format", choices=("mjcf",), default="mjcf", help="output format")
    p.add_argument("--out", default="pollard.xml", metavar="FILE",
                   help="output file ('-': standard output)")
    return ap


def _errors() -> tuple[type[BaseException], ...]:
    """The project's own errors: each is one line for the user, never a traceback."""
    from .dynamics.control import ControlError
    from .dynamics.forward import SimulationError
    from .dynamics.plant import PlantError
    from .dynamics.actuators import ActuatorError
    from .io.atomic import OutputError
    from .io.table import ResultFileError
    from .io.trajectory import TrajectoryError
    from .kinematics.errors import ClosureError, KinematicsError
    from .model.build import ModelFileError
    from .model.params import ParameterError
    from .sweep import SweepError

    return (ControlError, PlantError, SimulationError,
            ParameterError, TrajectoryError, KinematicsError, ClosureError, ModelFileError,
            SweepError, OutputError, _UsageError, ImportError, ActuatorError, ResultFileError)


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    logging.basicConfig(level=logging.WARNING - 10 * min(args.verbose, 2),
                        format="%(levelname)s %(name)s: %(message)s", stream=sys.stderr)
    errors = _errors()
    previous = _catch_sigterm()
    try:
        return args.func(args)
    except errors as exc:
        message = " ".join(str(exc).split()) or type(exc).__name__
        out = getattr(args, "out", None) or getattr(args, "html", None)
        if out and out != STDOUT and args.command != "plot":
            message += f" (nothing written to {out})"
        print(f"pollard-pin {args.command}: error: {message}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        how = "terminated" if isinstance(exc, _Terminated) else "interrupted"
        print(f"pollard-pin {args.command}: {how}, nothing written", file=sys.stderr)
        return 143 if isinstance(exc, _Terminated) else 130
    except OSError as exc:
        if not _broken_pipe(exc):
            raise
        # The reader of standard output or of a FIFO stopped (`run --out - | head`): stop
        # quietly like any Unix filter, 128 + SIGPIPE, with no flush error at exit.
        with contextlib.suppress(OSError, ValueError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


class _Terminated(KeyboardInterrupt):
    """SIGTERM (kill, a scheduler's time limit) raised like Ctrl-C, so that the temporary
    output files are removed; Python's default would end the process on the spot."""


def _catch_sigterm():
    """Turn SIGTERM into :class:`_Terminated` (main thread only); the previous handler."""
    if threading.current_thread() is not threading.main_thread():
        return None

    def terminate(signum, frame):
        raise _Terminated

    return signal.signal(signal.SIGTERM, terminate)


def _broken_pipe(exc: OSError) -> bool:
    """EPIPE, from Python or from polars' writer (a plain OSError naming the Rust os error)."""
    return (isinstance(exc, BrokenPipeError) or exc.errno == errno.EPIPE
            or f"(os error {errno.EPIPE})" in str(exc))


if __name__ == "__main__":
    sys.exit(main())
