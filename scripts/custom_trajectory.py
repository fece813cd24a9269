"""A user trajectory from a CSV file: a circle painted on the wall in front of the robot.

    .venv/bin/python scripts/custom_trajectory.py [--csv circle.csv] [--out circle_run.csv]

Writes ``t,x,y,z,psi,theta,phi`` (s, m, rad), reads it back with ``pollard_pin.from_csv``
(derivatives from a quintic spline, since the file has no ``d_*``/``dd_*`` columns), solves it
and writes the run CSV. The same file works on the command line:
``pollard-pin run --trajectory circle.csv`` (or ``view``, ``plot``, ``report``).
"""
import argparse
import csv
import warnings

import numpy as np

import pollard_pin as pp


def write_circle(path, radius=0.06, period=8.0, samples=801, centre=(0.55, 0.0, 0.16)):
    t = np.linspace(0.0, period, samples)
    a = 2 * np.pi * t / period
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "x", "y", "z", "psi", "theta", "phi"])
        for tk, ak in zip(t, a):
            # The gun keeps spraying along +x (psi = theta = phi = 0) at the wall x = 0.55 m.
            w.writerow([f"{tk:.6f}", centre[0], f"{centre[1] + radius * np.cos(ak):.9f}",
                        f"{centre[2] + radius * np.sin(ak):.9f}", 0, 0, 0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csv", default="circle.csv", help="trajectory file to write and read")
    ap.add_argument("--out", default="circle_run.csv", help="run CSV")
    args = ap.parse_args()

    write_circle(args.csv)
    with warnings.catch_warnings():  # the spline note, printed below instead
        warnings.simplefilter("ignore", UserWarning)
        traj = pp.from_csv(args.csv)
    print(f"{args.csv}: {len(traj)} samples, derivatives from a {traj.derivatives}")
    robot = pp.load()
    result = pp.run_pipeline(robot, traj)
    pp.write_run_table(result, args.out)
    tau = result.dynamics.tau
    print(f"wrote {args.out}; peak |tau| {abs(tau).max(axis=0).round(4).tolist()} N·m "
          f"(order {', '.join(robot.actuated)})")
    print(f"wrist margin |sin θ1716| >= {result.ik.wrist_margin.min():.3f}, "
          f"max closure residual {result.ik.closure_residual.max():.2g} m")


if __name__ == "__main__":
    main()
