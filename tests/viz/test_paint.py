"""The paint figure (viz/paint.py): the heat map is the film it is given, in µm on the grid in
mm, coloured over target ± 2 %; the path and the panel outline are drawn where they are."""
import numpy as np

from pollard_pin.viz.paint import BAND, thickness_figure, write_thickness_png


def _data():
    U, V = np.linspace(-0.1, 0.1, 21), np.linspace(-0.05, 0.05, 11)
    th = 25e-6 * (1 + 0.01 * np.outer(np.sin(V * 40), np.cos(U * 30)))
    path = np.array([np.linspace(-0.15, 0.15, 50), np.linspace(-0.04, 0.04, 50)])
    return U, V, th, path


def test_artists_carry_the_data():
    U, V, th, path = _data()
    fig = thickness_figure(U, V, th, 25e-6, path_uv=path, width=0.2, height=0.1)
    ax = fig.axes[0]
    (mesh,) = [c for c in ax.collections if c.get_gid() == "film"]
    assert np.allclose(np.asarray(mesh.get_array()).reshape(th.shape), th * 1e6, rtol=1e-12)
    assert mesh.get_clim() == (25 * (1 - BAND), 25 * (1 + BAND))
    lines = {ln.get_gid(): ln for ln in ax.get_lines()}
    assert np.array_equal(lines["path"].get_xdata(), path[0] * 1e3)
    assert np.array_equal(lines["path"].get_ydata(), path[1] * 1e3)
    edge = lines["panel"]
    assert np.allclose(edge.get_xdata(), [-100, 100, 100, -100, -100])
    assert np.allclose(edge.get_ydata(), [-50, -50, 50, 50, -50])
    assert f"min {th.min() * 1e6:.4g}, max {th.max() * 1e6:.4g} µm" in ax.get_title()


def test_png_is_written(tmp_path):
    U, V, th, _ = _data()
    out = write_thickness_png(tmp_path / "t.png", U, V, th, 25e-6)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.png"]  # no temporary left
