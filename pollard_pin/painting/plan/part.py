"""Plan a paint job over a part's mesh (docs/model.md §23): the passes of
:mod:`.passes.surface` timed into one C² rest-to-rest program (:mod:`.passes.program`) the
robot and its motors can run; its film is :mod:`.film.part`'s. The turnarounds lie off the
part (the passes run EXTENSION σ past its edges) with the gun closed (``spray`` 0), the
passes open (1).

Each turnaround and ramp is the shortest whose motors stay within the policy's
``utilisation`` of peak torque and speed (:func:`.checks.motion.fastest`); then the whole
path is checked like ``run`` (reach, margins, joint limits) and against the motors' peak
torque, speed and continuous (RMS) rating at ``check_refine`` times its sampling (the knobs: the
planner's :class:`..policy.PlannerPolicy`, ``policy=``).
"""
from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...dynamics.averages import time_rms
from ...dynamics.motors import Actuators
from ...errors import say_less, without_asides
from ...paths.trajectory import Trajectory
from ..checks.clearance import job_clearance
from ..checks.motion import GUESS_HALVINGS, fastest, motion
from ..errors import BudgetError, PlanError, ReachError
from ..passes.program import Program, build_program, pass_pieces
from ..passes.surface import SMOOTHING, SurfaceLayout, pass_spacing, pass_speed, surface_layout
from ..policy import DEFAULT_POLICY, PlannerPolicy
from ..spray.occlusion import load_painted_part
from ..workpiece.mesh import Part
from .result import PlanResult


@dataclass(frozen=True)
class SurfacePlan(PlanResult):
    """A still part's program (``spray``: 1 on the passes, 0 on the turnarounds off it)."""

    job: object  # PartJob
    part: Part
    layout: SurfaceLayout
    program: Program
    speed: float  # surface speed of the spot on the passes [m/s]
    coats: int

    @property
    def cycle_time(self) -> float:
        return self.program.total

    @property
    def passes(self) -> int:
        return len(self.layout.passes) * self.coats

    @property
    def lower_bound(self) -> float:
        """Painting-only lower bound [s]: painted area × target / flow."""
        return self.part.painted_area * self.job.thickness / self.job.flow


def pass_samples(layout: SurfaceLayout, pieces) -> list:
    """Each pass piece's (poses, rates, accelerations) at its pass's surface samples: where
    the motors are judged on the passes alone (the still planner's and the line's)."""
    return [p.evaluate(np.linspace(0, p.duration, len(layout.passes[p.index].s)))
            for p in pieces]


def _pass_use(robot, act, layout: SurfaceLayout, pieces) -> float:
    """The motors' peak utilisation over one coat's passes (at their samples)."""
    ev = pass_samples(layout, pieces)
    poses, d, dd = (np.concatenate([e[i] for e in ev]) for i in range(3))
    try:
        m = motion(robot, act, poses, d, dd)
    except ReachError as exc:
        lengths = np.cumsum([len(layout.passes[p.index].s) for p in pieces])
        k = int(np.searchsorted(lengths, exc.sample, side="right"))
        p = layout.passes[pieces[k].index]
        tip = np.asarray(exc.pose[:3])
        j = int(np.argmin(np.linalg.norm(p.tip - tip, axis=1)))
        x = p.surface[j]
        raise ReachError(f"pass {pieces[k].index + 1} of {len(layout.passes)} leaves the "
                         f"reach at part point ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m "
                         f"({_cause(exc)})", exc.sample, exc.pose) from None
    return float(m.utilisation.max())


def _cause(exc: ReachError) -> str:
    """The kinematics' reason without its figures ('chain 0 cannot reach the wrist centre')."""
    return " ".join(re.split(r": | \[", str(exc))[0].split())  # (a joint's limits: its name)


def _refusal(robot, job, act, part: Part, exc: ReachError, hints: bool,
             policy: PlannerPolicy) -> ReachError:
    """The reach error of a still part, one line with what would paint it
    (:func:`.layout.place.reach_hint`: vertical passes, a move, or by how much it misses)."""
    from ..layout.place import reach_hint

    if not hints:
        return exc

    def paints(other) -> bool:
        try:
            plan_surface(robot, other, act, part, hints=False, policy=policy)
        except PlanError:
            return False
        return True

    name, hint = Path(part.source).name, reach_hint(robot, job, paints, policy)
    where = str(exc)
    # said with less: without the asides in words (the figures of a miss), then without the
    # part point, then without the kinematics' cause
    short = without_asides(hint)
    pointless = re.sub(r" at part point \([^()]*\) m", "", where)
    return ReachError(say_less(f"{name}: {where}; {hint}", f"{name}: {where}; {short}",
                               f"{name}: {pointless}; {short}", f"{pointless}; {short}",
                               f"{without_asides(where)}; {short}"),
                      exc.sample, exc.pose)


def time_step(job, pieces, v: float, policy: PlannerPolicy = DEFAULT_POLICY) -> float:
    """The path's time step [s]: ``policy.step_sigma`` σ of the tip's travel, the tip moving
    up to tip_rate × the spot's speed ``v`` (a convex part's stretch); the passes alone within
    the sample budget."""
    tip_rate = max(1.0, max(float(np.linalg.norm(p.d1(p.spline.t[5:-5])[:, :3], axis=1).max())
                            for p in pieces if p.kind == "pass"))
    dt = policy.step(job.sigma, v * tip_rate)
    swept = sum(p.duration for p in pieces)
    if swept / dt > policy.max_path_samples:
        raise BudgetError(f"{job.source}: the passes alone need {swept / dt:.3g} samples "
                          f"({swept:.4g} s at {v:.4g} m/s), budget {policy.max_path_samples:.3g}: "
                          f"{policy.coarser(dt, job.speed is not None)} or fewer coats, "
                          f"{policy.budget_fix}")
    return dt


def _where(program: Program, layout: SurfaceLayout, t: float, pose) -> str:
    piece = program.pieces[int(program.piece_at(np.array([t]))[0])]
    tip = np.asarray(pose[:3])
    where = f"tool tip ({tip[0]:.3f}, {tip[1]:.3f}, {tip[2]:.3f}) m"
    if piece.kind == "pass":
        p = layout.passes[piece.index]
        k = int(np.argmin(np.linalg.norm(p.tip - tip, axis=1)))
        x = p.surface[k]
        return (f"on pass {piece.index + 1} of {len(layout.passes)} (level "
                f"{p.level:.4g} m) over the part at ({x[0]:.3f}, {x[1]:.3f}, {x[2]:.3f}) m, "
                f"{where}")
    return f"in a {piece.kind}, {where}"


def _piece_name(program: Program, layout: SurfaceLayout, t: float) -> str:
    piece = program.pieces[int(program.piece_at(np.array([t]))[0])]
    if piece.kind == "pass":
        return f"on pass {piece.index + 1} of {len(layout.passes)}"
    return f"in a {piece.kind}"


def plan_surface(robot, job, act: Actuators, part: Part | None = None,
                 hints: bool = True, policy: PlannerPolicy = DEFAULT_POLICY) -> SurfacePlan:
    """The spray program over the job's part (read from ``job.mesh`` unless given): see the
    module notes; ``policy`` the planner's knobs. Raises :class:`PlanError` (or
    :class:`ReachError`) naming where it fails (out of reach, with ``hints``: what would paint
    it, :func:`.layout.place.reach_hint`)."""
    clock = [time.perf_counter()]
    part = load_painted_part(job) if part is None else part
    v = pass_speed(job, pass_spacing(job))
    coats = job.coats or 1
    smoothing = 0.0
    while True:  # the least smoothing whose passes the motors follow at speed v
        layout = surface_layout(part, job, min_smoothing=smoothing, policy=policy)
        pieces = pass_pieces(layout, v, coats)
        try:
            use = _pass_use(robot, act, layout, pieces[:len(layout.passes)])
        except ReachError as exc:
            raise _refusal(robot, job, act, part, exc, hints, policy) from None
        if use <= policy.utilisation:
            break
        wider = [w for w in SMOOTHING if w > layout.smoothing]
        if not wider:
            raise PlanError(f"{part.source}: the motors need {use:.3g}× their peak torque or "
                            f"speed on the passes at {v:.4g} m/s even with the gun's normal "
                            f"averaged over {layout.smoothing:g} m: a slower pass (fewer, "
                            "thicker coats or less gun flow), a smaller standoff or a "
                            "gentler part")
        smoothing = wider[0]
    dt = time_step(job, pieces, v, policy)
    ns = policy.turn_samples
    clock.append(time.perf_counter())

    def evaluate(taus):
        prog = build_program(pieces, taus)
        sel = [i for i, p in enumerate(prog.pieces) if p.kind != "pass"]
        start = prog.start
        x = np.linspace(0.0, 1.0 - 1e-12, ns)
        t = np.concatenate([start[i] + prog.pieces[i].duration * x for i in sel])
        try:
            m = motion(robot, act, *prog.evaluate(t))
        except ReachError as exc:
            k = exc.sample // ns
            raise ReachError(f"the path leaves the reach "
                             f"{_where(prog, layout, t[exc.sample], exc.pose)} ({taus[k]:.3g} "
                             f"s; {_cause(exc)})", exc.sample, exc.pose) from None
        return m.utilisation.reshape(len(sel), ns, -1).max(axis=(1, 2))

    try:
        taus = fastest(evaluate, np.full(len(pieces) + 1, policy.first_guess(v)),
                       policy.utilisation, halvings=GUESS_HALVINGS)
    except ReachError as exc:
        raise _refusal(robot, job, act, part, exc, hints, policy) from None
    program = build_program(pieces, taus)
    clock.append(time.perf_counter())
    n = math.ceil(program.total / dt) + 1
    if n > policy.max_path_samples:
        raise BudgetError(f"{job.source}: the path needs {n:.3g} samples ({program.total:.4g} "
                          f"s), budget {policy.max_path_samples:.3g}: "
                          f"{policy.coarser(dt, job.speed is not None)}, "
                          f"{policy.budget_fix}")
    t = np.linspace(0.0, program.total, n)
    traj = Trajectory(t, *program.evaluate(t), name="paint", derivatives="analytic",
                      curve=program.evaluate)
    tf = np.linspace(0.0, program.total, policy.check_refine * (n - 1) + 1)
    try:
        fine = motion(robot, act, *program.evaluate(tf))
    except ReachError as exc:
        raise _refusal(robot, job, act, part, ReachError(
            f"the path leaves the reach {_where(program, layout, tf[exc.sample], exc.pose)} "
            f"({_cause(exc)})", exc.sample, exc.pose), hints, policy) from None
    ratios = {"peak_torque": fine.torque_ratio.max(0),
              "rms_torque": time_rms(tf, fine.torque) / act.column("continuous_torque"),
              "speed": fine.speed_ratio.max(0)}
    for what, r in ratios.items():
        if r.max() > 1.0:
            k = int(np.argmax(r))
            raise PlanError(f"motor {act.names[k]} needs {r[k]:.3g}× its "
                            f"{what.replace('_', ' ')} rating on the passes at "
                            f"{v:.4g} m/s: a slower pass (fewer, thicker coats, less gun "
                            "flow or a wider spacing)")
    clear = job_clearance(robot, job, part.mesh, traj.poses, t,
                          lambda i: _piece_name(program, layout, t[i]), policy.clearance_stride)
    clock.append(time.perf_counter())
    return SurfacePlan(job, part, layout, program, v, coats, trajectory=traj,
                       spray=program.spray(t), ratios=ratios, clearance=clear,
                       timings={"layout": clock[1] - clock[0],
                                "turnarounds": clock[2] - clock[1],
                                "check": clock[3] - clock[2]})


__all__ = ["SurfacePlan", "pass_samples", "plan_surface", "time_step"]
