"""The one film colour scale (viz/film_scale.py): matplotlib's RdBu_r over the target ± 10 %,
the same in thickness.png, the part figure, film.ply and the viewer's legend."""
import numpy as np
import pytest

from pollard_pin.viz.film_scale import FILM_BAND, film_label, film_range, film_rgba, legend_html

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
    html = legend_html(TARGET)
    assert film_label(TARGET) in html and all(f"<span>{x}</span>" in html
                                              for x in ("22.5", "25", "27.5"))


def test_thickness_png_and_part_png_state_the_scale():
    from pollard_pin.viz.paint import thickness_figure
    from pollard_pin.viz.paint_part import part_figure

    U, V = np.linspace(-0.1, 0.1, 5), np.linspace(-0.05, 0.05, 3)
    figs = [thickness_figure(U, V, np.full((3, 5), TARGET), TARGET),
            part_figure(np.zeros((4, 3)), np.full(4, TARGET), TARGET, [1, 0, 0], [0, 1, 0])]
    for fig in figs:
        ax, cax = fig.axes
        film = next(a for a in ax.get_children() if a.get_gid() == "film")
        assert film.get_clim() == pytest.approx((22.5, 27.5), rel=1e-12)
        assert cax.get_ylabel() == film_label(TARGET)
