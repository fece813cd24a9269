"""A paint output folder read back (``view --paint DIR``): the files it holds, its report
through paint.json's schema, its film (a panel's grid from the film table, a part's mesh from
film.ply) with every value checked, a line's conveyor and a cell's robots; one line for a
folder or file that is not what ``pollard-pin paint`` wrote."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from .schema import PaintJson, load_paint_json, read_paint_json
from .sections import check_grid

FILES = ("path.csv", "path.units.json", "paint.json", "thickness.csv", "thickness.units.json",
         "thickness.parquet", "film.ply")
CELL_FILES = ("path.csv", "path.units.json")  # each robot's, in DIR/<name>/


class PaintFolderError(InputError):
    """A folder that is not a paint output folder, or lacks a file it needs (one line,
    naming the folder first; the CLI names its flag before it)."""


def paint_inputs(folder) -> list[tuple[str, Path]]:
    """(what, path) of the files a paint folder gives its reader (``view --paint``)."""
    return [(f"the paint folder's {n}", Path(folder) / n) for n in FILES]


def cell_inputs(folder) -> list[tuple[str, Path]]:
    """(what, path) of a cell's robots' files in ``folder``: ``DIR/*/path.csv``."""
    folder = Path(folder)
    if not folder.is_dir():
        return []
    return [(f"the paint folder's {d.name}/{n}", d / n) for d in sorted(folder.iterdir())
            if d.is_dir() for n in CELL_FILES]


def read_report(folder) -> PaintJson:
    """DIR/paint.json through the schema (:func:`.schema.read_paint_json`).

    Parameters
    ----------
    folder : str or Path
        A folder ``pollard-pin paint`` wrote.

    Returns
    -------
    PaintJson
        Its report; a malformed one is refused in one line.
    """
    return read_paint_json(Path(folder) / "paint.json")


def is_cell(folder) -> bool:
    """Whether DIR/paint.json is a cell's (a non-empty ``robots`` list); an unreadable
    report is left to the film's reader to refuse."""
    from ..io.table import ResultFileError

    try:
        report = load_paint_json(Path(folder) / "paint.json")
    except ResultFileError:
        return False
    return isinstance(report.get("robots"), list) and bool(report["robots"])


def cell_robots(folder, report: PaintJson):
    """The report's robots as :class:`~pollard_pin.painting.cell.robots.CellRobot` (the
    job's rules: names fit for a folder and unique, bases and rotations finite)."""
    from ..painting.cell.robots import ROBOT_KEYS, robots_from_tables

    tables = [{k: r[k] for k in ROBOT_KEYS if k in r} for r in report.robots or ()]
    return robots_from_tables(str(Path(folder) / "paint.json"), tables)


def check_robot_files(folder, report: PaintJson, cells) -> None:
    """One line when a robot of paint.json (name, base, rotation, gravity) is not the robot
    its DIR/<name>/path.csv records (``robot_metadata`` of paint_cell_files.py): a base moved
    in one file, or robots' folders swapped, no longer draw as if they were what paint
    planned.

    Parameters
    ----------
    folder : str or Path
        A cell's paint folder.
    report : PaintJson
        Its paint.json (:func:`read_report`).
    cells : tuple of CellRobot
        The report's robots (:func:`cell_robots`), in its order.

    Raises
    ------
    PaintFolderError
        A robot's sidecar unreadable or at odds with paint.json.
    """
    import json

    from ..io.table import units_path
    from ..io.trajectory import GRAVITY_KEY

    folder = Path(folder)
    for c, entry in zip(cells, report.robots or ()):
        side = units_path(folder / c.name / "path.csv")
        try:
            meta = json.loads(side.read_text(encoding="utf-8")).get("metadata") or {}
            recorded = dict(meta.get("robot") or {}, gravity=meta.get(GRAVITY_KEY))
        except (OSError, UnicodeDecodeError, ValueError, AttributeError, TypeError):
            raise PaintFolderError(f"{folder}: robot {c.name!r}: {c.name}/{side.name} is "
                                   "unreadable or records no robot") from None
        said = {"name": c.name, "base": c.base, "rotation": c.rotation,
                "gravity": entry.get(GRAVITY_KEY)}
        for key, value in said.items():
            if not _same(value, recorded.get(key)):
                raise PaintFolderError(
                    f"{folder}: robot {c.name!r}: paint.json's {key} {_short(value)} is not "
                    f"its {c.name}/path.csv's {_short(recorded.get(key))}: the folder was "
                    "edited or mixed")


def _same(a, b) -> bool:
    if isinstance(a, str) or isinstance(b, str) or a is None or b is None:
        return a == b
    try:
        x, y = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return False
    return x.shape == y.shape == (3,) and bool(np.all(np.abs(x - y) <= 1e-9))


def _short(value) -> str:
    from ..checks import clip

    if value is None:
        return "nothing"
    if isinstance(value, (list, tuple)) and all(isinstance(v, (int, float)) for v in value):
        return "[" + ", ".join(f"{float(v):.4g}" for v in value) + "]"
    return clip(repr(value), 40)


def robot_paths(folder, cells) -> list[Path]:
    """Each robot's DIR/<name>/path.csv, one line for one missing."""
    folder = Path(folder)
    paths = []
    for c in cells:
        path = folder / c.name / "path.csv"
        if not path.is_file():
            raise PaintFolderError(f"{folder}: robot {c.name!r} has no {c.name}/path.csv")
        paths.append(path)
    return paths


def conveyor(folder, report: PaintJson):
    """The line carrying the film (docs/model.md §24), read from the report's ``line`` by the
    job's rule (0 < speed ≤ 2 m/s, a direction): a
    :class:`~pollard_pin.painting.line.conveyor.Line`, or None when still."""
    from ..io.table import ResultFileError
    from ..painting.line.conveyor import LINE_KEYS, line_from_table

    if report.line is None:
        return None
    table = {k: report.line[k] for k in LINE_KEYS if k in report.line}
    return line_from_table(str(Path(folder) / "paint.json"), table, ResultFileError)


@dataclass(frozen=True)
class FolderFilm:
    """The film of a paint output folder, checked: a panel's ``nv`` × ``nu`` grid from its
    film table, or a part's refined mesh from film.ply.

    Attributes
    ----------
    points : numpy.ndarray
        (nv, nu, 3) grid points of a panel, (V, 3) vertices of a part [m].
    thickness : numpy.ndarray
        (nv, nu) or (V,) [m].
    faces : numpy.ndarray or None
        A part's triangles (M, 3); None for a panel (its grid).
    target : float
        The target film thickness [m].
    """

    points: np.ndarray
    thickness: np.ndarray
    faces: np.ndarray | None
    target: float


def film_tables(folder, path: str = "path.csv") -> list[Path]:
    """The folder's film table(s), one line if it is no paint output folder (no ``path``,
    film table or paint.json)."""
    folder = Path(folder)
    found = [p for p in (folder / "thickness.csv", folder / "thickness.parquet") if p.is_file()]
    if not (folder / path).is_file() or not found or not (folder / "paint.json").is_file():
        raise PaintFolderError(f"{folder}: not a paint output folder (expected {path}, "
                               "thickness.csv or .parquet and paint.json from pollard-pin "
                               "paint)")
    return found


def read_film(folder, report: PaintJson, found) -> FolderFilm:
    """The folder's film: a part's from film.ply, a panel's from its one film table
    ``found`` (of :func:`film_tables`) shaped by the report's grid."""
    folder = Path(folder)
    if report.is_part:
        return _part_film(folder, report.target)
    if len(found) > 1:  # pollard-pin paint never leaves both: which film is meant?
        raise PaintFolderError(f"{folder}: holds both thickness.csv and thickness.parquet, "
                               "two different films perhaps: remove the one not meant")
    return _panel_film(found[0], report)


def _panel_film(found: Path, report: PaintJson) -> FolderFilm:
    from ..checks import clip, shorten
    from ..io.table import ResultFileError, read_result

    grid = report.grid
    nu, nv = (None, None) if grid is None else (grid.nu, grid.nv)
    check_grid(found.parent / "paint.json", nu, nv)
    table = read_result(found)
    try:
        pts = np.column_stack([table["x"], table["y"], table["z"]]).reshape(nv, nu, 3)
        th = table["thickness"].reshape(nv, nu)
    except (KeyError, ValueError, OverflowError) as exc:
        raise ResultFileError(f"{found}: not the film of paint.json's {shorten(nu)} × "
                              f"{shorten(nv)} grid ({clip(exc, 100)})") from None
    check_film(found, pts.reshape(-1, 3), th.ravel(), report.target, "row", 1)
    return FolderFilm(pts, th, None, report.target)


def _part_film(folder: Path, target: float) -> FolderFilm:
    from ..io.ply import read_film_ply

    if not (folder / "film.ply").is_file():
        raise PaintFolderError(f"{folder}: a part's paint folder without film.ply")
    v, f, th = read_film_ply(folder / "film.ply", target)
    check_film(folder / "film.ply", v, th, target, "vertex", 0)
    return FolderFilm(v, th, f, target)


def check_film(where: Path, points, th, target: float, what: str, first: int) -> None:
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


__all__ = ["CELL_FILES", "FILES", "FolderFilm", "PaintFolderError", "cell_inputs",
           "cell_robots", "check_film", "check_robot_files", "conveyor", "film_tables",
           "is_cell", "paint_inputs", "read_film", "read_report", "robot_paths"]
