"""Plan a paint cell (docs/model.md §26): every robot's program in its own base frame on the
common clock (t = 0: the part at its ``position``), each painting its zone of the shared
strokes (:mod:`.cell.program`), checked as a single robot's is today (reach, limits,
margins, motors with gravity in its base frame, the gun body's clearance from the part).
The slowest robot sets the cell's line speed.
"""
from __future__ import annotations

import contextlib
import hashlib
import math
import time
from collections import OrderedDict
from contextvars import ContextVar
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ...dynamics.motors import Actuators
from ...errors import say_less, without_asides
from ..errors import BudgetError, LineSpeedError, PlanError, kept, made_again
from ..job import PartJob
from ..line.dwell import waiting_floor
from ..line.panel import line_clearance
from ..line.speeds import (
    INTERVAL_RESOLUTION,
    SPEED_RESOLUTION,
    SpeedInterval,
    fastest_line_speed,
    line_speed_interval,
    remembering,
)
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..workpiece.mesh import Part
from .frames import check_panel_turn, panel_in_base, part_in_base, robot_model_in_base
from .program import ZoneView, plan_zone
from .robots import CellRobot, base_footprint, check_spacing
from .split import split_cell
from .zones import Split, Zone


@dataclass(frozen=True)
class RobotPlan:
    """One robot of the cell: its ``robot`` (base pose), ``zone``, and ``plan`` (a
    :class:`.line.panel.LinePlan` or :class:`.line.part.LinePartPlan`) in its base frame."""

    robot: CellRobot
    zone: Zone
    plan: object


@dataclass(frozen=True, eq=False)
class CellPlan:
    """A cell's plan at one line speed, from :func:`plan_cell` (docs/model.md §26).

    Attributes
    ----------
    job : PaintJob or pollard_pin.painting.job.PartJob
        The job, world coordinates.
    split : Split
        Which robot paints which zone.
    robots : tuple of RobotPlan
        Per robot its ``robot`` (a :class:`~pollard_pin.painting.cell.robots.CellRobot`), its
        ``zone`` and its ``plan`` (the program in its base frame, on the cell's clock).
    speed : float
        The line speed [m/s].
    part : object or None
        For a part, the world part at t = 0 painting every zone's faces (None for a panel).
    timings : dict or None
        Seconds spent per stage.
    clearance : CellClearance or None
        The cell's least distances, once checked.
    """

    job: object
    split: Split
    robots: tuple[RobotPlan, ...]
    speed: float
    part: Part | None = None
    timings: dict | None = None
    clearance: object = None  # .checks.cell_clearance.CellClearance, once checked

    @property
    def cycle(self) -> float:
        """The cell's cycle [s]: its slowest robot's."""
        return max(r.plan.times.cycle for r in self.robots)


def cell_part(job: PartJob, part: Part, split: Split) -> Part:
    """The world part painting every zone's faces (within max_angle of each zone's facing,
    seen from the standoff)."""
    from ..spray.occlusion import painted_part

    masks = [part.painted]
    for f in {z.facing for z in split.zones if z.facing is not None}:
        other = painted_part(replace(part, painted=part.normals @ np.asarray(f) >= math.cos(
            math.radians(part.max_angle)) - 1e-12, facing=f), job.standoff)
        masks.append(other.painted)
    painted = np.logical_or.reduce(masks)
    painted.flags.writeable = False
    return replace(part, painted=painted)


@lru_cache(maxsize=32)  # a speed search plans the cell ~10 times: the ray tests once
def robot_part(standoff: float, part: Part, cr: CellRobot, facing) -> Part:
    """The world part in the robot's base frame painting the faces of ``facing`` that a gun
    at ``standoff`` sees."""
    from ..spray.occlusion import painted_part

    return painted_part(part_in_base(part, cr, facing), standoff)


def plan_cell(robot, job, act: Actuators, speed: float | None = None,
              part: Part | None = None, split: Split | None = None,
              clearance: bool = True, policy: PlannerPolicy = DEFAULT_POLICY) -> CellPlan:
    """Every robot's program of a cell at one line speed (docs/model.md §26).

    Parameters
    ----------
    robot : Robot
        The model every robot shares (:func:`pollard_pin.load`).
    job : PaintJob or pollard_pin.painting.job.PartJob
        A job with ``[line]`` and its ``robots`` (``[[robot]]`` tables).
    act : Actuators
        The motor ratings every program must keep.
    speed : float or None, optional
        The line speed [m/s] (default the job's).
    part : object or None, optional
        The job's painted part if already read (default None: read here; a panel has none).
    split : Split or None, optional
        The zones (default :func:`split_cell`'s).
    clearance : bool, optional
        Check the gun bodies' clearance from the part (default True).
    policy : pollard_pin.painting.policy.PlannerPolicy, optional
        The planner's reserve, sampling and budgets (default the planners' own).

    Returns
    -------
    CellPlan
        The split and each robot's program.

    Raises
    ------
    pollard_pin.painting.errors.LineSpeedError
        A robot cannot paint its zone at this speed (named), so the fastest speed is
        searched as for one robot.
    PlanError
        A robot's program breaks a check (reach, limits, margins, motors).
    """
    clock = time.perf_counter()
    speed = job.line.speed if speed is None else float(speed)
    robots = job.robots or (CellRobot("robot"),)
    if split is None:
        split = split_cell(robot, job, robots, part, policy.seams, policy)
    axis = np.asarray(split.axis, float)
    out = []
    for cr in robots:
        if not isinstance(job, PartJob):
            check_panel_turn(job, cr)
        zone = split.zone_of(cr.name)
        model = robot_model_in_base(robot, cr)
        is_part = isinstance(job, PartJob)
        job_b = replace(job, line=_line_b(job, cr), robots=()) if is_part else \
            panel_in_base(job, cr)
        part_b = robot_part(job.standoff, part, cr, zone.facing) if is_part else None
        try:
            view = ZoneView(zone, split.runout, cr.direction_to_base(axis),
                            float(cr.origin @ axis))
            key = (cr, zone, split.runout, split.axis, act, replace(job, robots=()), speed,
                   _part_key(part), replace(policy, seams=None))  # seams: in the zone
            plan = _planned(robot, key, plan_zone, model, act, job_b, view, speed, part_b,
                            policy)
        except LineSpeedError as exc:
            raise LineSpeedError(_robot_said(cr, exc), exc.too_fast, exc.why,
                                 exc.hint) from None
        except BudgetError as exc:  # a speed search's slow floor: kept apart (line.speeds)
            raise BudgetError(_robot_said(cr, exc)) from None
        except PlanError as exc:
            raise PlanError(_robot_said(cr, exc)) from None
        if clearance:
            plan = replace(plan, clearance=line_clearance(model, plan,
                                                          policy.clearance_stride))
        out.append(RobotPlan(cr, zone, plan))
    world_part = cell_part(job, part, split) if isinstance(job, PartJob) else None
    return CellPlan(job, split, tuple(out), speed, world_part,
                    {"plan": time.perf_counter() - clock})


ZONE_PLANS = 16  # zone plans a memo holds at most (a seat search's plans, §26.5)
_memo: ContextVar[OrderedDict | None] = ContextVar("zone_plans", default=None)


@contextlib.contextmanager
def zone_plans_remembered():
    """Within it, :func:`plan_cell` remembers each robot's zone plan (its refusal too) by
    everything the plan depends on, the last :data:`ZONE_PLANS`: a layout's search plans each
    robot alone, then the cell with the same robots (docs/model.md §26.5); the same inputs,
    the same plan, made once. Outside it nothing is remembered (no state between calls)."""
    token = _memo.set(OrderedDict())
    try:
        yield
    finally:
        _memo.reset(token)


def _part_key(part: Part | None):
    """The part by its contents (a part read again is the same part), None for a panel."""
    if part is None:
        return None
    digest = hashlib.sha1()
    for a in (part.vertices, part.faces, part.painted):
        digest.update(np.ascontiguousarray(a).tobytes())
    return digest.hexdigest(), part.facing, part.max_angle


def _planned(robot, key, plan, *args):
    """``plan(*args)``, remembered by ``key`` within :func:`zone_plans_remembered` (the shared
    model compared by identity); a budget spent is not the inputs' answer: not remembered."""
    memo = _memo.get()
    if memo is None:
        return plan(*args)
    key = (id(robot), key)
    hit = memo.get(key)
    if hit is None or hit[0] is not robot:
        try:
            hit = (robot, plan(*args), None)
        except BudgetError:
            raise
        except PlanError as exc:
            hit = (robot, None, kept(exc))  # its words: no frames held
        memo[key] = hit
        while len(memo) > ZONE_PLANS:
            memo.popitem(last=False)
    else:
        memo.move_to_end(key)
    if hit[2] is not None:
        raise made_again(hit[2])
    return hit[1]


def _line_b(job, cr: CellRobot):
    from .frames import line_in_base

    return line_in_base(job.line, cr)


def cell_planner(robot, job, act: Actuators, part: Part | None = None,
                 split: Split | None = None, policy: PlannerPolicy = DEFAULT_POLICY):
    """speed ↦ the cell's plan at that speed (clearance left to the plan returned), the
    split made once, the bases first checked to stand apart (two base footprints);
    ``policy`` the planner's knobs. A speed refused once is refused again without planning
    (the plan is the same every time)."""
    check_spacing(job.robots, 2 * base_footprint(robot.model), job.source)
    if split is None:
        split = split_cell(robot, job, job.robots or (CellRobot("robot"),), part,
                           policy.seams, policy)
    # a refusal's search starts at the refused speed: refused again without planning
    memo = remembering(lambda speed: plan_cell(robot, job, act, speed, part, split,
                                               clearance=False, policy=policy))
    return lambda speed=None: memo(job.line.speed if speed is None else float(speed))


def max_cell_speed(robot, job, act: Actuators, resolution: float = SPEED_RESOLUTION,
                   part: Part | None = None, split: Split | None = None,
                   policy: PlannerPolicy = DEFAULT_POLICY):
    """The fastest line speed [m/s] (within ``resolution``, relative) at which every robot
    paints its zone, and that plan (the slowest robot sets it: docs/model.md §26.1);
    ``policy`` the planner's knobs."""
    speed, plan = fastest_line_speed(cell_planner(robot, job, act, part, split, policy),
                                     job.line.speed, job.source, resolution)
    return speed, _with_clearance(robot, plan, policy)


def cell_waiting_floor(plan: CellPlan, policy: PlannerPolicy = DEFAULT_POLICY):
    """Where every robot's program waits at its turnarounds, the line speed [m/s] down to
    which the cell paints (the highest of the robots' budget floors,
    :func:`.line.dwell.waiting_floor`); else None."""
    floors = [waiting_floor(r.plan, policy) for r in plan.robots]
    return None if any(f is None for f in floors) else max(floors)


def cell_speeds(robot, job, act: Actuators, plan: CellPlan | None = None,
                part: Part | None = None, split: Split | None = None,
                policy: PlannerPolicy = DEFAULT_POLICY,
                resolution: float = INTERVAL_RESOLUTION) -> SpeedInterval:
    """The line speeds at which every robot paints its zone
    (:func:`.line.speeds.line_speed_interval` from the job's speed, each end to
    ``resolution`` and its clearances checked, as :func:`max_cell_speed` checks its answer);
    ``plan``: the cell's plan at a speed already made (its split kept), not made again."""
    split = plan.split if plan is not None and split is None else split
    plan_at = cell_planner(robot, job, act, part, split, policy)
    return line_speed_interval(lambda s: plan if plan is not None and s == plan.speed
                               else plan_at(s), job.line.speed, job.source, resolution,
                               check=lambda p: _with_clearance(robot, p, policy),
                               floor=lambda p: cell_waiting_floor(p, policy))


def plan_cell_job(robot, job, act: Actuators, part: Part | None = None,
                  split: Split | None = None,
                  policy: PlannerPolicy = DEFAULT_POLICY) -> CellPlan:
    """The job's line speed planned (``policy``: the planner's knobs); a speed no robot
    ordering can paint is refused naming the interval that does
    (:func:`.line.speeds.plan_or_name_fastest`; not searched where ``policy.name_speeds`` is
    False)."""
    from ..line.speeds import plan_or_name_fastest

    plan = plan_or_name_fastest(cell_planner(robot, job, act, part, split, policy),
                                job.line.speed, job.source,
                                floor=lambda p: cell_waiting_floor(p, policy),
                                name=policy.name_speeds)
    return _with_clearance(robot, plan, policy)


def _with_clearance(robot, plan: CellPlan, policy: PlannerPolicy = DEFAULT_POLICY) -> CellPlan:
    """Each robot's gun body from the part (today's check), then every pair of robots and
    every robot's links against the moving part along the clock (docs/model.md §26.4); every
    ``policy.clearance_stride``-th sample of each program."""
    stride = policy.clearance_stride
    robots = tuple(replace(r, plan=replace(r.plan, clearance=line_clearance(
        robot_model_in_base(robot, r.robot), r.plan, stride))) for r in plan.robots)
    return replace(plan, robots=robots, clearance=cell_clearance_of(robot, plan, stride))


def cell_clearance_of(robot, plan: CellPlan, stride: int = 1):
    """:func:`.checks.cell_clearance.cell_clearance` of the plan: the robots' programs on the clock
    (every ``stride``-th sample of each, :func:`.checks.clearance.strided`), the part's (or
    panel's) mesh at t = 0 riding the line, the job's gun clearance."""
    from ..checks.cell_clearance import MovingPart, cell_clearance
    from ..checks.clearance import CLEARANCE, panel_mesh, strided
    from ..workpiece.panel import panel_frame

    job = plan.job
    mesh = panel_mesh(panel_frame(job)) if plan.part is None else plan.part.mesh
    v = plan.speed * np.asarray(job.line.direction, float)
    members = []
    for r in plan.robots:
        tr = r.plan.trajectory
        k = strided(len(tr.t), stride)
        members.append((r.robot, tr.t[k], tr.poses[k]))
    required = CLEARANCE if job.clearance is None else job.clearance
    return cell_clearance(robot, members, MovingPart(mesh, tuple(float(c) for c in v)),
                          required)


def _robot_said(cr, exc: Exception) -> str:
    """A robot's refusal named, within the line's room (say_less)."""
    return say_less(f"robot {cr.name!r}: {exc}", f"robot {cr.name!r}: {without_asides(str(exc))}")


__all__ = ["ZONE_PLANS", "CellPlan", "RobotPlan", "cell_part", "cell_planner", "cell_speeds",
           "cell_waiting_floor", "max_cell_speed", "plan_cell", "plan_cell_job", "robot_part",
           "zone_plans_remembered"]
