"""The grid of a workspace map (workspace/lattice.py, docs/model.md §22): the default bounds
hold the whole reach, a finer grid holds the coarser's points, and a bad plane, bound or
resolution is one error."""

import numpy as np
import pytest

from pollard_pin.workspace.grid import map_workspace
from pollard_pin.workspace.lattice import make_grid, reach_sphere
from pollard_pin.workspace.options import WorkspaceError, WorkspaceOptions


@pytest.mark.parametrize("orientation", [(0.0, 0.0, 0.0), (0.35, -0.35, 0.5)])
def test_default_bounds_hold_the_whole_reach(wide, orientation):
    """With every joint limit a full turn (the largest reach), the reachable points of a
    default volume grid stay at least two cells inside its bounds: nothing is cut off."""
    h = 0.04
    vol = map_workspace(wide, None, WorkspaceOptions(volume=True, resolution=h,
                                                   orientation=orientation))
    g = vol.grid.as_dict()
    lo, hi = (np.asarray(vol.summary["bounding_box"][k]) for k in ("low", "high"))
    assert (lo >= np.asarray(g["start"]) + 2 * h - 1e-9).all()
    assert (hi <= np.asarray(g["stop"]) - 2 * h + 1e-9).all()


def test_a_finer_grid_holds_the_coarser_points(robot):
    """Default bounds snap outward to multiples of the step: every point of the h grid within
    the h/3 grid's span is one of its points (by coordinates: they agree to 1.1e-16 m), and
    both cover the reach sphere."""
    orient = (0.2, -0.1, 0.3)
    centre, radius = reach_sphere(robot.params, orient)
    coarse, fine = (make_grid(robot.params, orient, h, plane=(0, 0.55)) for h in (0.03, 0.01))
    for axis in range(2):
        c, f = coarse.coordinates(axis), fine.coordinates(axis)
        a = coarse.axes[axis]
        for g in (c, f):
            assert g[0] <= centre[a] - radius and g[-1] >= centre[a] + radius
        inside = c[(c >= f[0] - 1e-9) & (c <= f[-1] + 1e-9)]
        assert len(inside) >= len(c) - 4  # the coarse grid's two extra cells on each side
        assert np.abs(inside[:, None] - f[None, :]).min(axis=1).max() <= 1e-14
    assert fine.origin[0] == coarse.origin[0] == 0.55


@pytest.mark.parametrize("kw, words", [
    ({"plane": "x=0.55", "resolution": 0.0}, ["resolution", "> 0"]),
    ({"plane": "x=0.55", "resolution": -1}, ["resolution", "> 0"]),
    ({"plane": "x=0.55", "resolution": 1e-5}, ["would need", "GiB", "at least"]),
    ({"volume": True, "resolution": 1e-3}, ["would need", "at least"]),
    ({"plane": "w=0.5"}, ["x, y or z"]),
    ({"plane": "x0.5"}, ["AXIS=VALUE"]),
    ({"plane": "x=abc"}, ["not a number"]),
    ({"plane": "x=nan"}, ["finite"]),
    ({"plane": "x=0.55", "bounds": {"y": (0.3, -0.3)}}, ["below the upper bound"]),
    ({"plane": "x=0.55", "bounds": {"x": (0, 1)}}, ["other two axes"]),
])
def test_bad_input(robot, kw, words):
    with pytest.raises(WorkspaceError) as err:
        plane = kw.pop("plane", None)
        map_workspace(robot, plane, WorkspaceOptions(**kw))
    msg = str(err.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg
