"""The workspace figure draws the map it is given: the rectangle where the map put it, one
legend entry per reason present (docs/model.md §22)."""
from pathlib import Path

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


def test_stiffness_figure_draws_the_maps_columns(robot):
    """One image per stiffness column, each the map's column on the grid in the shown unit
    (kN/m, Hz, µm); a map without stiffnesses has no such figure."""
    import pytest

    from pollard_pin.viz.workspace import STIFFNESS_PANELS, stiffness_figure

    act = pp.load_actuators(Path(__file__).resolve().parents[2] / "examples" / "actuators.toml")
    ws = pp.map_workspace(robot, "x=0.55", pp.WorkspaceOptions(resolution=0.02, actuators=act))
    fig = stiffness_figure(ws)
    images = {im.get_gid(): im for ax in fig.axes for im in ax.images}
    for col, _, scale in STIFFNESS_PANELS:
        shown = np.ma.filled(images[col].get_array(), np.nan)
        want = scale * ws.columns[col].reshape(ws.grid.shape).T
        assert np.array_equal(np.isnan(shown), np.isnan(want))
        ok = ~np.isnan(want)
        assert ok.sum() == ws.summary["reachable_points"]
        assert np.abs(shown[ok] - want[ok]).max() <= 1e-12 * np.abs(want[ok]).max()
    with pytest.raises(ValueError, match="stiffness"):
        stiffness_figure(pp.map_workspace(robot, "x=0.55",
                                          pp.WorkspaceOptions(resolution=0.02)))
