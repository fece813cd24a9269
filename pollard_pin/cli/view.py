"""pollard-pin view: the MeshCat viewer."""
from __future__ import annotations

import sys

from ..io.atomic import check_destination
from .common import STDOUT, UsageError, command, name, positive, say_notes, solve, trajectory_args


def run(args) -> int:
    from ..viz import viewer

    if args.html:
        check_destination(args.html)
    robot, result = solve(args, dynamics=False)
    try:
        viewer.check_frame_rate(result.ik.t, args.fps)
    except viewer.ViewerError as exc:
        raise UsageError(f"--fps {args.fps:g}: {exc}") from None
    if args.html:
        path = viewer.write_html(args.html, robot, result.ik, frames=args.frames, fps=args.fps)
        if args.html != STDOUT:
            print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB, {len(result.ik)} samples,"
                  f" {result.ik.t[-1] - result.ik.t[0]:.4g} s): open it in a browser, no server "
                  "needed; Open Controls → Animations to play and scrub", file=sys.stderr)
        return 0
    say_notes(args)  # serving lasts until interrupted
    viewer.serve(robot, result.ik, frames=args.frames, fps=args.fps)
    return 0


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "view", "MeshCat 3D viewer: live on localhost, or --html FILE", run)
    trajectory_args(p)
    p.add_argument("--html", type=name, metavar="FILE", default=None,
                   help="write a self-contained static page instead of serving (default: "
                        "serve on localhost)")
    p.add_argument("--frames", action="store_true", help="also draw the tool and platform frames")
    p.add_argument("--fps", type=positive, default=25.0,
                   help="animation key frames per second of trajectory time")
