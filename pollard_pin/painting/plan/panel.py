"""Plan a paint job: passes, speed, coats, the fastest turnarounds the motors allow, the
trajectory, (docs/model.md §21). The film it leaves is
:mod:`.film.grid`, the numbers of ``paint.json`` :mod:`.report`.

1. Spacing: the widest whose interior ripple is ≤ PROFILE_TOLERANCE/2 (or the job's); the
   fewest passes whose cross profile stays within PROFILE_TOLERANCE up to the edges.
2. Speed: film = flow/(speed·spacing) per coat. The fastest constant pass speed the motors
   allow (every pass, peak torque and speed derated to the policy's ``utilisation``) caps
   it: a target that needs more is refused, naming the thinnest film per coat.
3. Turnarounds and ramps: each the shortest of its family (raster.py) whose motors stay within
   ``utilisation`` of peak torque and speed (vectorised bisection, ``turn_samples`` per
   piece). The cycle repeats on a line, so each motor's RMS torque over it (``size``'s
   definition, dynamics/averages.py) must also stay within ``utilisation`` of its
   continuous rating: if it
   does not, every turnaround and ramp is lengthened by one common factor (bisection) until
   it does, or the job is refused naming the motor and its RMS use.
4. The whole trajectory is checked like ``run`` (reach, margins, joint limits) and against the
   motors at ``check_refine`` times its sampling, then the film is integrated over the panel.

The knobs are the planner's :class:`..policy.PlannerPolicy` (``policy=``).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from ...dynamics.averages import time_rms
from ...dynamics.motors import ActuatorError, Actuators, uniform_min_duration
from ...dynamics.path import path_dynamics
from ...errors import say_less, without_asides
from ...paths.trajectory import Trajectory
from ..checks.clearance import job_clearance, panel_mesh
from ..checks.motion import GUESS_HALVINGS, fastest, motion, reach
from ..errors import BudgetError, JobKindError, PlanError, ReachError
from ..job import MIN_PANEL_SIGMAS, PaintJob, job_kind
from ..passes.raster import (
    Segments,
    raster_motion,
    raster_segments,
    task_motion,
)
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..workpiece.panel import PanelFrame
from .layout import PanelLayout, panel_layout, path_times, spot_too_fine
from .result import PlanResult


@dataclass(frozen=True)
class PaintPlan(PlanResult):
    """A still panel's raster (:func:`~pollard_pin.painting.plan.plan_paint`; the gun sprays
    throughout: ``spray`` all 1).

    Attributes
    ----------
    job : PaintJob
        The job.
    trajectory : Trajectory
        The program: the tool path, world frame.
    offsets : ndarray
        The passes' positions across the passes [m].
    spacing : float
        Pass spacing [m].
    speed, max_speed : float
        Pass speed [m/s], and the fastest the motors allow.
    coats : int
        Coats.
    frame : pollard_pin.painting.workpiece.panel.PanelFrame
        The panel's frame (centre, u, v, normal).
    segments : pollard_pin.painting.passes.raster.Segments
        The program's segments (passes, ramps, turnarounds) and their durations.
    half_length : float
        Passes run at constant speed over ``|U| ≤ half_length`` [m].
    horizontal : bool
        Horizontal (True) or vertical passes.
    spray : ndarray
        The trigger per sample (all 1 here).
    ratios : dict
        Each motor's use of each rating (peak_torque, rms_torque, speed).
    timings : dict
        Seconds spent planning.
    clearance : object
        The gun body's smallest distance to the panel and where.

    ``cycle_time`` [s], ``passes`` and ``lower_bound`` (the painting-only bound [s]) are
    properties.
    """

    job: PaintJob
    frame: PanelFrame
    segments: Segments
    offsets: np.ndarray  # pass positions across the passes [m]
    spacing: float
    speed: float  # pass speed [m/s]
    coats: int
    half_length: float  # passes run at constant speed over |U| ≤ half_length
    max_speed: float  # the fastest pass speed the motors allow [m/s]
    horizontal: bool = True

    @property
    def cycle_time(self) -> float:
        return self.segments.total

    @property
    def passes(self) -> int:
        return len(self.offsets) * self.coats

    @property
    def lower_bound(self) -> float:
        """Painting-only lower bound [s]: panel area × target / flow."""
        j = self.job
        return j.width * j.height * j.thickness / j.flow


def derated(act: Actuators, factor: float) -> Actuators:
    """The actuators with peak torque and max speed scaled by ``factor``."""
    units = tuple(replace(u, peak_torque=u.peak_torque * factor,
                          max_speed=u.max_speed * factor) for u in act.units)
    return replace(act, units=units)


def _sample_pieces(seg: Segments, pieces: np.ndarray, n: int):
    x = np.linspace(0.0, 1.0, n)
    t = (seg.start[pieces, None] + seg.duration[pieces, None] * x[None, :]).ravel()
    # keep every sample inside its own piece (searchsorted picks the later at a boundary)
    t = np.minimum(t, np.repeat(seg.start[pieces] + seg.duration[pieces] * (1 - 1e-12), n))
    return t


def _task(plan_frame, job, seg: Segments, t, horizontal):
    return raster_motion(plan_frame, job.standoff, seg, t, horizontal)


def max_pass_speed(robot, act: Actuators, frame: PanelFrame, job: PaintJob, offsets,
                   half_length: float, horizontal: bool,
                   policy: PlannerPolicy = DEFAULT_POLICY) -> float:
    """The fastest constant speed [m/s] at which every pass keeps each motor within
    ``policy.utilisation`` of its peak torque and speed (uniform time scaling of the passes,
    §19)."""
    n = 64
    U = np.linspace(-half_length, half_length, n)
    length = 2 * half_length
    U_all = np.tile(U, len(offsets))
    V_all = np.repeat(offsets, n)
    one = np.ones_like(U_all)
    poses, d, dd = task_motion(frame, job.standoff, U_all, V_all, one, 0 * one, 0 * one,
                               0 * one, horizontal)
    # passes laid end to end at 1 m/s (a gap of one step between them): t is arc length
    t = (np.tile(U + half_length, len(offsets))
         + np.repeat(np.arange(len(offsets)) * (length + length / n), n))
    # reach and limits, with their messages; the motors' question is path_dynamics' below
    ik = replace(reach(robot, poses, d, dd), t=t)
    try:
        scaling = uniform_min_duration(derated(act, policy.utilisation), path_dynamics(robot, ik))
    except ActuatorError as exc:
        raise PlanError(f"the motors cannot hold the gun on the passes: {exc}") from None
    binding = max(scaling.by_limit["peak_torque"], scaling.by_limit["speed"])
    return math.inf if binding == 0 else float(t[-1] - t[0]) / binding


def plan_paint(robot, job: PaintJob, act: Actuators,
               policy: PlannerPolicy = DEFAULT_POLICY) -> PaintPlan:
    """The fastest raster program for a still panel that the motors and the workspace allow
    (docs/model.md §21): passes at the constant speed the target film needs, every ramp and
    turnaround as short as the motors allow.

    Parameters
    ----------
    robot : Robot
        The model.
    job : PaintJob
        A still panel's job (:func:`~pollard_pin.load_job`).
    act : Actuators
        The motor ratings the program must keep.
    policy : pollard_pin.painting.policy.PlannerPolicy, optional
        The planner's reserve, sampling and budgets (default the planners' own).

    Returns
    -------
    PaintPlan
        The program (``trajectory``), its passes, speed, spacing and cycle time.

    Raises
    ------
    PlanError
        A path out of reach, naming where it leaves the workspace and the largest panel of
        the same centre and proportions that was planned in full (a float scale, not
        :func:`~pollard_pin.largest_panel`'s rectangle); a budget the job breaks.
    JobKindError
        A job of another kind (a part, a line): those are
        :func:`~pollard_pin.painting.api.paint_job`'s.
    """
    kind = job_kind(job)
    if kind != "panel":
        raise JobKindError(f"{job.source}: plan_paint plans a still panel, not a {kind}: "
                           "paint it with pollard_pin.paint(robot, job)")
    try:
        return _plan(robot, job, act, policy)
    except ReachError as exc:
        lay = panel_layout(job, policy)
        where = str(exc).split(": ")[0]
        cause = None if " on a pass" in where else spot_too_fine(job, lay.speed, lay.spacing)
        if cause is not None:  # a smaller panel needs the same speed
            raise PlanError(say_less(f"{where}: {cause}",
                                     f"{where.split(' at panel')[0]}: {cause}")) from None
        scale, _ = _largest_scale(robot, job, act, policy=policy)
        if scale == 0:
            fits = (f"no {job.width / job.height:.3g}:1 panel centred at "
                    f"{tuple(round(c, 4) for c in job.center)} fits")
        else:
            fit = printed_panel(job, scale)  # the panel planned, as printed
            fits = (f"the largest panel that fits (same centre, proportions) is "
                    f"{fit.width:.3f} × {fit.height:.3f} m, planned in full")
        first = ": ".join(str(exc).split(": ")[:2])  # where, and the kinematics' cause
        raise PlanError(say_less(f"{exc}; {fits}", f"{first}; {fits}")) from None


def printed_panel(job: PaintJob, scale: float) -> PaintJob:
    """The job's panel at ``scale``, each side rounded down to the millimetre: the panel
    :func:`plan_paint` plans and then prints as the one that fits (a side rounded up may not
    fit)."""
    def down(x: float) -> float:  # the 1e-9 mm: a side of exactly k mm is not floored to k − 1
        return math.floor(x * 1e3 + 1e-9) / 1e3

    return replace(job, width=down(scale * job.width), height=down(scale * job.height))


LARGEST_STEPS = 6  # bisection steps of the largest panel whose crude raster stays in reach
# ... then planned in full, stepping down by STEP_DOWN until one plans, at most this often
LARGEST_TRIES = 12
STEP_DOWN = 0.95


def largest_scale(robot, job: PaintJob, act: Actuators, steps: int = LARGEST_STEPS,
                  policy: PlannerPolicy = DEFAULT_POLICY) -> float:
    """The largest scale s ∈ [0, 1) of the job's panel, same centre and proportions, whose
    :func:`printed_panel` (sides rounded down to the mm) :func:`plan_paint` plans (a float;
    :func:`pollard_pin.workspace.grid.largest_panel` is the workspace's rectangle): a
    bisection (to 2^-steps) over a crude raster checked for reach only, then the candidate
    planned in full and stepped down by STEP_DOWN until one plans (at most LARGEST_TRIES
    plans); 0 if none does. ``policy``: the planner's (:class:`..policy.PlannerPolicy`)."""
    return _largest_scale(robot, job, act, steps, policy)[0]


def _largest_scale(robot, job: PaintJob, act: Actuators, steps: int = LARGEST_STEPS,
                   policy: PlannerPolicy = DEFAULT_POLICY):
    """(scale, relative accuracy) of :func:`largest_scale`; (0, 0) if no scale plans."""
    scale = _reach_scale(robot, job, steps, policy)
    for k in range(LARGEST_TRIES if scale > 0 else 0):
        scaled = printed_panel(job, scale)
        if min(scaled.width, scaled.height) < MIN_PANEL_SIGMAS * job.sigma:
            break  # the job's own rule (job.py): a smaller panel is refused
        try:
            _plan(robot, scaled, act, policy)
        except PlanError:
            scale *= STEP_DOWN
            continue
        # the bisection's bracket, or the step from the last scale that did not plan
        return scale, (2.0 ** -steps if k == 0 else 1 / STEP_DOWN - 1)
    return 0.0, 0.0


def _reach_scale(robot, job: PaintJob, steps: int, policy: PlannerPolicy) -> float:
    """The bisection of :func:`largest_scale`: each try samples the whole raster at the job's
    speed with every turnaround and ramp at the duration search's first guess, reach only
    (IK, margins, joint limits: :func:`.checks.motion.reach`, no dynamics)."""
    lo, hi = 0.0, 1.0
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        scaled = replace(job, width=mid * job.width, height=mid * job.height)
        try:
            frame, offsets, half_length, speed, coats, _ = panel_layout(scaled, policy)
            tau = policy.first_guess(speed)
            seg = raster_segments(offsets, half_length, speed, tau, (tau, tau), coats)
            t = path_times(seg, scaled, speed, np.arange, policy)
            reach(robot, *_task(frame, scaled, seg, t, job.direction == "horizontal"))
            lo = mid
        except BudgetError:
            raise
        except PlanError:
            hi = mid
    return lo


def _plan(robot, job: PaintJob, act: Actuators, policy: PlannerPolicy) -> PaintPlan:
    clock = {"start": time.perf_counter()}
    lay = panel_layout(job, policy)
    frame, offsets, half_length, speed, coats, spacing = lay
    horizontal = job.direction == "horizontal"
    try:
        vmax = max_pass_speed(robot, act, frame, job, offsets, half_length, horizontal,
                              policy)
    except ReachError as exc:
        raise _reach_error(exc, "on a pass", frame, job) from None
    if speed > vmax:
        # Film per coat = flow/(speed·spacing): the motors' fastest pass sets the thinnest
        # coat; more coats only make each one thinner still.
        per_coat = job.flow / (vmax * spacing)
        cause = spot_too_fine(job, speed, spacing, vmax)
        if cause is not None:
            raise PlanError(cause)
        most = math.floor(job.thickness / per_coat * (1 + 1e-9))
        hint = (f"; at most {most} coat(s) of this target" if most >= 1 else
                f"; a target below that cannot be painted at spacing {spacing * 1e3:.4g} mm")
        raise PlanError(f"the target needs a gun speed of {speed:.4g} m/s ({coats} coat(s) of "
                        f"{job.thickness / coats * 1e6:.4g} µm at spacing {spacing * 1e3:.4g} "
                        f"mm) but the motors allow {vmax:.4g} m/s: the thinnest film per coat "
                        f"is {per_coat * 1e6:.4g} µm{hint}")
    film_per_coat = job.flow / (speed * spacing)
    if abs(film_per_coat * coats / job.thickness - 1) > 1e-6:
        raise PlanError(f"speed {speed:.4g} m/s and spacing {spacing * 1e3:.4g} mm give "
                        f"{film_per_coat * 1e6:.4g} µm per coat, and {coats} coat(s) make "
                        f"{film_per_coat * coats * 1e6:.4g} µm, not the target "
                        f"{job.thickness * 1e6:.4g} µm")
    clock["layout"] = time.perf_counter()
    seg = _fastest_segments(robot, act, job, lay, horizontal, policy)
    seg = _within_rms(robot, act, job, lay, seg, horizontal, policy)
    clock["turns"] = time.perf_counter()
    t = path_times(seg, job, speed, policy=policy)
    n = len(t)
    poses, d, dd = _task(frame, job, seg, t, horizontal)
    traj = Trajectory(t, poses, d, dd, name="paint", derivatives="analytic",
                      curve=lambda times: _task(frame, job, seg, times, horizontal))
    tf = np.linspace(0.0, seg.total, policy.check_refine * (n - 1) + 1)
    try:
        fine = motion(robot, act, *_task(frame, job, seg, tf, horizontal))
    except ReachError as exc:
        where = seg.kind[int(np.searchsorted(seg.start, tf[exc.sample], "right") - 1)]
        raise _reach_error(exc, f"in a {where}", frame, job) from None
    ratios = {"peak_torque": fine.torque_ratio.max(0),
              "rms_torque": time_rms(tf, fine.torque) / act.column("continuous_torque"),
              "speed": fine.speed_ratio.max(0)}
    if ratios["rms_torque"].max() > 1.0:  # the search's samples missed it: say so, never pass
        raise PlanError(_rms_text(act, ratios["rms_torque"], "the planned cycle"))
    clear = job_clearance(robot, job, panel_mesh(frame), poses, t, lambda i: "in a " + str(
        seg.kind[int(np.searchsorted(seg.start, t[i], "right") - 1)]), policy.clearance_stride)
    clock["check"] = time.perf_counter()
    return PaintPlan(job, frame, seg, offsets, spacing, speed, coats, half_length, vmax,
                     horizontal, trajectory=traj, spray=np.ones(n), ratios=ratios,
                     clearance=clear,
                     timings={"layout": clock["layout"] - clock["start"],
                              "turnarounds": clock["turns"] - clock["layout"],
                              "check": clock["check"] - clock["turns"]})


def _fastest_segments(robot, act, job, lay: PanelLayout, horizontal: bool,
                      policy: PlannerPolicy) -> Segments:
    """Every turnaround and ramp at the shortest duration within ``policy.utilisation``
    (bisection)."""
    n = policy.turn_samples
    frame, offsets, half_length, speed, coats, _ = lay
    seg = raster_segments(offsets, half_length, speed, 1.0, (1.0, 1.0), coats)
    pieces = np.array([i for i, k in enumerate(seg.kind) if k != "pass"])

    def build(tau):
        return raster_segments(offsets, half_length, speed, tau[1:-1], (tau[0], tau[-1]),
                               coats)

    def evaluate(tau):
        s = build(tau)
        t = _sample_pieces(s, pieces, n)
        try:
            m = motion(robot, act, *_task(frame, job, s, t, horizontal))
        except ReachError as exc:
            k = exc.sample // n
            what = "ramp" if k in (0, len(pieces) - 1) else "turnaround"
            raise _reach_error(exc, f"in a {what} ({tau[k]:.3g} s)", frame, job) from None
        return m.utilisation.reshape(len(pieces), n, -1).max(axis=(1, 2))

    guess = np.full(len(pieces), policy.first_guess(speed))
    # a fast pass's first guess may run out of reach (a ramp runs v·τ/2 on): halved
    return build(fastest(evaluate, guess, policy.utilisation, halvings=GUESS_HALVINGS))


RMS_DOUBLINGS = 6  # turnarounds and ramps at most 2^6 × their fastest for the RMS rating


def _rms_text(act: Actuators, use: np.ndarray, what: str) -> str:
    j = int(np.argmax(use))
    return (f"motor {act.names[j]} runs at {100 * use[j]:.4g} % of its continuous (RMS) torque "
            f"over {what} (docs/model.md §19): the cycle repeats, so it would overheat")


def _within_rms(robot, act, job, lay: PanelLayout, seg: Segments, horizontal: bool,
                policy: PlannerPolicy) -> Segments:
    """``seg`` with every turnaround and ramp × k, the smallest k ≥ 1 (doubling, then
    bisection) at which each motor's RMS torque over the cycle, sqrt(∫τm² dt / T), is within
    ``policy.utilisation`` of its continuous rating. The passes do not change with k: their
    ∫τm² is computed once; the pieces' by the trapezoid rule on ``policy.turn_samples``
    each."""
    n, within = policy.turn_samples, policy.utilisation
    frame, offsets, half_length, speed, coats, _ = lay
    pieces = np.array([i for i, k in enumerate(seg.kind) if k != "pass"])
    passes = np.array([i for i, k in enumerate(seg.kind) if k == "pass"])
    base = seg.duration[pieces]
    cont = act.column("continuous_torque")
    w = np.full(n, 1.0 / (n - 1))
    w[[0, -1]] *= 0.5  # trapezoid weights on [0, 1]

    def square_integral(s: Segments, idx) -> np.ndarray:  # per motor ∫τm² dt over pieces idx
        t = _sample_pieces(s, idx, n)
        tm = motion(robot, act, *_task(frame, job, s, t, horizontal)).torque
        per = np.einsum("s,psj->pj", w, tm.reshape(len(idx), n, -1) ** 2)
        return (per * s.duration[idx, None]).sum(axis=0)

    def build(k: float) -> Segments:
        tau = k * base
        return raster_segments(offsets, half_length, speed, tau[1:-1], (tau[0], tau[-1]),
                               coats)

    on_passes = square_integral(seg, passes)

    def use(k: float) -> np.ndarray:
        s = build(k)
        return np.sqrt((on_passes + square_integral(s, pieces)) / s.total) / cont

    u = use(1.0)
    if u.max() <= within:
        return seg
    advice = ("; paint fewer coats or a slower pass (job.speed with more coats), or choose "
              "stronger motors")
    lo, hi = 1.0, 2.0
    for _ in range(RMS_DOUBLINGS):
        try:
            u_hi = use(hi)
        except ReachError:  # a longer turnaround reaches further out (raster.py)
            raise PlanError(_rms_text(act, u, f"the cycle with turnarounds and ramps {lo:g}× "
                                              "their fastest") + "; longer ones leave the "
                            "workspace" + advice) from None
        if u_hi.max() <= within:
            break
        lo, hi, u = hi, 2 * hi, u_hi
    else:
        raise PlanError(_rms_text(act, u, f"the cycle even with turnarounds and ramps "
                                          f"{lo:g}× their fastest") + advice)
    for _ in range(8):  # to 2^-8 of the bracket: between lo and hi every turnaround is in reach
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if use(mid).max() <= within else (mid, hi)
    return build(hi)


def _reach_error(exc: ReachError, where: str, frame: PanelFrame, job: PaintJob) -> ReachError:
    """The error with where the path leaves the workspace: panel (u, v)."""
    msg = f"the path leaves the workspace {where}"
    if exc.pose is not None:
        xyz = np.asarray(exc.pose[:3])
        p = xyz - frame.c - job.standoff * frame.n
        msg += f" at panel (u, v) = ({p @ frame.u * 1e3:.0f}, {p @ frame.v * 1e3:.0f}) mm"
    return ReachError(say_less(f"{msg}: {exc}", f"{msg}: {without_asides(str(exc))}",
                               f"{msg}: {str(exc).split(': ')[0]}"), exc.sample, exc.pose)


__all__ = ["PaintPlan", "derated", "largest_scale", "max_pass_speed", "plan_paint",
           "printed_panel"]
