"""One model's least-squares fit (painting/spray/stripe_fit.py): exact stripes give back the
spot exactly; a fit that rests on a bound or leaves a size undetermined does not count; the
elliptic spot's σ_short and its error come through the ratio it is fitted as."""
import math

import numpy as np
import pytest
from stripe_sets import make_stripes

from pollard_pin.painting.spray.calibrate import stripe_data
from pollard_pin.painting.spray.spots import BetaSpot, EllipticGaussian, RoundGaussian
from pollard_pin.painting.spray.stripe_fit import fit_model, fit_variables, spot_params

SPREAD = {"across": 0.03, "along": 0.012}


def _fit(spot, name, noise=0.0, seed=0, **kw):
    stripes = make_stripes(spot, seed, noise=noise, speeds=(0.4,), **kw)
    data = stripe_data(stripes)
    centres = [float(np.sum(d.x * d.t) / np.sum(d.t)) for d in data]
    spread = {d: math.sqrt(np.mean([np.sum((x.x - c) ** 2 * x.t) / np.sum(x.t)
                                    for x, c in zip(data, centres) if x.direction == d]))
              for d in {x.direction for x in data}}
    return fit_model(name, data, 0.2, centres, spread, fit_apex=True, efficiency=None,
                     efficiency0=0.5)


def test_exact_stripes_give_the_spot_back_exactly():
    fit = _fit(EllipticGaussian(0.03, 0.012), "elliptic", noise=1e-12)
    assert fit.usable and fit.k == 2 + 2 + 4
    assert fit.params["sigma_long"] == pytest.approx(0.03, rel=1e-6)
    assert fit.params["sigma_short"] == pytest.approx(0.012, rel=1e-6)
    assert fit.apex == pytest.approx(0.02, abs=1e-7)
    assert fit.efficiency == pytest.approx(0.6, rel=1e-6)
    assert fit.rms_share < 1e-6 and max(fit.stripe_rms) < 1e-5


def test_the_ratio_carries_sigma_short_and_its_error():
    fit = _fit(EllipticGaussian(0.03, 0.012), "elliptic", noise=0.2e-6, seed=3)
    # σ_short = ρ σ_long: its error from both and their covariance, never more than the two
    # relative errors added (what the covariance may at most give)
    rel = fit.errors["sigma_short"] / fit.params["sigma_short"]
    assert 0 < rel < 0.01
    assert spot_params("elliptic", {"sigma_long": 0.03, "ratio": 0.4}) == {
        "sigma_long": 0.03, "sigma_short": pytest.approx(0.012, rel=1e-15)}
    assert spot_params("beta", {"radius": 0.05, "beta": 2.0}) == {"radius": 0.05, "beta": 2.0}


def test_a_beta_spot_on_gaussian_stripes_does_not_count():
    fit = _fit(RoundGaussian(0.02), "beta", noise=0.2e-6, seed=1)
    assert not fit.usable and fit.why.startswith("beta → ") and "gaussian model's" in fit.why, fit
    good = _fit(RoundGaussian(0.02), "gaussian", noise=0.2e-6, seed=1)
    assert good.usable and good.why == "" and good.bic < fit.bic


def test_the_starts_come_from_the_measured_spreads():
    v = dict((n, s) for n, s, *_ in fit_variables("elliptic", SPREAD, 0.03))
    assert v == {"sigma_long": 0.03, "ratio": pytest.approx(0.4)}
    (name, start, scale, lo, hi), = fit_variables("gaussian", SPREAD, 0.03)
    assert name == "sigma" and start == pytest.approx(0.021) and lo < start < hi
    beta = dict((n, s) for n, s, *_ in fit_variables("beta", {"across": 0.02}, 0.02))
    assert beta["radius"] / math.sqrt(2 * (beta["beta"] + 1)) == pytest.approx(0.02)
    with pytest.raises(KeyError):
        fit_variables("square", SPREAD, 0.03)


def test_a_flat_beta_spot_counts():
    # β = 1.5, a flat-topped disc: near β's lower bound, not its Gaussian limit (β → 60); the
    # 1 % of (1, 60] that marks a Gaussian-like β once refused every β below 1.59
    fit = _fit(BetaSpot(0.06, 1.5), "beta", noise=0.2e-6, seed=2)
    assert fit.usable and fit.why == "", fit.why
    assert abs(fit.params["beta"] - 1.5) < 3.5 * fit.errors["beta"] < 0.1
    gauss = _fit(BetaSpot(0.06, 1.5), "gaussian", noise=0.2e-6, seed=2)
    assert fit.bic < gauss.bic - 100
