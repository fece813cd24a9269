"""One film statistics (paint/film/stats.py): a grid's points weigh alike, a part's by area;
each figure against a direct numpy computation on a film built to have known shares."""
import numpy as np
import pytest

from pollard_pin.painting.film.stats import ACCEPTANCE_SHARE, film_check, film_stats, misses

TARGET = 25e-6


def film_with_shares():
    """40 points: 10 at the target, 10 at +4 %, 10 at −8 %, 10 at +20 %."""
    return TARGET * np.repeat([1.0, 1.04, 0.92, 1.2], 10)


def test_grid_points_weigh_alike():
    th = film_with_shares()
    st = film_stats(th, TARGET)
    assert st["within_5pct"] == 0.5 and st["within_10pct"] == 0.75
    assert st["mean"] == th.mean() and st["std"] == th.std()
    assert (st["min"], st["max"]) == (th.min(), th.max())
    assert st["uniformity"] == pytest.approx(0.92 / 1.2, rel=1e-15)
    assert st["deviation_min"] == pytest.approx(-0.08, rel=1e-12)  # achieved ~1e-16
    assert st["deviation_max"] == pytest.approx(0.20, rel=1e-12)


def test_areas_weigh_the_mean_std_and_shares():
    """Area shares: the +20 % points cover 70 % of the area; equal areas give the unweighted
    figures (to 1e-15 relative: only the sum order differs, achieved ~1e-16)."""
    th = film_with_shares()
    areas = np.repeat([0.1, 0.1, 0.1, 0.7], 10)
    st = film_stats(th, TARGET, areas)
    w = areas / areas.sum()
    assert st["within_5pct"] == pytest.approx(0.2, rel=1e-12)
    assert st["within_10pct"] == pytest.approx(0.3, rel=1e-12)
    assert st["mean"] == pytest.approx(np.average(th, weights=w), rel=1e-14)
    assert st["std"] == pytest.approx(np.sqrt(np.cov(th, aweights=w, bias=True)), rel=1e-12)
    alike = film_stats(th, TARGET, np.ones_like(th))
    plain = film_stats(th, TARGET)
    assert alike.keys() == plain.keys()
    for k in plain:
        assert alike[k] == pytest.approx(plain[k], rel=1e-15, abs=1e-30)


def test_film_check_states_the_shares_outside_and_the_extremes():
    """The 40-point film: 25 % of the area beyond ±10 % (the +20 % points), 50 % beyond
    ±5 %, 0.92–1.2 × the target: it misses the acceptance; a film at 0.95–1.05 meets it."""
    st = film_stats(film_with_shares(), TARGET)
    c = film_check(st, TARGET)
    assert (c["outside_5pct"], c["outside_10pct"]) == (0.5, 0.25)
    assert c["min_relative"] == pytest.approx(0.92, rel=1e-12)  # achieved ~1e-16
    assert c["max_relative"] == pytest.approx(1.2, rel=1e-12)
    assert c["acceptance"] == {"band": 0.10, "min_share": ACCEPTANCE_SHARE}
    assert c["meets"] is False and misses(c)
    good = film_check(film_stats(TARGET * np.linspace(0.95, 1.05, 41), TARGET), TARGET)
    assert good["meets"] is True and not misses(good) and good["outside_10pct"] == 0.0


def test_the_acceptance_share_is_where_the_film_tips():
    """99 % of the area within ±10 %: met; 98.9 %: missed; a stated share overrides it."""
    areas = np.array([0.99, 0.01])
    at = film_check(film_stats(TARGET * np.array([1.0, 0.5]), TARGET, areas), TARGET)
    assert at["meets"] and not misses(at)
    below = film_check(film_stats(TARGET * np.array([1.0, 0.5]), TARGET,
                                  np.array([0.989, 0.011])), TARGET)
    assert not below["meets"] and misses(below)
    assert not misses(below, 0.98) and misses(at, 0.995)
    assert film_check(film_stats(TARGET * np.array([1.0, 0.5]), TARGET, areas), TARGET,
                      0.995)["meets"] is False
