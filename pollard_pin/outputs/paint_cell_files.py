"""What ``paint`` writes for a cell (docs/model.md §26): ``DIR/<robot>/path.csv`` (each robot's
program in its own base frame, with the trigger, on the cell's clock; its base pose and the
gravity in its base frame in the units sidecar), one film table, film.ply and
thickness.png for the whole part (world at t = 0, all robots), paint.json; every one or
none."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io.atomic import all_or_nothing, atomic_open, make_folder, remove_stale
from .schema import PaintJson, dumps

CELL_FRAME = "the part at its t = 0 pose, world coordinates; all robots"
# a cell part's thickness.png: the line's direction, then the cell's axis the robots' zones
# stack along (docs/model.md §26.2), whatever way the passes run
CELL_PART_AXES = ("along the line [mm]", "across the line, along the cell's axis [mm]")


def robot_metadata(rp) -> dict:
    """A robot's path.csv metadata: its base pose and gravity in its base frame (``run``,
    ``size``, ``simulate`` and ``stiffness`` check the program with that gravity, as
    ``paint`` did)."""
    from ..io.trajectory import GRAVITY_KEY
    from ..painting.cell.frames import gravity_in_base

    cr = rp.robot
    return {"trajectory": rp.plan.trajectory.name, "derivatives": "analytic",
            "frame": f"robot {cr.name!r} base frame (world <- base: base {list(cr.base)} m, "
                     f"rotation {list(cr.rotation)} deg, R = Rx·Ry·Rz)",
            "robot": cr.to_dict(),
            GRAVITY_KEY: [float(g) for g in gravity_in_base(cr)]}


def write_cell(result, out: Path, fmt: str = "csv") -> Path:
    """Every output of a cell's :class:`~pollard_pin.PaintResult` in ``out``, or
    none; the film table's path."""
    from ..errors import InputError
    from ..io.atomic import check_outputs
    from ..io.table import FORMATS, write_table
    from .paint_files import report_json

    if fmt not in FORMATS:
        raise InputError(f"format {fmt!r}: expected one of {', '.join(FORMATS)}")
    rep = report_json(result)

    cell = result.plan
    files, stale = result.painter.outputs.files(out, fmt, result.robot_folders)
    check_outputs(*files, folders=(out, *(out / r.robot.name for r in cell.robots)))
    name = out / f"thickness.{fmt}"
    meta = {"command": "paint", "job": rep["job"], "frame": CELL_FRAME}
    table, ply, png = (_panel if cell.part is None else _part)(result, out)
    with all_or_nothing():
        make_folder(out)
        for rp in cell.robots:
            make_folder(out / rp.robot.name)
            tr = rp.plan.trajectory
            cols = {"t": tr.t}
            for prefix, arr in (("", tr.poses), ("d_", tr.d_poses), ("dd_", tr.dd_poses)):
                cols.update({prefix + n: arr[:, i] for i, n in
                             enumerate(("x", "y", "z", "psi", "theta", "phi"))})
            cols["spray"] = np.asarray(rp.plan.spray, dtype=float)
            write_table(out / rp.robot.name / "path.csv", cols, robot_metadata(rp), fmt="csv")
        write_table(name, table, meta, fmt=fmt)
        with atomic_open(out / "paint.json") as fh:
            fh.write(dumps(PaintJson.from_dict(rep)))
        ply()
        png()
        remove_stale(*stale)
    return name


def _panel(result, out: Path):
    from ..film_scale import film_rgba as film_colours
    from ..io.ply import write_film_ply
    from ..painting.film.ply_mesh import grid_mesh
    from ..painting.workpiece.panel import panel_frame
    from ..viz.paint import write_thickness_png
    from .paint_files import panel_table

    job, f = result.job, result.film
    fr = panel_frame(job)
    U, V = f.grid
    th = f.thickness
    table = panel_table(U, V, f.points, th, fr.n)
    tips = [_aims(rp) for rp in result.plan.robots]
    rel = np.concatenate(tips) - fr.c if tips else np.zeros((0, 3))

    def ply():
        write_film_ply(out / "film.ply", f.points.reshape(-1, 3),
                       grid_mesh(f.points, fr.n), th, film_colours(th, job.thickness),
                       f"film: {CELL_FRAME}")

    def png():
        write_thickness_png(out / "thickness.png", U, V,
                            th.reshape(len(V), len(U)), job.thickness,
                            np.array([rel @ fr.u, rel @ fr.v]), job.width, job.height)

    return table, ply, png


def _part(result, out: Path):
    from ..film_scale import film_rgba as film_colours
    from ..io.ply import write_film_ply
    from ..painting.film.ply_mesh import refined_mesh
    from ..viz.paint_part import write_part_png

    cell, f = result.plan, result.film
    job, pts, painted = cell.job, f.points, f.painted
    P, N, th = pts.points[painted], pts.normals[painted], f.thickness[painted]
    table = {"x": P[:, 0], "y": P[:, 1], "z": P[:, 2], "nx": N[:, 0], "ny": N[:, 1],
             "nz": N[:, 2], "area": pts.areas[painted], "thickness": th}
    used, triangles = refined_mesh(cell.part, pts)
    axis = np.asarray(cell.split.axis, float)
    e = np.asarray(job.line.direction, float)

    def ply():
        write_film_ply(out / "film.ply", pts.points[used], triangles,
                       f.thickness[used], film_colours(f.thickness[used], job.thickness),
                       f"film: {CELL_FRAME}")

    def png():
        write_part_png(out / "thickness.png", P, th, job.thickness, e, axis,
                       [_aims(rp) for rp in cell.robots], labels=CELL_PART_AXES)

    return table, ply, png


def _aims(rp) -> np.ndarray:
    """A robot's spray spot centres while it sprays (world, the part at t = 0)."""
    from ..painting.film.cell import world_gun

    _, p, a, s = world_gun(rp)
    return (p + rp.plan.job.standoff * a[:, :, 0])[s > 0]


__all__ = ["CELL_FRAME", "CELL_PART_AXES", "robot_metadata", "write_cell"]
