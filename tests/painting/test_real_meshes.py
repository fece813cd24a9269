"""Real third-party meshes (tests/data/meshes/LICENSES.md) placed by pollard_pin.place and
painted, still and on a line: the film's mean within ±5 % of target, its statistics pinned,
the painted area against trimesh's own area of the faces that face the robot.

plate_holes.STL (trimesh, mm): a 203.2 × 304.8 × 12.7 mm plate with holes, its +z face
turned to the robot (ry = −90°): 0.305 m wide and 0.203 m tall it fits the reach as it
stands; turned a quarter (0.305 m tall) it does not. wavy_mesh_with_hole.ply (noether, unit
unknown, 10.5 × 10.5 × 4 units): at scale = 0.02 a 0.21 × 0.21 m pressed sheet with 8 cm
waves, a plausible part for a 0.6 × 0.35 m reach; from 0.03 up (0.32 m) its gun tilts out
of reach on the waves, and at 0.15 m standoff it needs a Gaussian normal of 4 mm.
"""
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from pollard_pin.outputs import paint
from pollard_pin.painting.job import load_job
from pollard_pin.painting.layout.place import PlaceOptions, place
from pollard_pin.painting.line.conveyor import Line
from pollard_pin.painting.options import PaintOptions
from pollard_pin.painting.workpiece.mesh import load_job_part

DATA = Path(__file__).resolve().parents[1] / "data" / "meshes"
RESOLUTION = 0.01  # m, the film points at σ: the coarsest paint takes, seconds per part
LINE = Line(0.03, (0.0, 1.0, 0.0))  # as examples/line_part.toml
UPSTREAM = 0.6  # m the line job starts upstream of the still placement

# The film statistics [µm] and shares, still and on the line. Run to run they repeat to the
# last bit on this machine; the tolerance, rel 1e-3, is twice the spread between Embree's
# float32 ray verdicts and trimesh's numpy intersector at shadow edges (docs/model.md §23,
# 5e-4 of the film), not room for a change of the model:
# mean, std, min, max [µm], within ±5 %, ±10 % (area shares)
PINNED = {
    ("plate_holes", "still"):
        (24.98766203, 0.367795653, 6.60783487, 25.12502509, 0.9994626547, 0.9994626547),
    ("wavy", "still"):
        (24.30283869, 1.703279573, 18.62589387, 27.98319438, 0.6217606305, 0.8312442469),
    ("plate_holes", "line"):  # the line's path sampled from the program's start (§24)
        (24.98009495, 0.3691928574, 4.867599070, 25.12502509, 0.9968946647, 0.9994626547),
    ("wavy", "line"):
        (24.36173765, 1.978222583, 18.43081497, 30.32522893, 0.587339075, 0.7748364334),
}


@pytest.fixture(scope="module")
def placed(robot):
    """Each mesh's job placed, turns of 0 and ±90° tried."""
    out = {}
    for name in ("plate_holes", "wavy"):
        job = load_job(DATA / f"{name}.toml")
        out[name] = place(robot, job, PlaceOptions(max_turn=90.0, turn_step=90.0))
    return out


def test_placements(placed):
    """The plate fits only as it stands (0.305 m wide); turned a quarter, 0.305 m tall, it
    misses. The near-square wavy sheet fits at every turn tried: 90° has the most margin."""
    plate, wavy = placed["plate_holes"], placed["wavy"]
    assert plate.turn == 0.0 and plate.turns[90.0] < 0 and plate.turns[-90.0] < 0, plate.turns
    assert min(wavy.turns.values()) > 0.02, wavy.turns
    for result in placed.values():
        assert result.margin > 0.02, result  # plate 34 mm, wavy 52 mm
        # the placed rotation at the gimbal lock ry = −90°: the file's vertices turned by
        # Ry(−90°), then about the facing axis −x, then moved, as numpy turns them
        job = result.job
        t = np.radians(result.turn)
        ry = np.array([[0.0, 0, -1], [0, 1, 0], [1, 0, 0]])  # Ry(−90°)
        rt = np.array([[1, 0, 0], [0, np.cos(t), np.sin(t)], [0, -np.sin(t), np.cos(t)]])
        v = trimesh.load(job.mesh, force="mesh", process=False).vertices * job.unit
        got = load_job_part(job).vertices  # (its corners merged: compared as point sets)
        want = v @ (rt @ ry).T + job.position
        gap = max(cKDTree(want).query(got)[0].max(), cKDTree(got).query(want)[0].max())
        assert gap < 1e-9, gap  # achieved ~1e-16 (angles written to 1e-9°)


def _trimesh_area(job) -> float:
    """The area [m²] of the file's faces within max_angle of facing, by trimesh alone: the
    file's +z turned to −x by the job's ry = −90°, so the faces within 45° of file +z."""
    mesh = trimesh.load(job.mesh, force="mesh")
    near = mesh.face_normals @ np.array([0.0, 0.0, 1.0]) >= np.cos(np.radians(45.0))
    return float(mesh.area_faces[near].sum()) * job.unit ** 2


@pytest.mark.parametrize("name", ["plate_holes", "wavy"])
@pytest.mark.parametrize("kind", ["still", "line"])
def test_paint(robot, placed, name, kind):
    job = placed[name].job
    if kind == "line":
        x, y, z = job.position
        job = replace(job, position=(x, y - UPSTREAM, z), line=LINE)
    # compliance is not asserted here (tests/painting/checks/test_compliance.py checks it on
    # the example parts): its second film integration is left out
    res = paint(robot, job, options=PaintOptions(resolution=RESOLUTION, compliance=False))
    rep = res.report.data
    th = rep["thickness"]
    assert abs(th["mean"] / job.thickness - 1) < 0.05, th
    # the part's painted area against trimesh's: achieved 1e-15 relative
    assert rep["part"]["painted_area"] == pytest.approx(_trimesh_area(job), rel=1e-12)
    got = [th[k] * 1e6 for k in ("mean", "std", "min", "max")] + [
        th["within_5pct"], th["within_10pct"]]
    assert got == pytest.approx(PINNED[name, kind], rel=1e-3), got
