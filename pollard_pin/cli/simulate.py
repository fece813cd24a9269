"""pollard-pin simulate: closed-loop simulation."""
from __future__ import annotations

import sys
import time

from ..io.atomic import check_outputs
from .common import (
    STDOUT,
    UsageError,
    command,
    count,
    load_robot,
    load_trajectory,
    log,
    name,
    nonnegative,
    number,
    positive,
    progress,
    refuse_inputs,
    robot_for_trajectory,
    trajectory_args,
    wrote,
)


def run(args) -> int:
    from ..dynamics.control import Gains
    from ..dynamics.plant import ModelMismatch
    from ..dynamics.tracking import (
        MeasurementNoise,
        TrackingOptions,
        default_step,
        simulate_tracking,
        step_used,
    )
    from ..io.table import table_files, write_table

    check_outputs(*table_files(args.out))  # the table and its units sidecar
    refuse_inputs(args, *table_files(args.out))
    if args.flexible and not args.actuators:
        raise UsageError("--flexible needs --actuators FILE.toml with a 'stiffness' [N·m/rad] "
                         "per actuator: the drives' springs (docs/model.md §28)")
    given_dt = args.dt
    if args.dt is None:
        args.dt = default_step(args.control_period)
    elif args.dt > args.control_period:
        raise UsageError(f"--dt {args.dt:g} s is longer than --control-period "
                         f"{args.control_period:g} s: each control period is integrated in "
                         "RK4 steps of at most --dt; give --dt <= --control-period")
    gains = Gains(args.wn, args.zeta)
    noise = (MeasurementNoise(args.noise, args.velocity_noise, args.seed)
             if args.noise or args.velocity_noise else None)
    if args.torque_limit is not None and len(args.torque_limit) not in (1, 6):
        raise UsageError(f"--torque-limit takes 1 value (all actuators) or 6, got "
                          f"{len(args.torque_limit)}")
    robot = load_robot(args)
    losses, known, limit, motors = _losses(args, robot)
    drives = None
    if args.flexible:  # the motors' inertia and friction are the drives' (docs/model.md §28)
        drives, losses = _drives(motors, args.flexible), None
    errors = ModelMismatch(args.payload, args.mass_error, losses)
    traj = load_trajectory(args, robot.params)
    robot = robot_for_trajectory(args, robot)
    if drives is not None:
        args.dt = _flexible_step(robot, traj, drives, errors, args, given_dt)
    start = None if args.start == "path" else robot.home()
    duration = float(traj.t[-1] - traj.t[0])
    banner = _budget(args, duration)
    log.info(banner)
    t0 = time.perf_counter()
    result = simulate_tracking(robot, traj, TrackingOptions(
        controller=args.controller, errors=errors, gains=gains, dt=args.dt,
        control_period=args.control_period, torque_limit=limit, noise=noise,
        start=start, known_losses=known, joint_limits=not args.ignore_limits,
        progress=progress(banner, not args.quiet), drives=drives))
    wall = time.perf_counter() - t0
    meta = {"command": "simulate", "trajectory": traj.name, "actuators": args.actuators,
            "flexible": args.flexible,
            "gravity": [float(c) for c in robot.model.gravity.linear],
            "armature": args.armature, "viscous": args.viscous, "coulomb": args.coulomb,
            **result.settings,
            "summary": result.summary()}
    rows = write_table(args.out, result.columns(), metadata=meta)
    lines = [f"{args.controller} on {traj.name}: {len(traj)} samples over "
             f"{duration:.4g} s, RK4 step {step_used(args.dt, args.control_period):g} s, "
             "control period "
             f"{args.control_period:g} s, ω {args.wn:g} rad/s, ζ {args.zeta:g}",
             *_drive_line(result.settings.get("drives")), *result.summary_lines(),
             f"wall time {wall:.2f} s (desired trajectory included)"]
    print("\n".join(lines), file=sys.stderr if args.out == STDOUT else sys.stdout)
    wrote(args.out, f" ({rows} rows)")
    return 0


def _losses(args, robot):
    """(plant losses, losses the controller knows, torque limit) of --actuators or
    --armature/--viscous/--coulomb (docs/model.md §18, §19)."""
    import numpy as np

    from ..dynamics.inverse import JointLosses

    losses = known = motors = None
    limit = args.torque_limit
    if args.actuators:  # motors known to the controller
        from ..dynamics.motors import load_actuators

        if args.armature or args.viscous or args.coulomb:
            raise UsageError("--actuators gives the rotor inertia and friction; do not "
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
    return losses, known, limit, motors


def _drive_line(drives: dict | None) -> list[str]:
    if drives is None:
        return []
    return [f"flexible drives (springs {'known' if drives['known'] else 'unknown'} to the "
            f"controller): fastest mode {drives['fastest_mode_hz']:.4g} Hz"]


def _drives(motors, which: str):
    """The flexible drives of the actuator file (its stiffness required); ``which``: 'known'
    (the controller tracks the motors' reference) or 'unknown' (the rigid one)."""
    from ..dynamics.drives.flexible import FlexibleDrives

    return FlexibleDrives.from_actuators(motors, known=which == "known")


def _flexible_step(robot, traj, drives, errors, args, given_dt) -> float:
    """The RK4 step that resolves the drives' fastest mode over up to 17 of the trajectory's
    poses (docs/model.md §28), or ``given_dt`` checked against it."""
    import numpy as np

    from ..dynamics.drives.flexible import FlexiblePlant, flexible_step, mode_configurations
    from ..dynamics.tracking import default_step
    from ..kinematics.ik import inverse_kinematics

    idx = mode_configurations(np.arange(len(traj.t)))
    ik = inverse_kinematics(robot, traj.poses[idx], traj.d_poses[idx], traj.dd_poses[idx],
                            traj.t[idx])
    step, _ = flexible_step(FlexiblePlant(robot, errors, drives), ik.q,
                            default_step(args.control_period), given_dt)
    return step


def _budget(args, duration: float) -> str:
    """Refuse a run the controller cannot act in or that is over the step budget (without
    --force) or over what memory holds; the banner of a run that starts."""
    from ..dynamics.tracking import MAX_STEPS, estimated_wall, integration_steps

    if args.control_period > duration:
        raise UsageError(f"--control-period {args.control_period:g} s is longer than the "
                         f"trajectory ({duration:.6g} s): the controller would act once, at the "
                         f"start; give --control-period <= {duration:.6g}")
    steps = integration_steps(duration, args.dt, args.control_period)
    guess = estimated_wall(duration, args.dt, args.control_period)
    what = (f"{_count(steps)} RK4 steps ({duration:g} s, --control-period "
            f"{args.control_period:g} s, --dt {args.dt:g} s)")
    if steps > MAX_STEPS:
        raise UsageError(f"{what}: more than a simulation can hold ({MAX_STEPS:.3g}), even "
                         "with --force; give a longer --control-period or --dt")
    if steps > STEP_BUDGET and not args.force:
        raise UsageError(
            f"{what} would take about {_duration(guess)}, over the budget of {STEP_BUDGET:,} "
            "steps: give --force to run it anyway, or a longer --control-period or --dt")
    # said beside the bar, on a terminal only: an error is then the only line
    return f"simulating {duration:g} s: {_count(steps)} RK4 steps, about {_duration(guess)}"


STEP_BUDGET = 500_000  # RK4 steps a run may take without --force (25 × the default run)


def _count(n: int) -> str:
    """'220,000' or, past a thousand billion, '2.2e+299' (not 300 digits)."""
    return f"{n:,}" if n < 10 ** 12 else f"{n:.3g}"


def _duration(seconds: float) -> str:
    """'40 s', '12 min', '3.2 h': a rough wall time for the user."""
    if seconds < 120:
        return f"{seconds:.2g} s"
    return f"{seconds / 60:.3g} min" if seconds < 7200 else f"{seconds / 3600:.3g} h"


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "simulate", "closed-loop simulation: a controller tracking a "
                "trajectory on a (perturbed) plant → CSV or Parquet", run)
    trajectory_args(p)
    p.add_argument("--controller", choices=("computed-torque", "feedforward-pd", "pd"),
                   default="computed-torque",
                   help="computed-torque (the classical law at the measured state), "
                        "feedforward-pd (reference feedforward + inertia-scaled PD) or pd (PD + "
                        "gravity compensation); docs/model.md §18")
    p.add_argument("--wn", type=nonnegative, default=60.0, metavar="RAD/S",
                   help="natural frequency ω of the actuator error dynamics")
    p.add_argument("--zeta", type=nonnegative, default=1.0, metavar="Z",
                   help="damping ratio ζ of the actuator error dynamics")
    p.add_argument("--dt", type=positive, default=None, metavar="S",
                   help="longest RK4 step, at most --control-period (default: 0.001 or the "
                        "control period, the shorter)")
    p.add_argument("--control-period", type=positive, default=1e-3, metavar="S",
                   help="controller period, torque held in between (default: 0.001)")
    p.add_argument("--force", action="store_true",
                   help=f"run even past the budget of {STEP_BUDGET:,} RK4 steps (default: "
                        "refuse, with an estimate of the time)")
    p.add_argument("--torque-limit", type=positive, nargs="+", default=None, metavar="N·M",
                   help="|τ| limit: one value for all actuators or six (default: none)")
    p.add_argument("--payload", type=nonnegative, default=0.0, metavar="KG",
                   help="point mass at the tool tip, unknown to the controller (default: 0)")
    p.add_argument("--mass-error", type=number, default=0.0, metavar="FRACTION",
                   help="plant link masses and inertias × (1 + FRACTION) (default: 0, exact)")
    p.add_argument("--actuators", type=name, metavar="FILE.toml", default=None,
                   help="motors and gearboxes (format of examples/actuators.toml): their "
                        "reflected rotor inertia N²·Jm and friction act in the plant and are "
                        "known to the controller; --torque-limit defaults to N × peak motor "
                        "torque (default: ideal joints)")
    p.add_argument("--flexible", nargs="?", const="known", choices=("known", "unknown"),
                   default=None,
                   help="flexible drives: each motor (rotor inertia, friction) drives its joint "
                        "through a spring of the actuator file's 'stiffness'; the controller "
                        "reads the motors and knows the springs ('unknown': it tracks the "
                        "rigid reference); needs --actuators; docs/model.md §28 (default: rigid "
                        "drives)")
    p.add_argument("--armature", type=nonnegative, default=0.0, metavar="KG·M²",
                   help="rotor inertia on each actuated joint (plant only; default: 0)")
    p.add_argument("--viscous", type=nonnegative, default=0.0, metavar="N·M·S",
                   help="viscous friction on each actuated joint (plant only; default: 0)")
    p.add_argument("--coulomb", type=nonnegative, default=0.0, metavar="N·M",
                   help="Coulomb friction on each actuated joint (plant only; default: 0)")
    p.add_argument("--noise", type=nonnegative, default=0.0, metavar="RAD",
                   help="standard deviation of the measured actuator angles (default: 0, exact)")
    p.add_argument("--velocity-noise", type=nonnegative, default=0.0, metavar="RAD/S",
                   help="standard deviation of the measured actuator rates (default: 0, exact)")
    p.add_argument("--seed", type=count(0), default=0, help="noise seed (default: 0)")
    p.add_argument("--start", choices=("path", "home"), default="path",
                   help="plant start: on the path (the reference's first state) or at rest at "
                        "home (the trajectory must then start at the home pose, at rest)")
    p.add_argument("--out", type=name, default="sim.csv", metavar="FILE.csv|FILE.parquet",
                   help="output table ('-': CSV on standard output)")
