"""One cell robot's program (docs/model.md §26.1, §26.3): the shared strokes of the whole
part, in the robot's base frame, clipped to its zone, run on the line by today's line
planner (:func:`.line.world.plan_world`), the seam instants inserted as samples.

A panel's raster over [−H, H] (H the half pass length) is clipped to [a, b] = [lo − R,
hi + R] ∩ [−H, H] by running the same raster over a half length (b − a)/2 about the frame's
centre moved to (a + b)/2 along the passes. A part's pass, a spline of its surface arc s, is
run over the arc between the points where its aim point crosses lo − R and hi + R.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from ...paths.trajectory import Trajectory
from ..errors import PlanError
from ..line.dwell import dwell_time, plan_dwelling
from ..line.panel import LinePlan, pass_direction, step_order
from ..line.part import LinePartPlan, across_the_travel, leading_first
from ..line.phases import (
    LineProgram,
    one_coat,
    track,
    world_motion,
    world_motion_reusing,
)
from ..line.strokes import Strokes, across
from ..passes.program import PassPiece, build_program, pass_pieces
from ..passes.raster import raster_motion, raster_segments
from ..passes.surface import pass_speed, surface_layout
from ..plan.layout import panel_layout
from ..plan.part import time_step
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..workpiece.panel import panel_frame
from .zones import CLOSED, OPEN, ZoneRelative, past_seam, seam_fractions, window, with_samples


@dataclass(frozen=True)
class ZoneView:
    """A robot's zone seen from its base: the ``zone`` (world coordinates along the split's
    axis), the run-on ``runout`` R [m], the ``axis`` in the base frame and ``offset`` = the
    base origin's world coordinate along it (x_base = x_world − offset)."""

    zone: object
    runout: float
    axis: np.ndarray
    offset: float


class ClippedPass(PassPiece):
    """A pass run over the arc [s0, s1] of its parent (a :class:`.passes.program.PassPiece`)
    at the same speed and in the same direction."""

    def __init__(self, parent: PassPiece, s0: float, s1: float):
        self.spline, self.d1, self.d2 = parent.spline, parent.d1, parent.d2
        self.v, self.forward, self.index = parent.v, parent.forward, parent.index
        self.s0, self.s1 = float(s0), float(s1)
        self.length = self.s1 - self.s0
        self.duration = self.length / self.v

    def evaluate(self, tau):
        rate = self.v if self.forward else -self.v
        s = self.s0 + tau * self.v if self.forward else self.s1 - tau * self.v
        s = np.clip(s, self.s0, self.s1)
        return self.spline(s), self.d1(s) * rate, self.d2(s) * self.v ** 2


def _seam_run(view: ZoneView, policy: PlannerPolicy) -> ZoneView:
    """The view with the run past a seam the policy's (:func:`.zones.past_seam`,
    docs/model.md §26.5): the trigger still closes at the seam, so the film is the same."""
    return replace(view, runout=past_seam(view.runout, policy.seam_run))


def _axis_sign(along, axis_b, what: str,
               rule: str = "zones are stacked along the passes, across the travel") -> float:
    c = float(np.asarray(along) @ axis_b)
    if abs(c) < 1 - 1e-6:
        raise PlanError(f"the split's axis runs {math.degrees(math.acos(min(1, abs(c)))):.3g}° "
                        f"off the {what}: {rule}")
    return 1.0 if c > 0 else -1.0


def _in_zone(x_world: float, zone, tol: float = 1e-6) -> bool:
    """A whole pass at ``x_world`` along the split's axis is the zone's (strokes along the
    travel: a seam between two passes, the upper zone taking a pass on it or within ``tol``
    [m] of it, whatever round-off each robot's base frame puts on its level)."""
    return zone.lo - tol <= x_world < zone.hi - tol


def _limits(zone, runout: float, offset: float, sign: float):
    """The zone's (lo, hi) and the stroke's (lo − R, hi + R) in a coordinate u = sign·(x −
    offset) along the passes (x along the split's axis in the world)."""
    lo, hi = sorted((sign * (zone.lo - offset), sign * (zone.hi - offset)))
    return (lo, hi), (lo - runout if math.isfinite(lo) else lo,
                      hi + runout if math.isfinite(hi) else hi)


def _panel_windows(seg, on, m: float) -> tuple:
    """Each piece's trigger window: a pass while its U is within ``on`` (the zone, in the
    raster's own U, the centre moved by ``m``); a turn or ramp open beyond a free edge."""
    lo, hi = on[0] - m, on[1] - m
    out = []
    for i, kind in enumerate(seg.kind):
        if kind == "pass":
            out.append(window(lo, hi, seg.cu[i, 0], seg.cu[i, 1], seg.duration[i]))
        else:
            free = math.isinf(hi) if seg.cu[i, 0] > 0 else math.isinf(lo)
            out.append(OPEN if free else CLOSED)
    return tuple(out)


def panel_program(job_b, view: ZoneView, e, policy: PlannerPolicy = DEFAULT_POLICY):
    """(LineProgram, job, frame, offsets, horizontal, spacing, pass speed) of the panel job
    in a robot's base frame (``job_b``), its raster clipped to its zone (``view``);
    ``policy`` the planner's knobs."""
    view = _seam_run(view, policy)
    zone, runout, axis_b, offset = view.zone, view.runout, view.axis, view.offset
    strokes = cell_strokes(policy)
    horizontal = across(strokes, pass_direction(panel_frame(job_b), e))
    job_x = replace(job_b, direction="horizontal" if horizontal else "vertical")
    frame, offsets, half, v, _, spacing = panel_layout(job_x, policy)
    ep, es = (frame.u, frame.v) if horizontal else (frame.v, frame.u)
    offsets = step_order(offsets, es, e, strokes)
    if strokes.direction == "along":  # whole passes, the zone's by their level
        sign = _axis_sign(es, axis_b, "strokes' step", _ALONG_RULE)
        at = float(frame.c @ axis_b) + offset
        offsets = np.array([o for o in offsets if _in_zone(at + sign * o, zone)])
        if not len(offsets):
            raise PlanError(f"robot {zone.robot!r}: no pass of the panel lies in its zone")

        def build_whole(tau):
            seg = raster_segments(offsets, half, v, tau[1:-1], (tau[0], tau[-1]))
            return ZoneRelative(lambda t: raster_motion(frame, job_x.standoff, seg, t,
                                                        horizontal),
                                seg.start, seg.duration, seg.kind, program=seg,
                                windows=(OPEN,) * len(seg.kind))

        program = LineProgram(build_whole, np.full(len(offsets) + 1, policy.first_guess(v)),
                              policy.step(job_x.sigma, v),
                              track(frame.c + job_x.standoff * frame.n, e),
                              f"the passes ({v:.4g} m/s on the part)", job_x.source)
        return program, job_x, frame, offsets, horizontal, spacing, v
    sign = _axis_sign(ep, axis_b, "passes")
    on, (a, b) = _limits(zone, runout, offset + float(frame.c @ axis_b), sign)
    a, b = max(a, -half), min(b, half)
    if not a < b:
        raise PlanError(f"robot {zone.robot!r}: its zone misses the panel")
    m, h = 0.5 * (a + b), 0.5 * (b - a)
    shifted = replace(frame, c=frame.c + m * ep)

    def build(tau):
        seg = raster_segments(offsets, h, v, tau[1:-1], (tau[0], tau[-1]))
        return ZoneRelative(lambda t: raster_motion(shifted, job_x.standoff, seg, t,
                                                    horizontal),
                            seg.start, seg.duration, seg.kind, program=seg,
                            windows=_panel_windows(seg, on, m))

    guess = np.full(len(offsets) + 1, policy.first_guess(v))
    program = LineProgram(build, guess, policy.step(job_x.sigma, v),
                          track(frame.c + job_x.standoff * frame.n, e),
                          f"the passes ({v:.4g} m/s on the part)", job_x.source)
    return program, job_x, frame, offsets, horizontal, spacing, v


def _aim(layout, index: int, standoff: float, axis_b) -> np.ndarray:
    p = layout.passes[index]
    return (p.tip + standoff * p.axis) @ axis_b


def _arc_at(s, aim, x: float) -> float:
    """The arc at which the aim coordinate (monotone in s) reaches ``x``; ±inf for ±inf
    (the end it leads to)."""
    rising = aim[-1] > aim[0]
    if math.isinf(x):
        return math.copysign(math.inf, x if rising else -x)
    return float(np.interp(x, aim, s) if rising else np.interp(x, aim[::-1], s[::-1]))


def _arcs(s, aim, lo: float, hi: float) -> tuple:
    return tuple(sorted((_arc_at(s, aim, lo), _arc_at(s, aim, hi))))


def zone_pieces(layout, pieces, view: ZoneView, standoff: float):
    """The passes clipped to the zone (a pass whose trigger would never open dropped, the
    rest run in serpentine order) and each one's trigger window (local times)."""
    zone, runout, axis_b, offset = view.zone, view.runout, view.axis, view.offset
    kept, windows = [], []
    for p in pieces:
        lp = layout.passes[p.index]
        aim = _aim(layout, p.index, standoff, axis_b)
        on, stroke = _limits(zone, runout, offset, 1.0)
        s0, s1 = _arcs(lp.s, aim, *stroke)
        s0, s1 = max(s0, 0.0), min(s1, p.length)
        a, b = _arcs(lp.s, aim, *on)
        if not (s0 < s1 and a < min(b, s1) and max(a, s0) < b):
            continue
        kept.append((p, s0, s1, a, b))
    if not kept:
        raise PlanError(f"robot {zone.robot!r}: no pass of the part crosses its zone")
    out = []
    for i, (p, s0, s1, a, b) in enumerate(kept):
        forward = i % 2 == 0
        if p.forward != forward:  # a dropped pass: the serpentine runs on
            p = PassPiece(layout.passes[p.index].s, _poses(layout, p), p.v, forward, p.index)
        q = p if (s0 <= 0.0 and s1 >= p.length) else ClippedPass(p, s0, s1)
        start, rate = (s0, p.v) if forward else (s1, -p.v)
        windows.append(window(a, b, start, rate, q.duration))
        out.append(q)
    return out, windows


def whole_pieces(layout, pieces, view: ZoneView, standoff: float):
    """Strokes along the travel (docs/model.md §24.2, §26.3): the passes whose aim point's
    middle lies in the zone, whole, in serpentine order, each one's trigger open
    throughout (a seam lies between two passes, so no pass is shared)."""
    zone, offset = view.zone, view.offset
    kept = [p for p in pieces if _in_zone(float(np.median(_aim(
        layout, p.index, standoff, view.axis))) + offset, zone)]
    if not kept:
        raise PlanError(f"robot {zone.robot!r}: no pass of the part lies in its zone")
    out = []
    for i, p in enumerate(kept):
        forward = i % 2 == 0
        if p.forward != forward:  # a dropped pass: the serpentine runs on
            p = PassPiece(layout.passes[p.index].s, _poses(layout, p), p.v, forward, p.index)
        out.append(p)
    return out, [OPEN] * len(out)


def _poses(layout, piece):
    from ..passes.program import pass_poses

    return pass_poses(layout)[piece.index]


def part_program(job_b, part_b, view: ZoneView, e, policy: PlannerPolicy = DEFAULT_POLICY):
    """(LineProgram, job, layout, pass speed) of the part (``part_b``, base frame) for one
    robot, its passes clipped to its zone (``view``); ``policy`` the planner's knobs."""
    view = _seam_run(view, policy)
    strokes = cell_strokes(policy)
    horizontal = across(strokes, across_the_travel(part_b, e))
    job_x = replace(job_b, direction="horizontal" if horizontal else "vertical")
    layout = leading_first(surface_layout(part_b, job_x, min_smoothing=policy.smoothing,
                                          policy=policy), e, strokes.start)
    v = pass_speed(job_x, layout.spacing)
    full = pass_pieces(layout, v, 1)
    dt = time_step(job_x, full, v, policy)  # the whole part's: every robot samples alike
    pick = whole_pieces if strokes.direction == "along" else zone_pieces
    pieces, windows = pick(layout, full, view, job_x.standoff)

    def build(tau):
        prog = build_program(pieces, tau)
        w = [CLOSED] + [x for k, wk in enumerate(windows)
                        for x in ((wk,) if k + 1 == len(windows) else (wk, CLOSED))] + [CLOSED]
        return ZoneRelative(prog.evaluate, prog.start,
                            np.array([p.duration for p in prog.pieces]),
                            tuple(p.kind for p in prog.pieces), passes_only=True,
                            program=prog, windows=tuple(w))

    f = layout.frame
    program = LineProgram(build, np.full(len(pieces) + 1, policy.first_guess(v)), dt,
                          track(f.centre + job_x.standoff * f.n, e),
                          f"the passes ({v:.4g} m/s on the part's surface)", job_x.source)
    return program, job_x, layout, v


def seamed(world, speed: float, e, dt: float):
    """The world path with the seam instants among its samples and the trigger's fractions
    there (:func:`.zones.seam_fractions`): (trajectory, spray)."""
    rel, times = world.relative, world.times
    seams = times.delay + rel.seam_times()
    if not len(seams):
        return world.trajectory, world.spray
    tr = world.trajectory
    t = with_samples(tr.t, seams, 1e-6 * dt)
    poses, d, dd, spray = world_motion_reusing(rel, speed, e, times, t, (tr.t, (
        tr.poses, tr.d_poses, tr.dd_poses, world.spray)))
    traj = Trajectory(t, poses, d, dd, name="paint line", derivatives="analytic",
                      curve=lambda t_: world_motion(rel, speed, e, times, t_)[:3])
    return traj, seam_fractions(t, spray, seams, 1e-9 * max(1.0, float(t[-1])))


def plan_zone(robot, act, job_b, view: ZoneView, speed: float, part_b=None,
              policy: PlannerPolicy = DEFAULT_POLICY):
    """One robot's plan on the line at ``speed`` (a :class:`.line.panel.LinePlan` or
    :class:`.line.part.LinePartPlan`, in its base frame), clearance not checked; ``policy``
    the planner's knobs."""
    clock = time.perf_counter()
    e = np.asarray(job_b.line.direction, float)
    one_coat(job_b)
    if part_b is None:
        program, job_x, frame, offsets, horizontal, spacing, v = panel_program(job_b, view, e,
                                                                               policy)
    else:
        program, job_x, layout, v = part_program(job_b, part_b, view, e, policy)
    world = plan_dwelling(robot, act, program, speed, e, policy)
    traj, spray = seamed(world, speed, e, program.dt)
    common = {"trajectory": traj, "spray": spray, "ratios": world.ratios,
              "timings": {"plan": time.perf_counter() - clock}}
    strokes = replace(cell_strokes(policy), dwell=dwell_time(world.relative))
    if part_b is None:
        return LinePlan(job_x, frame, world.relative.program, horizontal, e, speed, world.times,
                        offsets, spacing, v, world.relative, strokes, **common)
    return LinePartPlan(job_x, part_b, layout, world.relative.program, world.relative, e,
                        speed, world.times, v, strokes, **common)


def cell_strokes(policy: PlannerPolicy = DEFAULT_POLICY) -> Strokes:
    """A cell's strokes (docs/model.md §24.2, §26.1): across the travel (its zones stacked
    along them, each stroke shared at a seam), from the policy's end; forced ``along`` the
    travel, whole passes, each zone holding those whose level lies in it. The same for every
    robot (a seam is invisible only between two halves of one raster), so ``auto`` keeps
    across."""
    if policy.strokes == "along":
        return Strokes("along", None, why="forced")
    return Strokes("across", policy.step_from, why="forced" if policy.strokes == "across"
                   else "auto: a cell's strokes run across the travel (along only when "
                        "forced)")


_ALONG_RULE = "with strokes along the travel the zones are stacked across the passes"


__all__ = ["ClippedPass", "ZoneView", "cell_strokes", "panel_program", "part_program",
           "plan_zone", "seamed", "whole_pieces", "zone_pieces"]
