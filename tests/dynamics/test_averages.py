"""Time integrals and averages over samples (dynamics/averages.py): the trapezoid and mean
weights against numpy's trapezoid rule and exact integrals, uneven steps, and the degenerate
cases."""
import numpy as np
import pytest

from pollard_pin.dynamics.averages import (
    cubic_mean,
    mean_weights,
    time_mean,
    time_rms,
    trapezoid_weights,
)


def test_weights_integrate_a_line_exactly_on_uneven_steps():
    t = np.array([0.0, 0.1, 0.5, 0.55, 2.0])
    w = mean_weights(t)
    assert w.sum() == pytest.approx(1.0, rel=1e-15)
    # ∫₀² (3 + 2t) dt / 2 = (6 + 4) / 2 = 5: the trapezoid rule is exact for lines
    assert w @ (3 + 2 * t) == pytest.approx(5.0, rel=1e-15)
    assert w == pytest.approx([0.025, 0.125, 0.1125, 0.375, 0.3625], rel=1e-14)


@pytest.mark.parametrize("seed", range(5))
def test_integral_and_mean_weights_against_numpys_trapezoid(seed):
    # Uneven steps over a duration ≠ 1 (so that ∫ and ∫/T differ), several columns at once.
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.01, 0.7, 40)) - 0.3
    f = rng.normal(size=(40, 3))
    T = t[-1] - t[0]
    want = np.trapezoid(f, t, axis=0)
    # achieves ≈ 1e-16 relative to the column's scale
    scale = np.trapezoid(np.abs(f), t, axis=0)
    assert np.abs(trapezoid_weights(t) @ f - want).max() <= 1e-13 * scale.max()
    assert np.abs(mean_weights(t) @ f - want / T).max() <= 1e-13 * scale.max() / T
    assert trapezoid_weights(t).sum() == pytest.approx(T, rel=1e-14)


def test_integral_weights_of_one_sample_are_zero_and_mean_weights_the_plain_mean():
    assert trapezoid_weights([0.3]).tolist() == [0.0]
    assert trapezoid_weights([1.0, 1.0]).tolist() == [0.0, 0.0]
    assert mean_weights([1.0, 1.0]).tolist() == [0.5, 0.5]


def test_mean_and_rms_converge_to_the_integrals():
    """sin over one period: mean 0, RMS 1/√2; the trapezoid rule on a periodic function is
    spectrally accurate (achieved 1e-16), asserted 1e-12."""
    t = np.linspace(0.0, 2 * np.pi, 201)
    x = np.column_stack([np.sin(t), 2 + 0 * t])
    assert time_mean(t, x) == pytest.approx([0.0, 2.0], abs=1e-12)
    assert time_rms(t, x) == pytest.approx([2 ** -0.5, 2.0], rel=1e-12)


@pytest.mark.parametrize("t", [[0.3], [1.0, 1.0, 1.0]])
def test_one_sample_or_no_duration_is_the_plain_mean(t):
    t = np.asarray(t)
    x = np.arange(1.0, len(t) + 1)
    assert time_mean(t, x) == pytest.approx(x.mean(), rel=1e-15)


def test_cubic_mean_is_time_weighted():
    t = np.array([0.0, 1.0, 1.5, 3.0])
    x = np.full(4, -2.0)
    assert cubic_mean(t, x) == pytest.approx(2.0, rel=1e-15)
    t = np.linspace(0.0, 1.0, 20001)  # ∫₀¹ t³ dt = 1/4
    assert cubic_mean(t, t) == pytest.approx(0.25 ** (1 / 3), rel=1e-8)
    # 1 N for 1 s then 2 N for 3 s (a step resolved by a short ramp): ((1 + 24) / 4)^(1/3)
    t = np.array([0.0, 1.0, 1.0 + 1e-9, 4.0])
    assert cubic_mean(t, np.array([1.0, 1.0, 2.0, 2.0])) == pytest.approx(
        (25 / 4) ** (1 / 3), rel=1e-8)
