"""The paint job file: the shipped example reads back, its tables make the job, and each bad
value is one line (the tables key by key: test_job_tables.py)."""
from pathlib import Path

import numpy as np
import pytest
from job_dicts import good_panel
from refusals import WRONG, refused

from pollard_pin.painting.errors import JobError
from pollard_pin.painting.job import job_from_dict, load_job

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "paint.toml"


def test_example_reads_as_specified():
    job = load_job(EXAMPLE)
    assert job.center == (0.70, 0.0, 0.16) and job.normal == (-1.0, 0.0, 0.0)
    assert (job.width, job.height, job.standoff, job.sigma, job.flow, job.thickness) == \
        (0.26, 0.12, 0.15, 0.010, 1.5e-7, 25e-6)
    assert job.direction == "horizontal" and job.coats is None and job.speed is None


def test_normal_is_normalised_and_a_yaw_is_fine():
    d = good_panel()
    d["panel"]["normal"] = [-3.0, -4.0, 0.0]
    job = job_from_dict(d)
    assert job.normal == pytest.approx((-0.6, -0.8, 0.0), abs=1e-15)


def test_missing_and_unknown_tables():
    d = good_panel()
    del d["gun"]
    with pytest.raises(JobError, match=r"missing table \[gun\]"):
        job_from_dict(d)
    d = good_panel()
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

    d = {"part": {"mesh": "p.stl", "position": [0.0, 0.0, 0.0]}, "gun": good_panel()["gun"],
         "job": {"thickness": 25e-6, "coats": coats}}
    if ok:
        assert job_from_dict(d, "job.toml").coats == coats
        return
    with pytest.raises(JobError) as info:
        job_from_dict(d, "job.toml")
    msg = str(info.value)
    assert msg.startswith(f"job.toml: 'job.coats' = {coats}: must be at most {MAX_PART_COATS}")
    assert "\n" not in msg and len(msg) <= 250, msg


@pytest.mark.parametrize("turn, ok", [(360.0, True), (-360.0, True), (360.5, False),
                                      (1e300, False)])
def test_a_parts_rotation_is_within_a_turn(turn, ok):
    """A part's rotation beyond ±360° is a slip (1e300 was taken and failed later as out of
    reach): one line naming the angle, the rule of a cell robot's rotation (cell/robots.py)."""
    d = {"part": {"mesh": "p.stl", "position": [0.0, 0.0, 0.0], "rotation": [0, 0, turn]},
         "gun": good_panel()["gun"], "job": {"thickness": 25e-6}}
    if ok:
        assert job_from_dict(d, "job.toml").rotation == (0.0, 0.0, turn)
        return
    with pytest.raises(JobError) as info:
        job_from_dict(d, "job.toml")
    msg = str(info.value)
    assert msg == f"job.toml: 'part.rotation[2]' = {turn:g}: must be within ±360 deg", msg


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


@pytest.mark.parametrize("wrong", [v for v in WRONG if not isinstance(v, str)], ids=repr)
def test_job_from_dict_refuses_a_source_that_is_not_a_string(wrong):
    refused(lambda: job_from_dict({}, wrong), "source")
