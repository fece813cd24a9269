"""pollard-pin view: the MeshCat viewer."""
from __future__ import annotations

import sys
from pathlib import Path

from ..io.atomic import check_outputs
from .common import (
    STDOUT,
    UsageError,
    command,
    name,
    positive,
    refuse_inputs,
    say_notes,
    solve,
    trajectory_args,
)


def _inputs(args) -> list:
    """(what, path) of the files ``view`` reads besides the shared options' (the paint
    folder's, the workspace map's): never one of its outputs."""
    from ..outputs.folder import cell_inputs, paint_inputs

    files = []
    if args.paint is not None:
        files += paint_inputs(args.paint) + cell_inputs(args.paint)
    if args.workspace is not None:
        files += [(f"the workspace map's {n}", Path(args.workspace) / n)
                  for n in ("workspace.csv", "workspace.units.json", "workspace.parquet")]
    return files


def run(args) -> int:
    from ..viz import viewer

    if args.html:
        check_outputs(args.html)
        refuse_inputs(args, args.html, also=_inputs(args))
    overlay = None
    if args.paint is not None:
        from ..outputs.folder import is_cell
        from .view_cell import view_cell
        from .view_paint import paint_overlay

        if args.trajectory != "thesis":
            raise UsageError("--paint DIR shows DIR/path.csv: give no --trajectory with it")
        if is_cell(Path(args.paint)):  # a cell: DIR/<name>/path.csv each
            return view_cell(args, None if args.workspace is None else
                             lambda paint: _with_workspace(paint, args.workspace))
        args.trajectory = str(Path(args.paint) / "path.csv")
        overlay = paint_overlay(Path(args.paint))
    if args.workspace is not None:  # read before solving: a bad folder fails at once
        overlay = _with_workspace(overlay, args.workspace)
    robot, result = solve(args, dynamics=False)
    try:
        viewer.check_frame_rate(result.ik.t, args.fps)
    except viewer.ViewerError as exc:
        raise UsageError(f"--fps {args.fps:g}: {exc}") from None
    if getattr(overlay, "view", None) is not None:  # from the gun's side, over the travel
        moving = getattr(overlay, "moving", None) or {}
        overlay.view = overlay.view.seen_from(result.ik.poses[:, :3], result.ik.t,
                                              next(iter(moving.values()), None))
    if args.html:
        path = viewer.write_html(args.html, robot, result.ik, frames=args.frames, fps=args.fps,
                                 overlay=overlay)
        if args.html != STDOUT:
            print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB, {len(result.ik)} samples,"
                  f" {result.ik.t[-1] - result.ik.t[0]:.4g} s): open it in a browser, no server "
                  "needed; Open Controls → Animations to play and scrub", file=sys.stderr)
        return 0
    say_notes(args)  # serving lasts until interrupted
    if getattr(overlay, "view", None) is not None:  # the live page has no legend
        print(f"film colours: {overlay.view.scale}, blue thin, white on target, red thick",
              file=sys.stderr)
    viewer.serve(robot, result.ik, frames=args.frames, fps=args.fps, overlay=overlay)
    return 0


def _with_workspace(paint, folder):
    """The overlay drawing the film ``paint`` (or None) and the workspace map's points; the
    film's moving nodes and view kept."""
    from ..viz.viewer import point_cloud
    from ..viz.workspace import workspace_cloud

    cloud = workspace_cloud(folder)

    def overlay(vis):
        if paint is not None:
            paint(vis)
        point_cloud(vis, *cloud)

    overlay.moving = getattr(paint, "moving", None)
    overlay.view = getattr(paint, "view", None)
    return overlay


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "view", "MeshCat 3D viewer: live on localhost, or --html FILE", run)
    trajectory_args(p)
    p.add_argument("--html", type=name, metavar="FILE", default=None,
                   help="write a self-contained static page instead of serving (default: "
                        "serve on localhost)")
    p.add_argument("--frames", action="store_true", help="also draw the tool and platform frames")
    p.add_argument("--paint", type=name, metavar="DIR", default=None,
                   help="show a paint output folder (pollard-pin paint --out DIR): the robot "
                        "running DIR/path.csv (a cell: every robot at its base running "
                        "DIR/<name>/path.csv) and the panel or part coloured by film "
                        "thickness, framed by the default view, with the colour scale's "
                        "legend (default: no film)")
    p.add_argument("--workspace", type=name, metavar="DIR", default=None,
                   help="also draw the reachable points of a workspace map written by "
                        "pollard-pin workspace --out DIR (default: none)")
    p.add_argument("--fps", type=positive, default=25.0,
                   help="animation key frames per second of trajectory time (at least 1)")
