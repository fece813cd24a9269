"""The paint job file: the shipped example reads back, and each bad value is one line."""
import math
from pathlib import Path

import numpy as np
import pytest
from refusals import WRONG, refused

from pollard_pin.painting.errors import JobError
from pollard_pin.painting.job import job_from_dict, load_job

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "paint.toml"


def _good() -> dict:
    return {"panel": {"center": [0.70, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
                      "width": 0.26, "height": 0.12},
            "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
            "job": {"thickness": 25e-6}}


def test_example_reads_as_the_issue_gives_it():
    job = load_job(EXAMPLE)
    assert job.center == (0.70, 0.0, 0.16) and job.normal == (-1.0, 0.0, 0.0)
    assert (job.width, job.height, job.standoff, job.sigma, job.flow, job.thickness) == \
        (0.26, 0.12, 0.15, 0.010, 1.5e-7, 25e-6)
    assert job.direction == "horizontal" and job.coats is None and job.speed is None


def test_normal_is_normalised_and_a_yaw_is_fine():
    d = _good()
    d["panel"]["normal"] = [-3.0, -4.0, 0.0]
    job = job_from_dict(d)
    assert job.normal == pytest.approx((-0.6, -0.8, 0.0), abs=1e-15)


def _set(path: str, value):
    d = _good()
    table, key = path.split(".")
    if value is _DELETE:
        del d[table][key]
    else:
        d[table][key] = value
    return d


_DELETE = object()


@pytest.mark.parametrize("path, value, words", [
    ("panel.widht", 0.2, ["'panel.widht'", "unknown key", "did you mean 'width'"]),
    ("job.thicknes", 1e-5, ["unknown key", "did you mean 'thickness'"]),
    ("panel.width", _DELETE, ["'panel.width' is missing"]),
    ("gun.flow", _DELETE, ["'gun.flow' is missing"]),
    ("gun.sigma", math.nan, ["'gun.sigma'", "must be a finite number"]),
    ("gun.flow", math.inf, ["'gun.flow'", "must be a finite number"]),
    ("panel.height", 0.0, ["'panel.height'", "must be > 0"]),
    ("gun.standoff", -0.15, ["must be > 0"]),
    ("job.thickness", 0, ["must be > 0"]),
    ("job.speed", -1.0, ["'job.speed'", "must be > 0"]),
    ("job.spacing", 0.0, ["'job.spacing'", "must be > 0"]),
    ("panel.normal", [0.0, 0.0, 0.0], ["'panel.normal'", "zero length"]),
    ("panel.normal", [0.0, 0.0, -1.0], ["'panel.normal'", "vertical"]),
    ("panel.normal", [1.0, 0.0], ["list of 3 numbers"]),
    ("panel.center", [0.7, "a", 0.1], ["'panel.center[1]'", "must be a number"]),
    ("panel.width", 260.0, ["metres, not mm"]),
    ("gun.sigma", True, ["must be a number"]),
    ("job.direction", "horizontl", ["did you mean 'horizontal'"]),
    ("job.coats", 0, ["'job.coats'", "whole number >= 1"]),
    ("job.coats", 1.5, ["whole number"]),
    ("job.actuators", 3, ["file name"]),
])
def test_each_bad_value_is_one_line(path, value, words):
    with pytest.raises(JobError) as info:
        job_from_dict(_set(path, value), "job.toml")
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith("job.toml: ")
    for w in words:
        assert w in msg


def test_missing_and_unknown_tables():
    d = _good()
    del d["gun"]
    with pytest.raises(JobError, match=r"missing table \[gun\]"):
        job_from_dict(d)
    d = _good()
    d["guns"] = {}
    with pytest.raises(JobError, match="did you mean 'gun'"):
        job_from_dict(d)


def test_file_errors_are_one_line(tmp_path):
    with pytest.raises(JobError, match="does not exist"):
        load_job(tmp_path / "none.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[panel\nwidth = 1\n")
    with pytest.raises(JobError, match="not valid TOML"):
        load_job(bad)


def test_actuators_path_is_relative_to_the_job(tmp_path):
    text = EXAMPLE.read_text().replace("# optional:", 'actuators = "motors.toml"\n# optional:')
    (tmp_path / "job.toml").write_text(text)
    assert load_job(tmp_path / "job.toml").actuators == str(tmp_path / "motors.toml")


@pytest.mark.parametrize("coats, ok", [(5, True), (6, False), (1_000_000_000, False)])
def test_a_parts_coats_are_capped(coats, ok):
    """A part's coats repeat every pass: more than MAX_PART_COATS = 5 is one line (a billion
    grew memory without bound)."""
    from pollard_pin.painting.job import MAX_PART_COATS

    d = {"part": {"mesh": "p.stl", "position": [0.0, 0.0, 0.0]}, "gun": _good()["gun"],
         "job": {"thickness": 25e-6, "coats": coats}}
    if ok:
        assert job_from_dict(d, "job.toml").coats == coats
        return
    with pytest.raises(JobError) as info:
        job_from_dict(d, "job.toml")
    msg = str(info.value)
    assert msg.startswith(f"job.toml: 'job.coats' = {coats}: must be at most {MAX_PART_COATS}")
    assert "\n" not in msg and len(msg) <= 250, msg


def _part(**part) -> dict:
    return {"part": {"mesh": "p.stl", "position": [0.0, 0.0, 0.0], **part},
            "gun": {"standoff": 0.15, "sigma": 0.010, "flow": 1.5e-7},
            "job": {"thickness": 25e-6}}


@pytest.mark.parametrize("part, unit", [
    ({}, 1.0), ({"units": "m"}, 1.0), ({"units": "cm"}, 0.01), ({"units": "mm"}, 0.001),
    ({"units": "in"}, 0.0254), ({"scale": 0.02}, 0.02), ({"scale": 1}, 1.0),
])
def test_mesh_unit_one_rule(part, unit):
    """The mesh file's length unit [m]: a name, or scale as a number (an inch is 25.4 mm
    exactly)."""
    assert job_from_dict(_part(**part)).unit == unit


@pytest.mark.parametrize("part, words", [
    ({"units": "ft"}, "'part.units' = 'ft': must be 'm', 'cm', 'mm', 'in'"),
    ({"units": "inch"}, "did you mean 'in'"),
    ({"scale": 0.0}, "'part.scale' = 0.0: must be > 0"),
    ({"scale": 1e9}, "'part.scale' = 1000000000.0: must be within 1e-6..1e3 m per file unit"),
    ({"scale": "0.02"}, "'part.scale' = '0.02': must be a number"),
    ({"units": "mm", "scale": 0.001}, "give part.units or part.scale, not both"),
])
def test_bad_mesh_units_are_one_line(part, words):
    with pytest.raises(JobError) as exc:
        job_from_dict(_part(**part), "j.toml")
    msg = str(exc.value)
    assert words in msg and len(msg) <= 250 and "\n" not in msg, msg


def test_scale_scales_the_mesh(tmp_path):
    """A file in inches read with units = 'in' and with scale = 0.0254: the same vertices,
    the file's × 0.0254 (numpy)."""
    from pollard_pin.painting.workpiece.mesh import load_job_part

    (tmp_path / "p.obj").write_text("v 0 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\n")
    parts = []
    for extra in ('units = "in"', "scale = 0.0254"):
        (tmp_path / "j.toml").write_text(
            f'[part]\nmesh = "p.obj"\n{extra}\nposition = [0.5, 0.0, 0.0]\n[gun]\n'
            "standoff = 0.15\nsigma = 0.01\nflow = 1.5e-7\n[job]\nthickness = 25e-6\n")
        parts.append(load_job_part(load_job(tmp_path / "j.toml")).vertices)
    want = np.array([[0, 0, 0], [0, 10, 0], [0, 0, 10]]) * 0.0254 + [0.5, 0, 0]
    for v in parts:
        assert np.abs(v - want).max() < 1e-15  # achieved 0


@pytest.mark.parametrize("wrong", [v for v in WRONG if not isinstance(v, str)], ids=repr)
def test_load_job_refuses_what_is_not_a_path(wrong):
    refused(lambda: load_job(wrong), "path")


@pytest.mark.parametrize("wrong", [v for v in WRONG if not isinstance(v, dict)], ids=repr)
def test_job_from_dict_refuses_what_is_not_tables(wrong):
    refused(lambda: job_from_dict(wrong), "d")


@pytest.mark.parametrize("key", [1, None, 2.5, ("panel",)], ids=repr)
def test_a_key_that_is_not_a_string_is_one_line(key):
    """{1: ...} at the top or in a table: one line naming the key (it was a TypeError from
    difflib's did-you-mean)."""
    good = {"panel": {"center": [0.7, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.26,
                      "height": 0.12}, "gun": {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7},
            "job": {"thickness": 25e-6}}
    refused(lambda: job_from_dict({**good, key: {}}), str(key))
    refused(lambda: job_from_dict({**good, "gun": {**good["gun"], key: 1}}), str(key))


@pytest.mark.parametrize("wrong", [v for v in WRONG if not isinstance(v, str)], ids=repr)
def test_job_from_dict_refuses_a_source_that_is_not_a_string(wrong):
    refused(lambda: job_from_dict({}, wrong), "source")
