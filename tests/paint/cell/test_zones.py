"""The Split's contract (paint/cell/zones.py, docs/model.md §26.2) as split_cell keeps it for
a cell painting both faces of a plate: zones sorted by (facing, lo), neighbours of one facing
sharing their seam, free edges ±inf at each side's ends, a unit axis across the travel."""
import math

import numpy as np
from cell_split_jobs import plate_part

from pollard_pin.paint.cell.robots import CellRobot
from pollard_pin.paint.cell.split import split_cell
from pollard_pin.paint.cell.zones import Split, Zone
from pollard_pin.paint.job import load_job


def test_a_two_sided_split_keeps_the_contract(robot, tmp_path):
    job = load_job(plate_part(tmp_path))
    turned = (0.0, 0.0, 180.0)  # the far side: gun along −x
    robots = [CellRobot("b_high", (1.40, 0.75, 0.17), turned), CellRobot("low"),
              CellRobot("b_low", (1.40, 0.0, 0.0), turned),
              CellRobot("high", (0.0, 0.75, 0.17))]
    split = split_cell(robot, job, robots)
    assert isinstance(split, Split) and all(isinstance(z, Zone) for z in split.zones)
    a = np.array(split.axis)
    assert abs(a @ a - 1) < 1e-15 and abs(a @ job.line.direction) < 1e-15
    assert [(z.robot, z.facing) for z in split.zones] == [
        ("low", None), ("high", None), ("b_low", (1.0, 0.0, 0.0)), ("b_high", (1.0, 0.0, 0.0))]
    for side in (split.zones[:2], split.zones[2:]):
        assert side[0].lo == -math.inf and side[-1].hi == math.inf
        assert side[0].hi == side[1].lo and side[0].lo < side[0].hi < side[1].hi
    # both sides see the same plate and bands: the same seam (the middle, 0.17 m)
    assert split.zones[0].hi == split.zones[2].hi
    assert abs(split.zones[0].hi - 0.17) < 1e-3  # seen 2e-6 (bisection)
