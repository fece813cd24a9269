"""A paint output folder read back (outputs/folder.py): its files, its report through the
schema, its film (a panel's grid, a part's film.ply) checked, a line's conveyor and a cell's
robots; one line for a folder that is not what ``pollard-pin paint`` wrote. The folders are
made here, small, in the shapes paint writes (tests/cli/test_view*.py view real ones)."""
import json
import os

import numpy as np
import pytest

from pollard_pin.io.ply import write_film_ply
from pollard_pin.io.table import ResultFileError
from pollard_pin.outputs.folder import (
    FILES,
    FolderFilm,
    PaintFolderError,
    cell_inputs,
    cell_robots,
    check_film,
    conveyor,
    film_tables,
    is_cell,
    paint_inputs,
    read_film,
    read_report,
    robot_paths,
)
from pollard_pin.painting.cell.robots import CellError

TARGET = 25e-6
FILM = "x,y,z,u,v,thickness\n" + "".join(f"0.55,{u},{v},{u},{v},{TARGET + 1e-7 * (u + v)}\n"
                                          for v in (0, 0.1) for u in (0, 0.1, 0.2))
ROBOTS = [{"name": "low", "base": [0.0, 0.0, 0.0], "rotation": [0.0, 0.0, 0.0],
           "zone": {"lo": None, "hi": 0.4}, "start": 0.0},
          {"name": "high", "base": [0.0, 0.75, 0.17], "rotation": [0.0, 0.0, 90.0],
           "zone": {"lo": 0.4, "hi": None}, "start": 1.0}]


def _panel(folder, **report):
    folder.mkdir()
    (folder / "path.csv").write_text("t\n0\n")  # only its presence is read here
    (folder / "thickness.csv").write_text(FILM)
    rep = {"target": TARGET, "grid": {"nu": 3, "nv": 2, "resolution": 0.1}, **report}
    (folder / "paint.json").write_text(json.dumps(rep))
    return folder


def _part(folder, with_ply=True):
    folder.mkdir()
    (folder / "path.csv").write_text("t\n0\n")
    (folder / "thickness.csv").write_text("x,y,z,thickness\n0,0,0,2.5e-5\n")
    if with_ply:
        v = np.array([[0.6, 0, 0], [0.6, 0.1, 0], [0.6, 0, 0.1]])
        write_film_ply(folder / "film.ply", v, [[0, 1, 2]], np.full(3, TARGET),
                       np.full((3, 4), 255, np.uint8))
    rep = {"job": {"part": {"mesh": "plate.stl"}}, "target": TARGET}
    (folder / "paint.json").write_text(json.dumps(rep))
    return folder


def test_the_files_a_folder_gives_its_reader(tmp_path):
    assert [p for _, p in paint_inputs(tmp_path)] == [tmp_path / n for n in FILES]
    assert cell_inputs(tmp_path / "none") == []
    (tmp_path / "low").mkdir()
    assert cell_inputs(tmp_path) == [("the paint folder's low/path.csv",
                                      tmp_path / "low" / "path.csv"),
                                     ("the paint folder's low/path.units.json",
                                      tmp_path / "low" / "path.units.json")]


def test_a_panel_folder_read_back(tmp_path):
    folder = _panel(tmp_path / "p")
    found = film_tables(folder)
    report = read_report(folder)
    film = read_film(folder, report, found)
    assert isinstance(film, FolderFilm) and film.faces is None and film.target == TARGET
    assert film.points.shape == (2, 3, 3) and film.thickness.shape == (2, 3)
    assert film.points[1, 2].tolist() == [0.55, 0.2, 0.1]  # row by row: v, then u
    assert film.thickness[1, 2] == pytest.approx(TARGET + 3e-8, rel=1e-12)
    assert conveyor(folder, report) is None and not is_cell(folder)


def test_a_part_folder_read_back(tmp_path):
    folder = _part(tmp_path / "p")
    report = read_report(folder)
    film = read_film(folder, report, film_tables(folder))
    assert report.is_part and film.faces.tolist() == [[0, 1, 2]]
    assert film.points.shape == (3, 3) and film.thickness.tolist() == [TARGET] * 3
    with pytest.raises(PaintFolderError, match=r"p2: a part's paint folder without film.ply$"):
        folder = _part(tmp_path / "p2", with_ply=False)
        read_film(folder, read_report(folder), film_tables(folder))


def test_a_folder_that_paint_did_not_write_is_one_line(tmp_path):
    says = "not a paint output folder (expected path.csv, thickness.csv or .parquet and " \
           "paint.json from pollard-pin paint)"
    with pytest.raises(PaintFolderError, match=r"^\S*nope: " + f"{says}".replace("(", r"\(")
                       .replace(")", r"\)").replace(".", r"\.")):
        film_tables(tmp_path / "nope")
    folder = _panel(tmp_path / "p")
    with pytest.raises(PaintFolderError, match="expected low/path.csv"):
        film_tables(folder, "low/path.csv")
    (folder / "thickness.parquet").write_bytes(b"PAR1")
    with pytest.raises(PaintFolderError, match="holds both thickness.csv and thickness.parquet"):
        read_film(folder, read_report(folder), film_tables(folder))


@pytest.mark.parametrize("report, says", [
    ({"grid": None}, "paint.json: not a paint report (grid nu = None, nv = None"),
    ({"grid": {"nu": 4, "nv": 2}}, "thickness.csv: not the film of paint.json's 4 × 2 grid"),
    ({"target": -1}, "paint.json: target = -1: expected a film thickness > 0 [m]"),
])
def test_a_report_that_does_not_fit_its_film_is_one_line(tmp_path, report, says):
    folder = _panel(tmp_path / "p", **report)
    with pytest.raises(ResultFileError) as err:
        read_film(folder, read_report(folder), film_tables(folder))
    assert says in str(err.value) and "\n" not in str(err.value)


def test_a_panel_report_without_a_grid_says_so(tmp_path):
    folder = _panel(tmp_path / "p")
    (folder / "paint.json").write_text(json.dumps({"target": TARGET}))
    with pytest.raises(ResultFileError, match=r"paint.json: not a paint report \(grid nu = None, "
                                              r"nv = None: expected point counts >= 1\)"):
        read_film(folder, read_report(folder), film_tables(folder))


def test_film_values_that_are_no_film_are_one_line(tmp_path):
    pts = np.zeros((3, 3))
    check_film(tmp_path, pts, np.full(3, TARGET), TARGET, "row", 1)
    pts[1, 2] = np.nan
    with pytest.raises(ResultFileError, match="row 2: x, y, z not finite"):
        check_film(tmp_path, pts, np.full(3, TARGET), TARGET, "row", 1)
    with pytest.raises(ResultFileError, match=r"vertex 1 \(from 0\): thickness = -1e-06 m"):
        check_film(tmp_path, np.zeros((3, 3)), [TARGET, -1e-6, TARGET], TARGET, "vertex", 0)


def test_the_line_is_read_by_the_jobs_rule(tmp_path):
    folder = _panel(tmp_path / "p", line={"speed": 0.03, "direction": [0.0, 2.0, 0.0],
                                          "cycle": 30.0, "searched": False})
    line = conveyor(folder, read_report(folder))
    assert line.speed == 0.03 and line.direction == (0.0, 1.0, 0.0)
    (folder / "paint.json").write_text(json.dumps(
        {"target": TARGET, "line": {"speed": True, "direction": [0, 1, 0]}}))
    with pytest.raises(ResultFileError, match="'line.speed' = True: must be a number"):
        conveyor(folder, read_report(folder))


def test_a_cells_robots(tmp_path):
    folder = _part(tmp_path / "c")
    rep = json.loads((folder / "paint.json").read_text())
    (folder / "paint.json").write_text(json.dumps({**rep, "robots": ROBOTS}))
    assert is_cell(folder)
    cells = cell_robots(folder, read_report(folder))
    assert [c.name for c in cells] == ["low", "high"] and cells[1].base == (0.0, 0.75, 0.17)
    with pytest.raises(PaintFolderError, match=r"c: robot 'low' has no low/path.csv$"):
        robot_paths(folder, cells)
    for r in ROBOTS:
        (folder / r["name"]).mkdir()
        (folder / r["name"] / "path.csv").write_text("t\n0\n")
    assert robot_paths(folder, cells) == [folder / "low" / "path.csv",
                                          folder / "high" / "path.csv"]
    (folder / "paint.json").write_text(json.dumps({**rep, "robots": ROBOTS + ROBOTS[:1]}))
    with pytest.raises(CellError, match="two robots are named 'low'"):
        cell_robots(folder, read_report(folder))


@pytest.mark.parametrize("text", ["{", '{"robots": []}', '{"robots": {"a": 1}}', "[1]"])
def test_a_cell_is_a_report_listing_robots(tmp_path, text):
    (tmp_path / "paint.json").write_text(text)
    assert not is_cell(tmp_path)


def test_a_fifo_report_is_not_a_cell_and_never_blocks(tmp_path):
    os.mkfifo(tmp_path / "paint.json")
    assert not is_cell(tmp_path)
