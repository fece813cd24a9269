"""Make a custom painting path: a figure eight on the wall, with the gun nodding as it goes.

    .venv/bin/python examples/make_trajectory.py [--out-dir examples]

Writes two trajectory CSVs of the same path, the input format of ``pollard-pin run``:

* ``figure8.csv``: ``t,x,y,z,psi,theta,phi`` and their exact rates ``d_*`` and accelerations
  ``dd_*`` (s, m, rad, rad/s, rad/s²), all at full float64 precision;
* ``figure8_poses.csv``: the poses only (to the nm / nrad), as a CAM program or a measured
  path would give them; the command then takes the derivatives from a quintic spline through
  the samples and says so.

Then: ``pollard-pin run --trajectory examples/figure8.csv`` (or ``view``, ``plot``,
``report``). Poses follow docs/model.md §2: tip at (x, y, z), R = Rx(θ) Ry(ψ) Rz(φ).
"""
import argparse
from pathlib import Path

import numpy as np

import pollard_pin as pp

HOME = np.array([0.55, 0.0, 0.16, 0.0, 0.0, 0.0])  # the home tool pose, docs/model.md §9


def figure_eight(t, period=6.0, width=0.08, height=0.04, nod=0.1):
    """Poses, rates and accelerations (each (N, 6)) of a lemniscate of Gerono in the wall
    plane x = 0.55 m, with the gun pitching (ψ) by ±``nod`` rad in step with the height."""
    w = 2 * np.pi / period
    s, c = np.sin(w * t), np.cos(w * t)
    s2, c2 = np.sin(2 * w * t), np.cos(2 * w * t)
    zero = np.zeros_like(t)
    # y = W sin ωt, z = H sin 2ωt / 2 (the eight), ψ = nod · sin 2ωt
    pose = np.column_stack([zero, width * s, height * s2 / 2, nod * s2, zero, zero]) + HOME
    rate = np.column_stack([zero, width * w * c, height * w * c2, 2 * nod * w * c2, zero, zero])
    acc = np.column_stack([zero, -width * w**2 * s, -2 * height * w**2 * s2,
                           -4 * nod * w**2 * s2, zero, zero])
    return pose, rate, acc


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", default=str(Path(__file__).resolve().parent),
                    help="folder for figure8.csv and figure8_poses.csv")
    args = ap.parse_args()
    out = Path(args.out_dir)
    t = np.linspace(0.0, 6.0, 301)
    traj = pp.Trajectory(t, *figure_eight(t), name="figure8", derivatives="analytic")
    pp.to_csv(traj, out / "figure8.csv")
    names = ("t", "x", "y", "z", "psi", "theta", "phi")
    np.savetxt(out / "figure8_poses.csv", np.column_stack([t, traj.poses]), delimiter=",",
               header=",".join(names), comments="", fmt="%.9f")
    print(f"wrote {out / 'figure8.csv'} and {out / 'figure8_poses.csv'} ({len(t)} samples)")


if __name__ == "__main__":
    main()
