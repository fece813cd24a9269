"""Analytic tool-pose curves with exact derivatives: the thesis painting curve
(docs/model.md §9) and smooth test motions, as curves ``curve(t) -> (poses, rates,
accelerations)`` and as :class:`~.trajectory.Trajectory` samples."""
from __future__ import annotations

import math
from functools import partial

import numpy as np

from .trajectory import MAX_TIME, Trajectory, TrajectoryError

THESIS_DURATION = 20.0  # s (docs/model.md §9)
THESIS_SAMPLES = 2001
U_RANGE = 60.0 * math.pi  # u ∈ [−60π, 60π], thesis appendix B (mm)
# Sample budgets of the thesis trajectory, checked before anything is allocated: solved whole
# (view, plot, report, size, simulate, sweep) a sample costs ≈ 3 KB; streamed window by window
# (run) it costs ≈ 11 µs and 30-300 bytes of output (docs/guide.md: a million samples in 11 s).
MAX_SAMPLES = 1_000_000  # ≈ 3 GB solved
MAX_STREAMED_SAMPLES = 100_000_000  # ≈ 20 min and 3-30 GB of output


def thesis_curve(t, duration: float = THESIS_DURATION,
                 home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0)):
    """Poses, rates and accelerations (each (N, 6)) of the thesis curve at times ``t`` [s].

    Appendix B: x = −0.001u², y = u, z = 100 sin(0.3u) [mm], u linear in t from −60π at
    t = 0 to 60π at ``duration``, added to the home pose (docs/model.md §9). Exact derivatives.

    Parameters
    ----------
    t : ndarray
        Times [s], any values (the curve extends past [0, ``duration``]).
    duration : float, optional
        The time to run the curve once [s] (default 20).
    home_pose : tuple of float, optional
        The pose the curve is added to: x, y, z [m], ψ, θ, φ [rad].

    Returns
    -------
    poses, rates, accelerations : ndarray
        Each (N, 6): [m, rad], [m/s, rad/s], [m/s², rad/s²].

    Examples
    --------
    >>> from pollard_pin.paths import thesis_curve
    >>> poses, rates, acc = thesis_curve([10.0])         # halfway: u = 0, the home pose
    >>> poses.round(6).tolist()
    [[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]]
    """
    t = np.atleast_1d(np.asarray(t, dtype=float))
    ud = 2.0 * U_RANGE / duration
    u = -U_RANGE + ud * t
    mm = 1e-3
    poses = np.tile(np.asarray(home_pose, dtype=float), (len(t), 1))
    d, dd = np.zeros_like(poses), np.zeros_like(poses)
    poses[:, 0] += -0.001 * u**2 * mm
    poses[:, 1] += u * mm
    poses[:, 2] += 100.0 * np.sin(0.3 * u) * mm
    d[:, 0] = -0.002 * u * ud * mm
    d[:, 1] = ud * mm
    d[:, 2] = 30.0 * np.cos(0.3 * u) * ud * mm
    dd[:, 0] = -0.002 * ud**2 * mm
    dd[:, 2] = -9.0 * np.sin(0.3 * u) * ud**2 * mm
    return poses, d, dd


def check_samples(samples, budget: int, how: str = "") -> None:
    """An integer sample count >= 2 within ``budget`` (checked before anything is allocated)."""
    whole = isinstance(samples, (int, np.integer)) and not isinstance(samples, bool) or (
        isinstance(samples, float) and math.isfinite(samples) and samples.is_integer())
    if not whole or samples < 2:
        raise TrajectoryError(f"samples must be an integer >= 2, got {samples!r}")
    if samples > budget:
        raise TrajectoryError(f"{count_text(samples)} samples are over the{how} budget of "
                              f"{budget:.4g}: use fewer samples")


def count_text(n) -> str:
    """A count, however large, as a short number (no 700-digit integers in messages)."""
    return f"{n:.4g}" if n < 1e300 else "more than 1e300"


def thesis_trajectory(duration: float = THESIS_DURATION, samples: int = THESIS_SAMPLES,
                      home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0)) -> Trajectory:
    """The default painting trajectory (docs/model.md §9) sampled at ``samples`` points.

    Parameters
    ----------
    duration : float, optional
        Time to run the curve [s] (default 20).
    samples : int, optional
        Number of samples, evenly spaced from 0 to ``duration`` (default 2001), ≥ 2.
    home_pose : tuple of float, optional
        The pose the curve is added to: x, y, z [m], ψ, θ, φ [rad] (default the home pose
        (0.55, 0, 0.16, 0, 0, 0)).

    Returns
    -------
    Trajectory
        Exact derivatives; its ``curve`` is the exact curve between the samples.

    Raises
    ------
    TrajectoryError
        A duration that is not a positive number (or so short that the accelerations
        overflow, or over 1e6 s: a trajectory file's times' limit), a sample count that is not
        an integer ≥ 2 or over the budget.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> traj = pp.thesis_trajectory(duration=20.0, samples=401)
    >>> len(traj), float(traj.t[-1]), traj.derivatives
    (401, 20.0, 'analytic')
    >>> pp.thesis_trajectory(samples=1)
    Traceback (most recent call last):
    ...
    pollard_pin.paths.trajectory.TrajectoryError: samples must be an integer >= 2, got 1
    """
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration > 0):
        raise TrajectoryError(f"duration must be a positive number of seconds, got {duration}")
    if duration > MAX_TIME:  # a trajectory file's rule: 1e308 s overflowed the plots' axes
        raise TrajectoryError(f"duration {duration:g} s is beyond {MAX_TIME:g} s (seconds, not "
                              "ms?)")
    if not 2.0 * U_RANGE / duration < 1e150:  # the accelerations grow as 1/duration²
        raise TrajectoryError(f"duration {duration} s is too short: the curve's accelerations "
                              "overflow")
    check_samples(samples, MAX_SAMPLES)
    t = np.linspace(0.0, duration, int(samples))
    return Trajectory(t, *thesis_curve(t, duration, home_pose), name="thesis",
                      derivatives="analytic",
                      curve=partial(thesis_curve, duration=duration, home_pose=home_pose))


class ThesisTrajectory:
    """The thesis trajectory evaluated window by window, never whole: a million samples cost
    one window's memory. ``windows(size)`` yields exactly the slices of
    :func:`~pollard_pin.thesis_trajectory` with the same arguments (same bits:
    ``np.linspace``'s rule). :func:`~pollard_pin.stream_run` takes it.

    Parameters
    ----------
    duration : float, optional
        Time to run the curve [s] (default 20).
    samples : int, optional
        Number of samples (default 2001), ≥ 2 and within the streamed budget.
    home_pose : tuple of float, optional
        The pose the curve is added to: x, y, z [m], ψ, θ, φ [rad].

    Raises
    ------
    TrajectoryError
        The arguments :func:`~pollard_pin.thesis_trajectory` refuses, or too many samples.

    Examples
    --------
    >>> import numpy as np
    >>> from pollard_pin.paths import ThesisTrajectory, thesis_trajectory
    >>> starts = [start for start, _ in ThesisTrajectory(samples=10_001).windows(4096)]
    >>> starts
    [0, 4096, 8192]
    >>> start, window = list(ThesisTrajectory(samples=10_001).windows(4096))[1]
    >>> whole = thesis_trajectory(samples=10_001)
    >>> bool(np.array_equal(window.poses, whole.poses[4096:8192]))
    True
    """

    def __init__(self, duration: float = THESIS_DURATION, samples: int = THESIS_SAMPLES,
                 home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0)):
        thesis_trajectory(duration, 2, home_pose)  # the same argument checks
        check_samples(samples, MAX_STREAMED_SAMPLES, " streamed")
        self.duration, self.samples = float(duration), int(samples)
        self.home_pose = tuple(float(x) for x in home_pose)
        self.name, self.derivatives = "thesis", "analytic"

    def __len__(self) -> int:
        return self.samples

    def window(self, start: int, stop: int) -> Trajectory:
        stop = min(stop, self.samples)
        t = np.arange(start, stop, dtype=float) * (self.duration / (self.samples - 1))
        if stop == self.samples:
            t[-1] = self.duration  # as np.linspace: the end point exactly
        return Trajectory(t, *thesis_curve(t, self.duration, self.home_pose), name=self.name,
                          derivatives=self.derivatives)

    def windows(self, size: int):
        for start in range(0, self.samples, size):
            yield start, self.window(start, start + size)


def sinusoid_curve(t, home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0),
                   amplitude=(0.04, 0.05, 0.04, 0.25, 0.3, 0.35),
                   freq=(0.31, 0.23, 0.41, 0.37, 0.29, 0.19),
                   phase=(0.3, 1.1, 2.0, 0.7, 2.5, 1.6)):
    """Poses, rates, accelerations of a_k sin(2π f_k t + φ_k) about the home pose [m, rad, Hz]."""
    t = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
    a, w, ph = np.asarray(amplitude), 2 * math.pi * np.asarray(freq), np.asarray(phase)
    arg = w * t + ph
    return (np.asarray(home_pose, dtype=float) + a * np.sin(arg), a * w * np.cos(arg),
            -a * w * w * np.sin(arg))


def smooth_random_trajectory(seed: int = 0, duration: float = 4.0, samples: int = 401,
                             home_pose=(0.55, 0.0, 0.16, 0.0, 0.0, 0.0),
                             amplitude=(0.04, 0.06, 0.05, 0.2, 0.2, 0.3)) -> Trajectory:
    """Random sum-of-sines motion of all six task coordinates about home, exact derivatives.

    Parameters
    ----------
    seed : int, optional
        The random generator's seed: the same seed, the same motion.
    duration : float, optional
        Time span [s] (default 4).
    samples : int, optional
        Number of samples (default 401).
    home_pose : tuple of float, optional
        The start pose: x, y, z [m], ψ, θ, φ [rad].
    amplitude : tuple of float, optional
        The largest amplitude of each coordinate [m, rad]; each is drawn in [0.5, 1] × it.

    Returns
    -------
    Trajectory
        Starting exactly at ``home_pose``.

    Examples
    --------
    >>> from pollard_pin.paths import smooth_random_trajectory
    >>> traj = smooth_random_trajectory(seed=3, samples=101)
    >>> traj.name, traj.poses[0].round(6).tolist()
    ('random3', [0.55, 0.0, 0.16, 0.0, 0.0, 0.0])
    """
    rng = np.random.default_rng(seed)
    amp = np.asarray(amplitude) * rng.uniform(0.5, 1.0, 6)
    freq = rng.uniform(0.5, 2.5, 6) / duration
    phase = rng.uniform(0, 2 * math.pi, 6)
    t = np.linspace(0.0, duration, samples)
    pose, d, dd = sinusoid_curve(t, home_pose, amp, freq, phase)
    pose -= amp * np.sin(phase)  # start exactly at home
    return Trajectory(t, pose, d, dd, name=f"random{seed}", derivatives="analytic")


__all__ = ["THESIS_DURATION", "THESIS_SAMPLES", "U_RANGE", "ThesisTrajectory", "sinusoid_curve",
           "smooth_random_trajectory", "thesis_curve", "thesis_trajectory"]


def wait_then_strokes(n: int, dt: float = 2e-3, wait: float = 0.47) -> Trajectory:
    """A line job's shape for timing and sizing checks: ``wait`` of the ``n`` samples at rest
    at the curve's start (``dt`` apart), then the thesis curve once over from rest to rest
    (a quintic time law, so the joins are C²)."""
    still = int(wait * n)
    moving = n - still
    T = (moving - 1) * dt
    x = np.linspace(0.0, 1.0, moving)
    u = T * (10 * x**3 - 15 * x**4 + 6 * x**5)
    du, ddu = 30 * x**2 - 60 * x**3 + 30 * x**4, (60 * x - 180 * x**2 + 120 * x**3) / T
    p, d, dd = thesis_curve(u, T)
    zero = np.zeros((still, 6))
    return Trajectory(np.concatenate([dt * np.arange(still), dt * still + x * T]),
                      np.vstack([np.repeat(p[:1], still, 0), p]),
                      np.vstack([zero, d * du[:, None]]),
                      np.vstack([zero, dd * du[:, None] ** 2 + d * ddu[:, None]]))

