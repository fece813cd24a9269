"""`pollard-pin paint` end to end: plan → files → run → size → film, the viewer overlay, and
one line with exit status 2 (nothing written) for each bad input."""
import json
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_and_size, run_cli

from pollard_pin.cli import main
from pollard_pin.io.table import read_result
from pollard_pin.io.trajectory import from_csv

ROOT = Path(__file__).resolve().parents[2]
JOB = ROOT / "examples" / "paint.toml"
ACT = ROOT / "examples" / "actuators.toml"




@pytest.fixture(scope="module")
def painted(panel_painted):
    """`paint --job examples/paint.toml --out DIR`, painted once per session
    (tests/examples_planned.py): DIR."""
    return panel_painted


def test_outputs(painted):
    names = {p.name for p in painted.iterdir()}
    assert {"path.csv", "thickness.csv", "paint.json", "thickness.png"} <= names
    rep = json.loads((painted / "paint.json").read_text())
    for key in ("job", "thickness", "cycle_time", "passes", "spacing", "speed", "coats",
                "motors"):
        assert key in rep
    assert set(rep["thickness"]) >= {"mean", "min", "max", "std", "uniformity",
                                     "within_10pct"}
    # the example meets the acceptance: nothing more printed (tests/painting/test_summary.py)
    assert rep["film_check"]["meets"] is True and rep["film_check"]["outside_10pct"] == 0.0
    assert list(rep)[list(rep).index("target") + 1] == "film_check"
    assert rep["job"]["gun"] == {"standoff": 0.15, "sigma": 0.01, "flow": 1.5e-7}
    table = read_result(painted / "thickness.csv")
    assert list(table.columns) == ["x", "y", "z", "nx", "ny", "nz", "area", "u", "v",
                                   "thickness"]
    assert table.units["thickness"] == "m" and table.units["u"] == "m"
    assert len(table) == rep["grid"]["nu"] * rep["grid"]["nv"]
    assert table["thickness"].min() == rep["thickness"]["min"]
    # the world points lie on the panel: x = 0.70 for the example's normal (−1, 0, 0)
    assert np.abs(table["x"] - 0.70).max() < 1e-15
    png = (painted / "thickness.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_panel_film_ply_and_spray(painted):
    """A [panel] job has a part's outputs too: path.csv with the trigger (on throughout) and
    film.ply, the film grid's cells as triangles wound about the panel's outward normal
    (−1, 0, 0), its thickness property the table's."""
    import trimesh

    from pollard_pin.io.ply import read_film_ply

    assert (read_result(painted / "path.csv")["spray"] == 1.0).all()
    rep = json.loads((painted / "paint.json").read_text())
    nu, nv = rep["grid"]["nu"], rep["grid"]["nv"]
    table = read_result(painted / "thickness.csv")
    v, f, th = read_film_ply(painted / "film.ply")
    assert len(v) == nu * nv and len(f) == 2 * (nu - 1) * (nv - 1)
    assert np.array_equal(th, table["thickness"])
    # float32 positions (io/ply.py): to 6e-8 m at 0.7 m
    assert np.abs(v - np.column_stack([table["x"], table["y"], table["z"]])).max() < 1e-7
    ply = trimesh.load(painted / "film.ply", process=False)
    assert ply.visual.vertex_colors.shape == (len(v), 4)
    assert (ply.face_normals @ [-1.0, 0.0, 0.0] > 1 - 1e-9).all()
    span = np.ptp(table["y"]) * np.ptp(table["z"])  # the grid's rectangle
    assert abs(ply.area / span - 1) < 1e-6
    assert rep["film_ply"]["colour_map"]


def test_panel_thickness_table_has_the_parts_columns(painted):
    """thickness.csv of a panel carries a part's columns: the unit normal towards the robot
    and each point's share of the area, which sum to the panel's width × height (0.26 × 0.12
    m; achieved to round-off, asserted 1e-12) and weight the film as the trapezoid rule does
    (the area-weighted mean against an independent np.trapezoid over the grid, 1e-12)."""
    rep = json.loads((painted / "paint.json").read_text())
    nu, nv = rep["grid"]["nu"], rep["grid"]["nv"]
    table = read_result(painted / "thickness.csv")
    n = np.column_stack([table["nx"], table["ny"], table["nz"]])
    assert np.abs(n - [-1.0, 0.0, 0.0]).max() == 0.0
    area = np.asarray(table["area"])
    assert abs(area.sum() / (0.26 * 0.12) - 1) < 1e-12
    U, V = np.asarray(table["u"])[:nu], np.asarray(table["v"])[::nu]
    th = np.asarray(table["thickness"]).reshape(nv, nu)
    brute = np.trapezoid(np.trapezoid(th, U, axis=1), V) / (0.26 * 0.12)
    assert abs(area @ np.asarray(table["thickness"]) / area.sum() / brute - 1) < 1e-12


def test_plan_run_size_film(painted, panel_sized, capsys, tmp_path):
    """The written path: run solves it, size confirms every motor within its ratings (the
    session's `size … --format json --out r.json` of it: tests/examples_planned.py), and
    the film map stays within ±2 % of the target."""
    traj = from_csv(painted / "path.csv")
    assert traj.derivatives == "file columns"
    code, out, err = run_cli(["run", "--trajectory", painted / "path.csv", "--out",
                           tmp_path / "run.csv", "--quiet"], capsys)
    assert code == 0, err
    code, err, folder = panel_sized
    assert code == 0, err
    sized = json.loads((folder / "r.json").read_text())
    assert sized["given_within_ratings"] is True
    rep = json.loads((painted / "paint.json").read_text())
    for name, m in rep["motors"].items():
        given = sized["actuators"][name]
        assert given["peak_motor_torque_ratio"] <= 1.0 and given["peak_motor_speed_ratio"] <= 1
        # the planner's own check (4× denser samples) sees at least what size sees
        assert m["peak_torque"] >= given["peak_motor_torque_ratio"] - 1e-12, name
        assert m["peak_torque"] <= 1.0 and m["speed"] <= 1.0, name
    th = read_result(painted / "thickness.csv")["thickness"]
    assert np.abs(th / rep["target"] - 1).max() <= 0.02


def test_summary_lines(tmp_path, capsys):
    code, out, err = run_cli(["paint", "--job", JOB, "--out", tmp_path / "p", "--format",
                           "parquet", "--resolution", "0.005"], capsys)
    assert code == 0, err
    assert err.startswith("wrote ") and err.count("\n") == 1  # not a terminal: no bar
    lines = out.strip().splitlines()
    assert lines[0].startswith("passes 9 (horizontal)")
    assert "lower bound" in lines[1] and "film" in lines[2] and "theta21_1" in lines[3]
    t = read_result(tmp_path / "p" / "thickness.parquet")
    assert np.diff(np.unique(t["u"])).max() <= 0.005 * (1 + 1e-12)


def test_a_terminal_sees_progress_bars_and_the_same_summary(tmp_path, capsys, monkeypatch):
    import sys

    argv = ["paint", "--job", JOB, "--out", tmp_path / "p", "--resolution", "0.005"]
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    code, out, err = run_cli(argv, capsys)
    assert code == 0, err
    assert "film:" in err and "compliance:" in err  # the film's and the compliance's bars
    assert "planning: ramps and turnarounds:" in err  # the planner's searches
    lines = out.strip().splitlines()
    assert lines[0].startswith("passes 9 (horizontal)") and "film" in lines[2]


def test_view_paint_overlay(painted, tmp_path, capsys):
    from pollard_pin.viz import meshcat_page, viewer

    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", painted, "--html", html, "--fps", "5"], capsys)
    assert code == 0, err
    cmds = meshcat_page.page_commands(html.read_text())
    paint = [c for c in cmds if c.get("type") == "set_object"
             and c["path"].endswith(f"{viewer.ROOT}/paint")]
    assert len(paint) == 1
    rep = json.loads((painted / "paint.json").read_text())
    attrs = paint[0]["object"]["geometries"][0]["data"]["attributes"]
    assert "color" in attrs
    n = rep["grid"]["nu"] * rep["grid"]["nv"]
    pos = attrs["position"]["array"]
    pos = np.frombuffer(getattr(pos, "data", pos), dtype=np.float32)
    assert pos.size == 3 * n


@pytest.mark.parametrize("edit, words", [
    (lambda t: t.replace("width = 0.26", "widht = 0.26"), "did you mean 'width'"),
    (lambda t: t.replace("sigma = 0.010", "sigma = nan"), "must be a finite number"),
    (lambda t: t.replace("flow = 1.5e-7", "flow = -1.5e-7"), "must be > 0"),
    (lambda t: t.replace("normal = [-1.0, 0.0, 0.0]", "normal = [0.0, 0.0, 0.0]"),
     "zero length"),
    (lambda t: t.replace("height = 0.12 ", "").replace("height = 0.12", ""), "is missing"),
    (lambda t: t.replace("width = 0.26", "width = 0.6"), "the largest panel that fits"),
    (lambda t: t.replace("thickness = 25e-6", "thickness = 3e-6"),
     "thinnest film per coat"),
    (lambda t: t.replace("solids = 0.45", "solids = 45"), "'paint.solids' = 45: must be a share"),
    (lambda t: t.replace("density = 1300.0", "density = 1.3"), "1.2 g/cm³ is 1200 kg/m³"),
    (lambda t: t.replace("transfer_efficiency =", "efficiency ="),
     "'paint.efficiency' = 0.65: unknown key (did you mean 'transfer_efficiency'?)"),
    (lambda t: t.replace("[paint] ", "[[paint]] "), "'paint' = [{'solids': 0.45"),
    (lambda t: t.replace("transfer_efficiency = 0.65", "transfer_efficiency = 1.5"),
     "'paint.transfer_efficiency' = 1.5: must be a share in (0, 1] "),
    (lambda t: t.replace("sigma = 0.010", 'model = "beta"\nradius = 0.03\nbeta = 2.0\n'
                                          "sigma = 0.010"),
     "'gun.sigma' = 0.01: is not a key of model 'beta'"),
    (lambda t: t.replace("sigma = 0.010", "sigma = 0.010\nsigma_long = 0.02"),
     "'gun.sigma_long' = 0.02: is not a key of model 'gaussian'"),
    (lambda t: t.replace("sigma = 0.010", 'model = "beta"\nradius = 0.03\nbeta = 1' + 400 * "0"),
     "'gun.beta' = 1e+400"),
    (lambda t: t.replace("sigma = 0.010", "sigma = 0.010\napex = 0.15"),
     "'gun.apex' = 0.15: must lie before the standoff (0.15 m)"),
])
def test_bad_jobs_are_one_line_and_write_nothing(tmp_path, capsys, edit, words):
    job = tmp_path / "job.toml"
    job.write_text(edit(JOB.read_text()))
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin paint: error: ")
    assert words in lines[0]
    assert not out.exists()


def test_bad_options(tmp_path, capsys):
    code, _, err = run_cli(["paint", "--job", JOB, "--out", tmp_path / "o", "--resolution",
                         "1e-6"], capsys)
    assert code == 2 and "coarser resolution" in err and not (tmp_path / "o").exists()
    code, _, err = run_cli(["paint", "--job", tmp_path / "none.toml", "--out", tmp_path / "o"],
                        capsys)
    assert code == 2 and "does not exist" in err
    code, _, err = run_cli(["view", "--paint", tmp_path, "--html", tmp_path / "v.html"], capsys)
    assert code == 2 and "not a paint output folder" in err


def test_default_actuators_are_the_example_ratings():
    """The package default (models/actuators.toml) is a copy of examples/actuators.toml."""
    from pollard_pin.model.paths import models_dir

    assert (models_dir() / "actuators.toml").read_bytes() == ACT.read_bytes()


# --- a part's mesh ([part] jobs) ---------------------------------------------------------------
PART_JOB = ROOT / "examples" / "parts" / "curved_panel.toml"


@pytest.fixture(scope="module")
def part_painted(tmp_path_factory):
    out = tmp_path_factory.mktemp("paint_part") / "out"
    # compliance not asserted here (tests/painting/checks/test_compliance.py checks it): left out
    assert main(["paint", "--job", str(PART_JOB), "--out", str(out), "--no-compliance"]) == 0
    return out


def test_part_outputs(part_painted):
    import trimesh

    names = {p.name for p in part_painted.iterdir()}
    assert {"path.csv", "thickness.csv", "film.ply", "paint.json", "thickness.png"} <= names
    rep = json.loads((part_painted / "paint.json").read_text())
    th = rep["thickness"]
    assert set(th) >= {"mean", "min", "max", "std", "within_5pct", "within_10pct"}
    assert th["within_5pct"] >= 0.99 and th["within_10pct"] == 1.0
    for key in ("largest_incidence_deg", "transfer_efficiency", "cycle_time", "lower_bound",
                "passes", "tip_speed_range", "coats", "motors"):
        assert key in rep
    assert 0 < rep["transfer_efficiency"] < 1
    assert rep["cycle_time"] > rep["lower_bound"] > 0
    for use in rep["motors"].values():
        assert max(use["peak_torque"], use["speed"], use["rms_torque"]) <= 1.0
    table = read_result(part_painted / "thickness.csv")
    assert list(table.columns) == ["x", "y", "z", "nx", "ny", "nz", "area", "thickness"]
    assert table.units["area"] == "m²" and table.units["nx"] == "1"
    # the area shares add up to the painted area
    assert abs(table["area"].sum() / rep["part"]["painted_area"] - 1) < 1e-9
    n = np.column_stack([table["nx"], table["ny"], table["nz"]])
    assert np.abs(np.linalg.norm(n, axis=1) - 1).max() < 1e-12
    # film.ply: a valid PLY that trimesh reads back, with the per-vertex thickness
    ply = trimesh.load(part_painted / "film.ply", process=False)
    raw = ply.metadata["_ply_raw"]["vertex"]["data"]
    assert "thickness" in raw.dtype.names and len(raw) == len(ply.vertices)
    assert abs(ply.area / rep["part"]["painted_area"] - 1) < 1e-6
    assert raw["thickness"].min() == pytest.approx(th["min"], rel=1e-12)
    assert ply.visual.vertex_colors.shape == (len(ply.vertices), 4)


def test_part_path_runs(part_painted, capsys, tmp_path):
    """path.csv carries the trigger (0 or 1, on during the passes) and `run` and `size` take
    it: the reach and the motors hold."""
    table = read_result(part_painted / "path.csv")
    spray = table["spray"]
    assert set(np.unique(spray)) == {0.0, 1.0} and spray[0] == 0 and spray[-1] == 0
    assert run_and_size(part_painted / "path.csv", ACT, capsys, tmp_path)["given_within_ratings"]


@pytest.mark.parametrize("edit, mesh, words", [
    (lambda t: t.replace('"curved_panel.stl"', '"broken.stl"'), b"solid nothing here\n",
     "broken.stl"),
    (lambda t: t.replace('"curved_panel.stl"', '"empty.obj"'), b"v 0 0 0\nv 1 0 0\n",
     "no triangles"),
    (lambda t: t.replace('"curved_panel.stl"', '"part.step"'), b"ISO-10303-21;\n",
     "not a mesh this reads"),
    (lambda t: t.replace("facing = [-1.0, 0.0, 0.0]", "facing = [0.0, 1.0, 0.0]")
     .replace("max_angle = 45.0", "max_angle = 10.0"), None, "no face has its outward normal"),
    # out of reach: the move that brings it back (place's placement, 75 mm of margin)
    (lambda t: t.replace("position = [0.0, 0.0, 0.0]", "position = [0.4, 0.0, 0.0]"), None,
     "move the part by (-0.410, -0.000, -0.056) m (75 mm of margin"),
    (lambda t: t.replace("position = [0.0, 0.0, 0.0]", "position = [0.0, 0.25, 0.0]"), None,
     "move the part by (-0.010, -0.250, -0.056) m"),
    # horizontal passes hit theta54's limit in their run-on; vertical ones paint it
    (lambda t: t.replace("position = [0.0, 0.0, 0.0]", "position = [-0.05, -0.1, -0.05]"), None,
     'direction = "vertical" paints it as placed'),
    (lambda t: t.replace('units = "m"', 'units = "mm"'), None, "read as millimetres"),
    # 0.2 m of part at scale 0.01: 2 mm, under the spot's σ = 10 mm
    (lambda t: t.replace('units = "m"', "scale = 0.01"), None,
     "the part is smaller than the spray spot: its painted faces span 0.00"),
    (lambda t: t.replace('mesh = ', 'mesch = '), None, "did you mean 'mesh'"),
])
def test_bad_part_jobs_are_one_line_and_write_nothing(tmp_path, capsys, edit, mesh, words):
    import shutil

    shutil.copy(PART_JOB.parent / "curved_panel.stl", tmp_path / "curved_panel.stl")
    for name in ("broken.stl", "empty.obj", "part.step"):
        (tmp_path / name).write_bytes(mesh or b"")
    job = tmp_path / "job.toml"
    job.write_text(edit(PART_JOB.read_text()))
    out = tmp_path / "out"
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin paint: error: ")
    assert words in lines[0], lines[0]
    assert not out.exists()


def test_part_in_mm_read_as_m_says_so(tmp_path, capsys):
    import trimesh

    mesh = trimesh.load(PART_JOB.parent / "curved_panel.stl", process=False)
    mesh.apply_scale(1000.0)
    mesh.export(tmp_path / "curved_panel.stl")
    job = tmp_path / "job.toml"
    job.write_text(PART_JOB.read_text())
    code, _, err = run_cli(["paint", "--job", job, "--out", tmp_path / "out"], capsys)
    assert code == 2 and "1000x too large: units = 'mm'?" in err, err
    assert len(err.strip().splitlines()) == 1 and not (tmp_path / "out").exists()


def test_view_part_overlay(part_painted, tmp_path, capsys):
    """view --paint of a part's folder draws film.ply's triangles, coloured by the film."""
    from pollard_pin.viz.meshcat_page import page_commands

    html = tmp_path / "v.html"
    code, _, err = run_cli(["view", "--paint", part_painted, "--html", html], capsys)
    assert code == 0, err
    cmds = page_commands(html.read_text())
    paint = [c for c in cmds if c.get("path", "").endswith("/paint")]
    assert paint and "color" in paint[0]["object"]["geometries"][0]["data"]["attributes"]
    # a broken film.ply is one line
    broken = tmp_path / "broken"
    broken.mkdir()
    for name in ("path.csv", "path.units.json", "thickness.csv", "paint.json"):
        (broken / name).write_bytes((part_painted / name).read_bytes())
    (broken / "film.ply").write_bytes(b"ply\nformat ascii 1.0\nend_header\n")
    code, _, err = run_cli(["view", "--paint", broken, "--html", tmp_path / "w.html"], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1 and "not a film PLY" in err, err


def test_a_mesh_with_repeated_faces_is_painted_once_with_a_note(tmp_path, capsys):
    """A 0.12 m square plate (two triangles) at x = 0.70 facing the robot, each face written
    twice: a note, and the painted area is the square's 0.0144 m², by hand."""
    verts = "v 0.7 -0.06 0.10\nv 0.7 0.06 0.10\nv 0.7 0.06 0.22\nv 0.7 -0.06 0.22\n"
    faces = "f 1 3 2\nf 1 4 3\n"
    (tmp_path / "plate.obj").write_text(verts + faces + faces)
    job = tmp_path / "plate.toml"
    job.write_text('[part]\nmesh = "plate.obj"\nposition = [0.0, 0.0, 0.0]\n[gun]\n'
                   "standoff = 0.15\nsigma = 0.010\nflow = 1.5e-7\n[job]\nthickness = 25e-6\n")
    out = tmp_path / "out"
    assert main(["paint", "--job", str(job), "--out", str(out), "--resolution", "0.01"]) == 0
    err = capsys.readouterr().err
    assert "note: " in err and "plate.obj: dropped 2 repeated faces" in err, err
    rep = json.loads((out / "paint.json").read_text())
    assert abs(rep["part"]["painted_area"] - 0.0144) < 1e-12 and rep["part"]["faces"] == 2
    assert rep["transfer_efficiency"] <= 1.0


# The gun body's clearance from the part (docs/model.md §25): a rib taller than the standoff
# and a clearance beyond the standoff are one line, exit 2, nothing written.
def _refused_clearance(capsys, job, out, words):
    code, _, err = run_cli(["paint", "--job", job, "--out", out], capsys)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("pollard-pin paint: error: ")
    for w in words:
        assert w in lines[0]
    assert not out.exists()
    return lines[0]


def test_a_rib_taller_than_the_standoff_is_refused_naming_the_place(tmp_path, capsys):
    from pollard_pin.painting.workpiece import shapes

    shapes.ribbed_plate(rib_height=0.2, step=0.01).export(tmp_path / "rib.obj")
    job = tmp_path / "rib.toml"
    ribbed = (ROOT / "examples" / "parts" / "ribbed_plate.toml").read_text()
    job.write_text(ribbed.replace("ribbed_plate.obj", "rib.obj"))
    _refused_clearance(capsys, job, tmp_path / "out",
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
    _refused_clearance(capsys, job, tmp_path / "out", words)


def test_a_kept_clearance_is_reported(tmp_path, capsys):
    job = tmp_path / "job.toml"
    job.write_text(JOB.read_text().replace("flow = 1.5e-7", "flow = 1.5e-7\nclearance = 0.02",
                                           1))
    out = tmp_path / "out"
    # compliance not asserted here (tests/painting/checks/test_compliance.py checks it)
    code, text, err = run_cli(["paint", "--job", job, "--out", out, "--no-compliance"], capsys)
    assert code == 0, err
    assert "gun body 145.6 mm from the part at its closest" in text
    assert "clearance 20 mm" in text
    rep = json.loads((out / "paint.json").read_text())
    # the gun normal to the panel at 0.15 m: 150 − √(4² + 1.8²) mm (the front sphere, §25)
    assert rep["min_clearance_m"] == pytest.approx(0.15 - (0.004 ** 2 + 0.0018 ** 2) ** 0.5,
                                                   abs=1e-9)  # achieves ~1e-16
    assert rep["clearance"]["required_m"] == 0.02
    assert rep["job"]["gun"]["clearance"] == 0.02


def test_a_film_that_misses_is_said_and_strict_exits_3_after_writing(tmp_path, capsys):
    """A plate with a rib 50 mm tall and 30 mm wide: the passes ride over the rib and leave
    its feet thin (94.2 % of the area within ±10 % at the test's resolution): the summary
    closes with a warning, paint.json's film_check says it, and --strict exits 3 (distinct
    from 2, a refusal) with every output written."""
    from pollard_pin.painting.workpiece import shapes

    shapes.ribbed_plate(width=0.16, height=0.06, rib_height=0.05, rib_width=0.03,
                        step=0.01).export(tmp_path / "rib.obj")
    job = tmp_path / "rib.toml"
    ribbed = (ROOT / "examples" / "parts" / "ribbed_plate.toml").read_text()
    job.write_text(ribbed.replace("ribbed_plate.obj", "rib.obj"))
    out = tmp_path / "out"
    code, text, err = run_cli(["paint", "--job", job, "--out", out, "--resolution", "0.006",
                               "--no-compliance", "--strict"], capsys)
    assert code == 3, err
    assert {p.name for p in out.iterdir()} >= {"path.csv", "thickness.csv", "film.ply",
                                               "paint.json", "thickness.png"}
    c = json.loads((out / "paint.json").read_text())["film_check"]
    assert c["meets"] is False and c["acceptance"] == {"band": 0.1, "min_share": 0.99}
    share = 1 - c["outside_10pct"]
    assert 0.5 < share < 0.99 and c["min_relative"] < 0.9
    warning = text.strip().splitlines()[-1]
    assert warning.startswith("warning: the film misses its acceptance: "
                              f"{100 * share:.2f} % of the area within ±10 %")
    assert err.strip().splitlines()[-1] == (
        f"pollard-pin paint: --strict: {100 * share:.2f} % of the area within ±10 % of the "
        "target, under 99 % (exit status 3; the outputs are written)")
    # a share the film meets: exit 0, the warning still printed
    again = tmp_path / "again"
    code, text2, err = run_cli(["paint", "--job", job, "--out", again, "--resolution",
                                "0.006", "--no-compliance", "--strict", f"{share - 0.01}"],
                               capsys)
    assert code == 0, err
    assert warning in text2


@pytest.mark.parametrize("value", ["1.5", "-0.1", "x"])
def test_a_strict_share_outside_0_1_is_refused(tmp_path, capsys, value):
    code, _, err = run_cli(["paint", "--job", JOB, "--out", tmp_path / "o", "--strict",
                            value], capsys)
    assert code == 2 and "--strict" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists()
