"""What a line plan searches before it makes the path (docs/model.md §24): the shift along
the line that keeps the world program in reach (its scan in ``shifts.py``; refused in words,
:mod:`.line.reach`, where none does), the ramps' and turnarounds' durations, the shortest
within the motors on the world path, and the return's. :func:`searched` is what
:func:`.line.world.plan_world` notes (:mod:`.line.notes`).
"""
from __future__ import annotations

import numpy as np

from ...dynamics.motors import Actuators
from ...kinematics.ik_batch import reachable_sequences
from ..checks.motion import fastest, motion
from ..errors import LineReachError, LineSpeedError, PlanError, ReachError
from ..policy import PlannerPolicy
from .phases import (
    CATCH,
    LineProgram,
    LineTimes,
    Relative,
    drift_along,
    drifted,
    line_shift,
    mid_along,
    mid_of,
    samples_budget,
    world_motion,
)
from .reach import ball_shift_range, coarse_to_fine, out_of_reach, unreachable_passes
from .shifts import SHIFT_RANGE, SHIFT_STEP, feasible_shifts, shift_window


def choose_shift(robot, rel: Relative, speed: float, e, where: str) -> float:
    """The line's shift speed·delay [m] at the middle of the shifts that keep the world
    program (coarse samples) in reach; :class:`LineSpeedError` if none does, a
    :class:`PlanError` naming the passes out of reach at any shift (:mod:`.line.reach`), or
    ``where`` (the gun's track) if none is ever in reach."""
    t = rel.coarse_times()
    poses = drifted(rel, speed, e, t)
    anchor = mid_of(poses, e)  # mid_along's, from the same poses
    lo, hi = speed * CATCH, speed * CATCH + SHIFT_RANGE
    known: dict = {}  # the first window's shifts, judged once (its grid is the second's)
    found = feasible_shifts(robot, poses, e, lo, SHIFT_RANGE, anchor=anchor, known=known)
    if found is None and shift_window(lo, anchor) != (lo, hi):  # a robot far down the line
        lo, hi = shift_window(lo, anchor)
        found = feasible_shifts(robot, poses, e, lo, SHIFT_RANGE, anchor=anchor, known=known)
    if found is None:
        # each pass alone, no drift: a pass out of reach at every shift fails at any speed
        bad, n = unreachable_passes(robot, rel, e, lo, hi)
        if len(bad) == n and all(b.nowhere for b in bad):
            raise PlanError(f"the part never comes within reach: {where}; none of its {n} "
                            f"passes is in reach within {lo:.3g}..{hi:.3g} m of travel: move "
                            "the part or the line")
        if bad:
            raise LineReachError(f"{out_of_reach(bad, n)}: turn, move or split the part")
        off = _off_passes_out(robot, rel, t, e)
        if off:  # no drift helps: refused as a plan, not as a line speed
            raise PlanError(f"no place on the line keeps {off} in reach (its passes each "
                            "fit): move the robot or the part")
        along = poses[:, :3] @ e
        drift = float(along[-1] - along[0])
        raise LineSpeedError(f"at line speed {speed:.4g} m/s the program drifts "
                             f"{drift:+.3f} m along the line in {rel.total:.4g} s and leaves "
                             "the reach wherever it starts", drift > 0,
                             f"the program drifts {drift:+.3f} m, out of the reach",
                             speed - drift / rel.total)  # the speed of no drift
    return 0.5 * float(found[0] + found[1])


def _in_reach_somewhere(robot, poses, e, xs) -> np.ndarray:
    """Per pose, whether it is in reach at some shift of ``xs`` along e, each judged alone
    (the shifts coarse to fine, a pose found no longer tried)."""
    poses, xs = np.asarray(poses, float), np.asarray(xs, float)
    found = np.zeros(len(poses), dtype=bool)
    for cols in coarse_to_fine(len(xs)):
        todo = np.flatnonzero(~found)
        if not len(todo):
            break
        p = np.repeat(poses[None, todo], len(cols), axis=0)  # (X', S', 6)
        p[..., :3] += xs[cols][:, None, None] * e
        found[todo] = reachable_sequences(robot, p.reshape(-1, 1, 6)).reshape(
            len(cols), -1).any(axis=0)
    return found


def _off_passes_out(robot, rel: Relative, t, e) -> str:
    """The ramps and turnarounds of ``rel`` (at the coarse times ``t``) of which a sample,
    without the drift, is in reach at no shift along e at all (every SHIFT_STEP over the
    reach ball's span, coarse to fine), each judged alone, in words ('' if none): then
    no line speed keeps the program in reach."""
    i = np.clip(np.searchsorted(rel.start, t, side="right") - 1, 0, len(rel.start) - 1)
    off = np.flatnonzero([rel.kind[k] != "pass" for k in i])
    if not len(off):
        return ""
    poses = rel.evaluate(t[off])[0]
    span = ball_shift_range(robot.params, poses[:, :3], e)
    if span is None:
        return ""  # nothing near the reach: the passes' own refusal covers it
    xs = np.arange(span[0], span[1] + SHIFT_STEP, SHIFT_STEP)
    off = off[~_in_reach_somewhere(robot, poses, e, xs)]
    if not len(off):
        return ""
    before = np.cumsum([k == "pass" for k in rel.kind])  # passes up to each piece
    n = int(before[-1])
    gaps = {int(before[k]) for k in i[off]}  # 0 and n: the ramps, else a turnaround
    turns = len(gaps - {0, n})
    said = [f"{turns} of its {n - 1} turnarounds"] if turns else []
    said += [f"its {w} ramp" for g, w in ((0, "first"), (n, "last")) if g in gaps]
    return " and ".join(said)


def searched(robot, act: Actuators, program: LineProgram, rel: Relative, speed: float, e,
             policy: PlannerPolicy, built: dict | None = None) -> dict:
    """What :func:`.line.world.plan_world` searches before it samples and checks the path
    (none of it reads ``policy.check_refine``): the ramps' and turnarounds' durations ``tau``, the
    ``delay`` [s] and the return's duration ``back`` [s], as plain numbers (a note,
    :mod:`.line.notes`); ``rel`` the program at its guess. ``built`` (a dict) gains the
    program built at the τ found, by τ's bytes, for the caller not to build it again."""
    build, guess, where, passes = program.build, program.guess, program.where, program.passes
    ns = policy.turn_samples
    shift = choose_shift(robot, rel, speed, e, where)
    # the wait and the passes alone, before the turnarounds are searched
    passes_time = float(sum(d for d, k in zip(rel.duration, rel.kind) if k == "pass"))
    samples_budget(shift / speed + passes_time, program.dt, program.source, policy)
    centre = shift + mid_along(rel, speed, e)
    first = {np.asarray(guess, dtype=float).tobytes(): rel}  # the search starts at the guess

    def evaluate(tau):
        r = first.pop(np.asarray(tau).tobytes(), None) or build(tau)
        pieces = r.not_passes()
        u = np.linspace(0.0, 1.0 - 1e-12, ns)
        tt = (r.start[pieces, None] + r.duration[pieces, None] * u[None, :]).ravel()
        ct, n = r.coarse_times(), len(tt)
        # the samples and mid_along's coarse times in one evaluation (row by row the same)
        p, v, a = r.evaluate(np.concatenate([tt, ct]))
        x = centre - mid_of(line_shift(p[n:], v[n:], ct, speed, e)[0], e)
        p, v = line_shift(p[:n], v[:n], tt + x / speed, speed, e)
        a = a[:n]
        try:
            m = motion(robot, act, p, v, a)
        except ReachError:  # per τ, as below: a slow line's turn halves and wait share one
            return _per_tau(pieces, np.full(len(pieces), np.inf))
        worst = m.utilisation.reshape(len(pieces), ns, -1).max(axis=(1, 2))
        return _per_tau(pieces, worst)

    try:
        tau = fastest(evaluate, np.asarray(guess, float), policy.utilisation)
    except PlanError:
        # too fast or too slow by the drift's sign, as every other failure here: the
        # turnarounds fail on the reach where the program drifts out of it (§24)
        raise LineSpeedError(f"at line speed {speed:.4g} m/s no ramp or turnaround between "
                             f"{passes} keeps the world path in reach and the motors within "
                             "their ratings with the line's speed added",
                             drift_along(rel, speed, e) > 0,
                             "no turnaround keeps the path in reach and the motors within "
                             "ratings") from None
    rel = build(tau)
    if built is not None:
        built[np.asarray(tau, dtype=float).tobytes()] = rel
    delay = choose_shift(robot, rel, speed, e, where) / speed
    back = return_time(robot, act, rel, speed, e, delay, policy)
    return {"tau": np.asarray(tau, dtype=float).tolist(), "delay": float(delay),
            "back": float(back)}


def _per_tau(pieces, worst) -> np.ndarray:
    """The pieces' ``worst`` use per ramp or turnaround duration τ: consecutive pieces off
    the passes share one (a slow line's turn halves and wait, dwell.py)."""
    group = np.cumsum(np.diff(pieces, prepend=-2) > 1) - 1
    return np.array([worst[group == g].max() for g in range(group[-1] + 1)])


def return_time(robot, act, rel: Relative, speed: float, e, delay: float,
                 policy: PlannerPolicy) -> float:
    """The shortest return to the start pose (rest to rest) within ``policy.utilisation``."""
    u = np.linspace(0.0, 1.0, policy.turn_samples)

    def evaluate(tau):
        times = LineTimes(delay, delay + rel.total, float(tau[0]))
        tt = times.end + CATCH + tau[0] * u
        try:
            m = motion(robot, act, *world_motion(rel, speed, e, times, tt)[:3])
        except ReachError:
            return np.array([np.inf])
        return np.array([m.utilisation.max()])

    return float(fastest(evaluate, np.array([0.5]), policy.utilisation)[0])


__all__ = ["choose_shift", "return_time", "searched"]
