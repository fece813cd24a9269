"""What ``paint`` writes for a panel, still or on a line, and the motor-use line it prints:
written once for both (cli/paint.py, cli/paint_line.py)."""
from __future__ import annotations

import json
from pathlib import Path

from ..io.atomic import all_or_nothing, atomic_open, make_folder, remove_stale


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
                        job, rep: dict, metadata: dict, tracks, stale) -> Path:
    """path.csv (with the trigger), the film table, film.ply, paint.json and thickness.png of
    a panel, every one or none (``tracks`` (2, K): the spot's panel coordinates on the
    passes, for the figure); the table's path."""
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
                       film_colours(thickness, job.thickness))
        write_thickness_png(out / "thickness.png", U, V, thickness.reshape(len(V), len(U)),
                            job.thickness, tracks, job.width, job.height)
        remove_stale(*stale)
    return name
