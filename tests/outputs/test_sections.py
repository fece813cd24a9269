"""paint.json's typed sections (outputs/sections.py): a figure that is not finite, absurdly
large or out of its range is one line naming its key; every shipped example's report lies
within the ranges (read back in tests/outputs/test_schema.py)."""
import json
import math
from dataclasses import fields
from pathlib import Path

import pytest

from pollard_pin.io.table import ResultFileError
from pollard_pin.outputs import sections
from pollard_pin.outputs.schema import PaintJson, read_paint_json

REPORTS = sorted((Path(__file__).resolve().parents[1] / "data" / "paint_reports").glob("*.json"))
THICK = {"mean": 2.5e-5, "min": 2.4e-5, "max": 2.6e-5, "std": 1e-7, "uniformity": 0.92,
         "within_5pct": 1.0, "within_10pct": 1.0, "deviation_min": -0.04,
         "deviation_max": 0.04}
MOTOR = {"peak_torque": 0.5, "rms_torque": 0.3, "speed": 0.2}


def _report(**sections_):
    return {"target": 2.5e-5, **sections_}


@pytest.mark.parametrize("text, says", [
    ('{"target": 2.5e-5, "thickness": {"mean": NaN}}',
     "'thickness.mean' = nan: must be a finite number of size at most 1e+15"),
    ('{"target": 2.5e-5, "cycle_time": Infinity}',
     "'cycle_time' = inf: must be a finite number"),
    ('{"target": 2.5e-5, "cycle_time": 1' + "0" * 400 + "}",
     "'cycle_time' = 1e+400 (a 401-digit integer): must be a finite number of size at most 1e+15"),
    ('{"target": 2.5e-5, "timings": {"plan": -Infinity}}',
     "'timings.plan' = -inf: must be a finite number"),
    ('{"target": 2.5e-5, "film_points": {"painted": 1' + "0" * 30 + ', "total": 2, '
     '"resolution": 0.001}}', "'film_points.painted' = 1e+30: must be a count of at most 1e+15"),
])
def test_a_figure_not_finite_or_absurd_is_one_line(tmp_path, text, says):
    path = tmp_path / "paint.json"
    path.write_text(text)
    with pytest.raises(ResultFileError) as err:
        read_paint_json(path)
    message = str(err.value)
    assert message.startswith(f"{path}: not a paint report (") and says in message
    assert "\n" not in message and len(message) - len(str(path)) <= 200, message


@pytest.mark.parametrize("key, table, field, value, interval", [
    ("thickness", THICK, "min", -1e-6, "[0, inf]"),
    ("thickness", THICK, "within_5pct", 1.5, "[0, 1]"),
    ("thickness", THICK, "deviation_min", -2.0, "[-1, inf]"),
    ("film_points", {"painted": 1, "total": 2, "resolution": 0.001}, "resolution", -0.001,
     "[0, inf]"),
    ("strokes", {"direction": "across", "dwell_s": 0.0}, "dwell_s", -3.0, "[0, inf]"),
    ("paint", {"solids": 0.5}, "solids", 50.0, "[0, 1]"),
    ("paint", {"dry_on_part_l": 0.01}, "dry_on_part_l", -0.01, "[0, inf]"),
])
def test_a_figure_out_of_its_range_is_one_line(key, table, field, value, interval):
    good = _report(**{key: table})
    assert PaintJson.from_dict(good).to_dict()[key] == table  # the edge of good is good
    with pytest.raises(ResultFileError) as err:
        PaintJson.from_dict(_report(**{key: {**table, field: value}}), "p.json")
    assert str(err.value) == (f"p.json: not a paint report ('{key}.{field}' = {value}: must be "
                              f"in {interval})")


def test_a_motor_and_a_cell_robots_paint_are_checked_where_they_stand():
    with pytest.raises(ResultFileError, match=r"'motors.theta21.speed' = -0.2: must be in "):
        PaintJson.from_dict(_report(motors={"theta21": {**MOTOR, "speed": -0.2}}))
    with pytest.raises(ResultFileError, match=r"'robots\[1\].paint.overspray' = 1.5: must be "
                                              r"in \[-1, 1\]"):
        PaintJson.from_dict(_report(robots=[{"name": "a"},
                                            {"name": "b", "paint": {"overspray": 1.5}}]))


def test_the_ranges_name_the_sections_numeric_fields():
    for cls in (sections.Thickness, sections.MotorUse, sections.Grid, sections.FilmPoints,
                sections.Seam, sections.LineSpeeds, sections.Strokes, sections.PaintUse):
        numeric = {f.name for f in fields(cls) if f.type in ("float", "float | None")}
        assert set(cls.RANGES) <= numeric, cls
        assert all(lo < hi for lo, hi in cls.RANGES.values())


@pytest.mark.parametrize("path", REPORTS, ids=[p.stem for p in REPORTS])
def test_every_examples_figures_lie_within_their_ranges_with_room(path):
    """The shipped reports read (test_schema reads them back text for text); their
    thickness and motor figures sit inside the ranges, not on an edge by accident."""
    report = read_paint_json(path)
    t = report.thickness
    assert 0 < t.min <= t.mean <= t.max < math.inf and 0 < t.uniformity <= 1
    assert all(0 < u.peak_torque < 10 for u in (report.motors or {}).values())
    raw = json.loads(path.read_text(encoding="utf-8"))
    assert raw["thickness"]["min"] == t.min
