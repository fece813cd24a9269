"""The example parts: closed, wound outwards, where and what their docstrings say."""
import math

import numpy as np
import pytest

from pollard_pin.painting.workpiece import shapes


@pytest.mark.parametrize("make", [shapes.curved_panel, shapes.bent_plate, shapes.ribbed_plate])
def test_closed_and_wound_outwards(make):
    m = make()
    assert m.is_watertight and m.is_winding_consistent
    # outward normals: the divergence theorem gives the sheet's volume with a + sign
    assert m.volume > 0
    # a sheet THICKNESS thick: its volume is about half its surface × the thickness
    assert m.volume == pytest.approx(m.area / 2 * shapes.THICKNESS, rel=0.03)
    lo, hi = m.bounds
    assert lo[2] == pytest.approx(shapes.CENTRE_Z - 0.05) and hi[2] == pytest.approx(
        shapes.CENTRE_Z + 0.05)


def test_curved_panel_is_the_cylinder():
    R = 0.4
    m = shapes.curved_panel(radius=R)
    v = m.vertices
    r = np.hypot(v[:, 0] - (shapes.FRONT_X + R), v[:, 1])
    front = r > R - 1e-4  # (the back lies THICKNESS nearer the axis)
    assert np.abs(r[front] - R).max() < 1e-12 and front.sum() == len(v) / 2
    assert v[:, 0].min() == pytest.approx(shapes.FRONT_X, abs=1e-12)
    # 0.24 m of arc: ±0.3 rad
    assert np.abs(np.arctan2(v[front, 1], shapes.FRONT_X + R - v[front, 0])).max() == \
        pytest.approx(0.12 / R, rel=1e-12)


def test_bent_plate_fillet_and_wing():
    m = shapes.bent_plate(angle_deg=30.0, fillet=0.030)
    n = m.face_normals
    front = n[:, 0] < -0.7  # (the wing's end, 2 mm wide, faces 60° off −x)
    ang = np.degrees(np.arccos(np.clip(-n[front, 0], -1, 1)))
    assert ang.max() == pytest.approx(30.0, abs=1e-9)
    # the fillet's front vertices lie 30 mm from its axis, on the robot's side
    c = np.array([shapes.FRONT_X - 0.030, 0.0])
    v = m.vertices[:, :2]
    on_arc = (v[:, 1] > 1e-9) & (v[:, 1] < 0.030 * math.sin(math.radians(30)) - 1e-9)
    on_arc &= np.abs(np.linalg.norm(v - c, axis=1) - 0.030) < 1e-3  # front, not back
    assert on_arc.sum() > 10
    assert np.abs(np.linalg.norm(v[on_arc] - c, axis=1) - 0.030).max() < 1e-12


def test_ribbed_plate_rib():
    m = shapes.ribbed_plate(rib_height=0.015, rib_width=0.006)
    v = m.vertices
    assert v[:, 0].min() == pytest.approx(shapes.FRONT_X - 0.015, abs=1e-12)
    top = np.abs(v[:, 0] - (shapes.FRONT_X - 0.015)) < 1e-12
    assert np.ptp(v[top, 1]) == pytest.approx(0.006, abs=1e-12)


def test_chamfered_plate_bends_its_edges_away():
    m = shapes.chamfered_plate(length=0.8, height=0.33, chamfer=0.04, angle_deg=40.0, z0=0.18)
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    assert m.volume == pytest.approx(m.area / 2 * shapes.THICKNESS, rel=0.03)
    lo, hi = m.bounds
    assert lo == pytest.approx([shapes.FRONT_X, -0.4, 0.18 - 0.165], abs=1e-12)
    assert hi[1:] == pytest.approx([0.4, 0.18 + 0.165], abs=1e-12)
    # the front (towards −x): the flat face and two chamfers 40° off it, tilted up and down
    n = m.face_normals
    front = n[:, 0] < -0.5
    tilt = np.degrees(np.arctan2(n[front, 2], -n[front, 0]))
    assert set(np.round(tilt, 6)) == {-40.0, 0.0, 40.0}
    assert np.all(np.abs(n[front, 1]) < 1e-12)  # a prism along the line (y)
    # the chamfers reach 0.04 m of surface back: x = FRONT_X + 0.04 sin 40°
    assert hi[0] == pytest.approx(shapes.FRONT_X + 0.04 * math.sin(math.radians(40))
                                  + shapes.THICKNESS, abs=1e-3)
