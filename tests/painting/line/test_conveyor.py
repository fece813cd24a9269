"""The [line] table of a paint job (docs/model.md §24)."""
from pathlib import Path

import pytest

from pollard_pin.model.params import read_toml
from pollard_pin.painting.errors import JobError
from pollard_pin.painting.job import job_from_dict
from pollard_pin.painting.line.conveyor import MAX_LINE_SPEED

LINE = Path(__file__).resolve().parents[3] / "examples" / "line.toml"


def _raw():
    return read_toml(LINE, "paint job file", JobError)


@pytest.mark.parametrize("line, words", [
    ({"speed": 0.03, "direction": [0.0, 0.0, 0.0]}, "zero length"),
    ({"speed": 0.0, "direction": [0.0, 1.0, 0.0]}, "must be > 0"),
    ({"speed": -0.1, "direction": [0.0, 1.0, 0.0]}, "must be > 0"),
    ({"speed": 30.0, "direction": [0.0, 1.0, 0.0]}, f"at most {MAX_LINE_SPEED:g} m/s"),
    ({"speed": float("inf"), "direction": [0.0, 1.0, 0.0]}, "finite"),
    ({"speed": float("nan"), "direction": [0.0, 1.0, 0.0]}, "'line.speed' = nan: must be a "
                                                          "finite number"),
    ({"speed": 0.03, "direction": [0.0, 1.0]}, "a list of 3 numbers"),
    ({"speed": 0.03}, "'line.direction' is missing"),
    ({"speed": 0.03, "direction": [0.0, 1.0, 0.0], "pitch": 1}, "unknown key"),
    ({"speed": 0.03, "direction": [0.0, "y", 0.0]}, "'line.direction[1]' = 'y': must be a number"),
])
def test_bad_line_tables(line, words):
    d = _raw()
    d["line"] = line
    with pytest.raises(JobError, match="line") as info:
        job_from_dict(d, "j.toml")
    assert words in str(info.value) and "\n" not in str(info.value)
    if "'line.speed' =" in str(info.value):  # a bad speed names the interval of speeds
        assert str(info.value).endswith(f"; a line speed is 0 < s ≤ {MAX_LINE_SPEED:g} m/s")


def test_line_table_read(line_job):
    d = _raw()
    d["line"] = {"speed": 0.02, "direction": [0.0, 3.0, 4.0]}
    job = job_from_dict(d, "j.toml")
    assert job.line.direction == (0.0, 0.6, 0.8) and job.line.speed == 0.02
    assert job.to_dict()["line"] == {"speed": 0.02, "direction": [0.0, 0.6, 0.8]}
    assert line_job.line.speed == 0.03 and line_job.line.direction == (0.0, 1.0, 0.0)
    d["line"] = {"speed": 0.02, "direction": [0.0, 3e300, 4e300]}  # |d|² overflows
    assert job_from_dict(d, "j.toml").line.direction == pytest.approx((0.0, 0.6, 0.8), abs=1e-15)
    del d["line"]
    assert job_from_dict(d, "j.toml").line is None


