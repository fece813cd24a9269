"""Time integrals and averages over the samples of a trajectory (trapezoid rule): one
quadrature for the RMS torques of the report, the sweep and the motor sizing, the equivalent
bearing loads (docs/model.md §17, §19) and the paint film (§20). :func:`trapezoid_weights`
integrate (∫f dt); :func:`mean_weights` average (∫f dt / T)."""
from __future__ import annotations

import numpy as np


def trapezoid_weights(t: np.ndarray) -> np.ndarray:
    """Weights w with w @ f = ∫f dt (the trapezoid rule over the samples ``t``); zeros for a
    single sample. The film's time integral (docs/model.md §20)."""
    t = np.asarray(t, dtype=float)
    w = np.zeros(len(t))
    dt = np.diff(t)
    w[:-1] += dt / 2
    w[1:] += dt / 2
    return w


def mean_weights(t: np.ndarray) -> np.ndarray:
    """Weights w with w @ f = ∫f dt / T, T the duration (:func:`trapezoid_weights` over T):
    the time mean; the plain mean for a single sample or a zero duration."""
    t = np.asarray(t, dtype=float)
    if len(t) < 2 or t[-1] == t[0]:
        return np.full(len(t), 1.0 / max(len(t), 1))
    return trapezoid_weights(t) / (t[-1] - t[0])


def time_mean(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """∫x dt / T along axis 0."""
    return mean_weights(t) @ np.asarray(x, dtype=float)


def time_rms(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """sqrt(∫x² dt / T) along axis 0."""
    return np.sqrt(time_mean(t, np.square(x)))


def cubic_mean(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(∫|x|³ dt / T)^(1/3) along axis 0: the ISO 281 equivalent load of a fluctuating load,
    time-weighted (docs/model.md §17)."""
    return np.cbrt(time_mean(t, np.abs(x) ** 3))


__all__ = ["cubic_mean", "mean_weights", "time_mean", "time_rms", "trapezoid_weights"]
