"""The one film colour scale (film_scale.py, a leaf): matplotlib's RdBu_r over the target
± 10 %, the same in thickness.png, the part figure, film.ply, paint.json and the viewer's
legend."""
import numpy as np
import pytest

from pollard_pin.film_scale import FILM_BAND, film_label, film_range, film_rgba, ply_colours

TARGET = 25e-6


def test_one_colour_scale():
    from matplotlib import colormaps

    lo, hi = film_range(TARGET)
    assert (lo, hi) == pytest.approx((TARGET * (1 - FILM_BAND), TARGET * (1 + FILM_BAND)))
    rdbu = colormaps["RdBu_r"]
    got = film_rgba([0.0, lo, TARGET, hi, 1.0], TARGET)
    want = (np.array([rdbu(0.0), rdbu(0.0), rdbu(0.5), rdbu(1.0), rdbu(1.0)]) * 255).round()
    # the ends exact; on target, one 256-colour table step either side (0.5 rounds to 0.4999…)
    assert np.array_equal(got[[0, 1, 3, 4]], want[[0, 1, 3, 4]])
    assert np.abs(got[2].astype(int) - want[2]).max() <= 1
    assert film_label(TARGET) == "film thickness [µm] (target 25 ± 10 %)"


def test_film_colours_span_the_band():
    c = film_rgba(np.array([0.5, 1 - FILM_BAND, 1.0, 1 + FILM_BAND, 2.0]) * TARGET, TARGET)
    assert c.dtype == np.uint8 and c.shape == (5, 4)
    assert np.array_equal(c[0], c[1]) and np.array_equal(c[3], c[4])  # clipped
    assert c[1, 2] > c[1, 0] and c[3, 0] > c[3, 2]  # thin blue, thick red
    assert c[2, :3].min() > 200  # on target: near white


def test_paint_json_states_what_film_ply_colours_mean():
    assert ply_colours(TARGET) == {"colour_map": "RdBu_r", "range": list(film_range(TARGET))}
