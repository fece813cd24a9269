"""The phases of a paint program on a moving line, for a panel or a part alike
(docs/model.md §24): the relative program behind :class:`Relative`, the line's phases (hold,
catch up, program, slow down, return) and the world path they make, the path's sample times
and budgets. What is searched before the path is made (the shift that keeps it in reach, the
turnarounds, the return) is in ``search.py``, the world path planned and checked in
``world.py`` (the motors': ``motors.py``; the speeds that paint: ``speeds.py``). ``panel.py``
(a panel) and ``part.py`` (a part's mesh) only build their relative programs.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import BudgetError, PlanError
from ..passes.raster import SMOOTHSTEP
from ..policy import DEFAULT_POLICY, PlannerPolicy
from .shifts import SHIFT_STEP

CATCH = 0.5  # s: the robot speeds up to (and down from) the line's speed over this time
_RISE = SMOOTHSTEP.integ(lbnd=0.0)  # ∫ smoothstep: travels 1/2 over [0, 1]
_RATE, _ACCEL = SMOOTHSTEP.deriv(), SMOOTHSTEP.deriv(2)  # made once: a search calls ~50 times


@dataclass(frozen=True)
class LineTimes:
    """The world path's phases [s]: hold until ``delay − CATCH``, speed up to the line until
    ``delay``, the program until ``end``, slow to rest until ``end + CATCH``, return until
    ``total``."""

    delay: float
    end: float
    back: float  # return duration

    @property
    def total(self) -> float:
        return self.end + CATCH + self.back

    @property
    def cycle(self) -> float:
        """The repeating cycle [s], from leaving the start pose to being back at it (catch
        up, program, slow down, return): the wait before is where the job placed the part,
        a phase, not part of the cycle (docs/model.md §24)."""
        return self.total - self.leave

    @property
    def leave(self) -> float:
        """When the robot leaves its start pose [s]."""
        return self.delay - CATCH


@dataclass(frozen=True, eq=False)
class Relative:
    """The gun's program relative to the part (at its t = 0 pose), on its own time from 0:
    ``motion(t)`` → (poses, rates, accelerations) (N, 6), at rest at both ends; its pieces'
    ``start``, ``duration`` and ``kind`` ("ramp", "pass", "turn"), the first a ramp, the
    second the first pass; ``passes_only``: the trigger is open on the passes only (a part),
    else throughout (a panel); ``program``: what it was built from (a panel's Segments, a
    part's Program)."""

    motion: Callable
    start: np.ndarray
    duration: np.ndarray
    kind: tuple
    passes_only: bool = False
    program: object = None

    @property
    def total(self) -> float:
        return float(self.start[-1] + self.duration[-1])

    def evaluate(self, t):
        return self.motion(np.asarray(t, dtype=float))

    def coarse_times(self) -> np.ndarray:
        """Piece ends and middles: the program's extremes along and across the passes."""
        return np.unique(np.concatenate([self.start, self.start + self.duration / 2,
                                         [self.total]]))

    def not_passes(self) -> np.ndarray:
        return np.array([i for i, k in enumerate(self.kind) if k != "pass"])

    def trigger(self, t) -> np.ndarray:
        """The trigger (0 or 1) at program times ``t``."""
        t = np.asarray(t, dtype=float)
        if not self.passes_only and "wait" not in self.kind:
            return np.ones(len(t))
        i = np.clip(np.searchsorted(self.start, t, side="right") - 1, 0, len(self.start) - 1)
        on = [k == "pass" if self.passes_only else k != "wait" for k in self.kind]
        return np.array(on, dtype=float)[i]  # a slow line's wait shut (dwell.py)


def line_shift(poses, d, t, speed: float, direction):
    """Relative motion → world (docs/model.md §24): positions + speed·t·direction, rates +
    speed·direction, accelerations unchanged (new arrays)."""
    p = np.array(poses, dtype=float)
    v = np.array(d, dtype=float)
    p[:, :3] += speed * np.asarray(t, float)[:, None] * np.asarray(direction)[None, :]
    v[:, :3] += speed * np.asarray(direction)[None, :]
    return p, v


def world_motion(rel: Relative, speed: float, e, times: LineTimes, t):
    """The world path at times ``t`` (hold, catch up, program, slow down, return):
    (poses, rates, accelerations, spray)."""
    t = np.asarray(t, dtype=float)
    e = np.asarray(e, dtype=float)
    D, E = times.delay, times.end
    poses = np.empty((len(t), 6))
    d, dd = np.zeros((len(t), 6)), np.zeros((len(t), 6))
    prog = (t >= D) & (t <= E)
    spray = np.zeros(len(t))
    if prog.any():
        p, v, a = rel.evaluate(t[prog] - D)
        poses[prog], d[prog] = line_shift(p, v, t[prog], speed, e)
        dd[prog] = a
        spray[prog] = rel.trigger(t[prog] - D)
    r0, _, _ = rel.evaluate(np.array([0.0]))
    r1, _, _ = rel.evaluate(np.array([rel.total]))
    hold = speed * (D - CATCH / 2)  # the start pose's shift along the line
    held = t < D - CATCH  # x = 0 there: one row made, the same to the bit (a slow line's wait)
    for rows, x in ((held, np.zeros(int(held.any()))), ((t < D) & ~held, None)):
        x = np.clip((t[rows] - (D - CATCH)) / CATCH, 0.0, 1.0) if x is None else x
        g = hold + speed * CATCH * _RISE(x)
        poses[rows] = r0[0]
        poses[rows, :3] += g[:, None] * e
        d[rows, :3] = (speed * SMOOTHSTEP(x))[:, None] * e
        dd[rows, :3] = (speed / CATCH * _RATE(x))[:, None] * e
    slow = (t > E) & (t <= E + CATCH)
    x = (t[slow] - E) / CATCH
    g = speed * E + speed * CATCH * (x - _RISE(x))
    poses[slow] = r1[0]
    poses[slow, :3] += g[:, None] * e
    d[slow, :3] = (speed * (1 - SMOOTHSTEP(x)))[:, None] * e
    dd[slow, :3] = (-speed / CATCH * _RATE(x))[:, None] * e
    back = t > E + CATCH
    if back.any():  # the whole pose, angles too: a part's gun turns between its passes
        a, b = r1[0].copy(), r0[0].copy()
        a[:3] += speed * (E + CATCH / 2) * e
        b[:3] += hold * e
        x = np.clip((t[back] - E - CATCH) / times.back, 0.0, 1.0)
        poses[back] = a + SMOOTHSTEP(x)[:, None] * (b - a)
        d[back] = (_RATE(x) / times.back)[:, None] * (b - a)
        dd[back] = (_ACCEL(x) / times.back ** 2)[:, None] * (b - a)
    return poses, d, dd, spray


def world_motion_reusing(rel: Relative, speed: float, e, times: LineTimes, t, known):
    """:func:`world_motion` at times ``t``, the rows of ``known`` = (its times, increasing;
    (poses, rates, accelerations, spray) there) taken where a time of ``t`` is one of them bit
    for bit, the rest evaluated: each row of :func:`world_motion` is its time's alone, so the
    result is the same to the bit (a path's samples among its 4× finer check's, a seam's
    samples among the path's)."""
    t = np.asarray(t, dtype=float)
    at, rows = np.asarray(known[0], dtype=float), known[1]
    k = np.minimum(np.searchsorted(at, t), len(at) - 1)
    hit = at[k] == t
    out = [np.empty((len(t),) + np.shape(a)[1:]) for a in rows]
    for o, a in zip(out, rows):
        o[hit] = np.asarray(a)[k[hit]]
    if not hit.all():
        for o, a in zip(out, world_motion(rel, speed, e, times, t[~hit])):
            o[~hit] = a
    return tuple(out)


def drifted(rel: Relative, speed: float, e, t):
    """The program's world positions with no wait (shift 0): relative + speed·t·direction."""
    p, v, _ = rel.evaluate(t)
    return line_shift(p, v, t, speed, e)[0]


def track(centre, e) -> str:
    """Where the gun's track over the part's centre runs (the never-in-reach message)."""
    return (f"the gun's track at the part's centre runs through ({centre[0]:.3f}, "
            f"{centre[1]:.3f}, {centre[2]:.3f}) m along ({e[0]:.3g}, {e[1]:.3g}, {e[2]:.3g})")


@dataclass(frozen=True)
class LineProgram:
    """What :func:`plan_world` runs on the line: the relative program ``build(τ)`` (τ the ramp
    and turnaround durations, from ``guess``), the path's time step ``dt`` [s], the gun's
    track ``where`` (:func:`track`), what the passes are (for the motors' message) and the
    job's ``source``."""

    build: Callable
    guess: np.ndarray
    dt: float
    where: str
    passes: str
    source: str


def one_coat(job) -> None:
    if job.coats not in (None, 1):
        raise PlanError(f"{job.source}: job.coats = {job.coats}: a part on the line is painted "
                        "in one coat (the second would run back against the travel)")


def path_times(times: LineTimes, steps: int) -> np.ndarray:
    """The path's sample times from 0 to ``times.total``: ``steps`` equal steps from the
    program's start to the end, the same steps back into the wait, so that the program
    (hence the film) is sampled alike wherever the job puts the part at t = 0; the first
    step, in the wait, is between 0.5 and 1.5 of the others."""
    m = steps
    h = (times.total - times.delay) / m
    k = math.floor(times.delay / h + 1e-9)
    t = times.delay + h * np.arange(-k, m + 1)
    t[-1] = times.total
    if t[0] < 0.5 * h:
        t[0] = 0.0
    else:
        t = np.concatenate([[0.0], t])
    return t


def samples_budget(duration: float, dt: float, source: str,
                   policy: PlannerPolicy = DEFAULT_POLICY) -> None:
    """A path of ``duration`` [s] sampled every ``dt`` within ``policy.max_path_samples``,
    else one :class:`BudgetError` line."""
    n = duration / dt + 1
    if n > policy.max_path_samples:
        raise BudgetError(f"{source}: the line's path needs {n:.3g} samples ({duration:.4g} s "
                          f"at {dt:.3g} s), budget {policy.max_path_samples:.3g}: a faster "
                          "line, the part placed nearer the robot, "
                          f"{policy.coarser(dt)}, "
                          f"{policy.budget_fix}")


def slow_budget(speed: float, dt: float, source: str,
                policy: PlannerPolicy = DEFAULT_POLICY) -> None:
    """Before anything is planned: over the longest path the budget allows, the line must
    carry the part at least the SHIFT_STEP the program is placed to; slower, the wait alone
    breaks the budget wherever the part starts, and no speed search starts from there."""
    longest = policy.max_path_samples * dt
    if speed * longest < SHIFT_STEP:
        raise BudgetError(f"{source}: line.speed = {speed:.3g} m/s carries the part "
                          f"{speed * longest:.3g} m in the longest path the budget allows "
                          f"({policy.max_path_samples:.3g} samples, {longest:.4g} s): give at "
                          f"least {SHIFT_STEP / longest:.3g} m/s, in m/s, or no [line] for a "
                          "still part")


def drift_along(rel: Relative, speed: float, e) -> float:
    """The program's world drift along the line [m], s·T − (relative travel): a failure at a
    positive drift is one of too fast a line, at a negative one of too slow (§24)."""
    along = drifted(rel, speed, e, np.array([0.0, rel.total]))[:, :3] @ e
    return float(along[1] - along[0])


def mid_along(rel: Relative, speed: float, e) -> float:
    """The middle, along the line, of the program's world extent at shift 0."""
    return mid_of(drifted(rel, speed, e, rel.coarse_times()), e)


def mid_of(poses, e) -> float:
    """The middle of ``poses``' extent along e."""
    along = poses[:, :3] @ e
    return 0.5 * float(along.min() + along.max())


__all__ = ["CATCH", "LineProgram", "LineTimes", "Relative", "drift_along", "drifted",
           "line_shift", "mid_along", "mid_of", "one_coat", "path_times", "samples_budget",
           "slow_budget", "track", "world_motion", "world_motion_reusing"]
