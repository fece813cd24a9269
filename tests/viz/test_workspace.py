"""The workspace figure draws the map it is given: the rectangle where the map put it, one
legend entry per reason present (docs/model.md §22)."""
import numpy as np

import pollard_pin as pp
from pollard_pin.viz.workspace import workspace_figure


def test_figure_draws_the_rectangle_and_the_reasons(robot):
    ws = pp.map_workspace(robot, "x=0.55", pp.WorkspaceOptions(resolution=0.02))
    fig = workspace_figure(ws)
    ax = fig.axes[0]
    box = [p for p in ax.patches if p.get_gid() == "rectangle"]
    assert len(box) == 1
    # corner point to corner point: the rectangle's corners are reachable grid points
    np.testing.assert_allclose(box[0].get_xy(), ws.rectangle.low[1:], atol=1e-12)
    np.testing.assert_allclose(np.add(box[0].get_xy(), (box[0].get_width(),
                                                        box[0].get_height())),
                               ws.rectangle.high[1:], atol=1e-12)
    image = [im for im in ax.images if im.get_gid() == "margin"]
    assert image and image[0].get_array().shape[:2] == ws.grid.shape[::-1]
    legend = fig.legends[0]
    shown = {t.get_text().rsplit(" (", 1)[0] for t in legend.get_texts()}
    present = {ws.reasons[c] for c in np.unique(ws.columns["reason"]) if c}
    assert present <= shown
