"""``view --paint DIR`` of a paint cell (docs/model.md §26): DIR/paint.json names the robots
(``robots``: name, base, rotation) and each runs DIR/<name>/path.csv in its own base frame
on the cell's clock; every robot is drawn at its base, the film on the part riding the line.
The folder is read by :mod:`pollard_pin.outputs.folder`; here the robots' programs are solved
and the page written or served."""
from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from .common import STDOUT, UsageError, load_robot, say_notes, warnings_as_notes


def cell_members(args, folder: Path, cells, report):
    """The model and each robot's program solved (:class:`...viz.cell_view.CellMember`), the
    robots' files first checked against the ``report``'s robots."""
    from ..io.trajectory import from_csv
    from ..outputs.folder import check_robot_files, robot_paths
    from ..run import run_pipeline
    from ..viz.cell_view import CellMember
    from .view_paint import paint_flag

    robot = load_robot(args)
    members = []
    with paint_flag():
        paths = robot_paths(folder, cells)
        check_robot_files(folder, report, cells)
    for c, path in zip(cells, paths):
        with warnings_as_notes(args):
            traj = from_csv(path)
        ik = run_pipeline(robot, traj, dynamics=False, joint_limits=not args.ignore_limits).ik
        base = np.eye(4)
        base[:3, :3], base[:3, 3] = c.R, c.origin
        members.append(CellMember(c.name, base, ik))
    return robot, members


def view_cell(args, decorate=None) -> int:
    """``view --paint DIR`` for a cell; ``decorate(overlay)`` adds more drawing (the
    workspace map)."""
    from ..outputs.folder import cell_robots, read_report
    from ..viz import viewer
    from ..viz.cell_view import build_cell_scene, cell_key_samples, write_cell_html
    from .view_paint import paint_overlay

    folder = Path(args.paint)
    report = read_report(folder)
    cells = cell_robots(folder, report)
    overlay = paint_overlay(folder, f"{cells[0].name}/path.csv")
    if decorate is not None:
        overlay = decorate(overlay)
    if args.frames:
        args.notes.append("--frames: a cell's view draws no frames")
    robot, members = cell_members(args, folder, cells, report)
    try:
        cell_key_samples(members, args.fps)
    except viewer.ViewerError as exc:
        raise UsageError(f"--fps {args.fps:g}: {exc}") from None
    if getattr(overlay, "view", None) is not None:  # from the guns' side, over the travel
        moving = getattr(overlay, "moving", None) or {}
        tips = np.concatenate([c.to_world(m.ik.poses[:, :3]) for c, m in zip(cells, members)])
        t = np.concatenate([m.ik.t for m in members])
        view = overlay.view.seen_from(tips, t, next(iter(moving.values()), None))
        reach = np.linalg.norm(tips - np.asarray(view.centre), axis=1).max()  # every gun seen
        overlay.view = replace(view, radius=max(view.radius, float(reach)))
    if args.html:
        path = write_cell_html(args.html, robot, members, fps=args.fps, overlay=overlay)
        if args.html != STDOUT:
            span = max(m.ik.t[-1] for m in members) - min(m.ik.t[0] for m in members)
            print(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB, {len(members)} robots, "
                  f"{span:.4g} s): open it in a browser, no server needed; Open Controls → "
                  "Animations to play and scrub", file=sys.stderr)
        return 0
    say_notes(args)  # serving lasts until interrupted
    if getattr(overlay, "view", None) is not None:
        print(f"film colours: {overlay.view.scale}, blue thin, white on target, red thick",
              file=sys.stderr)
    viewer.serve(robot, None, fps=args.fps, overlay=overlay, build=lambda vis: build_cell_scene(
        vis, robot, members, fps=args.fps, overlay=overlay))
    return 0
