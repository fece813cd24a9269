"""The constant-s̈ parametrisation of a path (TOPP-RA's output, as toppra's
``ParametrizeConstAccel``; docs/model.md §19), written once.

A timing is the grid s_0 < … < s_{n−1} with the path rate ṡ_i at each point; between two
points s̈ is constant, u_i = (ṡ_{i+1}² − ṡ_i²) / (2Δs_i), so that ṡ² = ṡ_i² + 2u_i(s − s_i)
and, with τ = t − t_i, s = s_i + ṡ_i τ + u_i τ²/2, ṡ = ṡ_i + u_i τ; the interval lasts
Δt_i = 2Δs_i / (ṡ_i + ṡ_{i+1}). Arrays in, arrays out; a timing object is anything with
``t``, ``s`` and ``s_dot`` (n,).
"""
from __future__ import annotations

import numpy as np


def interval_acceleration(s, s_dot) -> np.ndarray:
    """s̈ of each interval, (n − 1,): (ṡ_{i+1}² − ṡ_i²) / (2 Δs_i)."""
    return (s_dot[1:] ** 2 - s_dot[:-1] ** 2) / (2.0 * np.diff(s))


def interval_durations(s, s_dot) -> np.ndarray:
    """Δt_i = 2Δs_i / (ṡ_i + ṡ_{i+1}), (n − 1,); inf where ṡ = 0 at both ends."""
    with np.errstate(divide="ignore"):
        return 2.0 * np.diff(s) / (s_dot[:-1] + s_dot[1:])


def rate_squared(s, s_dot, theta, u=None) -> np.ndarray:
    """ṡ² at the points s_i + θ·Δs_i of each interval, (n − 1, len(θ)), θ ∈ [0, 1];
    ``u``: the intervals' s̈ when already at hand."""
    u = interval_acceleration(s, s_dot) if u is None else u
    return s_dot[:-1, None] ** 2 + 2.0 * theta * np.diff(s)[:, None] * u[:, None]


def at_path(t, grid, s_dot, s) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, ṡ, s̈) at any points ``s`` of the path (at a grid point, the interval that starts
    there), the timing being times ``t``, grid ``grid`` and rates ``s_dot`` (n,)."""
    s = np.asarray(s, dtype=float)
    i = np.clip(np.searchsorted(grid, s, side="right") - 1, 0, len(grid) - 2)
    u = interval_acceleration(grid, s_dot)[i]
    x = np.maximum(s_dot[i] ** 2 + 2.0 * u * (s - grid[i]), 0.0)
    sd = np.sqrt(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = np.where(sd + s_dot[i] > 0, 2.0 * (s - grid[i]) / (sd + s_dot[i]), 0.0)
    return t[i] + tau, sd, u


def at_time(t, grid, s_dot, times) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(s, ṡ, s̈) at any ``times`` (at a sample time, the interval that starts there)."""
    times = np.atleast_1d(np.asarray(times, dtype=float))
    u = interval_acceleration(grid, s_dot)
    i = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(u) - 1)
    tau = times - t[i]
    return grid[i] + s_dot[i] * tau + 0.5 * u[i] * tau * tau, s_dot[i] + u[i] * tau, u[i]


class RetimedCurve:
    """The retimed motion between the samples: s̈ constant per interval of ``timing`` (``t``,
    ``s``, ``s_dot``) on the path ``base(t0 + s·T)``; a ``curve(times) -> (poses, rates,
    accelerations)`` by the chain rule: p'(s)·ṡ and p'(s)·s̈ + p''(s)·ṡ², p' = T·ṗ and
    p'' = T²·p̈ of the base timing.

    Parameters
    ----------
    base : Callable
        The path in its own timing, ``base(times) → (poses, rates, accelerations)``.
    t0 : float
        The base time at s = 0 [s].
    duration : float
        T, the base time from s = 0 to s = 1 [s].
    timing : TimeOptimal
        The traversal (its ``t``, ``s``, ``s_dot``), e.g. from
        :func:`~pollard_pin.time_optimal_path`.
    """

    def __init__(self, base, t0: float, duration: float, timing):
        self.base, self.t0, self.T, self.timing = base, t0, duration, timing

    def __call__(self, times):
        tim, T = self.timing, self.T
        s, s_dot, u = at_time(tim.t, tim.s, tim.s_dot, times)
        s_dot, u = s_dot[:, None], u[:, None]
        poses, rates, accelerations = self.base(self.t0 + s * T)
        return poses, T * rates * s_dot, T * rates * u + T * T * accelerations * s_dot**2


class Piecewise:
    """Curves one after the other: ``curves[k]`` from time ``starts[k]`` (its own time 0
    there) to the next start; a ``curve(times) -> (poses, rates, accelerations)``."""

    def __init__(self, starts, curves):
        self.starts, self.curves = np.asarray(starts, dtype=float), tuple(curves)

    def __call__(self, times):
        times = np.atleast_1d(np.asarray(times, dtype=float))
        k = np.clip(np.searchsorted(self.starts, times, side="right") - 1, 0,
                    len(self.curves) - 1)
        out = [np.empty((len(times), 6)) for _ in range(3)]
        for j in np.unique(k):
            at = k == j
            for o, value in zip(out, self.curves[j](times[at] - self.starts[j])):
                o[at] = value
        return tuple(out)


__all__ = ["Piecewise", "RetimedCurve", "at_path", "at_time", "interval_acceleration",
           "interval_durations", "rate_squared"]
