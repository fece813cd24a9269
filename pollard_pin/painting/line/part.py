"""Paint a part's mesh riding a conveyor (docs/model.md §24): the surface planner's passes
(§23) across the travel, leading end first, one coat, as the line's relative program; the
world path, its checks and the fastest speed are :mod:`.line.world`'s as for a panel.

The pass layout is the still part's (:func:`.passes.surface.surface_layout`), its normal's
averaging the least the motors follow on the passes alone, each moved along the line into the
robot's base plane, where the line's window lies (:func:`pass_use`): a part longer than the
reach is never all in reach at one pose, as the still planner's rule needs. A step the passes
cross (a handle proud of a drawer's front) then takes a wider averaging instead of a motor
over its rating at every line speed; the world path's checks still decide.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ...dynamics.motors import Actuators
from ...paths.trajectory import Trajectory
from ..checks.motion import motion
from ..errors import ReachError
from ..job import PartJob
from ..passes.program import Program, build_program, pass_pieces
from ..passes.surface import SMOOTHING, SurfaceLayout, pass_speed, surface_frame, surface_layout
from ..plan.part import SurfacePlan, pass_samples, time_step
from ..plan.result import PlanResult
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..spray.occlusion import load_painted_part
from ..workpiece.mesh import Part
from .dwell import dwell_time, plan_dwelling
from .phases import LineProgram, LineTimes, Relative, line_shift, one_coat, track
from .strokes import Strokes, across, shortest


@dataclass(frozen=True)
class LinePartPlan(PlanResult):
    """A part's program on the line: the ``layout`` (passes in painting order), the relative
    ``program`` (the part at its t = 0 pose) and its world ``trajectory`` at line ``speed``
    along ``direction``; ``pass_speed`` the spot's speed on the surface."""

    job: PartJob  # direction: the passes', across the travel
    part: Part
    layout: SurfaceLayout
    program: Program
    relative: Relative
    direction: np.ndarray  # (3,) unit
    speed: float  # line speed [m/s]
    times: LineTimes
    pass_speed: float
    strokes: Strokes = Strokes()  # across or along the travel, from which end (§24.2)

    @property
    def length(self) -> float:
        """The painted faces' extent along the line [m]."""
        p = self.part
        return float(np.ptp(p.vertices[p.faces[p.painted]].reshape(-1, 3) @ self.direction))

    @property
    def area(self) -> float:
        return self.part.painted_area

    def in_part_frame(self) -> SurfacePlan:
        """The plan seen from the part (at its t = 0 pose): the world path less the line's
        displacement speed·t·direction (and velocity), the still part's planner's type, so
        that its film (:func:`.film.part.surface_film`) and report are the still part's."""
        tr = self.trajectory
        p, d = line_shift(tr.poses, tr.d_poses, tr.t, -self.speed, self.direction)
        rel = Trajectory(tr.t, p, d, tr.dd_poses, name="paint line, the part's frame")
        return SurfacePlan(self.job, self.part, self.layout, self.program, self.pass_speed, 1,
                           trajectory=rel, spray=self.spray, ratios=self.ratios,
                           timings=self.timings, clearance=self.clearance)


def across_the_travel(part: Part, direction) -> bool:
    """True for horizontal passes (along the surface frame's u): across the travel."""
    f = surface_frame(part, "horizontal")
    e = np.asarray(direction, float)
    return abs(e @ f.across) > abs(e @ f.along)


def leading_first(layout: SurfaceLayout, direction, start: str | None = "leading"
                  ) -> SurfaceLayout:
    """The passes ordered from the end furthest along the line (the leading end), or from
    the other (``start`` "trailing")."""
    side = float(layout.frame.across @ np.asarray(direction, float))
    side = -side if start == "trailing" else side
    order = sorted(layout.passes, key=lambda p: -p.level * side)
    return replace(layout, passes=tuple(order))


def part_relative(program: Program) -> Relative:
    """The surface program as the line's relative program (the gun open on the passes)."""
    return Relative(program.evaluate, program.start,
                    np.array([p.duration for p in program.pieces]),
                    tuple(p.kind for p in program.pieces), passes_only=True, program=program)


def plan_line_part(robot, job: PartJob, act: Actuators, speed: float | None = None,
                   part: Part | None = None,
                   policy: PlannerPolicy = DEFAULT_POLICY, check=None,
                   always: bool = False) -> LinePartPlan:
    """The surface program for a part on the line at ``speed`` (default the job's);
    ``policy`` the planner's knobs; ``check`` (plan ↦ plan, its clearance checked: given by
    :func:`.line.panel.plan_line`) run on the plan kept when ``always``, and to choose where
    two stroke strategies plan (:func:`.line.strokes.shortest`)."""
    clock = time.perf_counter()
    speed = job.line.speed if speed is None else float(speed)
    one_coat(job)
    part = load_painted_part(job) if part is None else part
    return shortest(lambda s: _plan_part(robot, job, act, speed, part, policy, s, clock),
                    policy, check, always, job.source)


def pass_use(robot, act: Actuators, layout: SurfaceLayout, pieces, speed: float, e
             ) -> float | None:
    """The motors' peak utilisation on the passes alone (``pieces``' first len(passes), at
    their samples), each pass moved along the line ``e`` to have its middle in the robot's base
    plane (e·x = 0, where the line's window lies) and the line's ``speed`` added to its rate
    (docs/model.md §24); None where a pass is out of reach there (the world path says it)."""
    e = np.asarray(e, dtype=float)
    ev = []
    for q, d, a in pass_samples(layout, pieces[:len(layout.passes)]):
        q, d = np.array(q, dtype=float), np.array(d, dtype=float)
        q[:, :3] -= float(q[:, :3].mean(axis=0) @ e) * e
        d[:, :3] += speed * e
        ev.append((q, d, a))
    try:
        m = motion(robot, act, *(np.concatenate([x[i] for x in ev]) for i in range(3)))
    except ReachError:
        return None
    return float(m.utilisation.max())


def _plan_part(robot, job, act, speed, part, policy, strokes: Strokes, clock) -> LinePartPlan:
    """The part's plan with ``strokes`` (:func:`plan_line_part`)."""
    e = np.asarray(job.line.direction, float)
    horizontal = across(strokes, across_the_travel(part, e))
    job_x = replace(job, direction="horizontal" if horizontal else "vertical")
    smoothing = 0.0
    while True:  # the least averaging whose passes the motors follow (pass_use)
        layout = leading_first(surface_layout(part, job_x, min_smoothing=smoothing,
                                              policy=policy), e, strokes.start)
        v = pass_speed(job_x, layout.spacing)
        pieces = pass_pieces(layout, v, 1)
        use = pass_use(robot, act, layout, pieces, speed, e)
        wider = [w for w in SMOOTHING if w > layout.smoothing]
        if use is None or use <= policy.utilisation or not wider:
            break
        smoothing = wider[0]
    dt = time_step(job_x, pieces, v, policy)

    def build(tau):
        return part_relative(build_program(pieces, tau))

    f = layout.frame
    program = LineProgram(build, np.full(len(pieces) + 1, policy.first_guess(v)), dt,
                          track(f.centre + job.standoff * f.n, e),
                          f"the passes ({v:.4g} m/s on the part's surface)", job.source)
    world = plan_dwelling(robot, act, program, speed, e, policy)
    return LinePartPlan(job_x, part, layout, world.relative.program, world.relative, e, speed,
                        world.times, v, replace(strokes, dwell=dwell_time(world.relative)),
                        trajectory=world.trajectory, spray=world.spray,
                        ratios=world.ratios, timings={"plan": time.perf_counter() - clock})


__all__ = ["LinePartPlan", "across_the_travel", "leading_first", "part_relative", "pass_use",
           "plan_line_part"]
