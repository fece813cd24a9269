"""What ``paint`` writes for a panel or a part, still or on a line, and the lines it prints
for a part: written once for both (cli/paint.py, cli/paint_line.py)."""
from __future__ import annotations

import json
import sys
from pathlib import Path

from ..io.atomic import all_or_nothing, atomic_open, make_folder, remove_stale
from .common import UsageError


def spacing(rule, job, resolution) -> float:
    """The film point spacing [m] by ``rule(job, --resolution)`` (a panel's grid or a part's
    points), its refusal as a usage error naming the flag."""
    from ..paint.errors import PlanError

    try:
        return rule(job, resolution)
    except PlanError as exc:
        raise UsageError(f"--resolution: {exc}") from None


def say_written(out: Path, table: Path) -> None:
    """The line on standard error naming what paint wrote in ``out``."""
    print(f"wrote {out}/path.csv, {table.name}, film.ply, paint.json, thickness.png",
          file=sys.stderr)


def motor_use_line(rep: dict, names) -> str:
    """Each motor's use of its ratings, one order for panels, parts and lines: peak torque,
    RMS (continuous) torque, speed."""
    use = rep["motors"]
    return "motor peak torque/RMS torque/speed use [%]: " + ", ".join(
        f"{n} {100 * use[n]['peak_torque']:.0f}/{100 * use[n]['rms_torque']:.0f}/"
        f"{100 * use[n]['speed']:.0f}" for n in names)


def panel_table(U, V, pts, thickness, normal) -> dict:
    """The film table of a panel with a part's columns (a panel is the two-triangle part):
    x, y, z, the unit normal towards the gun, each grid point's share of the area (trapezoid
    weights, summing to width × height), the panel coordinates u, v and the thickness."""
    import numpy as np

    from ..dynamics.averages import trapezoid_weights

    flat = pts.reshape(-1, 3)
    area = np.outer(trapezoid_weights(V), trapezoid_weights(U)).ravel()
    n = np.broadcast_to(normal, flat.shape)
    UU, VV = np.meshgrid(U, V)
    return {"x": flat[:, 0], "y": flat[:, 1], "z": flat[:, 2], "nx": n[:, 0], "ny": n[:, 1],
            "nz": n[:, 2], "area": area, "u": UU.ravel(), "v": VV.ravel(),
            "thickness": thickness}


def write_panel_outputs(out: Path, fmt: str, trajectory, spray, U, V, pts, thickness, frame,
                        job, rep: dict, metadata: dict, tracks, stale,
                        ply_comment: str | None = None) -> Path:
    """path.csv (with the trigger), the film table, film.ply, paint.json and thickness.png of
    a panel, every one or none (``tracks`` (2, K): the spot's panel coordinates on the
    passes, for the figure; ``ply_comment``: a line in film.ply's header); the table's
    path."""
    from ..io.ply import write_film_ply
    from ..io.table import write_table
    from ..io.trajectory import to_csv
    from ..paint.film_mesh import grid_mesh
    from ..viz.paint import write_thickness_png
    from ..viz.paint_part import film_colours

    name = out / f"thickness.{fmt}"
    flat = pts.reshape(-1, 3)
    with all_or_nothing():  # everything is computed: now write every output, or none
        make_folder(out)
        to_csv(trajectory, out / "path.csv", spray=spray)
        write_table(name, panel_table(U, V, pts, thickness, frame.n), metadata, fmt=fmt)
        with atomic_open(out / "paint.json") as f:
            f.write(json.dumps(rep, indent=2) + "\n")
        write_film_ply(out / "film.ply", flat, grid_mesh(pts, frame.n), thickness,
                       film_colours(thickness, job.thickness), ply_comment)
        write_thickness_png(out / "thickness.png", U, V, thickness.reshape(len(V), len(U)),
                            job.thickness, tracks, job.width, job.height)
        remove_stale(*stale)
    return name


def write_part_outputs(out: Path, fmt: str, plan, pts, film, painted, rep: dict,
                       metadata: dict, stale, ply_comment: str | None = None) -> Path:
    """path.csv (the plan's trajectory with its trigger), the film table on the painted
    faces, film.ply (the refined mesh, with ``ply_comment`` in its header), paint.json and
    thickness.png of a part (``plan``: a :class:`~pollard_pin.paint.surface_plan.SurfacePlan`
    whose layout and part give the figure; ``pts``, ``film``, ``painted``: its film), every
    one or none; the table's path."""
    from ..io.ply import write_film_ply
    from ..io.table import write_table
    from ..io.trajectory import to_csv
    from ..paint.film_mesh import refined_mesh
    from ..viz.paint_part import film_colours, write_part_png

    job, lay = plan.job, plan.layout
    name = out / f"thickness.{fmt}"
    used, triangles = refined_mesh(plan.part, pts)
    P, N, th = pts.points[painted], pts.normals[painted], film.thickness[painted]
    table = {"x": P[:, 0], "y": P[:, 1], "z": P[:, 2], "nx": N[:, 0], "ny": N[:, 1],
             "nz": N[:, 2], "area": pts.areas[painted], "thickness": th}
    tracks = [p.tip + job.standoff * p.axis for p in lay.passes]
    with all_or_nothing():  # everything is computed: now write every output, or none
        make_folder(out)
        to_csv(plan.trajectory, out / "path.csv", spray=plan.spray)
        write_table(name, table, metadata, fmt=fmt)
        with atomic_open(out / "paint.json") as f:
            f.write(json.dumps(rep, indent=2) + "\n")
        write_film_ply(out / "film.ply", pts.points[used], triangles, film.thickness[used],
                       film_colours(film.thickness[used], job.thickness), ply_comment)
        write_part_png(out / "thickness.png", P, th, job.thickness, lay.frame.along,
                       lay.frame.across, tracks)
        remove_stale(*stale)
    return name


def part_summary_lines(rep: dict, names) -> list[str]:
    """The lines ``paint`` prints for a part."""
    th, target = rep["thickness"], rep["target"]
    return [
        f"passes {rep['passes']} ({rep['direction']}), spacing on the surface "
        f"{rep['spacing'] * 1e3:.2f} mm, spot speed {rep['speed']:.4g} m/s (tip "
        f"{rep['tip_speed_range'][0]:.3g}–{rep['tip_speed_range'][1]:.3g}), coats "
        f"{rep['coats']}, normal averaged over {rep['normal_smoothing'] * 1e3:.3g} mm",
        f"cycle {rep['cycle_time']:.3f} s; painting-only lower bound {rep['lower_bound']:.3f} s "
        "(painted area × target / flow)",
        f"film {th['min'] * 1e6:.4g}–{th['max'] * 1e6:.4g} µm, mean {th['mean'] * 1e6:.4g} µm "
        f"(target {target * 1e6:.4g} µm), {100 * th['within_5pct']:.2f} % of the area within "
        f"±5 %, {100 * th['within_10pct']:.2f} % within ±10 %",
        f"largest incidence {rep['largest_incidence_deg']:.3g}°, transfer efficiency "
        f"{100 * rep['transfer_efficiency']:.1f} %",
        motor_use_line(rep, names),
        f"planned in {rep['timings']['plan']:.2f} s, film in {rep['timings']['film']:.2f} s "
        f"({rep['film_points']['painted']} painted film points, {rep['samples']} path "
        "samples)",
    ]
