"""``pollard-pin view --paint DIR`` of a paint cell (cli/view_cell.py): a folder of the cell's
shape (paint.json with robots, DIR/<name>/path.csv each, the film of the whole part) drawn
as a static page with every robot at its base; its bad folders refused in one line and its
files never overwritten."""
import json

import numpy as np
import pytest
import trimesh
from cli_run import run_cli

from pollard_pin.io.ply import write_film_ply
from pollard_pin.io.trajectory import to_csv
from pollard_pin.paths.trajectory import Trajectory
from pollard_pin.viz import meshcat_page, viewer

TARGET = 25e-6
ROBOTS = [{"name": "low", "base": [0.0, 0.0, 0.0], "rotation": [0.0, 0.0, 0.0]},
          {"name": "high", "base": [0.0, 0.75, 0.17], "rotation": [0.0, 0.0, 0.0]}]
GRAVITY = [0.0, 0.0, -9.81]


def _record_robot(path, r):
    """What paint records in a robot's path.csv sidecar: the robot and its gravity
    (outputs/paint_cell_files.py robot_metadata)."""
    side = path.with_name("path.units.json")
    units = json.loads(side.read_text())
    units["metadata"].update(robot=dict(r), gravity_base=GRAVITY)
    side.write_text(json.dumps(units))


def _program(params, t0, n=61):
    """2 s of the home pose swaying across, on the cell's clock from ``t0``."""
    t = t0 + np.linspace(0.0, 2.0, n)
    w = 2.0
    poses = np.tile(np.array(params.home_pose, float), (n, 1))
    d, dd = np.zeros_like(poses), np.zeros_like(poses)
    poses[:, 1] += 0.1 * np.sin(w * (t - t0))
    d[:, 1] = 0.1 * w * np.cos(w * (t - t0))
    dd[:, 1] = -0.1 * w * w * np.sin(w * (t - t0))
    return Trajectory(t, poses, d, dd, name="cell test")


@pytest.fixture(scope="module")
def folder(tmp_path_factory, robot):
    out = tmp_path_factory.mktemp("cell") / "out"
    out.mkdir()
    for r, t0 in zip(ROBOTS, (0.0, 1.0)):
        (out / r["name"]).mkdir()
        to_csv(_program(robot.params, t0), out / r["name"] / "path.csv",
               spray=np.ones(61))
        _record_robot(out / r["name"] / "path.csv", r)
    part = trimesh.creation.box((0.01, 0.8, 0.35))
    part.apply_translation((0.705, -0.75, 0.16))
    th = np.full(len(part.vertices), TARGET)
    write_film_ply(out / "film.ply", part.vertices, part.faces, th,
                   np.full((len(th), 4), 255, dtype=np.uint8))
    (out / "thickness.csv").write_text("x,y,z,thickness\n0,0,0,2.5e-5\n")
    report = {"job": {"part": {"mesh": "plate.stl"}}, "target": TARGET,
              "line": {"speed": 0.03, "direction": [0.0, 1.0, 0.0]},
              "robots": [dict(r, gravity_base=GRAVITY) for r in ROBOTS]}
    (out / "paint.json").write_text(json.dumps(report))
    return out


def test_the_page_draws_every_robot_and_the_riding_film(folder, tmp_path, capsys):
    page = tmp_path / "cell.html"
    code, _, err = run_cli(["view", "--paint", folder, "--html", page, "--fps", "10"], capsys)
    assert code == 0, err
    cmds = meshcat_page.page_commands(page.read_text())
    placed = {c["path"]: np.array(c["matrix"]).reshape(4, 4).T for c in cmds
              if c["type"] == "set_transform"}
    for r in ROBOTS:
        np.testing.assert_allclose(placed[f"/meshcat/{viewer.ROOT}/{r['name']}"][:3, 3],
                                   r["base"], atol=1e-12)
    (anim,) = [c for c in cmds if c["type"] == "set_animation"]
    clips = {a["path"]: a["clip"] for a in anim["animations"]}
    film = clips[f"/meshcat/{viewer.ROOT}/paint"]
    (track,) = [t for t in film["tracks"] if t["name"] == ".position"]
    times = np.array([k["time"] for k in track["keys"]]) / film["fps"]
    pos = np.array([k["value"] for k in track["keys"]])
    # the film rides 0.03 m/s along +y on the cell's clock, 0 … 3 s (achieved 1e-16)
    np.testing.assert_allclose(times, np.arange(31) / 10.0, atol=1e-9)
    np.testing.assert_allclose(pos[:, 1], 0.03 * times, atol=1e-9)
    assert "2 robots" in err


def test_an_output_over_a_robots_program_is_refused(folder, capsys):
    target = folder / "high" / "path.csv"
    before = target.read_bytes()
    code, _, err = run_cli(["view", "--paint", folder, "--html", target], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "is one of the inputs (the paint folder's high/path.csv)" in err
    assert target.read_bytes() == before


@pytest.mark.parametrize("change, words", [
    (lambda rep: rep["robots"].append(dict(ROBOTS[0])), "two robots are named 'low'"),
    (lambda rep: rep["robots"][1].update(base=[0.0, float("nan"), 0.0]), "robot[1].base[1]"),
    (lambda rep: rep["robots"].append({"name": "mid", "base": [0.0, 0.4, 0.0]}),
     "robot 'mid' has no mid/path.csv"),
])
def test_bad_cell_folders_are_one_line(folder, tmp_path, capsys, change, words):
    import shutil

    bad = tmp_path / "bad"
    shutil.copytree(folder, bad)
    rep = json.loads((bad / "paint.json").read_text())
    change(rep)
    (bad / "paint.json").write_text(json.dumps(rep))
    code, _, err = run_cli(["view", "--paint", bad, "--html", tmp_path / "p.html"], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and words in lines[0], err
    assert not (tmp_path / "p.html").exists()


def _swap_folders(bad):
    (bad / "low").rename(bad / "tmp")
    (bad / "high").rename(bad / "low")
    (bad / "tmp").rename(bad / "high")


def _move_base(bad):
    rep = json.loads((bad / "paint.json").read_text())
    rep["robots"][1]["base"] = [0.0, 5.75, 0.17]  # 5 m down the line
    (bad / "paint.json").write_text(json.dumps(rep))


def _turn_base(bad):
    rep = json.loads((bad / "paint.json").read_text())
    rep["robots"][0]["rotation"] = [90.0, 0.0, 0.0]
    (bad / "paint.json").write_text(json.dumps(rep))


def _no_robot_recorded(bad):
    side = bad / "high" / "path.units.json"
    units = json.loads(side.read_text())
    del units["metadata"]["robot"]
    side.write_text(json.dumps(units))


@pytest.mark.parametrize("tamper, words", [
    (_swap_folders, "robot 'low': paint.json's name 'low' is not its low/path.csv's 'high'"),
    (_move_base, "robot 'high': paint.json's base [0, 5.75, 0.17] is not its high/path.csv's "
                 "[0, 0.75, 0.17]"),
    (_turn_base, "robot 'low': paint.json's rotation [90, 0, 0] is not"),
    (_no_robot_recorded, "robot 'high': paint.json's name 'high' is not its high/path.csv's "
                         "nothing"),
])
def test_a_folder_at_odds_with_itself_is_one_line(folder, tmp_path, capsys, tamper, words):
    # paint.json's robots are what each robot's path.csv records (name, base, rotation,
    # gravity): a moved base or swapped folders once drew and exited 0
    import shutil

    bad = tmp_path / "bad"
    shutil.copytree(folder, bad)
    tamper(bad)
    code, _, err = run_cli(["view", "--paint", bad, "--html", tmp_path / "p.html"], capsys)
    lines = err.strip().replace(str(tmp_path), "DIR").splitlines()
    assert code == 2 and len(lines) == 1 and len(lines[0]) <= 250 and words in lines[0], err
    assert not (tmp_path / "p.html").exists()
