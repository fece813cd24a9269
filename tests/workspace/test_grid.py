"""Workspace maps (workspace/grid.py, docs/model.md §22): the area converges, the volume is
the stacked planes, the panel and its rectangle are
reachable and maximal, the map states what it does not know, and bad input is one error.
(Each point's reach rule: tests/workspace/test_reach.py; the grid and its bounds:
tests/workspace/test_lattice.py; the rectangle: tests/workspace/test_rectangle.py.)
"""
import math

import numpy as np
import pytest
from refusals import WRONG, refused

from pollard_pin.workspace.grid import (
    WorkspaceError,
    largest_panel,
    map_workspace,
    reachable_box,
)
from pollard_pin.workspace.options import WorkspaceOptions
from pollard_pin.workspace.reach import REASONS, ReachOptions, evaluate

BOUNDS = {"y": (-0.4, 0.4), "z": (-0.15, 0.35)}


@pytest.fixture(scope="module")
def bounded(robot):
    """The summary of the plane x = 0.55 m within BOUNDS at the resolution h, mapped once per
    module (the convergence and the bound tests share the grids)."""
    summaries = {}

    def summary(h):
        if h not in summaries:
            summaries[h] = map_workspace(robot, "x=0.55", WorkspaceOptions(
                resolution=h, bounds=BOUNDS)).summary
        return summaries[h]

    return summary


@pytest.fixture(scope="module")
def panels(robot):
    """``largest_panel`` of the plane x = 0.55 m at the resolution h, once per module."""
    found = {}

    def panel(h):
        if h not in found:
            found[h] = largest_panel(robot, "x=0.55", WorkspaceOptions(resolution=h))
        return found[h]

    return panel


# --- the grid and its figures -----------------------------------------------------------------
def test_area_converges_on_finer_grids(bounded):
    """Refining the grid (the coarse points are a subset of the fine ones): the area's error
    against the finest grid shrinks with h, within half a perimeter's worth of boundary cells
    (seen: 0.0051, 0.0018, 0.0004, 0.0003 m² at h = 20, 10, 5, 2.5 mm)."""
    steps = (0.02, 0.01, 0.005, 0.0025)
    areas = {h: bounded(h)["area"] for h in steps + (0.00125,)}
    errs = [abs(areas[h] - areas[0.00125]) for h in steps]
    perimeter = 2 * (0.6 + 0.34)  # m, of the region (its bounding box)
    for h, e in zip(steps, errs):
        assert e <= 0.5 * perimeter * h, (h, e)
    assert errs == sorted(errs, reverse=True)


def test_volume_streams_and_equals_the_stacked_planes(robot):
    """A coarse volume, streamed chunk by chunk: its volume is the sum over its x-slices of
    the plane maps' areas times the step (the grids coincide point for point). The planes
    share one reachable box for their refusals (``reach_box``): the same refusal as without."""
    h = 0.06
    chunks = []
    vol = map_workspace(robot, None, WorkspaceOptions(volume=True, resolution=h, chunk=1000),
                        sink=chunks.append)
    assert vol.columns is None and len(chunks) > 1
    assert sum(len(c["x"]) for c in chunks) == vol.grid.size
    xs = vol.grid.coordinates(0)
    o = WorkspaceOptions(resolution=h)
    box = reachable_box(robot, o.orientation, ReachOptions(o.margins))
    total, refusals = 0.0, {}
    for x in xs:
        try:
            ws = map_workspace(robot, ("x", float(x)), o, reach_box=box)
        except WorkspaceError as e:
            refusals[float(x)] = str(e)
            continue  # plane with no reachable point
        total += ws.summary["area"] * h
    assert math.isclose(total, vol.summary["volume"], rel_tol=1e-12)
    for kind in ("misses the robot", "no point of"):  # one of each: the box computed
        x = next(x for x, said in refusals.items() if kind in said)
        with pytest.raises(WorkspaceError) as err:
            map_workspace(robot, ("x", x), o)
        assert str(err.value) == refusals[x] and "reachable region spans" in refusals[x]


def test_largest_panel_is_reachable_and_maximal(robot, panels):
    rect = panels(0.01)
    ys = np.arange(rect.low[1], rect.high[1] + 1e-9, 0.01)
    zs = np.arange(rect.low[2], rect.high[2] + 1e-9, 0.01)
    Y, Z = np.meshgrid(ys, zs)
    poses = np.zeros((Y.size, 6))
    poses[:, 0], poses[:, 1], poses[:, 2] = 0.55, Y.ravel(), Z.ravel()
    assert (evaluate(robot, poses)["reachable"] == 1).all()
    assert rect.points == (len(ys), len(zs))


@pytest.mark.parametrize("h", [0.005, 0.01, 0.02])
def test_the_reported_rectangle_has_reachable_corners_and_edges(robot, panels, h):
    """The panel the map reports, ``size`` about ``centre``, re-checked at 7 samples per grid
    step along its four edges (corners included): all reachable. Its size was points × h,
    half a cell past the corner points on each side (at 5 mm its top corners were out of a
    leg's reach); it is now (points − 1) × h, corner point to corner point."""
    rect = panels(h)
    assert rect.axes == ("y", "z")
    assert rect.size == pytest.approx(tuple((n - 1) * h for n in rect.points), abs=1e-9)
    (y0, z0), (sy, sz) = rect.centre[1:], rect.size
    ys = y0 + sy * np.linspace(-0.5, 0.5, 7 * (rect.points[0] - 1) + 1)
    zs = z0 + sz * np.linspace(-0.5, 0.5, 7 * (rect.points[1] - 1) + 1)
    edge = np.concatenate([np.column_stack([ys, np.full_like(ys, z)]) for z in zs[[0, -1]]]
                          + [np.column_stack([np.full_like(zs, y), zs]) for y in ys[[0, -1]]])
    poses = np.zeros((len(edge), 6))
    poses[:, 0], poses[:, 1:3] = 0.55, edge
    cols = evaluate(robot, poses)
    bad = cols["reason"] != 0
    assert not bad.any(), (edge[bad][:3], [REASONS[r] for r in cols["reason"][bad][:3]])


def test_a_coarse_map_states_what_it_does_not_know(robot):
    """At a 10 m resolution one point is reachable: the rectangle is that point (0 × 0 m, it
    was 10 × 10 m) and the area, 100 m² as one cell, carries a bound larger than itself."""
    ws = map_workspace(robot, "x=0.55", WorkspaceOptions(resolution=10.0))
    assert ws.summary["reachable_points"] == 1
    assert ws.rectangle.size == (0.0, 0.0) and ws.rectangle.points == (1, 1)
    assert ws.summary["area"] == 100.0 and ws.summary["area_bound"] >= 100.0


def test_the_area_bound_holds_against_a_fine_grid(bounded):
    """area ± area_bound (the cells of points with a mixed neighbourhood) holds the area of a
    grid 8-16× finer (seen: errors 6.5 % and 4.6 % of the bound at h = 20 and 10 mm)."""
    fine = bounded(0.00125)["area"]
    for h in (0.02, 0.01):
        s = bounded(h)
        assert abs(s["area"] - fine) <= s["area_bound"], (h, s["area"], fine, s["area_bound"])
        assert s["area_bound"] < 0.5 * s["area"]


# --- bad input --------------------------------------------------------------------------------
@pytest.mark.parametrize("kw, words", [
    ({"plane": "x=2.5"}, ["misses the robot", "reachable region spans"]),
    ({"plane": "x=0.55", "orientation": (0, 0)}, ["three"]),
    ({"plane": "x=0.55", "orientation": (0, math.nan, 0)}, ["finite"]),
    ({"plane": "x=0.55", "orientation": (0, 0, 1e7)}, ["phi = 1e+07 rad is absurd"]),
    ({"plane": "x=1e9"}, ["plane x = 1e+09 m misses the robot", "reachable region spans"]),
    ({"plane": "x=0.55", "bounds": {"y": (1.0, 2.0)}}, ["no point", "reachable region"]),
    ({"plane": "x=0.55", "length_scale": -1}, ["length_scale = -1: must be > 0 [m]"]),
    ({}, ["either a plane"])])
def test_bad_input(robot, kw, words):
    with pytest.raises(WorkspaceError) as err:
        plane = kw.pop("plane", None)
        map_workspace(robot, plane, WorkspaceOptions(**kw))
    msg = str(err.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, msg


@pytest.mark.parametrize("wrong", WRONG, ids=repr)
def test_a_wrong_robot_is_one_line(wrong):
    refused(lambda: map_workspace(wrong, "x=0.55"), "robot")


@pytest.mark.parametrize("kw", [{"sink": "x"}, {"progress": 3}])
def test_a_callback_that_is_no_function_is_refused_first(robot, kw):
    """Refused before any point is solved, not a TypeError at the first chunk."""
    with pytest.raises(WorkspaceError, match=r"^(sink|progress) = .*: expected a function or None"):
        map_workspace(robot, "x=0.55", **kw)


def test_a_grid_coarser_than_its_bounds_is_named_as_the_grid(robot):
    """A step that does not divide the bounds gives a grid that spans less: here one point,
    (y, z) = (-0.3, -0.3). The refusal named that extent "the bounds" (y ∈ [-0.3, -0.3] m for
    bounds -0.3:0.3): it is the grid's."""
    with pytest.raises(WorkspaceError) as err:
        map_workspace(robot, "x=0.55", WorkspaceOptions(resolution=1.0, bounds={
            "y": (-0.3, 0.3), "z": (-0.3, 0.3)}))
    msg = str(err.value)
    assert msg.startswith("no point of plane x = 0.55 m is reachable on its grid y ∈ [-0.3, "
                          "-0.3] m, z ∈ [-0.3, -0.3] m"), msg
    assert "bounds" not in msg and "\n" not in msg, msg
