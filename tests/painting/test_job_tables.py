"""The job file's tables checked key by key (painting/job_tables.py), through the job reader:
each bad value one line naming the file and the key, the mesh's length unit one rule."""
import math

import pytest
from job_dicts import good_panel
from refusals import refused

from pollard_pin.painting.errors import JobError
from pollard_pin.painting.job import job_from_dict


def _set(path: str, value):
    d = good_panel()
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


@pytest.mark.parametrize("key", [1, None, 2.5, ("panel",)], ids=repr)
def test_a_key_that_is_not_a_string_is_one_line(key):
    """{1: ...} at the top or in a table: one line naming the key (it was a TypeError from
    difflib's did-you-mean)."""
    good = {"panel": {"center": [0.7, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0], "width": 0.26,
                      "height": 0.12}, "gun": {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7},
            "job": {"thickness": 25e-6}}
    refused(lambda: job_from_dict({**good, key: {}}), str(key))
    refused(lambda: job_from_dict({**good, "gun": {**good["gun"], key: 1}}), str(key))


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
