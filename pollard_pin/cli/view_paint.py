"""``view --paint DIR``: a paint output folder read back as a viewer overlay (the film on the
panel or on the part, on the film's colour scale, with its default view and legend), every
value checked first; and the folder's files, which ``view`` never overwrites."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .common import UsageError

FILES = ("path.csv", "path.units.json", "paint.json", "thickness.csv", "thickness.units.json",
         "thickness.parquet", "film.ply")


def paint_inputs(folder) -> list[tuple[str, Path]]:
    """(what, path) of the files ``view --paint folder`` reads."""
    return [(f"the paint folder's {n}", Path(folder) / n) for n in FILES]


def paint_report(folder: Path) -> dict:
    """DIR/paint.json, a table with a film target > 0 (one line otherwise)."""
    from ..io.table import ResultFileError
    from ..model.values import clip

    try:
        report = json.loads((folder / "paint.json").read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError) as exc:  # deep nesting
        raise ResultFileError(f"{folder / 'paint.json'}: not a paint report "
                              f"({clip(exc, 100)})") from None
    if not isinstance(report, dict):
        raise ResultFileError(f"{folder / 'paint.json'}: not a paint report (not a table)")
    target = report.get("target")
    if not (type(target) in (int, float) and 0 < target < math.inf):
        raise ResultFileError(f"{folder / 'paint.json'}: target = {target!r}: expected a film "
                              "thickness > 0 [m]")
    return report


def paint_overlay(folder: Path, path: str = "path.csv"):
    """The film of a ``paint`` output folder as a viewer overlay (``view --paint``); ``path``
    the program it needs (a cell's: "<name>/path.csv")."""
    found = [p for p in (folder / "thickness.csv", folder / "thickness.parquet") if p.is_file()]
    if not (folder / path).is_file() or not found or not (folder / "paint.json").is_file():
        raise UsageError(f"--paint {folder}: not a paint output folder (expected {path}, "
                         "thickness.csv or .parquet and paint.json from pollard-pin paint)")
    report = paint_report(folder)
    job = report.get("job")
    if isinstance(job, dict) and "part" in job:
        draw = _part_overlay(folder, report["target"])
    else:
        if len(found) > 1:  # pollard-pin paint never leaves both: which film is meant?
            raise UsageError(f"--paint {folder}: holds both thickness.csv and "
                             "thickness.parquet, two different films perhaps: remove the one "
                             "not meant")
        draw = _panel_overlay(found[0], report)
    if "line" in report:  # the film rides the line with the path (docs/model.md §24)
        from .paint_line import riding

        draw.moving = riding(report["line"], folder)
    return draw


def _panel_overlay(found: Path, report: dict):
    from ..io.table import ResultFileError, read_result
    from ..model.values import clip, shorten
    from ..viz.film_scale import film_range
    from ..viz.film_view import film_view, grid_faces
    from ..viz.viewer import film_panel

    grid, target = report.get("grid"), report["target"]
    nu, nv = (grid.get("nu"), grid.get("nv")) if isinstance(grid, dict) else (None, None)
    if not all(type(n) is int and n >= 1 for n in (nu, nv)):
        raise ResultFileError(f"{found.parent / 'paint.json'}: not a paint report (grid nu = "
                              f"{shorten(nu)}, nv = {shorten(nv)}: expected point counts >= 1)")
    table = read_result(found)
    try:
        pts = np.column_stack([table["x"], table["y"], table["z"]]).reshape(nv, nu, 3)
        th = table["thickness"].reshape(nv, nu)
    except (KeyError, ValueError, OverflowError) as exc:
        raise ResultFileError(f"{found}: not the film of paint.json's {shorten(nu)} × "
                              f"{shorten(nv)} grid ({clip(exc, 100)})") from None
    _check_film(found, pts.reshape(-1, 3), th.ravel(), target, "row", 1)

    def draw(vis):
        film_panel(vis, pts, th, *film_range(target))

    if min(nu, nv) > 1:  # a grid of one row has no faces to frame: the default view
        draw.view = film_view(pts.reshape(-1, 3), grid_faces(nv, nu), th.ravel(), target)
    return draw


def _part_overlay(folder: Path, target: float):
    from ..io.ply import read_film_ply
    from ..viz.film_scale import film_range
    from ..viz.film_view import film_view
    from ..viz.viewer import film_mesh

    if not (folder / "film.ply").is_file():
        raise UsageError(f"--paint {folder}: a part's paint folder without film.ply")
    v, f, th = read_film_ply(folder / "film.ply", target)
    _check_film(folder / "film.ply", v, th, target, "vertex", 0)

    def draw(vis):
        film_mesh(vis, v, f, th, *film_range(target))

    draw.view = film_view(v, f, th, target)
    return draw


def _check_film(where: Path, points, th, target: float, what: str, first: int) -> None:
    """One line for a point or thickness that is no film: not finite, negative, over
    ABSURD_FILM × target, or beyond the scene (element ``what`` numbered from ``first``)."""
    from ..io.ply import check_film_values
    from ..io.table import ResultFileError
    from ..viz.viewer import ViewerError, check_scene_points

    bad = ~np.isfinite(points).all(axis=1)
    if bad.any():
        k = int(np.argmax(bad))
        raise ResultFileError(f"{where}: {what} {k + first}: x, y, z not finite")
    check_film_values(where, th, target, what, first)
    try:
        check_scene_points(points, str(where), rows=np.arange(len(points)) + first)
    except ViewerError as exc:
        raise ResultFileError(str(exc)) from None
