"""The calibration figure (viz/calibration.py): each stripe's panel shows the measured film
and the chosen model's, in µm against mm from the fitted centre; the PNG is written whole."""
import numpy as np
import pytest
from stripe_sets import make_stripes

from pollard_pin.painting.spray.calibrate import fit_stripes
from pollard_pin.painting.spray.spots import EllipticGaussian
from pollard_pin.viz.calibration import fits_figure, write_fits_png


@pytest.fixture(scope="module")
def fit():
    return fit_stripes(make_stripes(EllipticGaussian(0.03, 0.012), 0, speeds=(0.4,)))


def test_each_stripe_against_its_fit(fit):
    fig = fits_figure(fit)
    axes = [ax for ax in fig.axes if ax.get_visible()]
    assert len(axes) == 4 and fit.chosen == "elliptic"
    for i, (ax, d) in enumerate(zip(axes, fit.data())):
        lines = {ln.get_gid(): ln for ln in ax.get_lines()}
        c = fit.best.offsets[i]
        assert np.allclose(lines[f"measured{i}"].get_xdata(), (d.x - c) * 1e3)
        assert np.allclose(lines[f"measured{i}"].get_ydata(), d.t * 1e6)
        chosen = lines[f"elliptic{i}"]
        x = np.asarray(chosen.get_xdata()) / 1e3 + c
        assert np.allclose(chosen.get_ydata(), fit.best.thickness(d, x, c) * 1e6)
        # the fit is the measurement to the noise (0.2 µm)
        assert np.abs(np.interp(d.x, x, chosen.get_ydata()) - d.t * 1e6).std() < 0.3
        assert f"RMS {fit.best.stripe_rms[i]:.1%}" in ax.get_title()
    assert "elliptic chosen (BIC)" in fig._suptitle.get_text()


def test_png_is_written(fit, tmp_path):
    out = write_fits_png(tmp_path / "fits.png", fit)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fits.png"]
