"""workspace/options.py: WorkspaceOptions checked once (one-line errors, values normalised),
and the map it drives is the one of the defaults it spells out."""
import math

import numpy as np
import pytest

from pollard_pin.kinematics.margins import MarginError, Margins
from pollard_pin.workspace.grid import map_workspace
from pollard_pin.workspace.options import (
    CHUNK,
    WorkspaceError,
    WorkspaceOptions,
    check_orientation,
    finite_value,
)


def test_keep_takes_true_false_or_none():
    for keep in (True, False, None):
        assert WorkspaceOptions(keep=keep).keep is keep


def test_values_are_normalised_once():
    o = WorkspaceOptions(orientation=[0, "0.5", np.float32(1)], length_scale=1)
    assert o.orientation == (0.0, 0.5, 1.0) and all(type(v) is float for v in o.orientation)
    assert o.margins == Margins() and o.chunk == CHUNK and o.length_scale == 1.0


@pytest.mark.parametrize("kwargs, error, says", [
    ({"orientation": (0, 0)}, WorkspaceError, "expected three finite numbers"),
    ({"orientation": (0, 0, 1e7)}, WorkspaceError, "phi = 1e+07 rad is absurd"),
    ({"margins": (0.05, 1e-3)}, MarginError, "expected Margins(wrist=…, singularity=…)"),
    ({"length_scale": -1}, WorkspaceError, "length_scale = -1: must be > 0 [m]"),
    ({"chunk": 0}, WorkspaceError, "chunk = 0: must be a whole number of points >= 1"),
    ({"chunk": 2.5}, WorkspaceError, "chunk = 2.5"),
    ({"chunk": True}, WorkspaceError, "chunk = True"),
    # "x" is truthy: the old options kept every chunk's columns of a volume
    ({"keep": "x"}, WorkspaceError, "keep = 'x': expected True, False or None, got str"),
    ({"keep": 0}, WorkspaceError, "keep = 0: expected True, False or None, got int"),
    ({"volume": "no"}, WorkspaceError, "volume = 'no': expected True or False, got str"),
])
def test_bad_options_are_one_line_at_construction(kwargs, error, says):
    with pytest.raises(error) as err:
        WorkspaceOptions(**kwargs)
    assert says in str(err.value) and "\n" not in str(err.value)


def test_the_shared_value_rules():
    assert check_orientation(("1", 2, 3.5)) == (1.0, 2.0, 3.5)
    # given in degrees, checked and named in degrees, returned in radians
    assert check_orientation((0, 90, -180), deg=True) == pytest.approx((0, np.pi / 2, -np.pi))
    with pytest.raises(WorkspaceError, match=r"^orientation psi = 1e\+300 deg is absurd: \|psi\| "
                                             r"> 5.72958e\+07 deg \(1e\+06 rad"):
        check_orientation((1e300, 0, 0), deg=True)
    assert finite_value("0.25", "x", "m") == 0.25
    with pytest.raises(WorkspaceError, match=r"x = 10000.0 must be a finite number within "
                                             r"±1000 m"):
        finite_value(1e4, "x", "m")
    with pytest.raises(WorkspaceError, match="is not a number"):
        finite_value("0.5_5", "x", "m")  # as typed: no digit separators


def test_no_options_is_the_default_options_and_chunks_do_not_change_the_map(robot):
    default = map_workspace(robot, "x=0.55", WorkspaceOptions(resolution=0.05))
    chunked = map_workspace(robot, "x=0.55", WorkspaceOptions(resolution=0.05, chunk=7))
    for name, col in default.columns.items():
        np.testing.assert_array_equal(chunked.columns[name], col, err_msg=name)
    assert default.summary["area"] == chunked.summary["area"] > 0
    with pytest.raises(WorkspaceError, match="must be a WorkspaceOptions, got dict"):
        map_workspace(robot, "x=0.55", {"resolution": 0.05})
    assert math.isclose(WorkspaceOptions().resolution, 0.005)


@pytest.mark.parametrize("kw", [{"chunk": -10**400}, {"orientation": 10**400},
                                {"orientation": (10**400,) * 40}], ids=["chunk", "int", "long"])
def test_a_huge_value_is_shown_short(kw):
    with pytest.raises(WorkspaceError) as got:
        WorkspaceOptions(**kw)
    assert len(str(got.value)) < 200 and "\n" not in str(got.value)
