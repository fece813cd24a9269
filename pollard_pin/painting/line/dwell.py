"""A slow line's dwell (docs/model.md §24.1): a line slower than the strokes' own pace carries
the part less far than the program steps along it, so the program drifts against the travel
and leaves the reach. The program then waits at each turnaround, at rest relative to the
part (so riding the line at its speed), the gun closed, until the drift is ≈ 0.

A turnaround of duration τ becomes three pieces: its first half run in τ (time σ(u) =
τ·R_out(u/τ), rate 1 → 0, so the gun comes to rest relative to the part where the turn is
furthest off it), the wait ("wait", the trigger closed) and its second half run in τ
(σ = τ/2 + τ·R_in(u/τ), rate 0 → 1). The gun's track on the part is the turn's own; the
pieces meet with equal poses, rates and accelerations (R's rate and its derivative match at
both ends). A line only a little slower than the pace needs less than the half-paced turn's
own extra τ: the turn's rate then dips only to c > 0 at its middle (each half run in
τ/(1 + c)) and waits 0, so that it adds just the time the line needs.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import LineSpeedError
from ..passes.raster import RAMP_IN, RAMP_OUT
from ..policy import DEFAULT_POLICY, PlannerPolicy
from .phases import LineProgram, Relative
from .world import plan_world

_OUT, _IN = RAMP_OUT, RAMP_IN  # σ/τ over u/τ: travels 1/2, rate 1 → 0 (0 → 1)
_OUT1, _OUT2, _IN1, _IN2 = _OUT.deriv(), _OUT.deriv(2), _IN.deriv(), _IN.deriv(2)


def drift_along(rel: Relative, speed: float, e) -> float:
    """The program's world drift along the line [m]: s·T + its relative travel along e."""
    p, _, _ = rel.evaluate(np.array([0.0, rel.total]))
    return speed * rel.total + float((p[1, :3] - p[0, :3]) @ np.asarray(e, float))


def slow(rel: Relative, speed: float, e) -> bool:
    """True when the line is slower than the program's own pace: its world drift
    s·T − L < 0 (docs/model.md §24.1), so it needs a dwell."""
    return drift_along(rel, speed, e) < 0.0


def wait_per_turn(rel: Relative, speed: float, e) -> float:
    """The wait [s] at each turnaround that brings the world drift to ≈ 0 once the
    turnarounds are run at half pace: (−drift/s)/n − the turn's own extra τ (its mean), ≥ 0."""
    turns = np.array([d for d, k in zip(rel.duration, rel.kind) if k == "turn"])
    if not len(turns):
        return 0.0
    extra = -drift_along(rel, speed, e) / speed  # the relative time the line needs added
    return max(0.0, extra / len(turns) - float(turns.mean()))


def turn_timing(rel: Relative, speed: float, e) -> tuple[np.ndarray, np.ndarray]:
    """Per turnaround, (its wait [s], the rate c its half-paced halves slow to at its middle)
    that bring the world drift to ≈ 0 (docs/model.md §24.1). Each turn must add x =
    −drift/(s·n) of relative time: at x ≥ τ̄ (the turns' mean) the halves stop (c = 0) and
    all wait x − τ̄ (:func:`wait_per_turn`); below, a turn of τ ≤ x stops and waits x − τ,
    one of τ > x waits 0 and its rate dips only to c = (τ − x)/(τ + x), its halves each run
    in τ/(1 + c), adding exactly x (half-paced, it would add τ: too much)."""
    tau = np.array([d for d, k in zip(rel.duration, rel.kind) if k == "turn"], dtype=float)
    if not len(tau):
        return tau, tau
    x = max(0.0, -drift_along(rel, speed, e) / speed / len(tau))
    if x >= tau.mean():
        return np.full(len(tau), x - float(tau.mean())), np.zeros(len(tau))
    dip = np.divide(tau - x, tau + x, out=np.ones_like(tau), where=tau + x > 0)
    return np.maximum(0.0, x - tau), np.maximum(0.0, dip)


def with_dwell(rel: Relative, wait, dip=0.0) -> Relative:
    """``rel`` with each turnaround split into its halves and a ``wait`` [s] at rest between
    them (the trigger closed), the halves' rate relative to the part slowing from 1 to
    ``dip`` at the middle (0: at rest, each half run in τ; c: in τ/(1 + c)); ``wait`` and
    ``dip`` one for all turns or one per turn. A :class:`ZoneRelative`'s windows follow (its
    turn's window for both halves, shut for the wait)."""
    pieces = []  # (kind, duration, base start, base duration, part: 0 whole, 1, 2, 3, dip)
    windows = getattr(rel, "windows", None)
    wins = []
    n = rel.kind.count("turn")
    waits = np.broadcast_to(np.asarray(wait, dtype=float), (n,))
    dips = np.broadcast_to(np.asarray(dip, dtype=float), (n,))
    j = 0
    for k, (s, d, kind) in enumerate(zip(rel.start, rel.duration, rel.kind)):
        w = windows[k] if windows else None
        if kind != "turn":
            pieces += [(kind, d, s, d, 0, 0.0)]
            wins += [w]
            continue
        c = float(dips[j])
        h = d / (1.0 + c) if c > 0 else d
        pieces += [("turn", h, s, d, 1, c), ("wait", float(waits[j]), s, d, 2, c),
                   ("turn", h, s, d, 3, c)]
        wins += [w, (np.inf, -np.inf), w]
        j += 1
    duration = np.array([p[1] for p in pieces], dtype=float)
    start = np.concatenate([[0.0], np.cumsum(duration)[:-1]])
    base_start = np.array([p[2] for p in pieces])
    base_dur = np.array([p[3] for p in pieces])
    part = np.array([p[4] for p in pieces])
    slows = np.array([p[5] for p in pieces])

    def motion(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        i = np.clip(np.searchsorted(start, t, side="right") - 1, 0, len(start) - 1)
        u = np.clip(t - start[i], 0.0, duration[i])
        tau = base_dur[i]
        x = np.divide(u, tau, out=np.zeros_like(u), where=tau > 0)
        sig, r1, r2 = u.copy(), np.ones_like(u), np.zeros_like(u)
        for which, f, f1, f2, at in ((1, _OUT, _OUT1, _OUT2, 0.0), (3, _IN, _IN1, _IN2, 0.5)):
            m = part[i] == which
            sig[m] = tau[m] * (at + f(x[m]))
            r1[m], r2[m] = f1(x[m]), f2(x[m]) / tau[m]
        m = part[i] == 2
        sig[m], r1[m] = 0.5 * tau[m], 0.0
        sig, r1, r2 = _dipped(sig, r1, r2, u, duration[i], tau, part[i], slows[i])
        p, v, a = rel.evaluate(base_start[i] + sig)
        return p, v * r1[:, None], a * (r1 ** 2)[:, None] + v * r2[:, None]

    out = replace(rel, motion=motion, start=start, duration=duration, kind=tuple(
        p[0] for p in pieces))
    return replace(out, windows=tuple(wins)) if windows else out


def _dipped(sig, r1, r2, u, h, tau, part, c):
    """The time σ, rate σ′ and σ″ of the turn halves whose rate dips only to c > 0 (each
    half run in h = τ/(1 + c)): σ = h·(x − (1 − c)·S(x)), then τ/2 + h·(c·x + (1 − c)·S(x)),
    x = u/h, S = R_in (S′ the smoothstep, zero slope at both ends)."""
    m = (c > 0) & ((part == 1) | (part == 3))
    if not m.any():
        return sig, r1, r2
    x = u[m] / h[m]
    k = 1.0 - c[m]
    S, S1, S2 = _IN(x), _IN1(x), _IN2(x) / h[m]
    first = part[m] == 1
    sig, r1, r2 = sig.copy(), r1.copy(), r2.copy()
    sig[m] = np.where(first, h[m] * (x - k * S), 0.5 * tau[m] + h[m] * (c[m] * x + k * S))
    r1[m] = np.where(first, 1.0 - k * S1, c[m] + k * S1)
    r2[m] = np.where(first, -k * S2, k * S2)
    return sig, r1, r2


def dwelled(build, speed: float, e):
    """τ ↦ the relative program ``build(τ)`` with the waits (or the turns' dips) that keep
    its drift ≈ 0 (:func:`turn_timing`)."""
    def build_d(tau):
        rel = build(tau)
        return with_dwell(rel, *turn_timing(rel, speed, e))
    return build_d


def dwelling(program: LineProgram, speed: float, e) -> LineProgram:
    """``program`` with the waits of :func:`dwelled` at line ``speed`` along ``e``."""
    return replace(program, build=dwelled(program.build, speed, e))


def plan_dwelling(robot, act, program: LineProgram, speed: float, e,
                  policy: PlannerPolicy = DEFAULT_POLICY):
    """:func:`.line.world.plan_world` of ``program``, waiting at the turnarounds where the
    line is too slow for it (docs/model.md §24.1): only when the program as it is fails
    as too slow (its drift beyond the reach's window, or what that brings), so that
    whatever planned before the waits plans as it did."""
    rel = program.build(program.guess)
    if not slow(rel, speed, e):
        return plan_world(robot, act, program, speed, e, policy)
    try:  # a too slow failure tries the waits whatever it was: screened (plan_world)
        return plan_world(robot, act, program, speed, e, policy, screen=True)
    except LineSpeedError as exc:
        if exc.too_fast:
            raise
        try:
            return plan_world(robot, act, dwelling(program, speed, e), speed, e, policy)
        except LineSpeedError as again:  # still a slow line's failure, for the searches
            raise LineSpeedError(str(again), False, again.why, exc.hint) from None


def dwell_time(rel: Relative) -> float:
    """The program's waits [s] in all."""
    return float(sum(d for d, k in zip(rel.duration, rel.kind) if k == "wait"))


def waiting_floor(plan, policy: PlannerPolicy = DEFAULT_POLICY) -> float | None:
    """Where a line plan (a panel's or a part's) waits at its turnarounds, the line speed
    [m/s] at which its path would reach ``policy.max_path_samples``: a slower line only
    waits longer, the strokes and the world window the same (§24.1), its samples growing
    as 1/speed, so it paints down to about there; else None."""
    if dwell_time(plan.relative) <= 0:
        return None
    return plan.speed * len(plan.trajectory.t) / policy.max_path_samples


__all__ = ["drift_along", "dwell_time", "dwelled", "dwelling", "plan_dwelling", "slow",
           "turn_timing", "wait_per_turn", "waiting_floor", "with_dwell"]
