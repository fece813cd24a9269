"""A relative program planned on the moving line (docs/model.md §24): the searches of
``search.py`` (noted, ``notes.py``), then the world path sampled on its grid and checked for the
motors (``motors.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...dynamics.averages import time_rms
from ...dynamics.motors import Actuators
from ...errors import say_less
from ...paths.trajectory import Trajectory
from ..errors import LineSpeedError, ReachError
from ..policy import DEFAULT_POLICY, PlannerPolicy
from .motors import first_kept, motors_within, screen_motors, wait_motion
from .notes import noted
from .phases import (
    LineProgram,
    LineTimes,
    Relative,
    drift_along,
    path_times,
    samples_budget,
    slow_budget,
    world_motion,
    world_motion_reusing,
)
from .search import searched

#: A note's mark (notes.py): the path's motors were within their ratings at its own samples.
SAMPLES_OK = "motors_at_samples"


@dataclass(frozen=True)
class World:
    """A relative program run on the line: its ``relative`` program, phases ``times``, the
    world ``trajectory`` with its ``spray`` column and the motors' ``ratios``."""

    relative: Relative
    times: LineTimes
    trajectory: Trajectory
    spray: np.ndarray
    ratios: dict


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
    built: dict = {}  # the program at the τ found, when searched here (not from a note)
    made = noted(lambda: searched(robot, act, program, rel, speed, e, policy, built), robot,
                 act, program, rel, speed, e, policy, screen)
    tau = np.asarray(made["tau"], dtype=float)
    rel = built.get(tau.tobytes()) or build(tau)
    delay, back = made["delay"], made["back"]
    times = LineTimes(delay, delay + rel.total, back)
    samples_budget(times.total, dt, source, policy)
    steps = math.ceil((times.total - times.delay) / dt - 1e-9)  # the program's, on
    t = path_times(times, steps)
    tf = path_times(times, policy.check_refine * steps)
    drift = drift_along(rel, speed, e)
    r = policy.check_refine  # a power of two: the check's times hold the path's, bit for bit
    # the screen is the check at the path's own samples: noted as passed there (a search's
    # check, check_refine 1, of this same path), it would pass again
    screened = screen and drift <= 0 and r > 1 and r & (r - 1) == 0 and not made.get(SAMPLES_OK)
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
    if r == 1:  # within plan_notes: the note says so to a plan of this path at a finer check
        made[SAMPLES_OK] = True
    return World(rel, times, traj, spray, ratios)


__all__ = ["SAMPLES_OK", "World", "plan_world"]
