"""The part's film figure (viz/paint_part.py), on the one film scale."""
import numpy as np
import pytest

from pollard_pin.film_scale import film_label
from pollard_pin.viz.paint_part import part_figure, write_part_png

TARGET = 25e-6


def test_part_figure(tmp_path):
    rng = np.random.default_rng(0)
    pts = np.column_stack([np.full(50, 0.7), rng.uniform(-0.1, 0.1, 50), rng.uniform(0.1, 0.2, 50)])
    along, across = np.array([0.0, 1, 0]), np.array([0.0, 0, 1])
    fig = part_figure(pts, np.full(50, 25e-6), 25e-6, along, across, [pts[:5]])
    gids = {a.get_gid() for a in fig.axes[0].get_children()}
    assert {"film", "passes"} <= gids
    path = write_part_png(tmp_path / "t.png", pts, np.full(50, 25e-6), 25e-6, along, across)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_thickness_png_and_part_png_state_the_scale():
    from pollard_pin.viz.paint import thickness_figure

    U, V = np.linspace(-0.1, 0.1, 5), np.linspace(-0.05, 0.05, 3)
    figs = [thickness_figure(U, V, np.full((3, 5), TARGET), TARGET),
            part_figure(np.zeros((4, 3)), np.full(4, TARGET), TARGET, [1, 0, 0], [0, 1, 0])]
    for fig in figs:
        ax, cax = fig.axes
        film = next(a for a in ax.get_children() if a.get_gid() == "film")
        assert film.get_clim() == pytest.approx((22.5, 27.5), rel=1e-12)
        assert cax.get_ylabel() == film_label(TARGET)


def test_the_axes_are_named_as_the_writer_says():
    """A still part's or a line's: along and across the passes; a cell's its own names."""
    from pollard_pin.viz.paint_part import PASS_AXES

    pts = np.zeros((4, 3))
    ax = part_figure(pts, np.full(4, TARGET), TARGET, [1, 0, 0], [0, 1, 0]).axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == PASS_AXES == ("along the passes [mm]",
                                                               "across the passes [mm]")
    ax = part_figure(pts, np.full(4, TARGET), TARGET, [1, 0, 0], [0, 1, 0],
                     labels=("x [mm]", "y [mm]")).axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [mm]", "y [mm]")
