"""A cell robot's band along the cell's axis (paint/cell/bands.py, docs/model.md §26.2),
against a brute-force scan of the reach rule over a dense grid of gun poses."""
import math

import numpy as np
import pytest
from cell_split_jobs import door_part, plate_part, tall_panel
from rotations import Rx, Ry, Rz

from pollard_pin.painting.cell.bands import MARGIN, STEP, Band, cell_axis, job_strokes, robot_band
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.errors import CellError
from pollard_pin.painting.job import load_job
from pollard_pin.workspace.reach import evaluate


def brute_band(robot, cell, x_plane: float, lo: float, hi: float, step: float = 0.0025):
    """The longest vertical chord [z0, z1] within [lo, hi] of gun poses spraying along
    world +x from the plane x = ``x_plane``, over every world y (5 mm apart) near the robot:
    the band of a vertical stroke at any shift along a +y line, written out."""
    R = (Rx(math.radians(cell.rotation[0])) @ Ry(math.radians(cell.rotation[1]))
         @ Rz(math.radians(cell.rotation[2])))
    a = R.T @ np.array([1.0, 0.0, 0.0])  # the spray axis in the base frame
    c = np.array([0.0, 0.0, 1.0]) - a[2] * a  # roll: base z off the spray axis
    c /= np.linalg.norm(c)
    G = np.column_stack([a, np.cross(c, a), c])
    ang = [math.asin(G[0, 2]), math.atan2(-G[1, 2], G[2, 2]), math.atan2(-G[0, 1], G[0, 0])]
    ys = cell.base[1] + np.arange(-0.9, 0.9, 0.005)
    zs = np.arange(lo, hi + step / 2, step)
    Y, Z = np.meshgrid(ys, zs, indexing="ij")
    world = np.stack([np.full(Y.shape, x_plane), Y, Z], axis=-1).reshape(-1, 3)
    poses = np.column_stack([(world - np.array(cell.base)) @ R, np.tile(ang, (len(world), 1))])
    ok = (evaluate(robot, poses)["reachable"] > 0).reshape(Y.shape)
    best = (0, 0.0, 0.0)
    for col in ok:
        run = 0
        for j, good in enumerate(col):
            run = run + 1 if good else 0
            if run > best[0]:
                best = (run, zs[j - run + 1], zs[j])
    return best[1:]


@pytest.mark.parametrize("cell", [
    CellRobot("origin"),
    CellRobot("raised", (0.0, 0.75, 0.17)),
    CellRobot("upside", (0.0, 0.0, 0.6), (180.0, 0.0, 0.0)),
    CellRobot("yawed", (0.03, 0.3, 0.05), (0.0, 0.0, 12.0)),
])
def test_band_is_the_longest_chord_of_the_reach(robot, cell):
    job = tall_panel()
    strokes = job_strokes(job)
    band = robot_band(robot, cell, strokes)
    w = strokes.grid()[0]
    z0, z1 = brute_band(robot, cell, 0.55, w[0], w[-1])
    assert z1 - z0 > 0.1  # the case has a band to compare
    # the band's grid is 5 mm, its shifts 10 mm apart; the scan's 2.5 mm and 5 mm: seen
    # ≤ 5 mm apart, so two grid steps
    assert abs(band.lo - z0) <= 2 * STEP and abs(band.hi - z1) <= 2 * STEP, (band, z0, z1)


def test_a_part_has_the_band_of_the_panel_of_its_face(robot, tmp_path):
    part = job_strokes(load_job(plate_part(tmp_path)))
    panel = job_strokes(tall_panel(x=0.69))
    assert part.extent == pytest.approx(panel.extent, abs=2e-7)  # STL float32: 1.8e-9
    # the same grid: the part's run-on is 3σ, the panel's 4σ
    margin = MARGIN + panel.run_on - part.run_on
    for cell in (CellRobot("a"), CellRobot("b", (0.0, 0.4, 0.2))):
        p, q = robot_band(robot, cell, part, margin), robot_band(robot, cell, panel)
        assert abs(p.lo - q.lo) <= STEP and abs(p.hi - q.hi) <= STEP, (p, q)


def test_the_axis_runs_across_the_travel_in_the_faces_plane():
    f, e = np.array([-1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    assert cell_axis(f, e) == pytest.approx([0.0, 0.0, 1.0], abs=1e-15)
    assert cell_axis(-f, e) == pytest.approx([0.0, 0.0, 1.0], abs=1e-15)
    g = np.array([-0.6, -0.8, 0.0])  # a slanted face on a line along z
    a = cell_axis(g, [0.0, 0.0, 1.0])
    assert abs(a @ g) < 1e-15 and abs(a[2]) < 1e-15 and a[1] > 0
    with pytest.raises(CellError, match="runs along the painted faces' facing"):
        cell_axis(f, [1.0, 0.0, 0.0])


@pytest.mark.parametrize("shift", [-0.06, 0.06])
def test_a_band_moves_with_its_base_on_a_flat_part(robot, tmp_path, shift):
    strokes = job_strokes(load_job(plate_part(tmp_path)))
    at = robot_band(robot, CellRobot("a"), strokes)
    moved = robot_band(robot, CellRobot("b", (0.0, 0.0, shift)), strokes)
    assert at.lo - shift > strokes.grid()[0][0]  # not cut by the grid's end
    # both ends move by the base's shift, to the grid (achieved: exactly)
    assert moved.lo - at.lo == pytest.approx(shift, abs=STEP)
    assert moved.hi - at.hi == pytest.approx(shift, abs=STEP)


def test_a_bevelled_edge_holds_a_shorter_stretch_than_the_longest(robot, tmp_path):
    strokes = job_strokes(load_job(door_part(tmp_path)))
    _, hi = strokes.needed(-math.inf, math.inf)
    at = robot_band(robot, CellRobot("a"), strokes)
    low = robot_band(robot, CellRobot("b", (0.0, 0.0, -0.06)), strokes)
    # the gun stands 0.15 m off a 40° chamfer along its normal and tilts: lowering the base
    # 60 mm moves the band's bottom by far less (about 15 mm of 60 is expected)
    assert 0.0 < at.lo - low.lo < 0.5 * 0.06, (at, low)
    # raised 0.27 m: the longest stretch stops 5 mm short of the top edge's run-on, a
    # shorter one holds it
    raised = robot_band(robot, CellRobot("c", (0.0, 0.0, 0.27)), strokes)
    edge = raised.holding(hi=hi)
    assert raised.hi < hi <= edge.hi and edge.width < raised.width, (raised, edge)


def test_holding_picks_the_stretch_reaching_an_end():
    w = 0.01 * np.arange(10)
    # held from each grid point: [0, 3] (4 points), then [1, 8] … [8, 8]
    n = np.array([4, 8, 7, 6, 5, 4, 3, 2, 1, 0])
    band = Band("r", 0.01, 0.08, (0.0, 0.08), (w, n))
    assert band.holding() is band and band.holding(lo=0.05, hi=0.07) is band
    down = band.holding(lo=0.0)
    assert (down.lo, down.hi) == (0.0, pytest.approx(0.03))
    assert band.holding(hi=0.085) is band  # none reaches it: unchanged
    assert band.holding(lo=-0.01) is band
    both = band.holding(lo=0.0, hi=0.025)
    assert (both.lo, both.hi) == (0.0, pytest.approx(0.03))
    assert band.holding(lo=0.0, hi=0.05) is band  # no stretch holds both ends
    up = band.holding(hi=0.08)  # already held by the longest
    assert up is band
