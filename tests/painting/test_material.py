"""A job's [paint] table (painting/material.py, docs/model.md §29): read once into a frozen
Paint, on every kind of job; each bad value (an unknown key, a share given in per cent, a
density given in g/cm³) one line naming the file and the key."""
import dataclasses
import json
import math
from pathlib import Path

import pytest

from pollard_pin.io.job_file import write_job
from pollard_pin.painting.errors import JobError
from pollard_pin.painting.job import job_from_dict, load_job
from pollard_pin.painting.material import Paint, paint_from_table

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def test_the_table_read_once_frozen():
    p = paint_from_table("job.toml", {"solids": 0.45, "density": 1300, "transfer_efficiency": 1})
    assert p == Paint(0.45, 1300.0, 1.0) and p.efficiency == 1.0
    assert isinstance(p.density, float)
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.solids = 0.5
    bare = paint_from_table("job.toml", {"solids": 1.0, "density": 300.0})
    assert bare.transfer_efficiency is None and bare.efficiency == 1.0  # none: the geometry's
    assert bare.to_dict() == {"solids": 1.0, "density": 300.0}  # as the file says it


@pytest.mark.parametrize("table, words", [
    ({"solids": 45, "density": 1300}, ["'paint.solids' = 45", "not a per cent", "is 0.45"]),
    ({"solids": 0.45, "density": 1.2}, ["'paint.density' = 1.2", "kg/m³", "1200"]),
    ({"solids": 0.45, "density": 1.2e6}, ["'paint.density'", "300..5000 kg/m³"]),
    ({"solids": 0.45, "density": 1300, "transfer_efficiency": 65},
     ["'paint.transfer_efficiency' = 65", "is 0.65"]),
    ({"solids": 0.45, "density": 1300, "transfer_efficiency": 0},
     ["'paint.transfer_efficiency'", "must be > 0"]),
    ({"solids": 0.0, "density": 1300}, ["'paint.solids'", "must be > 0"]),
    ({"solids": 0.0045, "density": 1300}, ["'paint.solids' = 0.0045", "at least 0.05"]),
    ({"solids": 0.45, "density": 1300, "transfer_efficiency": 1e-9},
     ["'paint.transfer_efficiency'", "at least 0.05"]),
    ({"solids": 1.5e3, "density": 1300}, ["'paint.solids'", "not a per cent"]),
    ({"solids": math.nan, "density": 1300}, ["'paint.solids'", "finite"]),
    ({"solids": True, "density": 1300}, ["'paint.solids'", "must be a number"]),
    ({"solids": "0.45", "density": 1300}, ["'paint.solids'", "must be a number"]),
    ({"solid": 0.45, "density": 1300}, ["'paint.solid'", "unknown key",
                                        "did you mean 'solids'"]),
    ({"density": 1300}, ["'paint.solids' is missing"]),
    ({"solids": 0.45}, ["'paint.density' is missing"]),
    ([0.45, 1300], ["'paint'", "must be a table"]),
])
def test_each_bad_value_is_one_line_naming_key_and_file(table, words):
    with pytest.raises(JobError) as info:
        paint_from_table("job.toml", table)
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith("job.toml: ") and len(msg) <= 250, msg
    for w in words:
        assert w in msg, (w, msg)


@pytest.mark.parametrize("name", ["paint.toml", "line.toml", "line_part.toml",
                                  "parts/bent_plate.toml", "cell.toml"])
def test_every_kind_takes_it_and_writes_it_back(name, tmp_path):
    """A panel, a line, a part on a line, a part, a cell: the table on the job, and the job's
    tables (paint.json's ``job``) read back to the same job."""
    text = (EXAMPLES / name).read_text(encoding="utf-8")
    if "[paint]" not in text:
        text += "\n[paint]\nsolids = 0.6\ndensity = 950.0\n"
    path = tmp_path / Path(name).name
    path.write_text(text, encoding="utf-8")
    for mesh in (EXAMPLES / name).parent.glob("*.stl"):
        (tmp_path / mesh.name).write_bytes(mesh.read_bytes())
    job = load_job(path)
    assert isinstance(job.paint, Paint)
    assert job.to_dict()["paint"] == job.paint.to_dict()
    back = job_from_dict(json.loads(json.dumps(job.to_dict())), str(path))
    assert back.paint == job.paint
    assert load_job(write_job(job, tmp_path / "written.toml")).paint == job.paint  # place's


def test_the_examples_carry_their_paint():
    assert load_job(EXAMPLES / "paint.toml").paint == Paint(0.45, 1300.0, 0.65)
    assert load_job(EXAMPLES / "cell.toml").paint == Paint(0.45, 1300.0, None)
    assert load_job(EXAMPLES / "line.toml").paint is None  # optional


def test_a_bad_table_in_a_file_names_the_file(tmp_path):
    path = tmp_path / "job.toml"
    path.write_text((EXAMPLES / "paint.toml").read_text(encoding="utf-8").replace(
        "density = 1300.0", "density = 1.3"), encoding="utf-8")
    with pytest.raises(JobError, match=r"job\.toml: 'paint\.density' = 1\.3: .*g/cm³"):
        load_job(path)


@pytest.mark.parametrize("value", [1.5, 2.0, 4.99])
def test_a_share_just_above_1_is_not_called_a_per_cent(value):
    """1.5 is no per cent of a paint (1.5 % solids or efficiency is none): the rule alone,
    no "1.5 % is 0.015"; from 5 up the per cent is said."""
    for key in ("solids", "transfer_efficiency"):
        with pytest.raises(JobError) as info:
            paint_from_table("job.toml", {"solids": 0.45, "density": 1300, key: value})
        msg = str(info.value)
        assert msg.endswith("must be a share in (0, 1]") and "per cent" not in msg, msg
    with pytest.raises(JobError, match=r"not a per cent \(5 % is 0.05\)"):
        paint_from_table("job.toml", {"solids": 5, "density": 1300})


@pytest.mark.parametrize("paint, words", [
    (Paint(45, 1300.0), "'paint.solids' = 45: must be a share in (0, 1], not a per cent"),
    (Paint(0.45, 1.2), "'paint.density' = 1.2: must be within 300..5000 kg/m³"),
    (Paint(0.45, 1300.0, 65), "'paint.transfer_efficiency' = 65"),
    (Paint("0.45", 1300.0), "'paint.solids' = '0.45': must be a number"),
    ({"solids": 0.45, "density": 1300.0}, "'paint' = {'solids': 0.45"),
])
def test_a_python_jobs_paint_is_checked_when_made(paint, words):
    """A job given its paint in Python (dataclasses.replace) meets [paint]'s rules when it is
    made: one JobError line naming the job's source, before anything is planned."""
    job = load_job(EXAMPLES / "paint.toml")
    with pytest.raises(JobError) as info:
        dataclasses.replace(job, paint=paint)
    msg = str(info.value)
    assert "\n" not in msg and msg.startswith(f"{job.source}: ") and words in msg, msg
    assert dataclasses.replace(job, paint=Paint(0.5, 1200.0, 0.6)).paint.efficiency == 0.6
