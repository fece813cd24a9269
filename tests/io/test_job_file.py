"""A paint job written as TOML reads back equal (load_job), its paths relative to the
written file's folder."""
from dataclasses import replace
from pathlib import Path

import pytest

from pollard_pin.io.job_file import job_toml, write_job
from pollard_pin.painting.job import load_job
from pollard_pin.painting.line.conveyor import Line

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("edit", [
    dict(),
    dict(position=(0.1234567, -0.25, 1e-7), rotation=(10.0, -90.0, 33.3), units="in"),
    dict(scale=0.02, line=Line(0.03, (0.0, 1.0, 0.0)), coats=2, spacing=0.012,
         direction="vertical"),
])
def test_round_trip(tmp_path, edit):
    job = replace(load_job(ROOT / "examples" / "parts" / "curved_panel.toml"), **edit)
    (tmp_path / "deep" / "er").mkdir(parents=True)
    out = write_job(job, tmp_path / "deep" / "er" / "job.toml", "a header\nof two lines")
    back = load_job(out)
    text = out.read_text()
    assert text.startswith("# a header\n# of two lines\n")
    assert 'mesh = "../../' in text  # relative to the written file's folder
    assert Path(back.mesh).samefile(job.mesh)
    for k in ("position", "rotation", "facing", "max_angle", "standoff", "sigma", "flow",
              "thickness", "coats", "spacing", "direction", "line", "scale"):
        assert getattr(back, k) == getattr(job, k), k
    assert back.unit == job.unit


def test_values_have_a_toml_form():
    job = load_job(ROOT / "examples" / "parts" / "curved_panel.toml")
    with pytest.raises(ValueError, match="no TOML form"):
        job_toml(replace(job, max_angle=float("nan")), Path("."))
