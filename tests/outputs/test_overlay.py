"""A paint output folder as the viewer's overlay (outputs/overlay.py): the film drawn on the
film scale from the folder's own values, framed by the default view, carried by the line
(tests/cli/test_view*.py check the pages ``view --paint`` writes)."""
import json

import numpy as np
import pytest

from pollard_pin.film_scale import scale_rgba
from pollard_pin.outputs.overlay import paint_overlay, riding
from pollard_pin.painting.line.conveyor import Line
from pollard_pin.viz.viewer import ROOT

TARGET = 25e-6


class _Scene:
    """What a drawing asks of a MeshCat visualizer: its nodes' objects, kept."""

    def __init__(self):
        self.objects = {}

    def __getitem__(self, node):
        scene = self

        class _Node:
            def set_object(self, geometry, material=None):
                scene.objects[node] = geometry

        return _Node()


def _panel(folder, **report):
    folder.mkdir()
    (folder / "path.csv").write_text("t\n0\n")
    th = [TARGET * (1 + 0.05 * k) for k in range(-3, 3)]
    (folder / "thickness.csv").write_text("x,y,z,u,v,thickness\n" + "".join(
        f"0.55,{u},{v},{u},{v},{th[3 * i + j]}\n" for i, v in enumerate((0, 0.1))
        for j, u in enumerate((0, 0.1, 0.2))))
    (folder / "paint.json").write_text(json.dumps(
        {"target": TARGET, "grid": {"nu": 3, "nv": 2, "resolution": 0.1}, **report}))
    return np.array(th)


def test_a_still_panel_is_drawn_on_the_film_scale_and_framed(tmp_path):
    th = _panel(tmp_path / "p")
    draw = paint_overlay(tmp_path / "p")
    scene = _Scene()
    draw(scene)
    geometry = scene.objects[f"{ROOT}/paint"]
    lo, hi = TARGET * 0.9, TARGET * 1.1
    assert np.allclose(np.reshape(geometry.color, (-1, 3)), scale_rgba(th, lo, hi)[:, :3])
    assert draw.moving is None
    assert draw.view.centre == pytest.approx((0.55, 0.1, 0.05), abs=1e-12)
    assert abs(draw.view.normal[0]) == pytest.approx(1.0)  # the plate x = 0.55 seen square
    assert "target 25 ± 10 %" in draw.view.scale


def test_a_grid_of_one_row_has_no_view(tmp_path):
    folder = tmp_path / "p"
    folder.mkdir()
    (folder / "path.csv").write_text("t\n0\n")
    (folder / "thickness.csv").write_text("x,y,z,u,v,thickness\n0.55,0,0,0,0,2.5e-5\n"
                                          "0.55,0.1,0,0.1,0,2.5e-5\n")
    (folder / "paint.json").write_text(json.dumps({"target": TARGET,
                                                   "grid": {"nu": 2, "nv": 1}}))
    assert paint_overlay(folder).view is None


def test_the_line_carries_the_film(tmp_path):
    _panel(tmp_path / "p", line={"speed": 0.03, "direction": [0.0, -1.0, 0.0]})
    draw = paint_overlay(tmp_path / "p")
    (node, place), = draw.moving.items()
    assert node == f"{ROOT}/paint"
    assert np.allclose(place(2.0)[:3, 3], [0.0, -0.06, 0.0])
    assert np.array_equal(place(2.0)[:3, :3], np.eye(3))
    assert riding(Line(0.03, (0.0, -1.0, 0.0)))[node](2.0) == pytest.approx(place(2.0))
