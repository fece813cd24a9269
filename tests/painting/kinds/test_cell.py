"""A cell's paint.json numbers (painting/kinds/cell.py, docs/model.md §26): each seam's film
over the run-on band around it, area-weighted."""
import math

import numpy as np
import pytest

from pollard_pin.painting.cell.zones import Split, Zone
from pollard_pin.painting.kinds.cell import seam_entries


def test_a_seams_band_is_the_points_within_the_runout():
    split = Split((0.0, 0.0, 1.0), (Zone("a", -math.inf, 0.2), Zone("b", 0.2, 0.5),
                                    Zone("c", 0.5, math.inf)), 0.04)
    x = np.linspace(0.0, 0.7, 701)
    th = np.where(np.abs(x - 0.2) <= 0.01, 1.1, 1.0) * 25e-6  # a doubled stripe at 0.2
    th[np.abs(x - 0.5) <= 0.005] = 0.9 * 25e-6  # a starved one at 0.5
    areas = np.full(len(x), 1e-3)
    (a, b) = seam_entries(split, x, th, areas, 25e-6)
    assert (a["at"], b["at"]) == (0.2, 0.5)
    assert a["max"] == pytest.approx(1.1) and a["min"] == pytest.approx(1.0)
    assert b["min"] == pytest.approx(0.9) and b["max"] == pytest.approx(1.0)
    # the stripe's share of the points within ±40 mm of 0.2 m (about 20 of 80)
    band, stripe = np.abs(x - 0.2) <= 0.04, np.abs(x - 0.2) <= 0.01
    assert a["mean"] == pytest.approx(1 + 0.1 * stripe.sum() / band.sum(), rel=1e-12)


def test_summary_lines():
    """The line, the film, each seam, the strokes and each robot's waits, each robot (its
    zone's open ends: 'edge'), the gun body's and the links' clearance, the robots' closest
    pair, the timing."""
    from pollard_pin.painting.kinds.cell import summary_lines

    use = {"m": {"peak_torque": 0.5, "rms_torque": 0.25, "speed": 0.1}}
    robot = {"zone": {"lo": None, "hi": 0.2}, "start": 1.0, "program_time": 8.0,
             "cycle": 9.0, "motors": use,
             "strokes": {"direction": "across", "step_from": "leading", "dwell_s": 0.0}}
    rep = {"line": {"speed": 0.03, "searched": True, "cycle": 9.0, "slowest_robot": "a",
                    "min_pitch": 0.27, "parts_per_hour": 400.0, "upper_bound": 0.05},
           "thickness": {"min": 24e-6, "max": 26e-6, "mean": 25e-6, "within_5pct": 0.99,
                         "within_10pct": 1.0},
           "target": 25e-6, "seams": [{"at": 0.2, "min": 0.95, "max": 1.05, "band_m": 0.04}],
           "robots": [{**robot, "name": "a"}, {**robot, "name": "b", "zone": {"lo": 0.2,
                                                                             "hi": None},
                       "strokes": {"direction": "across", "step_from": "leading",
                                   "dwell_s": 1.5}}],
           "clearance": {"gun_to_part_m": 0.14, "gun_robot": "a", "to_part_m": 0.05,
                         "robot": "b", "robot_at_s": 2.0, "between_robots_m": 0.3,
                         "pair": ["a", "b"], "pair_at_s": 3.0},
           "timings": {"plan": 1.0, "film": 2.0}}
    assert summary_lines(rep, ["m"]) == [
        "line speed 0.03 m/s (the fastest), cycle 9.000 s (robot 'a', the slowest), pitch "
        "0.270 m, 400.0 parts per hour; upper bound 0.05 m/s",
        "film 24–26 µm, mean 25 µm (target 25 µm), 99.00 % of the area within ±5 %, 100.00 % "
        "within ±10 %",
        "seam at 0.2000 m: film 0.9500–1.0500 of the target within ±40 mm",
        "strokes across the travel, stepping from the leading end; waits at the turnarounds "
        "'a' 0.000 s, 'b' 1.500 s",
        "robot 'a': zone edge..0.2000 m, starts 1.000 s, program 8.000 s, cycle 9.000 s, "
        "motors ≤ 50 % of peak torque, ≤ 25 % RMS",
        "robot 'b': zone 0.2000..edge m, starts 1.000 s, program 8.000 s, cycle 9.000 s, "
        "motors ≤ 50 % of peak torque, ≤ 25 % RMS",
        "gun body 140.0 mm from the part at its closest (robot 'a')",
        "the links of robot 'b' 50.0 mm from the part at their closest (t = 2.00 s)",
        "robots 'a' and 'b' 300.0 mm apart at their closest (t = 3.00 s)",
        "planned in 1.00 s, film in 2.00 s"]
