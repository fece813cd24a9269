"""The viewer's default view of a film (viz/film_view.py), checked against geometry worked out
here by hand."""
import math

import numpy as np
import pytest

from pollard_pin.film_scale import film_label
from pollard_pin.viz.film_view import MESHCAT_FOV, film_view, grid_faces, legend_html

TARGET = 25e-6
N0 = np.array([-1.0, 0.3, 0.2]) / np.linalg.norm([-1.0, 0.3, 0.2])  # the plate's normal


def _frame(n):
    a = np.cross(n, [0.0, 0.0, 1.0])
    a /= np.linalg.norm(a)
    return a, np.cross(n, a)  # (a, b, n) right-handed: grid_faces winds about +n


def _plate(origin, n, w, h, film):
    """A w × h rectangle about ``origin`` in the plane of normal ``n``, on a grid whose cells
    grow geometrically (so a vertex mean is not the area centroid), all at ``film``."""
    a, b = _frame(n)
    u = w * (np.geomspace(1, 20, 12) - 1) / 19 - w / 2
    v = h * (np.geomspace(1, 8, 7) - 1) / 7 - h / 2
    pts = origin + u[None, :, None] * a + v[:, None, None] * b
    return pts.reshape(-1, 3), grid_faces(len(v), len(u)), np.full(len(u) * len(v), film)


def _part():
    """A painted plate centred at c0, plus unpainted faces (a shadowed plate to one side, a
    back plate facing away) that would pull the view off it if counted."""
    c0 = np.array([0.7, 0.05, 0.3])
    parts = [_plate(c0, N0, 0.3, 0.16, TARGET),
             _plate(c0 + [0.0, 0.5, 0.2], N0, 0.4, 0.4, 0.3 * TARGET),
             _plate(c0 - 0.05 * N0, -N0, 0.3, 0.16, 0.0)]
    v, f, th, k = [], [], [], 0
    for pv, pf, pt in parts:
        v.append(pv), f.append(pf + k), th.append(pt)
        k += len(pv)
    return c0, np.concatenate(v), np.concatenate(f), np.concatenate(th)


def test_the_view_frames_the_painted_faces():
    c0, v, f, th = _part()
    view = film_view(v, f, th, TARGET)
    # the orbit centre is the painted rectangle's centre, not its vertices' mean (1.7 cm off)
    assert np.abs(np.asarray(view.centre) - c0).max() < 1e-12  # achieves 1e-16
    assert np.abs(v[: 12 * 7].mean(axis=0) - c0).max() > 0.01
    # the camera looks at it along the plate's normal (the winding's side)
    assert np.degrees(np.arccos(np.clip(np.asarray(view.normal) @ N0, -1, 1))) < 1e-6
    cam = np.asarray(view.centre) + view.offset
    # every painted corner inside MeshCat's 75° vertical field, the plate not a speck in it
    a, b = _frame(N0)
    corners = [c0 + sa * 0.15 * a + sb * 0.08 * b for sa in (-1, 1) for sb in (-1, 1)]
    axis = (c0 - cam) / np.linalg.norm(c0 - cam)
    angles = [math.degrees(math.acos((p - cam) @ axis / np.linalg.norm(p - cam)))
              for p in corners]
    assert 15 < max(angles) < MESHCAT_FOV / 2, angles  # 23.5° here


def test_seen_from_the_gun_side_and_over_the_travel():
    c0, v, f, th = _part()
    f = f[:, ::-1]  # wound the other way: the faces' normal is −N0
    view = film_view(v, f, th, TARGET)
    assert np.asarray(view.normal) @ N0 == pytest.approx(-1, abs=1e-12)
    tips = c0 + 0.15 * N0 + np.array([[0, 0.1, 0], [0, -0.1, 0]])  # the gun, at the standoff
    seen = view.seen_from(tips)
    assert np.asarray(seen.normal) @ N0 == pytest.approx(1, abs=1e-12)
    assert seen.centre == view.centre and seen.radius == view.radius
    assert view.scale == "film thickness [µm] (target 25 ± 10 %)"

    def place(t):  # a line carrying the part along +y at 0.1 m/s
        T = np.eye(4)
        T[1, 3] = 0.1 * t
        return T

    t = np.linspace(0.0, 2.0, 41)
    tips = c0 + 0.15 * N0 + np.outer(0.1 * t, [0, 1, 0])  # the gun follows the part
    moved = view.seen_from(tips, t, place)
    assert np.asarray(moved.normal) @ N0 == pytest.approx(1, abs=1e-12)
    assert np.allclose(np.asarray(moved.centre) - view.centre, [0, 0.1, 0], atol=1e-12)
    assert moved.radius == pytest.approx(view.radius + 0.1, abs=1e-12)


def test_the_legend_states_the_scale():
    html = legend_html(TARGET)
    assert film_label(TARGET) in html and all(f"<span>{x}</span>" in html
                                              for x in ("22.5", "25", "27.5"))
