"""Paint a panel riding a conveyor (docs/model.md §24).

The part is at ``center + speed·t·direction`` at time t of the path. The passes run across
the travel, leading end first, and are planned relative to the part (the raster of plan.py);
the robot runs the world path, relative + the line's displacement. The program begins with a
wait (gun off) whose length puts the program's drift inside the reach, found by a scan of the
shifts along the line where the whole world path stays in reach. Reach, limits, margins and
motors are checked on the world path (motion.py). After the program the robot slows to rest
and returns to its start pose: the cycle.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..dynamics.averages import time_rms
from ..dynamics.motors import Actuators
from ..paths.trajectory import Trajectory
from .errors import BudgetError, PlanError, ReachError
from .job import PaintJob
from .motion import fastest, motion, reach
from .plan import (
    CHECK_REFINE,
    MAX_PATH_SAMPLES,
    MAX_STEP,
    STEP_SIGMA,
    TURN_SAMPLES,
    UTILISATION,
    panel_layout,
)
from .raster import SMOOTHSTEP, PanelFrame, Segments, raster_motion, raster_segments

CATCH = 0.5  # s: the robot speeds up to (and down from) the line's speed over this time
SHIFT_RANGE = 2.0  # m: the line may carry the part this far before the program starts
SHIFT_STEP = 0.005  # m: the scan of shifts along the line
SHIFT_BISECT = 10  # bisection steps refining each end of the feasible shifts
SPEED_RESOLUTION = 0.01  # relative: --max-line-speed's bisection stops at this bracket
SPEED_TRIES = 12  # doublings/halvings bracketing the fastest speed
_RISE = SMOOTHSTEP.integ(lbnd=0.0)  # ∫ smoothstep: travels 1/2 over [0, 1]


class LineSpeedError(PlanError):
    """No program paints the part at this line speed (its drift does not fit the reach, or
    the motors cannot follow): ``too_fast`` says which side."""

    def __init__(self, message: str, too_fast: bool):
        super().__init__(message)
        self.too_fast = too_fast


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


@dataclass(frozen=True)
class LinePlan:
    job: PaintJob
    frame: PanelFrame
    segments: Segments  # the relative program (panel coordinates, its own time from 0)
    horizontal: bool
    direction: np.ndarray  # (3,) unit
    speed: float  # line speed [m/s]
    times: LineTimes
    trajectory: Trajectory  # the world path
    spray: np.ndarray  # (N,) 1 during the program, 0 while waiting and returning
    offsets: np.ndarray
    spacing: float
    pass_speed: float
    ratios: dict
    timings: dict = field(default_factory=dict)


def pass_direction(frame: PanelFrame, direction) -> bool:
    """True for horizontal passes (along u): the passes run across the travel."""
    d = np.asarray(direction, float)
    return abs(d @ frame.v) > abs(d @ frame.u)


def part_length(job: PaintJob, frame: PanelFrame, direction) -> float:
    """The panel's extent along the line [m]."""
    d = np.asarray(direction, float)
    return abs(job.width * (d @ frame.u)) + abs(job.height * (d @ frame.v))


def relative_motion(frame, job, seg: Segments, horizontal: bool, t):
    """The gun relative to the part (panel at its t = 0 pose), (poses, rates, accelerations)
    at the program's own times ``t``."""
    return raster_motion(frame, job.standoff, seg, t, horizontal)


def line_shift(poses, d, t, speed: float, direction):
    """Relative motion → world (docs/model.md §24): positions + speed·t·direction, rates +
    speed·direction, accelerations unchanged (new arrays)."""
    p = np.array(poses, dtype=float)
    v = np.array(d, dtype=float)
    p[:, :3] += speed * np.asarray(t, float)[:, None] * np.asarray(direction)[None, :]
    v[:, :3] += speed * np.asarray(direction)[None, :]
    return p, v


def world_motion(plan_parts, times: LineTimes, t):
    """The world path at times ``t`` (hold, catch up, program, slow down, return):
    (poses, rates, accelerations, spray)."""
    frame, job, seg, horizontal, speed, e = plan_parts
    t = np.asarray(t, dtype=float)
    D, E = times.delay, times.end
    poses = np.empty((len(t), 6))
    d, dd = np.zeros((len(t), 6)), np.zeros((len(t), 6))
    prog = (t >= D) & (t <= E)
    if prog.any():
        p, v, a = relative_motion(frame, job, seg, horizontal, t[prog] - D)
        poses[prog], d[prog] = line_shift(p, v, t[prog], speed, e)
        dd[prog] = a
    r0, _, _ = relative_motion(frame, job, seg, horizontal, np.array([0.0]))
    r1, _, _ = relative_motion(frame, job, seg, horizontal, np.array([seg.total]))
    hold = speed * (D - CATCH / 2)  # the start pose's shift along the line
    before = t < D
    x = np.clip((t[before] - (D - CATCH)) / CATCH, 0.0, 1.0)
    g = hold + speed * CATCH * _RISE(x)
    poses[before] = r0[0]
    poses[before, :3] += g[:, None] * e
    d[before, :3] = (speed * SMOOTHSTEP(x))[:, None] * e
    dd[before, :3] = (speed / CATCH * SMOOTHSTEP.deriv()(x))[:, None] * e
    slow = (t > E) & (t <= E + CATCH)
    x = (t[slow] - E) / CATCH
    g = speed * E + speed * CATCH * (x - _RISE(x))
    poses[slow] = r1[0]
    poses[slow, :3] += g[:, None] * e
    d[slow, :3] = (speed * (1 - SMOOTHSTEP(x)))[:, None] * e
    dd[slow, :3] = (-speed / CATCH * SMOOTHSTEP.deriv()(x))[:, None] * e
    back = t > E + CATCH
    if back.any():
        a = r1[0, :3] + speed * (E + CATCH / 2) * e
        b = r0[0, :3] + hold * e
        x = np.clip((t[back] - E - CATCH) / times.back, 0.0, 1.0)
        poses[back] = r0[0]
        poses[back, :3] = a + SMOOTHSTEP(x)[:, None] * (b - a)
        d[back, :3] = (SMOOTHSTEP.deriv()(x) / times.back)[:, None] * (b - a)
        dd[back, :3] = (SMOOTHSTEP.deriv(2)(x) / times.back ** 2)[:, None] * (b - a)
    return poses, d, dd, prog.astype(float)


def _drift(frame, job, seg, horizontal, speed, e, t):
    """The program's world positions with no wait (shift 0): relative + speed·t·direction."""
    p, v, _ = relative_motion(frame, job, seg, horizontal, t)
    return line_shift(p, v, t, speed, e)[0]


def _coarse_times(seg: Segments) -> np.ndarray:
    """Piece ends and middles: the program's extremes along and across the passes."""
    return np.unique(np.concatenate([seg.start, seg.start + seg.duration / 2, [seg.total]]))


def _fits(robot, poses, e, x) -> bool:
    p = np.array(poses)
    p[:, :3] += x * e
    try:
        reach(robot, p)
    except ReachError:
        return False
    return True


def feasible_shifts(robot, poses, e, lo: float, span: float = SHIFT_RANGE):
    """The longest run of shifts x ∈ [lo, lo + span] along the line with every pose + x·e in
    reach (scan at SHIFT_STEP, ends refined by bisection), or None."""
    xs = lo + np.arange(0.0, span + SHIFT_STEP / 2, SHIFT_STEP)
    ok = np.array([_fits(robot, poses, e, x) for x in xs])
    if not ok.any():
        return None
    # the longest run of True
    edges = np.diff(np.concatenate([[0], ok.astype(int), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    k = int(np.argmax(stops - starts))
    a, b = int(starts[k]), int(stops[k]) - 1

    def refine(good, bad):
        if bad < lo - 1e-15 or bad > lo + span + 1e-15:
            return good
        for _ in range(SHIFT_BISECT):
            mid = 0.5 * (good + bad)
            good, bad = (mid, bad) if _fits(robot, poses, e, mid) else (good, mid)
        return good

    return refine(xs[a], xs[a] - SHIFT_STEP), refine(xs[b], xs[b] + SHIFT_STEP)


def _where(frame: PanelFrame, job: PaintJob, e) -> str:
    c = frame.c + job.standoff * frame.n
    return (f"the gun's track at the panel's centre runs through ({c[0]:.3f}, {c[1]:.3f}, "
            f"{c[2]:.3f}) m along ({e[0]:.3g}, {e[1]:.3g}, {e[2]:.3g})")


def choose_shift(robot, frame, job, seg, horizontal, speed, e) -> float:
    """The line's shift speed·delay [m] at the middle of the shifts that keep the world
    program (coarse samples) in reach; :class:`LineSpeedError` if none does."""
    t = _coarse_times(seg)
    poses = _drift(frame, job, seg, horizontal, speed, e, t)
    found = feasible_shifts(robot, poses, e, speed * CATCH)
    if found is None:
        # one pass alone, no drift: does the part come within reach at all?
        first = seg.start[1] + seg.duration[1] * np.linspace(0, 1, 9)
        p, _, _ = relative_motion(frame, job, seg, horizontal, first)
        if feasible_shifts(robot, p, e, speed * CATCH) is None:
            raise PlanError(f"the part never comes within reach: {_where(frame, job, e)}, "
                            f"and no pass of it is reachable within {SHIFT_RANGE:g} m of "
                            "travel: move the part or the line")
        along = poses[:, :3] @ e
        drift = float(along[-1] - along[0])
        raise LineSpeedError(f"at line speed {speed:.4g} m/s the program drifts "
                             f"{drift:+.3f} m along the line in {seg.total:.4g} s and leaves "
                             "the reach wherever it starts", drift > 0)
    return 0.5 * float(found[0] + found[1])


def _times_of(seg: Segments, job: PaintJob, speed: float, total: float) -> np.ndarray:
    dt = min(MAX_STEP, STEP_SIGMA * job.sigma / speed)
    n = math.ceil(total / dt) + 1
    if n > MAX_PATH_SAMPLES:
        raise BudgetError(f"{job.source}: the line's path needs {n:.3g} samples ({total:.4g} s), "
                          f"budget {MAX_PATH_SAMPLES:.3g}: a thinner film or more flow")
    return np.linspace(0.0, total, n)


def plan_line(robot, job: PaintJob, act: Actuators, speed: float | None = None) -> LinePlan:
    """The raster program for a panel on the line at ``speed`` (default the job's)."""
    clock = time.perf_counter()
    line = job.line
    speed = line.speed if speed is None else float(speed)
    e = np.asarray(line.direction, float)
    if job.coats not in (None, 1):
        raise PlanError(f"{job.source}: job.coats = {job.coats}: a part on the line is painted "
                        "in one coat (the second would run back against the travel)")
    from .raster import panel_frame

    horizontal = pass_direction(panel_frame(job), e)
    job_x = replace(job, direction="horizontal" if horizontal else "vertical")
    frame, offsets, half_length, pass_speed, coats, spacing = panel_layout(job_x)
    es = frame.v if horizontal else frame.u
    offsets = np.array(sorted(offsets, key=lambda o: -o * float(es @ e)))  # leading end first
    guess = 4 * pass_speed / 10.0
    parts = (frame, job_x, None, horizontal, speed, e)

    def build(tau):
        return raster_segments(offsets, half_length, pass_speed, tau[1:-1], (tau[0], tau[-1]))

    n_pieces = 2 * len(offsets) + 1 - len(offsets)  # ramps and turns
    seg = build(np.full(n_pieces, guess))
    shift = choose_shift(robot, frame, job_x, seg, horizontal, speed, e)
    centre = shift + _mid_along(frame, job_x, seg, horizontal, speed, e)

    def evaluate(tau):
        s = build(tau)
        x = centre - _mid_along(frame, job_x, s, horizontal, speed, e)
        pieces = np.array([i for i, k in enumerate(s.kind) if k != "pass"])
        u = np.linspace(0.0, 1.0 - 1e-12, TURN_SAMPLES)
        tt = (s.start[pieces, None] + s.duration[pieces, None] * u[None, :]).ravel()
        p, v, a = relative_motion(frame, job_x, s, horizontal, tt)
        p, v = line_shift(p, v, tt + x / speed, speed, e)
        try:
            m = motion(robot, act, p, v, a)
        except ReachError:
            return np.full(len(pieces), np.inf)
        return m.utilisation.reshape(len(pieces), TURN_SAMPLES, -1).max(axis=(1, 2))

    try:
        seg = build(fastest(evaluate, np.full(n_pieces, guess), UTILISATION))
    except PlanError:
        raise LineSpeedError(f"at line speed {speed:.4g} m/s the motors cannot follow the "
                             f"passes ({pass_speed:.4g} m/s on the part) with the line's "
                             "speed added", True) from None
    shift = choose_shift(robot, frame, job_x, seg, horizontal, speed, e)
    delay = float(shift) / speed
    parts = (frame, job_x, seg, horizontal, speed, e)
    back = _return_time(robot, act, parts, delay, seg.total)
    times = LineTimes(delay, delay + seg.total, back)
    t = _times_of(seg, job, pass_speed, times.total)
    poses, d, dd, spray = world_motion(parts, times, t)
    traj = Trajectory(t, poses, d, dd, name="paint line", derivatives="analytic",
                      curve=lambda times_: world_motion(parts, times, times_)[:3])
    tf = np.linspace(0.0, times.total, CHECK_REFINE * (len(t) - 1) + 1)
    try:
        fine = motion(robot, act, *world_motion(parts, times, tf)[:3])
    except ReachError as exc:
        raise LineSpeedError(f"at line speed {speed:.4g} m/s the path leaves the workspace at "
                             f"t = {tf[exc.sample]:.3f} s: {exc}",
                             _drift_along(parts, seg) > 0) from None
    ratios = {"peak_torque": fine.torque_ratio.max(0),
              "rms_torque": time_rms(tf, fine.torque) / act.column("continuous_torque"),
              "speed": fine.speed_ratio.max(0)}
    worst = max(float(ratios["peak_torque"].max()), float(ratios["speed"].max()))
    if worst > 1.0:
        raise LineSpeedError(f"at line speed {speed:.4g} m/s a motor needs {100 * worst:.0f} % "
                             "of its peak torque or speed", _drift_along(parts, seg) > 0)
    return LinePlan(job_x, frame, seg, horizontal, e, speed, times, traj, spray, offsets,
                    spacing, pass_speed, ratios, {"plan": time.perf_counter() - clock})


def _drift_along(parts, seg: Segments) -> float:
    """The program's world drift along the line [m], s·T − (relative travel): a failure at a
    positive drift is one of too fast a line, at a negative one of too slow (§24)."""
    frame, job, _, horizontal, speed, e = parts
    along = _drift(frame, job, seg, horizontal, speed, e, np.array([0.0, seg.total]))[:, :3] @ e
    return float(along[1] - along[0])


def _mid_along(frame, job, seg, horizontal, speed, e) -> float:
    """The middle, along the line, of the program's world extent at shift 0."""
    along = _drift(frame, job, seg, horizontal, speed, e, _coarse_times(seg))[:, :3] @ e
    return 0.5 * float(along.min() + along.max())


def _return_time(robot, act, parts, delay: float, program: float) -> float:
    """The shortest return to the start pose (rest to rest) within UTILISATION."""
    u = np.linspace(0.0, 1.0, TURN_SAMPLES)

    def evaluate(tau):
        times = LineTimes(delay, delay + program, float(tau[0]))
        tt = times.end + CATCH + tau[0] * u
        try:
            m = motion(robot, act, *world_motion(parts, times, tt)[:3])
        except ReachError:
            return np.array([np.inf])
        return np.array([m.utilisation.max()])

    return float(fastest(evaluate, np.array([0.5]), UTILISATION)[0])


def max_line_speed(robot, job: PaintJob, act: Actuators,
                   resolution: float = SPEED_RESOLUTION) -> tuple[float, LinePlan]:
    """The fastest line speed [m/s] (within ``resolution``, relative) at which the panel is
    painted under the same checks, and its plan (docs/model.md §24): from the speed whose
    drift matches the part's length, doubled until it fails, then bisected."""
    s = job.line.speed
    best = None
    slow, fast = 0.0, math.inf  # the fastest too slow and the slowest too fast tried
    for _ in range(2 * SPEED_TRIES):  # a speed that works: the drift ≈ the part's length
        try:
            best = (s, plan_line(robot, job, act, s))
            break
        except LineSpeedError as exc:
            if exc.too_fast:
                fast = s
            else:
                slow = s
        if fast < math.inf and slow > 0:
            if fast - slow <= resolution * slow:
                break
            s = 0.5 * (slow + fast)
        else:
            s = 2 * s if fast == math.inf else 0.5 * s
    if best is None:
        raise PlanError(f"{job.source}: no line speed paints the panel (too slow at "
                        f"{slow:.4g} m/s, too fast at {fast:.4g} m/s)")
    lo, plan = best
    hi = None
    for _ in range(SPEED_TRIES):
        try:
            s2 = 2 * lo if hi is None else hi
            plan = plan_line(robot, job, act, s2)
            lo = s2
        except LineSpeedError:
            hi = s2
            break
    if hi is None:
        return lo, plan
    while (hi - lo) > resolution * lo:
        mid = 0.5 * (lo + hi)
        try:
            plan = plan_line(robot, job, act, mid)
            lo = mid
        except LineSpeedError:
            hi = mid
    if plan.speed != lo:
        plan = plan_line(robot, job, act, lo)
    return lo, plan


def plan_line_job(robot, job: PaintJob, act: Actuators) -> LinePlan:
    """The job's line speed planned; a speed that cannot be painted is refused naming the
    fastest that works (:func:`max_line_speed`)."""
    try:
        return plan_line(robot, job, act)
    except LineSpeedError as exc:
        try:
            fastest_speed, _ = max_line_speed(robot, job, act)
        except PlanError:
            raise exc from None
        raise PlanError(f"{exc}; the fastest line speed that paints it is "
                        f"{fastest_speed:.4g} m/s (--max-line-speed)") from None


__all__ = ["CATCH", "LinePlan", "LineSpeedError", "LineTimes", "SPEED_RESOLUTION",
           "choose_shift", "feasible_shifts", "line_shift", "max_line_speed", "part_length",
           "pass_direction", "plan_line", "plan_line_job", "relative_motion", "world_motion"]
