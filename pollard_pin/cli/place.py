"""pollard-pin place: where a part fits the reach (pollard_pin.painting.layout.place)."""
from __future__ import annotations

from .common import command, load_robot, model_args, name, nonnegative, positive, wrote


def run(args) -> int:
    from ..errors import InputError
    from ..io.atomic import check_outputs
    from ..painting.job import PartJob, load_job
    from ..painting.layout.place import PlaceOptions, place
    from .common import UsageError, refuse_inputs

    check_outputs(args.out)
    job = load_job(args.job)
    if not isinstance(job, PartJob):
        raise UsageError(f"--job {args.job}: a [panel] job; place moves a [part]'s mesh")
    refuse_inputs(args, args.out, also=[("the job", args.job), ("the mesh", job.mesh)])
    try:
        opts = PlaceOptions(step=args.step, max_turn=args.max_turn)
    except InputError as exc:  # the library names the option; the user typed the flag
        flag = "--step" if ".step" in str(exc) else "--max-turn"
        raise UsageError(f"{flag}: {str(exc).split(' = ', 1)[1]}") from None
    result = place(load_robot(args), job, opts)
    written = result.write(args.out) if args.out else None  # all of it, before the summary
    p, r = result.job.position, result.job.rotation
    print(f"position [{p[0]:.4f}, {p[1]:.4f}, {p[2]:.4f}] m, rotation [{r[0]:.4g}, "
          f"{r[1]:.4g}, {r[2]:.4g}] deg (turned {result.turn:+.0f}° about the facing axis); "
          f"margin {result.margin * 1e3:.0f} mm along every axis ({result.poses} gun poses)")
    if written is not None:
        wrote(written)
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "place", "find where a part's mesh fits the reach: the position "
                "(and turn about its facing axis) with the most margin", run)
    model_args(p)
    p.add_argument("--job", type=name, required=True, metavar="JOB.toml",
                   help="a paint job with a [part] (examples/parts/*.toml)")
    p.add_argument("--out", type=name, default=None, metavar="JOB2.toml",
                   help="write the job with that placement (default: print it only)")
    p.add_argument("--max-turn", type=nonnegative, default=90.0, metavar="DEG",
                   help="turns about the facing axis tried, every 30° up to this (0: the "
                        "job's orientation only)")
    p.add_argument("--step", type=positive, default=0.02, metavar="M",
                   help="coarse grid of positions [m] (refined to an eighth of it)")
