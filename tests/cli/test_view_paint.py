"""``pollard-pin view`` never writes over what it reads, refuses a film.ply or thickness table
that is no film in one line, and frames the film it shows (cli/view.py, cli/view_paint.py)."""
import json
import os
import shutil

import numpy as np
import pytest
from cli_run import run_cli

from pollard_pin.io.ply import read_film_ply, write_film_ply


@pytest.fixture(scope="module")
def painted(panel_painted):
    """`paint --job examples/paint.toml --out DIR`, painted once per session
    (tests/examples_planned.py): DIR."""
    return panel_painted


def _copy(src, dst):
    shutil.copytree(src, dst)
    return dst


def _snapshot(folder):
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def _refused(capsys, argv, *words):
    code, out, err = run_cli(["view", *argv], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, err
    assert lines[0].startswith("pollard-pin view: error: ") and all(w in lines[0] for w in words)
    return lines[0]


@pytest.mark.parametrize("name", ["film.ply", "paint.json", "path.csv", "thickness.csv",
                                  "path.units.json"])
def test_the_page_never_replaces_a_file_of_the_paint_folder(painted, tmp_path, capsys, name):
    folder = _copy(painted, tmp_path / "d")
    before = _snapshot(folder)
    _refused(capsys, ["--paint", folder, "--html", folder / name],
             f"{folder / name}: is one of the inputs (the paint folder's {name})")
    assert _snapshot(folder) == before


def test_a_link_to_an_input_is_that_input(painted, tmp_path, capsys):
    folder = _copy(painted, tmp_path / "d")
    before = _snapshot(folder)
    (tmp_path / "page.html").symlink_to(folder / "film.ply")
    os.link(folder / "paint.json", tmp_path / "hard.html")
    for out, name in ((tmp_path / "page.html", "film.ply"), (tmp_path / "hard.html",
                                                             "paint.json")):
        # the output named by its path, or by its name where the whole line would pass 250
        # characters (pollard_pin.errors.say_less); the input by its path
        _refused(capsys, ["--paint", folder, "--html", out], f"{out.name}: is one of the inputs",
                 str(folder / name))
    assert _snapshot(folder) == before


def test_the_trajectory_and_the_workspace_map_are_inputs(painted, tmp_path, capsys):
    traj = tmp_path / "t.csv"
    shutil.copy(painted / "path.csv", traj)
    shutil.copy(painted / "path.units.json", tmp_path / "t.units.json")
    ws = tmp_path / "ws"
    ws.mkdir()
    (ws / "workspace.csv").write_text("x,y,z\n")
    before = _snapshot(tmp_path / "ws"), traj.read_bytes(), (tmp_path / "t.units.json").read_bytes()
    _refused(capsys, ["--trajectory", traj, "--html", traj], "(the trajectory)")
    _refused(capsys, ["--trajectory", traj, "--html", tmp_path / "t.units.json"],
             "(the trajectory's units)")
    _refused(capsys, ["--workspace", ws, "--html", ws / "workspace.csv"],
             "(the workspace map's workspace.csv)")
    after = _snapshot(tmp_path / "ws"), traj.read_bytes(), (tmp_path / "t.units.json").read_bytes()
    assert after == before


def _as_part(painted, folder, edit):
    """The panel's folder read as a part's (its film.ply), film.ply rewritten by ``edit``."""
    _copy(painted, folder)
    rep = json.loads((folder / "paint.json").read_text())
    rep["job"]["part"] = {"mesh": "film.ply"}
    (folder / "paint.json").write_text(json.dumps(rep))
    v, f, th = read_film_ply(folder / "film.ply")
    v, f, th = edit(v.copy(), f.copy(), th.copy())
    write_film_ply(folder / "film.ply", v, f, th, np.full((len(v), 4), 255, np.uint8))
    return rep["target"]


def _set(a, k, x):
    a.flat[k] = x
    return a


@pytest.mark.parametrize("edit, words", [
    (lambda v, f, th: (v, _set(f, 7, len(v) + 1000), th),
     "film.ply: face 2 (from 0): vertex index {n}, outside 0 … {m}"),
    (lambda v, f, th: (v, _set(f, 4, -7), th), "film.ply: face 1 (from 0): vertex index -7"),
    (lambda v, f, th: (v, f, _set(th, 5, -1e-6)), "vertex 5 (from 0): thickness = -1e-06 m"),
    (lambda v, f, th: (v, f, _set(th, 9, 25e-6 * 1e30)),
     "vertex 9 (from 0): thickness = 2.5e+25 m, over 1000 × the target 2.5e-05 m"),
    (lambda v, f, th: (v, f, _set(th, 3, np.inf)), "vertex 3 (from 0): thickness not finite (inf)"),
])
def test_a_film_ply_that_is_no_film_is_one_line(painted, tmp_path, capsys, edit, words):
    folder = tmp_path / "d"
    _as_part(painted, folder, edit)
    n = len(read_film_ply(painted / "film.ply")[0])
    html = tmp_path / "v.html"
    _refused(capsys, ["--paint", folder, "--html", html],
             words.format(n=n + 1000, m=n - 1))
    assert not html.exists()


def test_a_panel_film_over_the_absurd_bound_is_one_line(painted, tmp_path, capsys):
    folder = _copy(painted, tmp_path / "d")
    text = (folder / "thickness.csv").read_text().splitlines()
    cols = text[0].split(",")
    row = text[4].split(",")
    row[cols.index("thickness")] = "1e-1"
    text[4] = ",".join(row)
    (folder / "thickness.csv").write_text("\n".join(text) + "\n")
    _refused(capsys, ["--paint", folder, "--html", tmp_path / "v.html"],
             "thickness.csv: row 4: thickness = 0.1 m, over 1000 × the target 2.5e-05 m")
    assert not (tmp_path / "v.html").exists()


def test_the_page_frames_the_film_and_states_its_scale(painted, tmp_path, capsys):
    """The default view, read back from the page, against film.ply worked through by trimesh:
    the orbit centre is the painted faces' area-weighted centroid, the camera on their mean
    normal's gun side; the film's colours are film.ply's; the legend states the scale."""
    import trimesh

    from pollard_pin.io.table import read_result
    from pollard_pin.viz.meshcat_page import page_commands
    from pollard_pin.viz.viewer import ROOT as NODE

    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", painted, "--html", html, "--fps", "1"], capsys)
    assert code == 0, err
    page = html.read_text()
    cmds = page_commands(page)
    shift = next(c for c in cmds if c["type"] == "set_transform" and c["path"] == "/meshcat")
    centre = -np.asarray(shift["matrix"], float).reshape(4, 4).T[:3, 3]
    cam = next(c for c in cmds if c["type"] == "set_property" and c["property"] == "position"
               and c["path"].startswith("/Cameras/default"))["value"]
    offset = np.array([cam[0], -cam[2], cam[1]])  # MeshCat's y-up camera frame to the world

    mesh = trimesh.load(painted / "film.ply", process=False)
    th = mesh.metadata["_ply_raw"]["vertex"]["data"]["thickness"]
    target = json.loads((painted / "paint.json").read_text())["target"]
    painted_faces = th[mesh.faces].mean(axis=1) >= 0.5 * target
    area = mesh.area_faces[painted_faces]
    want = (mesh.triangles_center[painted_faces] * area[:, None]).sum(axis=0) / area.sum()
    assert np.abs(centre - want).max() < 1e-6  # float32 film.ply positions: 1.2e-8 achieved
    n = (mesh.face_normals[painted_faces] * area[:, None]).sum(axis=0)
    path = read_result(painted / "path.csv")
    gun = np.array([path["x"].mean(), path["y"].mean(), path["z"].mean()])
    n *= np.sign(n @ (gun - want))
    cos = offset @ n / np.linalg.norm(offset) / np.linalg.norm(n)
    assert np.degrees(np.arccos(min(cos, 1.0))) < 0.5  # a flat panel: 0.0° achieved
    assert offset @ (gun - centre) > 0  # on the gun's side

    film = next(c for c in cmds if c["type"] == "set_object" and c["path"].endswith(
        f"{NODE}/paint"))
    colour = film["object"]["geometries"][0]["data"]["attributes"]["color"]["array"]
    colour = np.frombuffer(getattr(colour, "data", colour), np.float32).reshape(-1, 3)
    ply = np.asarray(mesh.visual.vertex_colors[:, :3], float) / 255
    assert np.abs(colour - ply).max() < 1.5 / 255  # film.ply rounds to bytes: 0.49/255
    assert 'id="film-legend"' in page and "film thickness [µm] (target 25 ± 10 %)" in page


def test_the_report_paint_wrote_reads_back_through_its_schema(painted):
    """paint.json as ``paint`` writes it today: read by the schema view reads it with, and
    written back, the same text (tests/outputs/test_schema.py: every example job's)."""
    from pollard_pin.outputs.schema import dumps, read_paint_json

    text = (painted / "paint.json").read_text(encoding="utf-8")
    report = read_paint_json(painted / "paint.json")
    assert report.grid is not None and report.thickness is not None and report.version
    assert dumps(report) == text
