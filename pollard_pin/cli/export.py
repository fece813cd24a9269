"""pollard-pin export: the model for another engine (MJCF)."""
from __future__ import annotations

from ..io.atomic import check_outputs
from .common import command, load_robot, model_args, name, refuse_inputs, wrote


def run(args) -> int:
    check_outputs(args.out)
    refuse_inputs(args, args.out)
    from ..io.mjcf import export_mjcf

    robot = load_robot(args)
    path = export_mjcf(args.out, urdf=robot.urdf)
    wrote(path, f" (MJCF: {len(robot.joint_names)} joints, {len(robot.closures)} connect "
                 "equalities)")
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "export", "write the model for another engine (MuJoCo MJCF)", run)
    model_args(p)
    p.add_argument("--format", choices=("mjcf",), default="mjcf", help="output format")
    p.add_argument("--out", type=name, default="pollard.xml", metavar="FILE",
                   help="output file ('-': standard output)")
