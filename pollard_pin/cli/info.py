"""pollard-pin info: print the model's home configuration and masses."""
from __future__ import annotations

from .common import command, load_robot, model_args


def run(args) -> int:
    import numpy as np

    from ..model.build import constraint_residual

    robot = load_robot(args)
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


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "info", "load the model and print home configuration and masses", run)
    model_args(p)
