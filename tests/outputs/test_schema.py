"""paint.json's schema (outputs/schema.py): every example job's report (tests/data/
paint_reports/, written by ``pollard-pin paint`` of examples/*.toml) read and written back is
the same text, its sections typed; a report computed in memory is written as json.dumps
writes it; a file that is no paint report is one line."""
import json
import os
import threading
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.film_scale import film_range
from pollard_pin.io.table import ResultFileError
from pollard_pin.outputs import schema, sections
from pollard_pin.outputs.schema import PaintJson, dumps, load_paint_json, read_paint_json
from pollard_pin.outputs.sections import FilmPly, Grid, MotorUse, Thickness

REPORTS = sorted((Path(__file__).resolve().parents[1] / "data" / "paint_reports").glob("*.json"))
NAMES = [p.stem for p in REPORTS]


def test_every_example_is_there():
    assert set(NAMES) == {"panel", "line", "line_part", "cell", "cell3", "parts_bent_plate",
                          "parts_curved_panel", "parts_ribbed_plate"}


@pytest.mark.parametrize("path", REPORTS, ids=NAMES)
def test_a_report_read_and_written_back_is_the_same_text(path):
    text = path.read_text(encoding="utf-8")
    report = read_paint_json(path)
    assert dumps(report) == text
    assert report.to_dict() == json.loads(text)
    assert list(report.to_dict()) == list(json.loads(text))  # the keys' order too
    # what a plan computes (numpy floats, tuples) is written as json.dumps writes it
    raw = json.loads(text)
    assert dumps(PaintJson.from_dict(raw)) == json.dumps(raw, indent=2) + "\n"


@pytest.mark.parametrize("path", REPORTS, ids=NAMES)
def test_the_sections_every_report_has_are_typed(path):
    raw = json.loads(path.read_text(encoding="utf-8"))
    r = read_paint_json(path)
    assert r.target == raw["target"] == r.job["job"]["thickness"]
    assert isinstance(r.thickness, Thickness) and r.thickness.mean == raw["thickness"]["mean"]
    assert r.cycle_time == raw["cycle_time"]
    assert all(isinstance(u, MotorUse) for u in r.motors.values())
    assert r.motors["theta21"].peak_torque == raw["motors"]["theta21"]["peak_torque"]
    assert set(r.timings) >= {"plan", "film"}
    assert r.version == raw["pollard_pin"] and r.version.count(".") == 2
    assert r.film_ply == FilmPly("RdBu_r", tuple(film_range(r.target)))
    assert r.is_cell == path.stem.startswith("cell")
    assert r.is_part == ("part" in path.stem)
    assert (r.grid is None) == r.is_part and (r.film_points is None) != r.is_part
    assert (r.line is not None) == (path.stem.startswith(("line", "cell")))
    assert set(r.extra).isdisjoint(schema.KEYS.values()) and "motors_source" in r.extra
    if r.is_cell:
        assert r.kind == "cell panel" and len(r.seams) == len(r.robots) - 1
        assert [s.to_dict() for s in r.seams] == raw["seams"]
        assert r.robots[0]["name"] == raw["robots"][0]["name"]
    else:
        assert r.kind is None and r.seams is None and r.robots is None
        assert r.extra["passes"] == raw["passes"]


def test_a_report_computed_in_memory():
    """The plan's numbers are numpy floats and tuples: written as json.dumps writes them, in
    the order given; built from typed sections, in the typed sections' order."""
    rep = {"job": {"job": {"thickness": 25e-6}}, "target": 25e-6, "passes": 3,
           "thickness": dict(zip(("mean", "min", "max", "std", "uniformity", "within_5pct",
                                  "within_10pct", "deviation_min", "deviation_max"),
                                 map(np.float64, np.linspace(0.1, 0.9, 9)))),
           "grid": {"nu": 3, "nv": 2, "resolution": np.float64(0.01)},
           "film_ply": {"colour_map": "RdBu_r", "range": film_range(25e-6)},
           "pollard_pin": "0.1.0"}
    assert dumps(PaintJson.from_dict(rep)) == json.dumps(rep, indent=2) + "\n"
    made = PaintJson(target=25e-6, version="0.1.0", grid=Grid(3, 2), extra={"passes": 3})
    assert list(made.to_dict()) == ["target", "grid", "pollard_pin", "passes"]
    assert made.to_dict()["grid"] == {"nu": 3, "nv": 2}  # no resolution given: none written
    with pytest.raises(ValueError, match="typed sections"):
        PaintJson(target=25e-6, extra={"grid": {}})


def test_the_paint_section_computed_and_read_back():
    """paint.json's ``paint`` (docs/model.md §29) as a job computes it, with a [paint] table and
    a cell's robots: written as json.dumps writes it, its keys typed (PaintUse), each
    robot's checked and kept as written."""
    from pollard_pin.painting.accounting import material_entry
    from pollard_pin.painting.job import job_from_dict
    from pollard_pin.painting.result import PaintFilm
    from pollard_pin.painting.spray.deposition import Film

    job = job_from_dict({"panel": {"center": [0.7, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
                                   "width": 0.2, "height": 0.1},
                         "gun": {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7},
                         "job": {"thickness": 25e-6},
                         "paint": {"solids": 0.5, "density": 1200.0}})
    robot = Film(np.full(4, 20e-6), np.zeros(4), np.float64(2e-6))
    f = PaintFilm(np.zeros((2, 2, 3)), Film(np.full(4, 20e-6), np.zeros(4), np.float64(2e-6),
                                            (robot,)), 0.01,
                  grid=(np.array([-0.1, 0.1]), np.array([-0.05, 0.05])))
    entry, robots = material_entry(job, f, np.float64(12.0))
    rep = {"target": 25e-6, "paint": entry, "robots": [{"name": "a", "paint": robots[0]}]}
    assert dumps(PaintJson.from_dict(rep)) == json.dumps(rep, indent=2) + "\n"
    r = PaintJson.from_dict(json.loads(json.dumps(rep)))
    assert isinstance(r.paint, sections.PaintUse) and r.paint.solids == 0.5
    assert r.paint.overspray == pytest.approx(1 - 0.02 * 20e-6 / 2e-6)
    assert r.paint.on_part_kg == pytest.approx(0.02 * 20e-6 / 0.5 * 1200.0)
    assert r.robots[0]["paint"] == robots[0]


GOOD = {"target": 2.5e-05, "grid": {"nu": 2, "nv": 2, "resolution": 0.1}}


def _with(**changes):
    rep = json.loads(json.dumps(GOOD))
    rep.update(changes)
    return json.dumps(rep)


@pytest.mark.parametrize("text, says", [
    ("{", "not a paint report (Expecting property name"),
    ("[]", "not a paint report (not a table)"),
    (b"\x89PNG\r\n\x1a\n", "not a paint report ('utf-8' codec can't decode"),
    ('{"a": ' * 100_000 + "1" + "}" * 100_000, "not a paint report (maximum recursion depth"),
    ('{"grid": {"nu": 2, "nv": 2}}', "target = None: expected a film thickness > 0 [m]"),
    (_with(target=0), "target = 0: expected a film thickness > 0 [m]"),
    (_with(target=True), "target = True: expected a film thickness > 0 [m]"),
    (_with(target="25e-6"), "target = '25e-6': expected a film thickness > 0 [m]"),
    ('{"target": Infinity}', "target = inf: expected a film thickness > 0 [m]"),
    (_with(grid={"nu": "two", "nv": 2}), "not a paint report (grid nu = 'two', nv = 2: "
                                         "expected point counts >= 1)"),
    (_with(grid=[2, 2]), "not a paint report (grid nu = None, nv = None"),
    (_with(grid={"nu": 2, "nv": 2, "step": 1}), "('grid.step' = 1: unknown key; grid holds "
                                                "nu, nv, resolution)"),
    (_with(thickness=3), "('thickness' = 3: must be a table)"),
    (_with(thickness={"mean": 1}), "('thickness.min' is missing)"),
    (_with(thickness={k: "x" for k in ("mean", "min", "max", "std", "uniformity",
                                       "within_5pct", "within_10pct", "deviation_min",
                                       "deviation_max")}), "('thickness.mean' = 'x': must be a "
                                                           "number)"),
    (_with(motors={"theta21": {"peak_torque": 1, "rms_torque": 1, "speed": None}}),
     "('motors.theta21.speed' = None: must be a number)"),
    (_with(timings={"plan": "soon"}), "('timings.plan' = 'soon': must be a number)"),
    (_with(line=None), "('line' = None: must be a table)"),
    (_with(line={"speed": 0.03, "speeds": {"min": 0.02, "max": "fast"}}),
     "('line.speeds.max' = 'fast': must be a number)"),
    (_with(line={"speed": 0.03, "speeds": {"min": 0.02, "max": 0.04, "resolution": 0.05,
                                          "min_bound": "budget floor"}}),
     "('line.speeds.max_bound' is missing)"),
    (_with(robots={"name": "a"}), "('robots' = {'name': 'a'}: must be a list)"),
    (_with(robots=[3]), "('robots[0]' = 3: must be a table)"),
    (_with(seams=[{"at": 0}]), "('seams[0].band_m' is missing)"),
    (_with(film_points={"painted": -1, "total": 2, "resolution": 0.1}),
     "('film_points.painted' = -1: must be a count (an integer >= 0)"),
    (_with(film_ply={"colour_map": "RdBu_r", "range": [1]}),
     "('film_ply.range' = [1]: must be a list of 2 numbers)"),
    (_with(pollard_pin=1), "('pollard_pin' = 1: must be a text)"),
    (_with(kind=["cell"]), "('kind' = ['cell']: must be a text)"),
    (_with(paint={"dry_sprayed_l": "a lot"}), "('paint.dry_sprayed_l' = 'a lot': must be a "
                                             "number)"),
    (_with(paint={"litres": 1.0}), "('paint.litres' = 1.0: unknown key; paint holds "),
    (_with(robots=[{"name": "a", "paint": {"overspray": None}}]),
     "('robots[0].paint.overspray' = None: must be a number)"),
])
def test_a_file_that_is_no_paint_report_is_one_line(tmp_path, text, says):
    path = tmp_path / "paint.json"
    (path.write_bytes if isinstance(text, bytes) else path.write_text)(text)
    with pytest.raises(ResultFileError) as err:
        read_paint_json(path)
    message = str(err.value)
    assert message.startswith(f"{path}: ") and says in message and "\n" not in message
    assert len(message) - len(str(path)) <= 200, message  # paint's 19 keys listed in part


def test_no_file_a_folder_a_fifo_and_a_huge_file_are_one_line(tmp_path, monkeypatch):
    for path, says in ((tmp_path / "none.json", "No such file or directory"),
                       (tmp_path, "Is a directory")):
        with pytest.raises(ResultFileError, match=f"not a paint report .*{says}"):
            read_paint_json(path)
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    done = []
    reader = threading.Thread(target=lambda: done.append(_refusal(fifo)), daemon=True)
    reader.start()
    reader.join(10)  # a FIFO with no writer would block a plain open for ever
    assert done and "not a regular file (a FIFO)" in done[0]
    monkeypatch.setattr(schema, "MAX_REPORT_BYTES", 1 << 10)
    big = tmp_path / "big.json"
    big.write_text(json.dumps({**GOOD, "note": "x" * 2000}))
    with pytest.raises(ResultFileError, match=r"big.json: not a paint report \(over 0.0009766 "
                                              r"MiB\)"):
        load_paint_json(big)


def _refusal(path) -> str:
    try:
        read_paint_json(path)
    except ResultFileError as exc:
        return str(exc)
    return ""


def test_load_checks_only_that_it_is_a_json_table(tmp_path):
    path = tmp_path / "paint.json"
    path.write_text('{"target": "thin", "robots": [1]}')
    assert load_paint_json(path) == {"target": "thin", "robots": [1]}


def test_a_non_finite_figure_is_refused_naming_its_key():
    """paint.json is strict JSON: a NaN or an infinity anywhere is one line naming the key
    (json.dumps would have written Infinity)."""
    from pollard_pin.io.json_text import NonFiniteError

    rep = dict(GOOD, compliance={"stiffness": True, "standoff_error_m": float("inf")})
    with pytest.raises(NonFiniteError, match=r"^paint\.json: compliance\.standoff_error_m = "
                                             r"inf is not a finite number"):
        dumps(PaintJson.from_dict(rep))


def test_a_line_with_its_speeds_reads_back_the_same_text(tmp_path):
    """``line.speeds`` (paint --speeds, docs/model.md §24.3) typed when read, the line table
    kept as written."""
    speeds = {"min": 0.0205, "max": 0.0343, "resolution": 0.05,
              "min_bound": "too slow: a motor at 104 % of its rating",
              "max_bound": "too fast: no turnaround keeps the path in reach"}
    path = tmp_path / "paint.json"
    path.write_text(_with(line={"speed": 0.03, "speeds": speeds}))
    report = read_paint_json(path)
    assert report.line["speeds"] == speeds
    assert json.loads(dumps(report))["line"]["speeds"] == speeds
    assert sections.LineSpeeds.from_dict(speeds, "line.speeds").to_dict() == speeds


def test_the_strokes_are_typed_and_a_robots_checked():
    """paint.json's ``strokes`` (docs/model.md §24.2): a line's typed, written back as read;
    a cell robot's checked where it stands."""
    from pollard_pin.outputs.sections import Strokes

    raw = json.loads(next(p for p in REPORTS if p.stem == "line").read_text(encoding="utf-8"))
    raw["strokes"] = {"direction": "across", "step_from": "leading", "dwell_s": 12.5}
    r = PaintJson.from_dict(raw)
    assert r.strokes == Strokes("across", "leading", 12.5)
    assert r.to_dict()["strokes"] == raw["strokes"] and "strokes" not in r.extra
    along = PaintJson.from_dict({**raw, "strokes": {"direction": "along", "step_from": None}})
    assert along.strokes == Strokes("along", None, 0.0)
    assert along.to_dict()["strokes"] == {"direction": "along", "dwell_s": 0.0}
    with pytest.raises(ResultFileError, match="strokes.dwell_s"):
        PaintJson.from_dict({**raw, "strokes": {"direction": "across", "dwell_s": "long"}})
    why = {"direction": "along", "step_from": None, "dwell_s": 0.0, "why": "auto: …"}
    assert PaintJson.from_dict({**raw, "strokes": why}).strokes.why == "auto: …"
    with pytest.raises(ResultFileError, match="strokes.why"):
        PaintJson.from_dict({**raw, "strokes": {"direction": "across", "why": 3}})
    cell = json.loads(next(p for p in REPORTS if p.stem == "cell").read_text(encoding="utf-8"))
    cell["robots"][1]["strokes"] = {"direction": "across", "wait": 1.0}
    with pytest.raises(ResultFileError, match=r"robots\[1\].strokes.wait"):
        PaintJson.from_dict(cell)
