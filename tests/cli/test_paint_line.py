"""`pollard-pin paint` of a job with [line] (docs/model.md §24): outputs, run and size on the
world path, bad inputs one line with nothing written."""
import json
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_and_size, run_cli

from pollard_pin.cli import main
from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv

ROOT = Path(__file__).resolve().parents[2]
JOB = ROOT / "examples" / "line.toml"
ACT = ROOT / "examples" / "actuators.toml"


@pytest.fixture(scope="module")
def painted(tmp_path_factory):
    out = tmp_path_factory.mktemp("line") / "out"
    # compliance not asserted here (tests/painting/checks/test_compliance.py checks it): left out
    assert main(["paint", "--job", str(JOB), "--out", str(out), "--resolution", "0.005",
                 "--no-compliance"]) == 0
    return out


def _line_outputs(folder) -> dict:
    """paint.json of a line job at 0.03 m/s along +y, its files and line table checked."""
    assert {"path.csv", "thickness.csv", "film.ply", "paint.json", "thickness.png"} <= {
        p.name for p in folder.iterdir()}
    rep = json.loads((folder / "paint.json").read_text())
    line = rep["line"]
    for key in ("speed", "direction", "start_delay", "window", "travel", "cycle", "min_pitch",
                "parts_per_hour", "upper_bound"):
        assert key in line, key
    assert rep["job"]["line"] == {"speed": 0.03, "direction": [0.0, 1.0, 0.0]}
    assert line["min_pitch"] == pytest.approx(0.03 * line["cycle"])
    assert line["parts_per_hour"] == pytest.approx(3600 / line["cycle"], rel=1e-12)
    return rep


def test_outputs(painted):
    rep = _line_outputs(painted)
    # auto: across the strip, leading end first (strokes along it are out of reach), no wait
    why = rep["strokes"].pop("why")
    assert rep["strokes"] == {"direction": "across", "step_from": "leading", "dwell_s": 0.0}
    assert why.startswith("auto: the shortest cycle that paints, ")  # and why not along:
    assert "; along: strokes along" not in why and "; along: all 8 passes out of reach" in why
    assert rep["thickness"]["within_5pct"] >= 0.99 and rep["thickness"]["within_10pct"] == 1
    table = read_result(painted / "thickness.csv")
    # the panel at its t = 0 pose, world coordinates: centred at y = −0.75
    assert abs(table["y"].mean() + 0.75) < 1e-12 and np.abs(table["x"] - 0.70).max() < 1e-15
    assert "t = 0 pose" in (painted / "thickness.units.json").read_text()
    assert b"comment film: the part at its t = 0 pose" in (painted / "film.ply").read_bytes()
    # film.ply: the same film on the same points (float32 positions: 6e-8 m at 0.75 m)
    from pollard_pin.io.ply import read_film_ply

    v, _, th = read_film_ply(painted / "film.ply")
    assert np.array_equal(th, table["thickness"])
    assert np.abs(v - np.column_stack([table["x"], table["y"], table["z"]])).max() < 1e-7
    # paint.json says what film.ply's colours mean, as a still job's does: target ± 10 %
    assert rep["film_ply"]["range"] == pytest.approx([0.9 * 25e-6, 1.1 * 25e-6], rel=1e-12)


def test_run_and_size_take_the_world_path(painted, capsys, tmp_path):
    traj = from_csv(painted / "path.csv")
    rep = json.loads((painted / "paint.json").read_text())
    assert traj.t[-1] == pytest.approx(rep["line"]["path_time"], rel=1e-12)
    first = int(np.argmax(np.abs(traj.d_poses).max(axis=1) > 0))  # leaves its start pose
    assert traj.t[-1] - traj.t[first] <= rep["line"]["cycle"] <= traj.t[-1] - traj.t[first - 1]
    sized = run_and_size(painted / "path.csv", ACT, capsys, tmp_path)
    assert sized["given_within_ratings"] is True
    for name, m in rep["motors"].items():
        given = sized["actuators"][name]
        assert given["peak_motor_torque_ratio"] <= 1.0 and given["peak_motor_speed_ratio"] <= 1
        assert m["peak_torque"] >= given["peak_motor_torque_ratio"] - 1e-12, name


def test_view_paint_of_a_line(painted, tmp_path, capsys):
    """The viewer takes the folder (the film drawn at the part's t = 0 pose)."""
    code, _, err = run_cli(["view", "--paint", painted, "--html", tmp_path / "v.html"], capsys)
    assert code == 0, err


def _refused(job, tmp_path, capsys, words: str) -> None:
    """paint of ``job`` is one line on stderr with ``words``, exit 2, and writes nothing."""
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin paint: error: "), err
    assert words in lines[0]
    assert not out.exists()


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace("direction = [0.0, 1.0, 0.0]", "direction = [0.0, 0.0, 0.0]"),
     "zero length"),
    (lambda t: t.replace("speed = 0.03 ", "speed = 0.0 "),
     "must be > 0; a line speed is 0 < s ≤ 2 m/s"),
    (lambda t: t.replace("speed = 0.03 ", "speed = -0.01 "),
     "'line.speed' = -0.01: must be > 0; a line speed is 0 < s ≤ 2 m/s"),
    (lambda t: t.replace("speed = 0.03 ", "speed = nan "),
     "must be a finite number; a line speed is 0 < s ≤ 2 m/s"),
    (lambda t: t.replace("speed = 0.03 ", "speed = 30.0 "), "must be at most 2 m/s"),
    (lambda t: t.replace("center = [0.70, -0.75, 0.16]", "center = [0.70, 2.5, 0.16]"),
     "never comes within reach"),
    # the interval, to 1 % (tests/painting/line/test_speeds.py); twice a speed that paints
    # (0.03375 m/s), so every speed its fast end's bisection tries fails, early in the plan
    (lambda t: t.replace("speed = 0.03 ", "speed = 0.0675 "),
     "; it paints at 0.0"),
    # refused before any reach is checked or speed searched (143 s of search otherwise)
    (lambda t: t.replace("speed = 0.03 ", "speed = 1e-12 "),
     "carries the part 5e-10 m in the longest path the budget allows"),
])
def test_bad_line_jobs_are_one_line_and_write_nothing(tmp_path, capsys, edit, words):
    job = tmp_path / "job.toml"
    text = edit(JOB.read_text())
    assert text != JOB.read_text()
    job.write_text(text)
    _refused(job, tmp_path, capsys, words)


@pytest.mark.parametrize("flags, words", [
    (["--strokes", "along"], "strokes along the travel (forced): all 8 passes out of reach"),
    (["--strokes", "along", "--step-from", "trailing"], "step across it, from no end"),
    (["--strokes", "sideways"], "invalid choice: 'sideways'"),
])
def test_a_forced_strategy_that_cannot_paint_is_one_line(tmp_path, capsys, flags, words):
    """--strokes/--step-from (docs/model.md §24.2): the 0.90 m strip is longer than the
    reach, so strokes along it cannot paint; named, exit 2, nothing written."""
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", JOB, "--out", out, *flags], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and words in lines[-1], err
    assert not out.exists()


@pytest.mark.parametrize("flag", ["--max-line-speed", "--speeds"])
def test_max_line_speed_needs_a_line(tmp_path, capsys, flag):
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", ROOT / "examples" / "paint.toml", "--out", out,
                            flag], capsys)
    assert flag in err
    assert code == 2 and "no [line] table" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_view_shows_the_part_riding(painted, tmp_path, capsys):
    """The film panel's node is animated along the line: at key frame time t it is shifted
    by speed·t·direction."""
    from pollard_pin.viz.meshcat_page import page_commands

    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", painted, "--html", html, "--fps", "1"], capsys)
    assert code == 0, err
    anim = [c for c in page_commands(html.read_text()) if c.get("type") == "set_animation"]
    assert len(anim) == 1
    tracks = [a for a in anim[0]["animations"] if a["path"].endswith("pollard/paint")]
    assert len(tracks) == 1
    (track,) = [t for t in tracks[0]["clip"]["tracks"] if t["name"] == ".position"]
    times = np.array([k["time"] for k in track["keys"]], float)  # frames at 1 fps: seconds
    values = np.array([k["value"] for k in track["keys"]], float)
    speed = json.loads((painted / "paint.json").read_text())["line"]["speed"]
    assert len(times) > 10
    assert np.abs(values[:, 1] - speed * times).max() < 1e-4
    assert np.abs(values[:, [0, 2]]).max() < 1e-9



@pytest.mark.parametrize("speed, direction, words", [
    (1e308, [0.0, 1e308, 0.0], "'line.speed' = 1e+308: must be at most 2 m/s"),  # drew inf
    (0.03, [0.0, 0.0, 0.0], "has zero length"),
    (True, [0.0, 1.0, 0.0], "'line.speed' = True: must be a number"),
])
def test_view_refuses_a_tampered_line(painted, tmp_path, capsys, speed, direction, words):
    """view reads paint.json's line by the job's own rule (paint.line_job)."""
    import shutil

    folder = tmp_path / "p"
    shutil.copytree(painted, folder)
    rep = json.loads((folder / "paint.json").read_text())
    rep["line"].update(speed=speed, direction=direction)
    (folder / "paint.json").write_text(json.dumps(rep))
    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", folder, "--html", html], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1 and words in err, err
    assert not html.exists()

# A [part] on the line: a small strip (tests/line_parts.py), a coarse film.

@pytest.fixture(scope="module")
def part_painted(tmp_path_factory):
    from line_parts import write_line_part

    folder = tmp_path_factory.mktemp("line_part")
    out = folder / "out"
    job = write_line_part(folder)
    # across the travel: auto keeps along for this short strip (a shorter cycle, §24.2);
    # compliance not asserted here (tests/painting/checks/test_compliance.py checks it)
    assert main(["paint", "--job", str(job), "--out", str(out), "--resolution", "0.007",
                 "--strokes", "across", "--no-compliance"]) == 0
    return out


def test_part_outputs(part_painted):
    rep = _line_outputs(part_painted)
    line = rep["line"]
    assert "part" in rep["job"] and rep["direction"] == "vertical"
    assert line["upper_bound"] == pytest.approx((line["part_length"] + line["window_length"])
                                                / (rep["lower_bound"]), rel=1e-12)
    assert rep["thickness"]["within_5pct"] >= 0.99 and rep["thickness"]["within_10pct"] == 1
    table = read_result(part_painted / "thickness.csv")
    # the part at its t = 0 pose, world coordinates: a 0.30 m strip centred at y = −0.45
    assert abs(0.5 * (table["y"].min() + table["y"].max()) + 0.45) < 1e-3
    assert "t = 0 pose" in (part_painted / "thickness.units.json").read_text()
    assert b"comment film: the part at its t = 0 pose" in (part_painted / "film.ply").read_bytes()
    traj = from_csv(part_painted / "path.csv")
    assert traj.t[-1] == pytest.approx(line["path_time"], rel=1e-12)
    first = int(np.argmax(np.abs(traj.d_poses).max(axis=1) > 0))  # leaves its start pose
    assert traj.t[-1] - traj.t[first] <= line["cycle"] <= traj.t[-1] - traj.t[first - 1]


def test_part_run_and_size_take_the_world_path(part_painted, capsys, tmp_path):
    sized = run_and_size(part_painted / "path.csv", ACT, capsys, tmp_path)
    assert sized["given_within_ratings"] is True
    rep = json.loads((part_painted / "paint.json").read_text())
    for name, m in rep["motors"].items():
        given = sized["actuators"][name]
        assert m["peak_torque"] >= given["peak_motor_torque_ratio"] - 1e-12, name


def test_view_shows_the_mesh_riding(part_painted, tmp_path, capsys):
    """A part's film.ply node rides the line as the panel's does."""
    from pollard_pin.viz.meshcat_page import page_commands

    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", part_painted, "--html", html, "--fps", "1"],
                           capsys)
    assert code == 0, err
    anim = [c for c in page_commands(html.read_text()) if c.get("type") == "set_animation"]
    tracks = [a for a in anim[0]["animations"] if a["path"].endswith("pollard/paint")]
    assert len(tracks) == 1
    (track,) = [t for t in tracks[0]["clip"]["tracks"] if t["name"] == ".position"]
    times = np.array([k["time"] for k in track["keys"]], float)
    values = np.array([k["value"] for k in track["keys"]], float)
    assert len(times) > 10 and np.abs(values[:, 1] - 0.03 * times).max() < 1e-4


@pytest.mark.parametrize("kwargs, words", [
    ({"position": (0.0, 2.5, 0.0)}, "never comes within reach: the gun's track at the part's "
                                    "centre runs through"),
    # the interval (test_speeds.py), searched over some 20 plans: a 0.08 m strip plans in
    # two thirds of the 0.30 m one's time (it paints at 0.0009277–0.1516 m/s). slow: ~11 s of
    # CPU for a path the default suite keeps: the same CLI → line_plan → plan_line_job →
    # plan_or_name_fastest chain refusing a panel on the line (test_bad_line_jobs_..., speed
    # 0.0675), a part's too-fast refusals and bracketing (painting/line/test_part.py,
    # test_fastest_plans_...), the refusal's words (test_speeds.py, stand-in planners)
    pytest.param({"speed": 0.4, "width": 0.08}, "; it paints at 0.0", marks=pytest.mark.slow),
])
def test_bad_part_line_jobs_are_one_line_and_write_nothing(tmp_path, capsys, kwargs, words):
    from line_parts import write_line_part

    job = write_line_part(tmp_path, **kwargs)
    _refused(job, tmp_path, capsys, words)


@pytest.mark.parametrize("rotation, head, why", [
    # stood on end: every pass 0.90 m tall
    ("[90.0, 0.0, 0.0]", "all 8 passes out of reach", " mm too tall for the reach"),
    # turned 25° about z: the ends too far from (or too near) the robot, the middle fits
    ("[0.0, 0.0, 25.0]", "passes 1–13, 43–52 of 52 out of reach", ") m at t = 0) is ever in "
                                                                  "reach"),
])
def test_passes_out_of_reach_are_named(tmp_path, capsys, rotation, head, why):
    """examples/line_part.toml's 0.90 m strip turned: one line naming the passes out of reach
    and why, before any speed search (seconds, not minutes)."""
    text = (ROOT / "examples" / "line_part.toml").read_text()
    mesh = (ROOT / "examples" / "parts" / "long_strip.stl").as_posix()
    turned = text.replace('"parts/long_strip.stl"', f'"{mesh}"').replace(
        "facing = ", f"rotation = {rotation}\nfacing = ")
    assert turned.count("rotation") == 1 and mesh in turned
    job = tmp_path / "job.toml"
    job.write_text(turned)
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2 and not out.exists()
    (line,) = err.strip().splitlines()
    msg = line.removeprefix("pollard-pin paint: error: ").split(" (nothing written")[0]
    assert msg.startswith(head + " at any place on the line: "), msg
    assert len(msg) <= 250 and why in msg, msg
