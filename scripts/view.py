"""Look at the robot moving along a trajectory in MeshCat.

    .venv/bin/python scripts/view.py                      # static page pollard.html
    .venv/bin/python scripts/view.py --live               # MeshCat server on localhost

The static page is self-contained: open it in any browser, no server needed. In both cases
use "Open Controls" → Animations → play / pause / time to scrub.
"""
import argparse

import pollard_pin as pp
from pollard_pin.viz.viewer import serve


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trajectory", default="thesis", help="'thesis' or a CSV file")
    ap.add_argument("--html", default="pollard.html")
    ap.add_argument("--live", action="store_true", help="serve on localhost until Ctrl-C")
    args = ap.parse_args()

    robot = pp.load()
    traj = pp.thesis_trajectory() if args.trajectory == "thesis" else pp.from_csv(args.trajectory)
    ik = pp.run_pipeline(robot, traj, dynamics=False).ik
    if args.live:
        serve(robot, ik, frames=True)  # prints the URL, serves until interrupted
    else:
        path = pp.write_html(args.html, robot, ik, frames=True)
        print(f"wrote {path}: open it in a browser")


if __name__ == "__main__":
    main()
