"""Paint a panel (or, through :mod:`.line.part`, a part's mesh) riding a conveyor
(docs/model.md §24).

The part is at ``center + speed·t·direction`` at time t of the path. The passes run across
the travel, leading end first, and are planned relative to the part (the raster of plan.py);
the robot runs the world path, relative + the line's displacement (:mod:`.line.phases`: the
wait, catch-up, program, slow-down and return, the shift that keeps it in reach, every check
on the world path, the fastest speed).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ...dynamics.motors import Actuators
from ..checks.clearance import job_clearance, panel_mesh
from ..errors import LineSpeedError
from ..job import PaintJob, PartJob
from ..passes.raster import Segments, raster_motion, raster_segments
from ..plan.layout import panel_layout
from ..plan.result import PlanResult
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..workpiece.mesh import Part
from ..workpiece.panel import PanelFrame
from .dwell import dwell_time, plan_dwelling, waiting_floor
from .phases import (
    CATCH,
    LineProgram,
    LineTimes,
    Relative,
    line_shift,
    one_coat,
    track,
    world_motion,
)
from .speeds import (
    INTERVAL_RESOLUTION,
    SPEED_RESOLUTION,
    SpeedInterval,
    fastest_line_speed,
    line_speed_interval,
    plan_or_name_fastest,
    remembering,
)
from .strokes import Strokes, across, shortest


@dataclass(frozen=True)
class LinePlan(PlanResult):
    """A panel's raster on the line: ``trajectory`` the world path, ``spray`` 1 during the
    program, 0 while waiting and returning."""

    job: PaintJob
    frame: PanelFrame
    segments: Segments  # the relative program (panel coordinates, its own time from 0)
    horizontal: bool
    direction: np.ndarray  # (3,) unit
    speed: float  # line speed [m/s]
    times: LineTimes
    offsets: np.ndarray
    spacing: float
    pass_speed: float
    relative: Relative  # the program relative to the part (line/phases.py)
    strokes: Strokes = Strokes()  # across or along the travel, from which end (§24.2)

    @property
    def length(self) -> float:
        """The panel's extent along the line [m]."""
        return part_length(self.job, self.frame, self.direction)

    @property
    def area(self) -> float:
        return self.job.width * self.job.height


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


def panel_relative(frame, job, seg: Segments, horizontal: bool) -> Relative:
    """The raster as the line's relative program (the gun open throughout, §21)."""
    return Relative(lambda t: relative_motion(frame, job, seg, horizontal, t), seg.start,
                    seg.duration, seg.kind, program=seg)


def plan_line(robot, job, act: Actuators, speed: float | None = None, part: Part | None = None,
              clearance: bool = True, policy: PlannerPolicy = DEFAULT_POLICY):
    """The raster program for a panel on the line at ``speed`` (default the job's); a
    [part] job goes to :func:`.line.part.plan_line_part` (``part``: its mesh, read once).
    ``clearance``: check the gun body's clearance (:func:`line_clearance`); the speed
    searches leave it to the plan they return, but where two stroke strategies plan,
    ``auto`` checks it to choose (docs/model.md §24.2). ``policy``: the planner's knobs."""
    def check(plan):
        return cleared(robot, plan, policy)

    if isinstance(job, PartJob):
        from .part import plan_line_part

        return plan_line_part(robot, job, act, speed, part, policy, check, clearance)
    clock = time.perf_counter()
    speed = job.line.speed if speed is None else float(speed)
    one_coat(job)
    return shortest(lambda s: _plan_panel(robot, job, act, speed, policy, s, clock), policy,
                    check, clearance, job.source)


def cleared(robot, plan, policy: PlannerPolicy = DEFAULT_POLICY):
    """``plan`` with its gun body's clearance checked (:func:`line_clearance`, every
    ``policy.clearance_stride``-th sample), unless it already is (auto's choice checks it
    where two strategies plan, docs/model.md §24.2)."""
    if plan.clearance is not None:
        return plan
    return replace(plan, clearance=line_clearance(robot, plan, policy.clearance_stride))


def step_order(offsets, es, e, strokes: Strokes) -> np.ndarray:
    """The passes' offsets along ``es`` in painting order: from the part's leading end (the
    furthest along the line ``e``) or its trailing end."""
    side = -1.0 if strokes.start == "trailing" else 1.0
    return np.array(sorted(offsets, key=lambda o: -side * o * float(es @ e)))


def _plan_panel(robot, job, act, speed, policy, strokes: Strokes, clock) -> LinePlan:
    """The panel's plan with ``strokes`` (:func:`plan_line`), clearance not checked."""
    from ..workpiece.panel import panel_frame

    e = np.asarray(job.line.direction, float)
    horizontal = across(strokes, pass_direction(panel_frame(job), e))
    job_x = replace(job, direction="horizontal" if horizontal else "vertical")
    frame, offsets, half_length, pass_speed, _, spacing = panel_layout(job_x, policy)
    es = frame.v if horizontal else frame.u
    offsets = step_order(offsets, es, e, strokes)

    def build(tau):
        seg = raster_segments(offsets, half_length, pass_speed, tau[1:-1], (tau[0], tau[-1]))
        return panel_relative(frame, job_x, seg, horizontal)

    guess = np.full(len(offsets) + 1, policy.first_guess(pass_speed))  # ramps and turns
    program = LineProgram(build, guess, policy.step(job.sigma, pass_speed),
                          track(frame.c + job.standoff * frame.n, e),
                          f"the passes ({pass_speed:.4g} m/s on the part)", job.source)
    world = plan_dwelling(robot, act, program, speed, e, policy)
    return LinePlan(job_x, frame, world.relative.program, horizontal, e, speed, world.times,
                    offsets, spacing, pass_speed, world.relative,
                    replace(strokes, dwell=dwell_time(world.relative)),
                    trajectory=world.trajectory, spray=world.spray, ratios=world.ratios,
                    timings={"plan": time.perf_counter() - clock})


def line_clearance(robot, plan, stride: int = 1):
    """The gun body's :class:`.checks.clearance.Clearance` from the panel or part of a plan on
    the line, seen from the part at rest (the world path less the line's displacement),
    refused as a :class:`.checks.clearance.ClearanceError` (docs/model.md §25); every
    ``stride``-th sample (:attr:`.policy.PlannerPolicy.clearance_stride`)."""
    tr = plan.trajectory
    rel, _ = line_shift(tr.poses, tr.d_poses, tr.t, -plan.speed, plan.direction)
    mesh = plan.part.mesh if isinstance(plan.job, PartJob) else panel_mesh(plan.frame)
    return job_clearance(robot, plan.job, mesh, rel, tr.t, lambda i: (
        "while spraying" if plan.spray[i] > 0 else "with the gun closed"), stride)


def line_planner(robot, job, act: Actuators, part: Part | None = None,
                 policy: PlannerPolicy = DEFAULT_POLICY):
    """speed ↦ the job's plan on the line at that speed (a part's mesh, ``part`` if given,
    read once; ``policy`` the planner's knobs)."""
    if part is None and isinstance(job, PartJob):
        from ..spray.occlusion import load_painted_part

        part = load_painted_part(job)
    # a refusal's search starts at the refused speed: refused again without planning
    memo = remembering(lambda speed: plan_line(robot, job, act, speed, part, clearance=False,
                                               policy=policy))
    return lambda speed=None: memo(job.line.speed if speed is None else float(speed))


def max_line_speed(robot, job, act: Actuators, resolution: float = SPEED_RESOLUTION,
                   part: Part | None = None, policy: PlannerPolicy = DEFAULT_POLICY,
                   plan=None):
    """The fastest line speed [m/s] (within ``resolution``, relative) at which the panel or
    part is painted under the same checks (``policy``'s), and its plan (docs/model.md §24,
    :func:`.line.speeds.fastest_line_speed`); ``plan``: the job's plan at a speed already
    made (as :func:`line_speeds` takes it), not made again."""
    plan_at = line_planner(robot, job, act, part, policy)
    speed, found = fastest_line_speed(lambda s: plan if plan is not None and s == plan.speed
                                      else plan_at(s), job.line.speed, job.source, resolution)
    return speed, cleared(robot, found, policy)


def line_speeds(robot, job, act: Actuators, plan=None, part: Part | None = None,
                policy: PlannerPolicy = DEFAULT_POLICY,
                resolution: float = INTERVAL_RESOLUTION) -> SpeedInterval:
    """The line speeds that paint the panel or part (:func:`.line.speeds.line_speed_interval`
    from the job's speed, each end to ``resolution`` and its clearance checked, as
    :func:`max_line_speed` checks its answer); ``plan``: the job's plan at a speed already
    made, not made again."""
    plan_at = line_planner(robot, job, act, part, policy)
    return line_speed_interval(lambda s: plan if plan is not None and s == plan.speed
                               else plan_at(s), job.line.speed, job.source, resolution,
                               check=lambda p: cleared(robot, p, policy),
                               floor=lambda p: waiting_floor(p, policy),
                               budget=lambda p: path_samples(p, policy))


def path_samples(plan, policy: PlannerPolicy = DEFAULT_POLICY) -> tuple[int, int]:
    """(the plan's path samples, the budget): guides the slow speed search to the budget's
    floor (:func:`.line.speeds.budget_floor`)."""
    return len(plan.trajectory.t), policy.max_path_samples


def plan_line_job(robot, job, act: Actuators, part: Part | None = None,
                  policy: PlannerPolicy = DEFAULT_POLICY):
    """The job's line speed planned (``policy``: the planner's knobs); a speed that cannot be
    painted is refused naming the interval that does (:func:`.line.speeds.plan_or_name_fastest`;
    not searched where ``policy.name_speeds`` is False)."""
    plan = plan_or_name_fastest(line_planner(robot, job, act, part, policy), job.line.speed,
                                job.source, floor=lambda p: waiting_floor(p, policy),
                                name=policy.name_speeds, budget=lambda p: path_samples(p, policy))
    return cleared(robot, plan, policy)


__all__ = ["CATCH", "LinePlan", "LineSpeedError", "LineTimes", "SPEED_RESOLUTION",
           "cleared", "line_clearance", "line_planner", "line_shift", "line_speeds",
           "max_line_speed", "panel_relative",
           "part_length", "pass_direction", "plan_line", "plan_line_job", "relative_motion",
           "step_order", "world_motion"]
