"""`pollard-pin calibrate`: the example stripes give back the pattern they were made from, a
gun.toml that `paint` takes as it is; every bad stripe is one line saying what to measure,
exit 2, nothing written."""
import contextlib
import io
import json
import math
import os
import shutil
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli, tree_state

from pollard_pin.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "stripes"
sys.path.insert(0, str(EXAMPLE))
try:
    import make_stripes
    from make_stripes import TRUTH
finally:
    sys.path.remove(str(EXAMPLE))


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    """The example calibrated once: (out folder, stdout, stderr)."""
    out = tmp_path_factory.mktemp("cal") / "out"
    o, e = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(o), contextlib.redirect_stderr(e):
        code = main(["calibrate", "--stripes", str(EXAMPLE / "stripes.toml"), "--out",
                     str(out)])
    assert code == 0, e.getvalue()
    return out, o.getvalue(), e.getvalue()


def test_the_example_gives_back_its_pattern(calibrated):
    out, text, err = calibrated
    assert sorted(p.name for p in out.iterdir()) == ["calibration.json", "fits.png", "gun.toml"]
    cal = json.loads((out / "calibration.json").read_text())
    assert cal["chosen"] == "elliptic" and cal["criterion"] == "bic"
    assert cal["spread"] == "fitted" and cal["reference_standoff"] == TRUTH["standoff"]
    best = next(m for m in cal["models"] if m["chosen"])
    got = {**best["params"], "apex": best["apex"], "efficiency": best["efficiency"]}
    err_ = {**best["errors"], "apex": best["apex_error"], "efficiency": best["efficiency_error"]}
    for key in ("sigma_long", "sigma_short", "apex", "efficiency"):
        assert abs(got[key] - TRUTH[key]) < 3.5 * err_[key], (key, got[key], err_[key])
    assert best["rms_share"] < 0.01 and len(best["stripes"]) == 8
    assert {m["model"] for m in cal["models"]} == {"gaussian", "elliptic", "beta"}
    gun = tomllib.loads((out / "gun.toml").read_text())["gun"]
    assert gun["model"] == "elliptic" and gun["standoff"] == 0.2
    assert gun["sigma_long"] == best["params"]["sigma_long"] and gun["apex"] == best["apex"]
    assert math.isclose(gun["flow"], 0.45 * best["efficiency"] * 1.5e-6, rel_tol=1e-12)
    assert text.startswith("elliptic spot chosen by BIC") and "sigma_long 29.98" in text
    assert "wrote " in err and "fits.png" in err
    assert (out / "fits.png").read_bytes()[:4] == b"\x89PNG"


def test_a_job_takes_the_gun_as_it_is(calibrated):
    from pollard_pin.painting.job import job_from_dict

    gun = tomllib.loads((calibrated[0] / "gun.toml").read_text())["gun"]
    job = job_from_dict({"panel": {"center": [0.7, 0.0, 0.16], "normal": [-1.0, 0.0, 0.0],
                                   "width": 0.3, "height": 0.2},
                         "gun": gun, "job": {"thickness": 25e-6}})
    assert job.spot.params() == {k: gun[k] for k in ("sigma_long", "sigma_short")}
    assert job.apex == gun["apex"] and job.flow == gun["flow"]


def _csv(x, t) -> str:
    return "position,thickness\n" + "".join(f"{float(a)!r},{float(b)!r}\n"
                                            for a, b in zip(x, t))


X = np.round(np.arange(-150, 151) * 1e-3, 6)
PEAK = 0.6 * 0.45 * 1.5e-6 / 0.4 / (math.sqrt(2 * math.pi) * 0.02)
T = PEAK * np.exp(-0.5 * (X / 0.02) ** 2)
ONE = ('solids = 0.45\n[[stripe]]\nfile = "s.csv"\nstandoff = 0.2\nspeed = 0.4\n'
       'flow = 1.5e-6\ndirection = "across"\n')
# (name, stripes.toml, s.csv, what the line says)
BAD = [
    ("non-monotone", ONE, _csv(np.r_[X[:9], X[10], X[9], X[11:]], T),
     "s.csv: line 12: position -0.141 m after -0.14 m: positions must rise"),
    ("nan", ONE, _csv(X, np.r_[T[:99], np.nan, T[100:]]),
     "line 101: thickness is nan: measure that point again"),
    ("negative", ONE, _csv(X, T - 2e-6 * (np.abs(X - 0.1) < 0.003)),
     "below zero beyond the noise"),
    ("negated", ONE, _csv(X, -T), "s.csv): no film: every reading is ≤ 0"),
    ("narrow", ONE, _csv(X[100:200], T[100:200] + PEAK * 0.4 * (X[100:200] < -0.03)),
     "the scan is narrower than the pattern; measure wider"),
    ("elliptic one direction", ONE, _csv(X, T),
     "an elliptic spot needs stripes in both directions"),
    ("spread one standoff", ONE, _csv(X, T),
     "a spread law needs stripes at two standoffs or more"),
    ("unknown key", ONE + "nozzle = 1\n", _csv(X, T), "unknown key 'nozzle'"),
    ("missing file", ONE.replace("s.csv", "gone.csv"), _csv(X, T), "gone.csv' does not exist"),
    ("fifo", ONE, "FIFO", "not a regular file (a FIFO)"),
    ("another format", ONE, "PK\x03\x04\x14\x00\x06\x00\x08\x00\xff\xfe",
     "not UTF-8 text (another format?)"),
    ("huge", ONE, _csv(X, np.r_[T[:9], 1e300, T[10:]]), "over 1 mm of dry film"),
    ("mm", ONE, _csv(X * 1e3, T), "positions in mm? give metres"),
    ("flow", ONE.replace("1.5e-6", "150"), _csv(X, T), "in ml/min or l/min? give m³/s"),
    ("efficiency", ONE, _csv(X, T * 3), "more paint than was sprayed"),
    ("swapped", ONE + ONE.split("\n", 1)[1].replace("s.csv", "w.csv").replace("across",
                                                                              "along"),
     _csv(X, T), "the 'along' stripes are wider than the 'across' ones"),
    ("far standoff", "standoff = 0.01\n" + ONE, _csv(X, T),
     "standoff = 0.01 m, beyond the stripes' 0.2-0.2 m by over ×1.5: measure stripes near it"),
    ("efficiency given", ONE, _csv(X, T),
     "efficiency 0.3 given, but the stripes hold 0.6 of the paint sprayed"),
]
FLAGS = {"elliptic one direction": ["--model", "elliptic"],
         "spread one standoff": ["--spread", "fit"], "efficiency given": ["--efficiency", "0.3"]}


@pytest.mark.parametrize("name, toml, csv, says", BAD, ids=[b[0] for b in BAD])
def test_a_bad_stripe_is_one_line_and_nothing_written(tmp_path, capsys, name, toml, csv, says):
    (tmp_path / "stripes.toml").write_text(toml)
    if csv == "FIFO":
        os.mkfifo(tmp_path / "s.csv")
    else:
        (tmp_path / "s.csv").write_bytes(csv.encode("latin-1" if name == "another format"
                                                    else "utf-8"))
    # a stripe twice as wide, for the directions swapped
    (tmp_path / "w.csv").write_text(_csv(X, 0.5 * T[np.arange(301) // 2 + 75]))
    before = tree_state(tmp_path)
    code, text, err = run_cli(["calibrate", "--stripes", tmp_path / "stripes.toml", "--out",
                               tmp_path / "out", *FLAGS.get(name, [])], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and text == "", err
    assert lines[0].startswith("pollard-pin calibrate: error: ") and says in lines[0], lines[0]
    assert tree_state(tmp_path) == before


def test_a_good_single_stripe_calibrates_a_round_gun_and_says_what_it_could_not(tmp_path,
                                                                                 capsys):
    (tmp_path / "stripes.toml").write_text(ONE)
    rng = np.random.default_rng(0)
    (tmp_path / "s.csv").write_text(_csv(X, T + rng.normal(0, 0.1e-6, X.shape)))
    code, text, err = run_cli(["calibrate", "--stripes", tmp_path / "stripes.toml", "--out",
                               tmp_path / "out"], capsys)
    assert code == 0, err
    assert "note: spread law not fitted (one standoff): apex 0" in err
    assert "note: elliptic not tried: an elliptic spot needs stripes in both directions" in err
    gun = tomllib.loads((tmp_path / "out" / "gun.toml").read_text())["gun"]
    assert "model" not in gun and abs(gun["sigma"] / 0.02 - 1) < 0.01  # a round Gaussian
    assert gun["apex"] == 0.0


def test_the_output_must_be_a_folder(tmp_path, capsys):
    shutil.copytree(EXAMPLE, tmp_path / "s")
    before = tree_state(tmp_path)
    code, _, err = run_cli(["calibrate", "--stripes", tmp_path / "s" / "stripes.toml",
                            "--out", tmp_path / "s" / "stripes.toml"], capsys)
    assert code == 2 and "names a file, but a folder is expected" in err
    assert tree_state(tmp_path) == before


def test_the_example_stripes_are_what_the_script_makes(tmp_path, capsys):
    make_stripes.main(["--out-dir", str(tmp_path)])
    assert "wrote" in capsys.readouterr().out
    made = sorted(p.name for p in tmp_path.iterdir())
    assert len(made) == 9 and made == sorted(p.name for p in EXAMPLE.iterdir()
                                             if p.suffix in (".csv", ".toml"))
    for name in made:
        assert (tmp_path / name).read_bytes() == (EXAMPLE / name).read_bytes(), name


@pytest.mark.parametrize("where, says", [
    ("full", "gun.toml: cannot write: no space left on device"),
    ("dangling", "a dangling symbolic link")])  # a FIFO waits 2 s: test_fuzz_output's
def test_an_output_that_cannot_be_written_leaves_all_as_it_was(tmp_path, capsys, where, says):
    # the stripes are refused first if bad: these are good (one, round), the outputs not
    (tmp_path / "stripes.toml").write_text(ONE)
    (tmp_path / "s.csv").write_text(_csv(X, T + 1e-8 * np.cos(X * 7e3)))
    out = tmp_path / "out"
    if where == "dangling":
        out.symlink_to(tmp_path / "nowhere")
    else:
        out.mkdir()
        (out / "gun.toml").symlink_to("/dev/full")
    before = tree_state(tmp_path)
    code, text, err = run_cli(["calibrate", "--stripes", tmp_path / "stripes.toml", "--out",
                               out], capsys)
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1, err
    assert tree_state(tmp_path) == before
