"""What ``paint`` writes for a panel or a part, still or on a line: path.csv (with the
trigger), the film table, film.ply, paint.json and thickness.png, every one or none
(:meth:`pollard_pin.PaintResult.write` and the CLI)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError
from ..io.atomic import all_or_nothing, atomic_open, check_outputs, make_folder, remove_stale
from .schema import PaintJson, dumps

# The frame a line's film and figure are given in (its paint.json, table and film.ply)
LINE_FRAME = "the part at its t = 0 pose, world coordinates"


def report_json(result) -> dict:
    """paint.json: the result's report with what film.ply's colours mean."""
    from ..film_scale import ply_colours

    rep = dict(result.report.data)
    version = rep.pop("pollard_pin", None)
    rep["film_ply"] = ply_colours(result.job.thickness)
    if version is not None:
        rep["pollard_pin"] = version
    return rep


def write_paint(result, out: Path, fmt: str = "csv") -> Path:
    """Every output of a :class:`~pollard_pin.PaintResult` in ``out``, or none;
    the table's path."""
    from ..io.table import FORMATS

    if fmt not in FORMATS:
        raise InputError(f"format {fmt!r}: expected one of {', '.join(FORMATS)}")
    files, stale = result.painter.outputs.files(out, fmt)
    check_outputs(*files, folders=(out,))
    rep = report_json(result)
    meta = {"command": "paint", "job": rep["job"]}
    if result.painter.outputs.part_frame:
        meta["frame"] = LINE_FRAME
    # a panel's film on its grid, a part's on its mesh
    writer = _write_panel if result.film.grid is not None else _write_part
    return writer(result, out / f"thickness.{fmt}", rep, meta, stale)


def panel_table(U, V, pts, thickness, normal) -> dict:
    """The film table of a panel with a part's columns (a panel is the two-triangle part):
    x, y, z, the unit normal towards the gun, each grid point's share of the area (trapezoid
    weights, summing to width × height), the panel coordinates u, v and the thickness."""
    from ..dynamics.averages import trapezoid_weights

    flat = pts.reshape(-1, 3)
    area = np.outer(trapezoid_weights(V), trapezoid_weights(U)).ravel()
    n = np.broadcast_to(normal, flat.shape)
    UU, VV = np.meshgrid(U, V)
    return {"x": flat[:, 0], "y": flat[:, 1], "z": flat[:, 2], "nx": n[:, 0], "ny": n[:, 1],
            "nz": n[:, 2], "area": area, "u": UU.ravel(), "v": VV.ravel(),
            "thickness": thickness}


def _write_panel(result, name: Path, rep: dict, meta: dict, stale) -> Path:
    """A panel's outputs, still or on the line (the figure's tracks: the spot's panel
    coordinates, in the part's frame on a line)."""
    from ..film_scale import film_rgba as film_colours
    from ..io.ply import write_film_ply
    from ..io.table import write_table
    from ..io.trajectory import to_csv
    from ..painting.film.ply_mesh import grid_mesh
    from ..viz.paint import write_thickness_png

    plan, f = result.plan, result.film
    job, tr, fr = plan.job, plan.trajectory, plan.frame
    U, V = f.grid
    thickness = f.thickness
    outputs = result.painter.outputs
    comment = f"film: {LINE_FRAME}" if outputs.part_frame else None
    tips = outputs.tips(plan)  # seen from the part
    rel = tips[plan.spray > 0] - fr.c - job.standoff * fr.n
    out = name.parent
    with all_or_nothing():  # everything is computed: now write every output, or none
        make_folder(out)
        to_csv(tr, out / "path.csv", spray=plan.spray)
        write_table(name, panel_table(U, V, f.points, thickness, fr.n), meta,
                    fmt=name.suffix[1:])
        with atomic_open(out / "paint.json") as fh:
            fh.write(dumps(PaintJson.from_dict(rep)))
        write_film_ply(out / "film.ply", f.points.reshape(-1, 3), grid_mesh(f.points, fr.n),
                       thickness, film_colours(thickness, job.thickness), comment)
        write_thickness_png(out / "thickness.png", U, V, thickness.reshape(len(V), len(U)),
                            job.thickness, np.array([rel @ fr.u, rel @ fr.v]), job.width,
                            job.height)
        remove_stale(*stale)
    return name


def _write_part(result, name: Path, rep: dict, meta: dict, stale) -> Path:
    """A part's outputs, still or on the line: the film table on the painted faces, film.ply
    the refined mesh (on a line: the part at its t = 0 pose, the world path in path.csv)."""
    from ..film_scale import film_rgba as film_colours
    from ..io.ply import write_film_ply
    from ..io.table import write_table
    from ..io.trajectory import to_csv
    from ..painting.film.ply_mesh import refined_mesh
    from ..viz.paint_part import write_part_png

    plan, f = result.plan, result.film  # on a line: the world path, the part at t = 0
    comment = f"film: {LINE_FRAME}" if result.painter.outputs.part_frame else None
    job, lay, pts, painted = plan.job, plan.layout, f.points, f.painted
    out = name.parent
    used, triangles = refined_mesh(plan.part, pts)
    P, N, th = pts.points[painted], pts.normals[painted], f.thickness[painted]
    table = {"x": P[:, 0], "y": P[:, 1], "z": P[:, 2], "nx": N[:, 0], "ny": N[:, 1],
             "nz": N[:, 2], "area": pts.areas[painted], "thickness": th}
    tracks = [p.tip + job.standoff * p.axis for p in lay.passes]
    with all_or_nothing():  # everything is computed: now write every output, or none
        make_folder(out)
        to_csv(plan.trajectory, out / "path.csv", spray=plan.spray)
        write_table(name, table, meta, fmt=name.suffix[1:])
        with atomic_open(out / "paint.json") as fh:
            fh.write(dumps(PaintJson.from_dict(rep)))
        write_film_ply(out / "film.ply", pts.points[used], triangles, f.thickness[used],
                       film_colours(f.thickness[used], job.thickness), comment)
        write_part_png(out / "thickness.png", P, th, job.thickness, lay.frame.along,
                       lay.frame.across, tracks)
        remove_stale(*stale)
    return name


__all__ = ["LINE_FRAME", "panel_table", "report_json", "write_paint"]
