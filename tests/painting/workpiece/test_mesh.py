"""A part from its mesh: every format reads back the same triangles, placement follows the
tool pose's rotation convention, and each bad file or value is one MeshError line."""
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from scipy.spatial.transform import Rotation

from pollard_pin.errors import InputError
from pollard_pin.painting.errors import MeshError
from pollard_pin.painting.job import load_job
from pollard_pin.painting.workpiece import mesh as mesh_module
from pollard_pin.painting.workpiece import shapes
from pollard_pin.painting.workpiece.mesh import MAX_ANGLE, load_part, make_part, panel_part

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "paint.toml"


@pytest.fixture(scope="module")
def rib():
    return shapes.ribbed_plate(step=0.02)


@pytest.mark.parametrize("name", ["part.stl", "ascii.stl", "part.obj", "part.ply"])
def test_every_format_reads_back_the_same_part(tmp_path, rib, name):
    path = tmp_path / name
    if name == "ascii.stl":
        path.write_text(trimesh.exchange.stl.export_stl_ascii(rib))
    else:
        rib.export(path)
    part = load_part(path)
    tri = part.vertices[part.faces]
    assert len(part.faces) == len(rib.faces)
    # the same triangles in the same order, corners in the same order (binary STL: float32)
    assert np.abs(tri - rib.triangles).max() < 1e-7
    # outward normals follow the winding: the same as trimesh's per face, unit length
    assert np.abs(part.normals - rib.face_normals).max() < 1e-5
    assert part.areas.sum() == pytest.approx(rib.area, rel=1e-6)
    assert np.array_equal(part.painted,
                          part.normals @ [-1.0, 0, 0] >= math.cos(math.radians(MAX_ANGLE)))
    # the painted faces of the ribbed plate: its front and the rib's top, 0.24 × 0.10 m
    # less the rib's footprint plus its top (walls are at 90°, not painted by default)
    assert part.painted_area == pytest.approx(0.24 * 0.10, rel=1e-6)


def test_units_position_and_rotation(tmp_path, rib):
    local = rib.copy()
    local.apply_translation(-local.bounds.mean(axis=0))
    local.apply_scale(1000.0)  # a file in mm
    path = tmp_path / "mm.stl"
    local.export(path)
    pos, rot = (0.7, -0.05, 0.2), (10.0, -20.0, 35.0)
    part = load_part(path, units="mm", position=pos, rotation=rot, facing=(-1, 0, 0))
    # R = Rx(rx)·Ry(ry)·Rz(rz) (docs/model.md §2) is scipy's intrinsic "XYZ"
    R = Rotation.from_euler("XYZ", rot, degrees=True).as_matrix()
    ref = trimesh.load(path, process=False).triangles * 1e-3 @ R.T + pos
    assert np.abs(part.vertices[part.faces] - ref).max() < 1e-12
    n_ref = np.cross(ref[:, 1] - ref[:, 0], ref[:, 2] - ref[:, 0])
    n_ref /= np.linalg.norm(n_ref, axis=1)[:, None]
    assert np.abs(part.normals - n_ref).max() < 1e-12


def test_an_inside_out_closed_mesh_is_turned_over(tmp_path, rib):
    inverted = trimesh.Trimesh(rib.vertices, rib.faces[:, ::-1], process=False)
    assert inverted.volume < 0
    part = make_part(inverted.vertices, inverted.faces)
    assert np.abs(part.normals - rib.face_normals).max() < 1e-12
    inverted.export(tmp_path / "inverted.stl")  # STL: a corner per face, merged on reading
    part = load_part(tmp_path / "inverted.stl")
    assert part.mesh.is_watertight
    assert np.abs(part.normals - rib.face_normals).max() < 1e-5
    sheet = make_part(rib.vertices, rib.faces[:1, ::-1], facing=-rib.face_normals[0])
    assert np.allclose(sheet.normals[0], -rib.face_normals[0])  # an open sheet: as given


def test_panel_part_is_the_jobs_panel():
    job = load_job(EXAMPLE)
    part = panel_part(job)
    assert part.painted.all() and len(part.faces) == 2
    assert np.abs(part.normals - np.array(job.normal)).max() < 1e-15
    assert part.areas.sum() == pytest.approx(job.width * job.height, rel=1e-14)
    lo, hi = part.vertices.min(axis=0), part.vertices.max(axis=0)
    assert np.allclose(lo, [0.70, -0.13, 0.10]) and np.allclose(hi, [0.70, 0.13, 0.22])


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


TRI = "v 0 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n"  # normal +x: faces away from the robot


@pytest.mark.parametrize("name, text, kwargs, fragment", [
    ("none.stl", None, {}, "does not exist"),
    ("part.step", "x", {}, "format '.step' is not a mesh"),
    ("junk.stl", "hello\n", {}, "6 bytes: not an ASCII STL (solid … endsolid), and shorter "
     "than a binary STL's 84-byte header"),
    ("junk.ply", "hello\n", {}, "not a PLY file"),
    ("cloud.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y"
     "\nproperty float z\nend_header\n0 0 0\n", {}, "no triangles in the file"),
    ("nan.obj", "v 0 0 0\nv 0 1 0\nv nan 0 1\nf 1 2 3\n", {}, "vertex 2 = (nan, 0.0, 1.0)"),
    ("flat.obj", "v 0 0 0\nv 0 1 0\nv 0 2 0\nf 1 2 3\n", {}, "all 1 faces have zero area"),
    ("away.obj", TRI, {}, "no face has its outward normal within 45° of facing (-1.0, 0.0"),
    ("huge.obj", "v 0 0 0\nv 0 300 0\nv 0 0 300\nf 1 2 3\n", {"facing": (1, 0, 0)},
     "300 m across, more than 5 m: 1000x too large: units = 'mm'?"),
    ("tri.obj", TRI, {"units": "ft"}, "units = 'ft' must be one of 'm', 'cm', 'mm', 'in'"),
    ("tri.obj", TRI, {"rotation": (0, 90)}, "rotation = (0, 90) must be 3 finite numbers"),
    ("tri.obj", TRI, {"position": (0, 0, math.inf)}, "position = (0, 0, inf) must be 3"),
    ("tri.obj", TRI, {"facing": (0, 0, 0)}, "facing = (0.0, 0.0, 0.0) has zero length"),
    ("tri.obj", TRI, {"facing": (1, 0, 0), "max_angle": 0}, "max_angle = 0° must be in"),
])
def test_bad_meshes_are_one_line(tmp_path, name, text, kwargs, fragment):
    path = tmp_path / name if text is None else _write(tmp_path, name, text)
    with pytest.raises(MeshError) as exc:
        load_part(path, **kwargs)
    msg = str(exc.value)
    assert isinstance(exc.value, InputError)
    assert fragment in msg and "\n" not in msg and len(msg) < 250, msg


def test_a_fifo_is_refused_not_waited_on(tmp_path):
    """A FIFO with no writer as the mesh: one line at once (a plain open would block)."""
    import os

    fifo = tmp_path / "part.stl"
    os.mkfifo(fifo)
    with pytest.raises(MeshError, match=r"cannot be read: not a regular file \(a FIFO\)"):
        load_part(fifo)


def test_face_budget(tmp_path, monkeypatch, rib):
    monkeypatch.setattr(mesh_module, "MAX_FACES", 10)
    with pytest.raises(MeshError, match=rf"{len(rib.faces)} faces, more than the 10"):
        make_part(rib.vertices, rib.faces)


PARTS = Path(__file__).resolve().parents[3] / "examples" / "parts"


def test_the_example_parts_load_and_are_what_make_parts_writes(tmp_path):
    import runpy

    runpy.run_path(str(PARTS / "make_parts.py"), run_name="make_parts")["main"](
        ["--out-dir", str(tmp_path)])
    for name in ("curved_panel.stl", "bent_plate.ply", "ribbed_plate.obj"):
        part = load_part(PARTS / name)
        fresh = load_part(tmp_path / name)
        assert np.array_equal(part.faces, fresh.faces)
        assert np.abs(part.vertices - fresh.vertices).max() < 1e-6  # STL stores float32
        assert 1000 < len(part.faces) < 5000 and part.mesh.is_watertight
        # in front of the robot: the painted front 0.24 × 0.10 m near x = 0.70, facing −x
        front = part.vertices[np.unique(part.faces[part.painted])]
        assert np.abs(front.mean(axis=0) - [0.69, 0.0, 0.16]).max() < 0.02
        assert 0.0235 < part.painted_area < 0.025


def test_the_cells_parts_in_mm_are_what_make_parts_writes(tmp_path):
    import runpy

    runpy.run_path(str(PARTS / "make_parts.py"), run_name="make_parts")["main"](
        ["--out-dir", str(tmp_path)])
    for name in ("tall_plate.stl", "curved_tall.stl"):
        assert (PARTS / name).read_bytes() == (tmp_path / name).read_bytes(), name
    # the curved part: a cylinder of radius 1.5 m (axis vertical, 2.2 m behind the apex at
    # x = 0.70 m), 0.80 m of arc, 0.33 m high from z = 0.015 m, written in mm
    v = load_part(PARTS / "curved_tall.stl", units="mm").vertices
    r = np.hypot(v[:, 0] - 2.2, v[:, 1])
    front = r > 1.5 - 1e-4
    assert np.abs(r[front] - 1.5).max() < 1e-6 and front.sum() == len(v) / 2
    assert np.abs(np.arctan2(v[front, 1], 2.2 - v[front, 0])).max() == pytest.approx(
        0.4 / 1.5, rel=1e-6)
    assert v[:, 2].min() == pytest.approx(0.015, abs=1e-6)
    assert v[:, 2].max() == pytest.approx(0.345, abs=1e-6)


def test_rise_is_the_height_of_the_part_above_each_face():
    """Part.rise against every vertex's height above each face's plane (not the hull's): 0
    on a box (convex), the rib's height over the plate's front and 0 on the rib's top and
    on the face furthest along +x, 0 on a flat sheet (no hull: every vertex counts); over the face
    budget it is not computed (inf)."""
    def brute(part):
        v0 = part.vertices[part.faces[:, 0]]
        return np.array([((part.vertices - v0[f]) @ part.normals[f]).max()
                         for f in range(len(part.faces))])

    box = trimesh.creation.box(bounds=[[0.6, -0.05, 0.1], [0.62, 0.05, 0.2]])
    part = make_part(box.vertices, box.faces)
    assert np.abs(part.rise).max() < 1e-15 and np.abs(brute(part)).max() < 1e-15
    m = shapes.ribbed_plate(step=0.02)
    part = make_part(m.vertices, m.faces)
    want = brute(part)
    assert np.abs(part.rise - want).max() < 1e-12
    front = np.abs(part.normals @ [-1.0, 0, 0] - 1) < 1e-9
    assert want[front].max() > 0.01 and (np.abs(want[front]) < 1e-12).any()
    back = part.vertices[part.faces].min(axis=1)[:, 0] >= part.vertices[:, 0].max() - 1e-12
    assert back.any() and (np.abs(want[back]) < 1e-12).all()
    sheet = make_part([[0.7, -0.05, 0.1], [0.7, 0.05, 0.1], [0.7, 0.05, 0.2],
                       [0.7, -0.05, 0.2]], [[0, 2, 1], [0, 3, 2]])
    assert np.abs(sheet.rise).max() < 1e-15
    import pollard_pin.painting.workpiece.mesh as mm

    old = mm.RISE_PRODUCTS
    try:
        mm.RISE_PRODUCTS = 10
        assert np.isinf(make_part(box.vertices, box.faces).rise).all()
    finally:
        mm.RISE_PRODUCTS = old
