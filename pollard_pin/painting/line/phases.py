"""The world path of a paint program on a moving line, for a panel or a part alike
(docs/model.md §24): the relative program behind :class:`Relative`, the line's phases (hold,
catch up, program, slow down, return), the shift along the line that keeps it in reach (its
scan in ``shifts.py``), the turnarounds timed on the world path, every check on the world path
(the motors': ``motors.py``; the speeds that paint: ``speeds.py``). ``line.py`` (a panel) and
``line_part.py`` (a part's mesh) only build their relative programs.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ...dynamics.averages import time_rms
from ...dynamics.motors import Actuators
from ...errors import say_less
from ...kinematics.ik_batch import reachable_sequences
from ...paths.trajectory import Trajectory
from ..checks.motion import fastest, motion
from ..errors import BudgetError, LineReachError, LineSpeedError, PlanError, ReachError
from ..passes.raster import SMOOTHSTEP
from ..policy import DEFAULT_POLICY, PlannerPolicy
from .motors import first_kept, motors_within, screen_motors, wait_motion
from .notes import noted
from .reach import ball_shift_range, coarse_to_fine, out_of_reach, unreachable_passes
from .shifts import SHIFT_RANGE, SHIFT_STEP, feasible_shifts, shift_window

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


def _drift(rel: Relative, speed: float, e, t):
    """The program's world positions with no wait (shift 0): relative + speed·t·direction."""
    p, v, _ = rel.evaluate(t)
    return line_shift(p, v, t, speed, e)[0]


def choose_shift(robot, rel: Relative, speed: float, e, where: str) -> float:
    """The line's shift speed·delay [m] at the middle of the shifts that keep the world
    program (coarse samples) in reach; :class:`LineSpeedError` if none does, a
    :class:`PlanError` naming the passes out of reach at any shift (:mod:`.line.reach`), or
    ``where`` (the gun's track) if none is ever in reach."""
    t = rel.coarse_times()
    poses = _drift(rel, speed, e, t)
    anchor = _mid(poses, e)  # _mid_along's, from the same poses
    lo, hi = speed * CATCH, speed * CATCH + SHIFT_RANGE
    found = feasible_shifts(robot, poses, e, lo, SHIFT_RANGE, anchor=anchor)
    if found is None and shift_window(lo, anchor) != (lo, hi):  # a robot far down the line
        lo, hi = shift_window(lo, anchor)
        found = feasible_shifts(robot, poses, e, lo, SHIFT_RANGE, anchor=anchor)
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


@dataclass(frozen=True)
class World:
    """A relative program run on the line: its ``relative`` program, phases ``times``, the
    world ``trajectory`` with its ``spray`` column and the motors' ``ratios``."""

    relative: Relative
    times: LineTimes
    trajectory: Trajectory
    spray: np.ndarray
    ratios: dict


def one_coat(job) -> None:
    if job.coats not in (None, 1):
        raise PlanError(f"{job.source}: job.coats = {job.coats}: a part on the line is painted "
                        "in one coat (the second would run back against the travel)")


def plan_world(robot, act: Actuators, program: LineProgram, speed: float, e,
               policy: PlannerPolicy = DEFAULT_POLICY, screen: bool = False) -> World:
    """The world path of the relative ``program`` (:class:`LineProgram`) at line ``speed``
    along ``e`` (docs/model.md §24): the turnarounds the shortest within
    ``policy.utilisation`` on the world path held at one world centre, the delay at the
    middle of the feasible shifts, the return the shortest, sampled every ``program.dt`` and
    checked at ``policy.check_refine`` times that. ``screen``: for a caller to whom a too
    slow line's failure says no more than its side (:func:`.line.dwell.plan_dwelling`'s
    first try), the motors are first checked at the path's own samples (with
    ``check_refine`` a power of two, every ``check_refine``-th of the check's, bit for
    bit): over their ratings there, the path is refused without the finer check, which
    would refuse it too."""
    build, dt, source = program.build, program.dt, program.source
    e = np.asarray(e, dtype=float)
    slow_budget(speed, dt, source, policy)
    rel = build(program.guess)
    # the searches (shift, turnarounds, return) once per inputs within plan_notes (notes.py)
    made = noted(lambda: _searched(robot, act, program, rel, speed, e, policy), robot, act,
                 program, rel, speed, e, policy, screen)
    rel = build(np.asarray(made["tau"], dtype=float))
    delay, back = made["delay"], made["back"]
    times = LineTimes(delay, delay + rel.total, back)
    samples_budget(times.total, dt, source, policy)
    steps = math.ceil((times.total - times.delay) / dt - 1e-9)  # the program's, on
    t = path_times(times, steps)
    tf = path_times(times, policy.check_refine * steps)
    drift = _drift_along(rel, speed, e)
    r = policy.check_refine  # a power of two: the check's times hold the path's, bit for bit
    screened = screen and drift <= 0 and r > 1 and r & (r - 1) == 0
    j = first_kept(tf, times.leave)  # the check's rows from j: a long wait's once (motors.py)
    if screened:  # the path first: the screen may refuse it before the finer samples
        poses, d, dd, spray = world_motion(rel, speed, e, times, t)
    else:  # the path's samples among the check's
        checked = world_motion(rel, speed, e, times, tf[j:])
        poses, d, dd, spray = world_motion_reusing(rel, speed, e, times, t, (tf[j:], checked))
    traj = Trajectory(t, poses, d, dd, name="paint line", derivatives="analytic",
                      curve=lambda t_: world_motion(rel, speed, e, times, t_)[:3])
    if screened:  # passed: the check's samples, the path's among them
        screen_motors(robot, act, (poses, d, dd), speed, first_kept(t, times.leave))
        checked = world_motion_reusing(rel, speed, e, times, tf[j:], (t, (poses, d, dd, spray)))
    try:
        fine = wait_motion(robot, act, checked[:3], j,
                           lambda: world_motion(rel, speed, e, times, tf)[:3])
    except ReachError as exc:
        said = f"at line speed {speed:.4g} m/s the path leaves the workspace at t = " \
               f"{tf[exc.sample]:.3f} s"
        raise LineSpeedError(say_less(f"{said}: {exc}", f"{said}: {str(exc).split(': ')[0]}",
                                      said), drift > 0,
                             f"the path leaves the workspace at t = {tf[exc.sample]:.3f} s"
                             ) from None
    tf = tf[j:]  # the rows checked: all but the wait's first j, the same as those kept
    cyc = tf >= times.leave - 1e-12  # RMS over the repeating cycle, not the wait
    ratios = {"peak_torque": fine.torque_ratio.max(0),
              "rms_torque": time_rms(tf[cyc], fine.torque[cyc])
              / act.column("continuous_torque"),
              "speed": fine.speed_ratio.max(0)}
    motors_within(max(float(ratios["peak_torque"].max()), float(ratios["speed"].max())),
                  speed, drift > 0)
    return World(rel, times, traj, spray, ratios)


def _searched(robot, act: Actuators, program: LineProgram, rel: Relative, speed: float, e,
              policy: PlannerPolicy) -> dict:
    """What :func:`plan_world` searches before it samples and checks the path (none of it
    reads ``policy.check_refine``): the ramps' and turnarounds' durations ``tau``, the
    ``delay`` [s] and the return's duration ``back`` [s], as plain numbers (a note,
    :mod:`.line.notes`); ``rel`` the program at its guess."""
    build, guess, where, passes = program.build, program.guess, program.where, program.passes
    ns = policy.turn_samples
    shift = choose_shift(robot, rel, speed, e, where)
    # the wait and the passes alone, before the turnarounds are searched
    passes_time = float(sum(d for d, k in zip(rel.duration, rel.kind) if k == "pass"))
    samples_budget(shift / speed + passes_time, program.dt, program.source, policy)
    centre = shift + _mid_along(rel, speed, e)
    built = {np.asarray(guess, dtype=float).tobytes(): rel}  # the search starts at the guess

    def evaluate(tau):
        r = built.pop(np.asarray(tau).tobytes(), None) or build(tau)
        pieces = r.not_passes()
        u = np.linspace(0.0, 1.0 - 1e-12, ns)
        tt = (r.start[pieces, None] + r.duration[pieces, None] * u[None, :]).ravel()
        ct, n = r.coarse_times(), len(tt)
        # the samples and _mid_along's coarse times in one evaluation (row by row the same)
        p, v, a = r.evaluate(np.concatenate([tt, ct]))
        x = centre - _mid(line_shift(p[n:], v[n:], ct, speed, e)[0], e)
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
                             _drift_along(rel, speed, e) > 0,
                             "no turnaround keeps the path in reach and the motors within "
                             "ratings") from None
    rel = build(tau)
    delay = choose_shift(robot, rel, speed, e, where) / speed
    back = _return_time(robot, act, rel, speed, e, delay, policy)
    return {"tau": np.asarray(tau, dtype=float).tolist(), "delay": float(delay),
            "back": float(back)}


def _per_tau(pieces, worst) -> np.ndarray:
    """The pieces' ``worst`` use per ramp or turnaround duration τ: consecutive pieces off
    the passes share one (a slow line's turn halves and wait, dwell.py)."""
    group = np.cumsum(np.diff(pieces, prepend=-2) > 1) - 1
    return np.array([worst[group == g].max() for g in range(group[-1] + 1)])


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


def _drift_along(rel: Relative, speed: float, e) -> float:
    """The program's world drift along the line [m], s·T − (relative travel): a failure at a
    positive drift is one of too fast a line, at a negative one of too slow (§24)."""
    along = _drift(rel, speed, e, np.array([0.0, rel.total]))[:, :3] @ e
    return float(along[1] - along[0])


def _mid_along(rel: Relative, speed: float, e) -> float:
    """The middle, along the line, of the program's world extent at shift 0."""
    return _mid(_drift(rel, speed, e, rel.coarse_times()), e)


def _mid(poses, e) -> float:
    """The middle of ``poses``' extent along e."""
    along = poses[:, :3] @ e
    return 0.5 * float(along.min() + along.max())


def _return_time(robot, act, rel: Relative, speed: float, e, delay: float,
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


__all__ = ["CATCH", "LineProgram", "LineTimes", "Relative", "World", "choose_shift",
           "line_shift", "one_coat", "path_times", "plan_world", "track", "world_motion",
           "world_motion_reusing"]
