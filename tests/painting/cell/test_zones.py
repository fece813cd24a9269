"""Zones, trigger windows and seam samples (paint/cell/zones.py, docs/model.md §26.2,
§26.3), and the Split's contract as split_cell keeps it for a cell painting both faces of a
plate: zones sorted by (facing, lo), neighbours of one facing sharing their seam, free edges
±inf at each side's ends, a unit axis across the travel."""

import math

import numpy as np
import pytest
from cell_split_jobs import plate_part

from pollard_pin.dynamics.averages import trapezoid_weights
from pollard_pin.painting.cell.robots import CellRobot
from pollard_pin.painting.cell.split import split_cell
from pollard_pin.painting.cell.zones import (
    CLOSED,
    OPEN,
    Split,
    Zone,
    ZoneRelative,
    seam_fractions,
    window,
    with_samples,
)
from pollard_pin.painting.errors import PlanError
from pollard_pin.painting.job import load_job


@pytest.mark.parametrize("lo, hi, start, rate", [
    (0.1, 0.3, 0.0, 0.33), (0.1, 0.3, 0.5, -0.33), (-math.inf, 0.2, 0.0, 0.33),
    (0.2, math.inf, 0.5, -0.33), (2.0, 3.0, 0.0, 0.33)])
def test_a_window_is_where_the_coordinate_lies_in_the_zone(lo, hi, start, rate):
    duration = 1.5
    a, b = window(lo, hi, start, rate, duration)
    tau = np.linspace(0.0, duration, 30001)
    x = start + rate * tau
    inside = (x >= lo) & (x <= hi)
    got = (tau >= a) & (tau <= b)
    # brute force on a 50 µs grid: the two differ at most at the grid point next to an end
    assert np.count_nonzero(got != inside) <= 2
    if not inside.any():
        assert (a, b) == CLOSED
    if inside.all():
        assert (a, b) == OPEN


def test_a_seam_fraction_integrates_a_switch_at_the_sample_exactly():
    """The trapezoid rule weighted by the trigger, its seam sample a fraction, integrates a
    linear rate over [0, seam] exactly (the rule is exact for linear functions)."""
    rng = np.random.default_rng(3)
    t = np.cumsum(rng.uniform(0.5, 1.5, 40))
    seam = 0.5 * (t[17] + t[18]) + 0.1
    t = with_samples(t, [seam], 1e-9)
    spray = (t <= seam + 1e-12).astype(float)
    f = 0.7 + 0.3 * t
    on_before = seam_fractions(t, spray, [seam])
    on_after = seam_fractions(t, 1.0 - spray + (np.abs(t - seam) < 1e-12), [seam])
    w = trapezoid_weights(t)
    exact_before = 0.7 * (seam - t[0]) + 0.15 * (seam ** 2 - t[0] ** 2)
    exact_after = 0.7 * (t[-1] - seam) + 0.15 * (t[-1] ** 2 - seam ** 2)
    assert (w * on_before) @ f == pytest.approx(exact_before, rel=1e-13)  # seen 1e-16
    assert (w * on_after) @ f == pytest.approx(exact_after, rel=1e-13)
    k = int(np.argmin(np.abs(t - seam)))
    assert on_before[k] + on_after[k] == pytest.approx(1.0, abs=1e-15)  # they share it


def test_samples_within_the_tolerance_move_onto_an_instant():
    t = np.arange(11) * 0.1
    assert np.array_equal(with_samples(t, [0.3 + 1e-12], 1e-9)[3], 0.3 + 1e-12)
    assert len(with_samples(t, [0.3 + 1e-12], 1e-9)) == 11
    assert len(with_samples(t, [0.35], 1e-9)) == 12


def test_a_zone_relative_opens_its_windows_and_names_its_seams():
    rel = ZoneRelative(lambda t: None, np.array([0.0, 1.0, 3.0]), np.array([1.0, 2.0, 1.0]),
                       ("ramp", "pass", "turn"), windows=(CLOSED, (0.5, math.inf), CLOSED))
    t = np.array([0.2, 1.2, 1.5, 2.9, 3.2])
    assert np.array_equal(rel.trigger(t), [0, 0, 1, 1, 0])
    assert np.allclose(rel.seam_times(), [1.5])


def test_a_split_names_its_seams_and_zones():
    s = Split((0.0, 0.0, 1.0), (Zone("low", -math.inf, 0.18), Zone("high", 0.18, math.inf)),
              0.04)
    assert s.seams() == [0.18] and s.zone_of("high").lo == 0.18
    assert s.to_dict("low") == {"lo": None, "hi": 0.18, "axis": [0.0, 0.0, 1.0],
                                "facing": None, "runout": 0.04}
    with pytest.raises(PlanError, match="robot 'mid' has no zone"):
        s.zone_of("mid")
    with pytest.raises(PlanError, match="zone 0.2..0.1 m is empty"):
        Zone("x", 0.2, 0.1)


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
