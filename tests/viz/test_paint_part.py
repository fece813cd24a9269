"""The part's film figure and film.ply's colours (viz/paint_part.py)."""
import numpy as np

from pollard_pin.viz.paint_part import PLY_BAND, film_colours, part_figure, write_part_png


def test_film_colours_span_the_band():
    target = 25e-6
    c = film_colours(np.array([0.5, 1 - PLY_BAND, 1.0, 1 + PLY_BAND, 2.0]) * target, target)
    assert c.dtype == np.uint8 and c.shape == (5, 4)
    assert np.array_equal(c[0], c[1]) and np.array_equal(c[3], c[4])  # clipped
    assert c[1, 2] > c[1, 0] and c[3, 0] > c[3, 2]  # thin blue, thick red
    assert c[2, :3].min() > 200  # on target: near white


def test_part_figure(tmp_path):
    rng = np.random.default_rng(0)
    pts = np.column_stack([np.full(50, 0.7), rng.uniform(-0.1, 0.1, 50), rng.uniform(0.1, 0.2, 50)])
    along, across = np.array([0.0, 1, 0]), np.array([0.0, 0, 1])
    fig = part_figure(pts, np.full(50, 25e-6), 25e-6, along, across, [pts[:5]])
    gids = {a.get_gid() for a in fig.axes[0].get_children()}
    assert {"film", "passes"} <= gids
    path = write_part_png(tmp_path / "t.png", pts, np.full(50, 25e-6), 25e-6, along, across)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
