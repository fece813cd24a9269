"""``pollard-pin workspace`` and ``view --workspace`` as users meet them: the files, their
agreement with the library, and one-line errors (exit 2) with nothing written."""
import json
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli

import pollard_pin as pp
from pollard_pin.io.table import read_result

ROOT = Path(__file__).resolve().parent.parent.parent
COARSE = ["--resolution", "0.02", "--quiet"]




@pytest.mark.parametrize("fmt", ["csv", "parquet"])
def test_plane_files_match_the_library(robot, tmp_path, capsys, fmt):
    out = tmp_path / "ws"
    code, text, err = run_cli(["workspace", "--plane", "x=0.55", "--out", str(out), "--format",
                            fmt, *COARSE], capsys)
    assert code == 0, err
    ws = pp.map_workspace(robot, "x=0.55", pp.WorkspaceOptions(resolution=0.02))
    table = read_result(out / f"workspace.{fmt}")
    for name, col in ws.columns.items():
        np.testing.assert_array_equal(table[name], np.asarray(col, dtype=float), err_msg=name)
    assert table.units["reason"].startswith("code") and table.units["x"] == "m"
    summary = json.loads((out / "workspace.json").read_text())
    assert summary["area"] == ws.summary["area"]
    assert summary["largest_rectangle"] == ws.rectangle.as_dict()
    assert summary["reason_codes"]["0"] == "reachable"
    assert (out / "workspace.png").stat().st_size > 10_000
    assert f"area {ws.summary['area']:.5g} ± {ws.summary['area_bound']:.2g} m²" in text
    assert "largest rectangle" in text and "global conditioning index" in text


def test_orientation_in_degrees_and_actuators(robot, tmp_path, capsys):
    out = tmp_path / "ws"
    code, text, err = run_cli(["workspace", "--out", str(out), "--orientation", "0,10,0",
                            "--bounds", "y=-0.3:0.3,z=-0.1:0.3", "--actuators",
                            str(ROOT / "examples" / "actuators.toml"), *COARSE], capsys)
    assert code == 0, err
    table = read_result(out / "workspace.csv")
    np.testing.assert_allclose(table["theta"], np.radians(10.0), rtol=1e-15)
    assert table["y"].min() == -0.3 and table["z"].max() == pytest.approx(0.3)
    ok = table["reachable"] == 1
    assert np.isfinite(table["payload_capacity"][ok]).all()
    assert "payload capacity" in text
    # the example's drives have stiffnesses: kmin, f1, sag and their figure (docs/model.md §27.6)
    for name, unit in (("kmin", "N/m"), ("f1", "Hz"), ("sag", "m")):
        assert np.isfinite(table[name][ok]).all() and np.isnan(table[name][~ok]).all()
        assert table.units[name] == unit
    summary = json.loads((out / "workspace.json").read_text())
    assert summary["stiffness"]["kmin"]["min"] == table["kmin"][ok].min()
    assert (out / "workspace_stiffness.png").stat().st_size > 0
    assert "stiffness over the reachable points" in text


def test_volume_streams(robot, tmp_path, capsys):
    out = tmp_path / "vol"
    code, text, err = run_cli(["workspace", "--volume", "--resolution", "0.05", "--quiet",
                            "--out", str(out)], capsys)
    assert code == 0, err
    summary = json.loads((out / "workspace.json").read_text())
    table = read_result(out / "workspace.csv")
    assert len(table) == summary["grid"]["points"]
    assert summary["volume"] == pytest.approx(table["reachable"].sum() * 0.05 ** 3)
    assert not (out / "workspace.png").exists()


BAD = [
    (["--plane", "x=3"], ["misses the robot", "reachable region spans"]),
    (["--plane", "x=0.55", "--bounds", "y=1:2"], ["no point", "reachable region spans"]),
    (["--resolution", "0"], ["--resolution", "must be > 0"]),
    (["--resolution", "-0.01"], ["--resolution"]),
    (["--resolution", "1e-5"], ["would need", "at least"]),
    (["--volume", "--resolution", "0.001"], ["would need", "at least"]),
    (["--orientation", "1,2"], ["--orientation", "three"]),
    (["--orientation", "a,b,c"], ["--orientation"]),
    (["--orientation", "1e300,0,0"], ["psi = 1e+300 deg is absurd", "5.72958e+07 deg"]),
    (["--bounds", "y=0.3"], ["--bounds", "AXIS=LOW:HIGH"]),
    (["--bounds", "y=0.3:-0.3"], ["below the upper bound"]),
    (["--bounds", "x=0:1"], ["other two axes"]),
    (["--plane", "q=1"], ["--plane", "x, y or z"]),
    (["--plane", "x0.5"], ["--plane", "AXIS=VALUE"]),
    (["--plane", "x=0.5", "--volume"], ["not allowed"]),
    (["--actuators", "missing.toml"], ["missing.toml"])]


@pytest.mark.parametrize("extra, words", BAD)
def test_bad_input_one_line_exit_2_nothing_written(tmp_path, capsys, monkeypatch, extra,
                                                    words):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(["workspace", "--out", "ws", "--quiet", *extra], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    for w in words:
        assert w in lines[0], lines[0]
    assert not (tmp_path / "ws").exists()


def test_view_draws_the_reachable_cloud(tmp_path, capsys):
    out = tmp_path / "ws"
    assert run_cli(["workspace", "--out", str(out), *COARSE], capsys)[0] == 0
    html = tmp_path / "view.html"
    code, _, err = run_cli(["view", "--samples", "51", "--quiet", "--html", str(html),
                         "--workspace", str(out)], capsys)
    assert code == 0, err
    from pollard_pin.viz.meshcat_page import page_commands

    cloud = [c for c in page_commands(html.read_text()) if c.get("path", "").endswith(
        "/workspace")]
    assert len(cloud) == 1
    code, _, err = run_cli(["view", "--samples", "51", "--quiet", "--html", str(html),
                         "--workspace", str(tmp_path)], capsys)
    assert code == 2 and "no workspace.csv" in err


@pytest.mark.parametrize("k", ["0.001", "100.0"])
def test_sag_beyond_the_linear_model_is_flagged(tmp_path, capsys, k):
    """Drives so soft that the weight turns them beyond the linear model's bound (docs/model.md
    §27.2) leave the sag blank (NaN) at those points, count them in workspace.json and say so
    in the summary; workspace.json stays strict JSON; kmin and f1, the load-free figures,
    stay. A stiffness out of range (1e-300, which used to write Infinity) is one line."""
    act = tmp_path / "act.toml"
    toml = (ROOT / "examples" / "actuators.toml").read_text()
    wrist = "0.001" if k == "0.001" else "10.0"  # 30 × softer than the examples'
    act.write_text(toml.replace("stiffness = 3000.0", f"stiffness = {k}")
                   .replace("stiffness = 300.0", f"stiffness = {wrist}"))
    out = tmp_path / "ws"
    code, text, err = run_cli(["workspace", "--out", str(out), "--actuators", str(act),
                               *COARSE], capsys)
    assert code == 0, err
    table = read_result(out / "workspace.csv")
    ok = table["reachable"] == 1
    blank = int(np.isnan(table["sag"][ok]).sum())
    raw = (out / "workspace.json").read_text()
    summary = json.loads(raw, parse_constant=lambda c: pytest.fail(f"{c} in workspace.json"))
    assert 0 < blank == summary["stiffness"]["sag_beyond_linear_points"]
    assert np.isfinite(table["kmin"][ok]).all() and np.isfinite(table["f1"][ok]).all()
    assert f"sag blank at {blank:,} points" in text
    if k == "0.001":
        assert blank == ok.sum() and "sag" not in summary["stiffness"]
    else:  # some points keep their sag, all of them within the bound's reach
        assert blank < ok.sum() and summary["stiffness"]["sag"]["max"] < 0.01
    act.write_text(toml.replace("stiffness = 3000.0", "stiffness = 1e-300"))
    bad = tmp_path / "bad"
    code, _, err = run_cli(["workspace", "--out", str(bad), "--actuators", str(act), *COARSE],
                           capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, err
    assert "'theta21.stiffness' = 1e-300: must be between 0.001 and 1e+09" in err, err
    assert not bad.exists()


def test_an_out_name_too_long_for_the_file_system_is_one_line(tmp_path, capsys):
    # the folder's own check (is it a file?) asked Path.exists(), whose ENAMETOOLONG was a
    # traceback before any output check
    out = tmp_path / ("w" * 300)
    code, _, err = run_cli(["workspace", "--quiet", "--out", out], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, err
    assert lines[0].startswith("pollard-pin workspace: error: ") and lines[0].endswith(
        "holds a name of 300 bytes, over the 255 a file system takes: give a shorter one "
        "(nothing written)"), lines[0]
    assert list(tmp_path.iterdir()) == []
