"""`pollard-pin paint` keeps the gun's body `gun.clearance` from the part (docs/model.md §25):
a part with a rib taller than the standoff, and a clearance beyond the standoff, are one line
with exit status 2 and nothing written; a plan that keeps it reports `min_clearance_m`."""
import json
from pathlib import Path

import pytest
from cli_run import run_cli

from pollard_pin.paint.target import shapes

ROOT = Path(__file__).resolve().parents[2]
JOB = ROOT / "examples" / "paint.toml"
RIBBED = ROOT / "examples" / "parts" / "ribbed_plate.toml"


def _refused(capsys, job, out, words):
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin paint: error: ")
    for w in words:
        assert w in lines[0]
    assert not out.exists()
    return lines[0]


def test_a_rib_taller_than_the_standoff_is_refused_naming_the_place(tmp_path, capsys):
    shapes.ribbed_plate(rib_height=0.2, step=0.01).export(tmp_path / "rib.obj")
    job = tmp_path / "rib.toml"
    job.write_text(RIBBED.read_text().replace("ribbed_plate.obj", "rib.obj"))
    _refused(capsys, job, tmp_path / "out",
             ["the gun's body cuts", "into the part at (505, -3, ", "on pass 2 of 8",
              "clearance 10 mm"])


@pytest.mark.parametrize("value, words", [
    ("0.16", ["comes 145.6 mm from the part", "clearance 160 mm"]),
    ("-0.01", ["gun.clearance", "must be ≥ 0 m"]),
    ('"1 cm"', ["gun.clearance"]),
])
def test_a_clearance_the_job_cannot_keep_is_one_line(tmp_path, capsys, value, words):
    job = tmp_path / "job.toml"
    job.write_text(JOB.read_text().replace("flow = 1.5e-7", f"flow = 1.5e-7\nclearance = {value}",
                                           1))
    _refused(capsys, job, tmp_path / "out", words)


def test_a_kept_clearance_is_reported(tmp_path, capsys):
    job = tmp_path / "job.toml"
    job.write_text(JOB.read_text().replace("flow = 1.5e-7", "flow = 1.5e-7\nclearance = 0.02",
                                           1))
    out = tmp_path / "out"
    code, text, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 0, err
    assert "gun body 145.6 mm from the part at its closest" in text
    assert "clearance 20 mm" in text
    rep = json.loads((out / "paint.json").read_text())
    # the gun normal to the panel at 0.15 m: 150 − √(4² + 1.8²) mm (the front sphere, §25)
    assert rep["min_clearance_m"] == pytest.approx(0.15 - (0.004 ** 2 + 0.0018 ** 2) ** 0.5,
                                                   abs=1e-9)  # achieves ~1e-16
    assert rep["clearance"]["required_m"] == 0.02
    assert rep["job"]["gun"]["clearance"] == 0.02
