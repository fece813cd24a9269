"""A cell's robots (paint/cell/robots.py, docs/model.md §26): the base frame's rotation is the
part's rule, world and base coordinates invert each other, bad tables refused."""
import numpy as np
import pytest

from pollard_pin.paint.cell.robots import CellError, CellRobot, robots_from_tables
from pollard_pin.paint.target.mesh import placement


def test_the_base_frame_is_the_parts_rotation_and_inverts():
    r = CellRobot("a", (0.1, -0.2, 0.3), (30.0, -45.0, 120.0))
    assert np.allclose(r.R, placement((0, 0, 0), r.rotation)[0], atol=1e-15)
    p = np.random.default_rng(1).normal(size=(5, 3))
    assert np.allclose(r.to_base(r.to_world(p)), p, atol=1e-15)
    assert np.allclose(r.direction_to_base(r.R @ p[0]), p[0], atol=1e-15)
    assert CellRobot("o").is_origin and not r.is_origin


@pytest.mark.parametrize("tables, words", [
    ([{"name": "a", "base": [0, 0, 0]}, {"name": "a", "base": [0, 1, 0]}], "two robots"),
    ([{"name": "a/b", "base": [0, 0, 0]}], "letters, digits"),
    ([{"name": "a", "base": [0, float("nan"), 0]}], "base"),
    ([{"name": "a"}], "is missing")])
def test_bad_tables_are_one_line(tables, words):
    with pytest.raises(CellError, match=words) as info:
        robots_from_tables("job.toml", tables)
    assert "\n" not in str(info.value)
