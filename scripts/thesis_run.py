"""Run the thesis painting trajectory (docs/model.md §9) and print the actuator sizing table.

    .venv/bin/python scripts/thesis_run.py [--out run.csv]

Public API only: load the model, build the trajectory, solve kinematics and dynamics, write
the same CSV as ``pollard-pin run`` and print the sizing report.
"""
import argparse

import pollard_pin as pp
from pollard_pin.viz import sizing_report
from pollard_pin.viz.report import to_markdown


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="run.csv")
    ap.add_argument("--samples", type=int, default=2001)
    args = ap.parse_args()

    robot = pp.load()  # models/pollard.urdf + pollard.srdf, docs/model.md §5 parameters
    traj = pp.thesis_trajectory(duration=20.0, samples=args.samples)
    result = pp.run_pipeline(robot, traj)  # constrained IK, then RNEA + closure forces
    pp.write_run_table(result, args.out)
    print(f"wrote {len(traj)} rows to {args.out}")

    dyn = result.dynamics
    print("peak |tau| per actuator [N·m]: "
          + ", ".join(f"{n} {abs(dyn.tau[:, i]).max():.4g}" for i, n in enumerate(robot.actuated)))
    print(to_markdown(sizing_report(robot, result, cross_check=False)))


if __name__ == "__main__":
    main()
