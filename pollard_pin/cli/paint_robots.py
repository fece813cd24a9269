"""``paint --robots N|auto``: a layout of N robots (or the fewest that paint) proposed for a
job on a line, planned, and written as ``DIR/robots.toml`` beside the outputs (docs/model.md
§26.5)."""
from __future__ import annotations

import sys
from pathlib import Path

from ..checks import clip
from .common import UsageError, as_flags


def robots_arg(text: str) -> str:
    """--robots' value as given: checked by :func:`robot_count` (its refusal names it)."""
    return text


def robot_count(text: str | None) -> int | str | None:
    """N in 1..MAX_ROBOTS, 'auto', or None (no --robots); one line otherwise."""
    from ..painting.cell.robots import MAX_ROBOTS

    if text is None:
        return None
    t = text.strip()
    if t == "auto":
        return t
    n = int(t) if t.isascii() and t.isdigit() and len(t) < 6 else 0
    if not 1 <= n <= MAX_ROBOTS:
        raise UsageError(f"--robots {clip(text, 24)}: expected 1..{MAX_ROBOTS} or auto")
    return n


def proposed_names(count) -> list[str]:
    """The folders a proposal of ``count`` robots may write (auto: up to MAX_ROBOTS), named
    as :func:`pollard_pin.painting.layout.cell.propose_layout` names them."""
    from ..painting.cell.robots import MAX_ROBOTS
    from ..painting.layout.cell import LayoutOptions

    n = 0 if count is None else MAX_ROBOTS if count == "auto" else count
    return [f"{LayoutOptions().prefix}{i + 1}" for i in range(n)]


def check_job(count, job) -> None:
    """--robots needs a job on a line without its own [[robot]] tables."""
    if count is None:
        return
    if job.robots:
        raise UsageError(f"--robots: {job.source} places its own {len(job.robots)} robot(s) "
                         "([[robot]] tables): drop them or drop --robots")
    if job.line is None:
        raise UsageError(f"--robots: {job.source} has no [line] table: a cell's robots paint "
                         "the part as the line carries it past them")


def paint_layout(count, robot, job, act, options, edge_room: float = 0.0,
                 end_pitch: float = 0.0):
    """(robots, PaintResult): the proposal of ``count`` robots planned (with the cell's
    levers if refused plain), or the fewest; the end robots holding ``edge_room`` [m] more
    past the part's free edges, the top one turned ``end_pitch`` [deg] about the line."""
    from ..outputs.result import fewest_robots
    from ..painting.layout.cell import LayoutOptions

    with as_flags("LayoutOptions"):  # a refusal names the flag that set it
        layout = LayoutOptions(edge_room=edge_room, end_pitch=end_pitch)
    return fewest_robots(robot, job, act, options, layout,
                         None if count == "auto" else count)


def write_layout(robots, out: Path, count, job, seams=None, levers=None) -> Path:
    """robots.toml in ``out`` (inside the command's all-or-nothing block), one line said;
    ``seams`` (the plan's, where given or seated) said in its header: the same cell needs
    them again; so do the planner's ``levers`` that ``--robots auto`` found (paint.json's
    ``levers``: the plain proposal refused), said on standard error too."""
    from ..outputs.robots_toml import write_robots

    how = "the fewest robots that paint" if count == "auto" else f"{count} robot(s)"
    again = ("" if seams is None else "\nplanned with its seams at "
             + ", ".join(f"{s:.6g}" for s in seams) + " m: plan them again with --seams "
             + ",".join(f"{s:.6g}" for s in seams))
    if levers:  # the planner's levers in the tables' command; the layout's are in the tables
        from ..painting.layout.levers import Levers

        found = Levers(**{k: v for k, v in levers.items() if k != "plain"})
        used = found.flags()
        again += (f"\nfound with {used} (the plain proposal refused: {levers['plain']}): "
                  "plan them again with " + Levers(found.seam_run, found.smoothing).flags())
        print(f"--robots {count}: the plain proposal refused, found with {used}",
              file=sys.stderr)
    path = write_robots(robots, out / "robots.toml", f"[[robot]] tables proposed by "
                        f"pollard-pin paint --robots {count} ({how}) for {job.source}\n"
                        "(docs/model.md §26.5): add them to the job to plan with them"
                        + again)
    print(f"proposed {len(robots)} robot(s): " + ", ".join(
        f"{r.name} at ({', '.join(f'{c:.3f}' for c in r.base)}) m" for r in robots),
        file=sys.stderr)
    return path


__all__ = ["check_job", "paint_layout", "proposed_names", "robot_count", "robots_arg",
           "write_layout"]
