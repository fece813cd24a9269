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
