"""The calibration (painting/spray/calibrate.py), the acceptance check (docs/model.md §30):
stripes made from a known pattern with measurement noise, at two standoffs and two speeds, give
back that pattern within its stated standard errors, and the model chosen is the true one; every
stripe a fit cannot use is one line saying what to measure."""
import math
from dataclasses import replace

import numpy as np
import pytest
from stripe_sets import APEX, EFFICIENCY, make_stripes

from pollard_pin.errors import InputError
from pollard_pin.io.stripes import Stripe, StripeError, StripeSet
from pollard_pin.painting.spray.calibrate import (
    CalibrateOptions,
    check_stripe,
    fit_stripes,
    noise,
    reference_standoff,
)
from pollard_pin.painting.spray.spots import BetaSpot, EllipticGaussian, RoundGaussian

ELLIPTIC = EllipticGaussian(0.030, 0.012)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_known_elliptic_pattern_comes_back_within_its_standard_errors(seed):
    fit = fit_stripes(make_stripes(ELLIPTIC, seed))
    assert fit.chosen == "elliptic" and fit.spread == "fitted" and fit.standoff == 0.20
    best = fit.best
    truth = {**ELLIPTIC.params(), "apex": APEX, "efficiency": EFFICIENCY}
    got = {**best.params, "apex": best.apex, "efficiency": best.efficiency}
    for key, true in truth.items():
        se = best.errors[key]
        # the errors are those of 0.2 µm noise on ~300 points a stripe: small, not zero
        assert 0 < se < 0.01 * abs(true) + 1e-3 * (key == "apex"), (key, se)
        assert abs(got[key] - true) < 3 * se, (key, got[key], true, se)
    assert best.rms_share < 0.01  # the noise: 0.2 µm of peaks of 5-50 µm
    # the round models fit worse by far, and BIC says so
    others = {f.name: f for f in fit.fits if f.name != "elliptic"}
    assert others["gaussian"].bic > best.bic + 1000
    assert others["gaussian"].rms_share > 5 * best.rms_share


def test_the_errors_are_what_the_scatter_says():
    """Over 12 noise draws the errors divided by the stated standard errors scatter like a
    unit normal (a wrong covariance, by a factor 2, fails)."""
    z = []
    for seed in range(12):
        best = fit_stripes(make_stripes(ELLIPTIC, 100 + seed, speeds=(0.4,)),
                           CalibrateOptions(model="elliptic")).best
        z.append([(best.params["sigma_long"] - 0.030) / best.errors["sigma_long"],
                  (best.params["sigma_short"] - 0.012) / best.errors["sigma_short"],
                  (best.efficiency - EFFICIENCY) / best.errors["efficiency"]])
    rms = float(np.sqrt(np.mean(np.square(z))))
    assert 0.6 < rms < 1.6, rms


@pytest.mark.parametrize("spot, name", [(RoundGaussian(0.02), "gaussian"),
                                        (BetaSpot(0.05, 2.5), "beta")])
def test_the_true_model_is_chosen(spot, name):
    fit = fit_stripes(make_stripes(spot, 7, speeds=(0.4,)))
    assert fit.chosen == name
    for key, true in spot.params().items():
        assert abs(fit.best.params[key] - true) < 4 * fit.best.errors[key], key


def test_one_direction_fits_the_round_models_and_says_why_not_the_elliptic():
    stripes = make_stripes(RoundGaussian(0.02), 3, directions=("across",))
    fit = fit_stripes(stripes)
    assert fit.chosen == "gaussian" and "elliptic" in fit.skipped
    assert [f.name for f in fit.fits] == ["gaussian", "beta"]
    assert any("elliptic not tried" in n for n in fit.notes)
    with pytest.raises(StripeError, match="an elliptic spot needs stripes in both directions"):
        fit_stripes(stripes, CalibrateOptions(model="elliptic"))


def test_one_standoff_is_a_cone_from_the_nozzle_and_said():
    stripes = make_stripes(ELLIPTIC, 4, standoffs=(0.2,), apex=0.0)
    fit = fit_stripes(stripes)
    assert fit.spread == "cone" and fit.best.apex == 0.0 and "apex" not in fit.best.errors
    assert any("spread law not fitted (one standoff)" in n for n in fit.notes)
    with pytest.raises(StripeError, match="a spread law needs stripes at two standoffs"):
        fit_stripes(stripes, CalibrateOptions(spread="fit"))


def test_a_given_efficiency_is_kept():
    fit = fit_stripes(make_stripes(ELLIPTIC, 5, speeds=(0.4,)),
                      CalibrateOptions(efficiency=EFFICIENCY))
    assert fit.best.efficiency == EFFICIENCY and "efficiency" not in fit.best.errors
    assert fit.best.k == 2 + 1 + 4  # sizes, apex, a centre per stripe


def test_the_reference_standoff_is_the_files_else_the_most_common():
    s = make_stripes(ELLIPTIC, 6, standoffs=(0.15, 0.25, 0.25), speeds=(0.4,))
    assert reference_standoff(s) == 0.20
    assert reference_standoff(replace(s, standoff=None)) == 0.25
    s = make_stripes(ELLIPTIC, 6, standoffs=(0.25, 0.15), speeds=(0.4,))
    assert reference_standoff(replace(s, standoff=None)) == 0.15  # a tie: the nearest


def _one(x, t, **kw):
    return Stripe(x, t, kw.get("standoff", 0.2), kw.get("speed", 0.5), kw.get("flow", 1.5e-6),
                  "across", source="s.csv")


def test_the_noise_estimate():
    rng = np.random.default_rng(0)
    x = np.linspace(-0.1, 0.1, 2001)
    t = 3e-5 * np.exp(-0.5 * (x / 0.02) ** 2) + rng.normal(0, 0.4e-6, x.shape)
    assert noise(t) == pytest.approx(0.4e-6, rel=0.1)


X = np.linspace(-0.1, 0.1, 201)
GOOD = 0.6 * 0.45 * 1.5e-6 / 0.5 * np.exp(-0.5 * (X / 0.02) ** 2) / (math.sqrt(2 * math.pi)
                                                                     * 0.02)


@pytest.mark.parametrize("t, says", [
    (GOOD - 3e-6 * (np.abs(X - 0.05) < 0.004), "below zero beyond the noise"),
    (GOOD + 0.3 * GOOD.max() * (X < -0.09), "still 30% of its peak at the left end"),
    (0.6 * 0.45 * 1.5e-6 / 0.5 * np.exp(-0.5 * (X / 0.08) ** 2) / (math.sqrt(2 * math.pi) * 0.08),
     "at the left end (-0.1 m): the scan is narrower than the pattern; measure wider"),
    (GOOD * 0, "no film: every reading is ≤ 0"),
    (np.random.default_rng(0).normal(0.0, 0.2e-6, X.shape), "no film above the noise"),
    (GOOD * 3, "more paint than was sprayed (transfer efficiency"),
    (GOOD * 0.01, "almost none of the paint"),
    (0.6 * 0.45 * 1.5e-6 / 0.5 * np.exp(-0.5 * (X / 0.0008) ** 2)
     / (math.sqrt(2 * math.pi) * 0.0008), "only 1 points above half the peak"),
])
def test_a_stripe_a_fit_cannot_use_says_what_to_measure(t, says):
    with pytest.raises(StripeError) as info:
        check_stripe(_one(X, t), 0.45)
    text = str(info.value)
    assert says in text and text.startswith("s.csv: ") and "\n" not in text, text
    with pytest.raises(StripeError, match="s.csv"):  # and the calibration stops there
        fit_stripes(StripeSet((_one(X, GOOD), _one(X, t)), 0.45))


def test_a_good_stripe_passes_with_its_moments():
    c, var = check_stripe(_one(X + 0.003, GOOD), 0.45)
    assert c == pytest.approx(0.003, abs=1e-6) and var == pytest.approx(0.02 ** 2, rel=1e-3)


@pytest.mark.parametrize("kw, says", [({"model": "round"}, "expected one of auto, gaussian"),
                                      ({"spread": "line"}, "spread = 'line'"),
                                      ({"efficiency": 1.5}, "must be at most 1"),
                                      ({"efficiency": 0.0}, "must be > 0")])
def test_options_are_checked_once(kw, says):
    with pytest.raises(InputError, match=says):
        CalibrateOptions(**kw)


def test_the_gun_is_the_chosen_spot_with_the_dry_flow():
    fit = fit_stripes(make_stripes(ELLIPTIC, 8, speeds=(0.4,)))
    gun = fit.gun()
    assert gun.spot == fit.best.spot and gun.apex == fit.best.apex
    assert gun.standoff == 0.20
    assert gun.flow == pytest.approx(1.5e-6 * 0.45 * fit.best.efficiency, rel=1e-12)


def test_directions_swapped_are_one_line():
    stripes = make_stripes(ELLIPTIC, 9, speeds=(0.4,))
    swapped = replace(stripes, stripes=tuple(
        replace(s, direction={"along": "across", "across": "along"}[s.direction])
        for s in stripes.stripes))
    with pytest.raises(StripeError, match="the 'along' stripes are wider than the 'across' "
                                          r"ones \(32.5 against 18.7 mm σ at 0.2 m\): a "
                                          "stroke along the long axis shows the short size"):
        fit_stripes(swapped)


def test_a_poor_fit_is_noted():
    """A pattern of two peaks (a fan with horns) fits no model to the noise: said."""
    x = np.linspace(-0.15, 0.15, 301)
    t = 0.6 * 0.45 * 1.5e-6 / 0.5 * (RoundGaussian(0.012).stripe(x - 0.02)
                                      + RoundGaussian(0.012).stripe(x + 0.02)) / 2
    fit = fit_stripes(StripeSet((_one(x, t),), 0.45))
    assert any("no model describes these stripes well" in n for n in fit.notes), fit.notes


def test_an_efficiency_over_one_is_noted():
    fit = fit_stripes(StripeSet((_one(X, GOOD * 1.05 / 0.6),), 0.45))
    assert fit.best.efficiency == pytest.approx(1.05, rel=1e-3)
    assert any("transfer efficiency fitted at 1.050, over 1" in n for n in fit.notes)


def test_no_model_fitting_is_one_short_line(monkeypatch):
    import pollard_pin.painting.spray.calibrate as module
    from pollard_pin.errors import SolveError

    real_fit = module.fit_model

    def unusable(*args, **kw):
        fit = real_fit(*args, **kw)
        return replace(fit, usable=False, why=f"{fit.name}'s sizes = 0.03 ± 2.2e+05: not "
                                               "determined by these stripes")

    monkeypatch.setattr(module, "fit_model", unusable)
    with pytest.raises(SolveError) as info:
        fit_stripes(make_stripes(EllipticGaussian(0.03, 0.012), 5, speeds=(0.4,)))
    text = str(info.value)
    assert text.startswith("no spot model fits the stripes: gaussian: gaussian's sizes = ")
    assert text.endswith("; nor elliptic or beta") and len(text) < 160, text
