"""Cross-check one trajectory with three engines: Pinocchio (the model), the thesis' own
method (closed-form IK + task-space Euler–Lagrange, numpy only) and MuJoCo.

    .venv/bin/python scripts/cross_check.py [--trajectory thesis|FILE.csv]

Prints the largest differences in joint motion, actuator torques and closure forces.
"""
import argparse

import pollard_pin as pp
from pollard_pin.viz import sizing_report


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trajectory", default="thesis", help="'thesis' or a CSV file")
    args = ap.parse_args()

    robot = pp.load()
    traj = pp.thesis_trajectory() if args.trajectory == "thesis" else pp.from_csv(args.trajectory)
    result = pp.run_pipeline(robot, traj)
    cc = sizing_report(robot, result)["cross_check"]
    th, mj = cc["thesis"], cc["mujoco"]
    print(f"{traj.name}: {len(traj)} samples")
    print(f"Pinocchio vs thesis: joint angles {th['joint_position_rad']['max_abs_diff']:.2e} rad, "
          f"rates {th['joint_velocity']['max_abs_diff']:.2e} rad/s, "
          f"accelerations {th['joint_acceleration']['max_abs_diff']:.2e} rad/s², "
          f"torques {th['torque']['max_abs_diff']:.2e} N·m "
          f"(relative {th['torque']['relative']:.1e})")
    if mj["available"]:
        print(f"Pinocchio vs MuJoCo: torques {mj['torque']['max_abs_diff']:.2e} N·m "
              f"(relative {mj['torque']['relative']:.1e}), closure forces "
              f"{mj['closure_force']['max_abs_diff']:.2e} N "
              f"(relative {mj['closure_force']['relative']:.1e})")
    else:
        print(f"MuJoCo skipped: {mj['reason']}")


if __name__ == "__main__":
    main()
