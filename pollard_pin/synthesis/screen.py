"""The cheap screen of a design (docs/model.md §31.3): what rejects it before any plan.

* **reach**: the robot's band along the cell's axis over the job's strokes, on a coarse grid
  (:data:`SCREEN_STEP`; the paint planner's own band rule,
  :func:`pollard_pin.painting.cell.bands.robot_band`, with the workspace map's per-pose checks:
  the closed-form IK, the joint limits and the singularity margins), against what the
  design's number of robots needs (:func:`pollard_pin.painting.layout.cell.zone_needs`), the
  run-on of a panel's turnarounds and ramps past its passes' ends included
  (:func:`turn_runon`: the planner's own raster geometry at its first duration);
* **reach** of a still panel (no line): the share of its gun poses, over the panel and its
  run-on on the same grid, that the workspace map's checks refuse;
* **motors**: the torques that hold the robot still (the weight alone) at the band's ends and
  middle on the middle stroke, over the chosen motors' ratings through their gears: above the
  peak torque anywhere, or above the continuous torque on average, no program can keep them.

Each constraint is a number, ≤ 0 when it holds and > 0 by how far it is off.
"""
from __future__ import annotations

import math

import numpy as np

from ..painting.cell.bands import Strokes, base_poses, robot_band
from ..painting.cell.robots import CellRobot
from ..painting.job import PartJob
from ..painting.layout.cell import fewest_for, zone_needs
from ..painting.line.reach import ball_shift_range, reach_ball
from ..painting.passes.raster import raster_segments
from ..painting.plan.layout import panel_layout
from ..painting.policy import DEFAULT_POLICY, PlannerPolicy
from ..workspace.reach import evaluate, holding_torques, kinematic_matrices

SCREEN_STEP = 0.02  # m between the band's grid points (the planner's: 0.005)
SCREEN_SHIFT = 0.05  # m between the part's shifts along the line (the planner's: 0.01)
SCREEN_STROKES = 1  # distinct stroke shapes checked (the planner's reference band: 5)
TURN_SAMPLES = 400  # samples of the turnaround and ramps whose furthest reach is taken


def turn_runon(job, policy: PlannerPolicy = DEFAULT_POLICY) -> float:
    """How far [m] a panel's gun runs past its passes' ends at a turnaround or a ramp: the
    planner's raster (:func:`pollard_pin.painting.passes.raster.raster_segments`, its pass
    speed and spacing) with every turnaround and ramp at the duration search's first guess
    (:meth:`~pollard_pin.painting.policy.PlannerPolicy.first_guess`), the longest the search
    keeps when the motors allow it (docs/model.md §31.3); a part's program: 0 (not screened)."""
    if isinstance(job, PartJob):
        return 0.0
    lay = panel_layout(job, policy)
    tau = policy.first_guess(lay.speed)
    seg = raster_segments([0.0, lay.spacing], 0.0, lay.speed, [tau], (tau, tau))
    u = seg.evaluate(np.linspace(0.0, seg.total, TURN_SAMPLES))[0]
    return float(np.abs(u).max())  # past the pass's end (its half length here 0)


def screen_margin(robot, strokes: Strokes) -> float:
    """How far past the part [m] along the axis the band grid must run to see every point of
    the strokes' plane in the robot's reach ball (a robot may be moved along the axis)."""
    c, r = reach_ball(robot.params)
    tip = strokes.samples[len(strokes.samples) // 2][1][0]
    depth = abs(float((tip - c) @ strokes.facing))
    half = math.sqrt(max(r * r - depth * depth, 0.0))
    cw = float(c @ strokes.axis)
    lo, hi = strokes.extent
    return max(cw + half - hi, lo - (cw - half), 0.0) + SCREEN_STEP


def reach(robot, strokes: Strokes, robots: int) -> tuple[float, dict, object]:
    """(constraint [m]: what a zone needs beyond the band, figures, the band): figures the
    band's width, the fewest robots it takes (0: none up to the most a cell has)."""
    band = robot_band(robot, CellRobot("reference"), strokes,
                      margin=screen_margin(robot, strokes), step=SCREEN_STEP,
                      most=SCREEN_STROKES, shift_step=SCREEN_SHIFT)
    need = max(b - a for a, b in zone_needs(strokes, robots))
    fewest = fewest_for(strokes, band.width)
    fig = {"band_m": band.width, "robots_needed": fewest or 0}
    if not band.empty:  # where it starts along the axis (none: no NaN in a table)
        fig["band_lo_m"] = band.lo
    return need - band.width, fig, band


def panel_reach(robot, job) -> tuple[float, dict]:
    """(constraint: the share of a still panel's gun poses out of reach, figures): the gun
    at the standoff over the panel and its run-on, :data:`SCREEN_STEP` apart, spraying along
    −n (the workspace map's checks, docs/model.md §22)."""
    from ..painting.passes.raster import SPOT_RADIUS
    from ..painting.workpiece.panel import panel_frame

    f = panel_frame(job)
    run = SPOT_RADIUS * job.sigma
    U, V = (np.linspace(-(d / 2 + run), d / 2 + run,
                        max(2, int(math.ceil((d + 2 * run) / SCREEN_STEP)) + 1))
            for d in (job.width, job.height))
    tips = f.world(*np.meshgrid(U, V), offset=job.standoff).reshape(-1, 3)
    spray = np.tile(-f.n, (len(tips), 1))
    poses = base_poses(CellRobot("reference"), tips, spray, True, f.n)
    share = float((evaluate(robot, poses)["reachable"] > 0).mean())
    return 1.0 - share, {"reached_share": share}


def held_poses(robot, strokes: Strokes, band) -> np.ndarray | None:
    """Gun poses (3, 6) at the band's ends and middle on the middle stroke, at the first
    shift along the line where all three are in reach (None: no such shift)."""
    lo, hi = strokes.extent
    margin = max(lo - strokes.run_on - band.lo, band.hi - hi - strokes.run_on, 0.0)
    w, tips, spray = strokes.grid(margin + SCREEN_STEP, SCREEN_STEP)  # continued straight
    k = len(tips) // 2
    at = [band.lo, (band.lo + band.hi) / 2, band.hi]
    tip = np.array([[np.interp(a, w, tips[k, :, i]) for i in range(3)] for a in at])
    ax = np.array([[np.interp(a, w, spray[k, :, i]) for i in range(3)] for a in at])
    poses = base_poses(CellRobot("reference"), tip, ax / np.linalg.norm(ax, axis=1)[:, None],
                       strokes.panel, strokes.facing)
    span = ball_shift_range(robot.params, poses[:, :3], strokes.direction)
    if span is None:
        return None
    shifts = np.arange(span[0], span[1] + SCREEN_SHIFT / 2, SCREEN_SHIFT)
    moved = np.repeat(poses[None], len(shifts), axis=0)
    moved[..., :3] += shifts[:, None, None] * strokes.direction
    ok = (evaluate(robot, moved.reshape(-1, 6))["reachable"] > 0).reshape(len(shifts), 3)
    rows = np.flatnonzero(ok.all(axis=1))
    if not len(rows):
        return None
    return moved[rows[len(rows) // 2]]  # the middle of the shifts that hold all three


def motors(robot, actuators, poses: np.ndarray) -> tuple[float, dict]:
    """(constraint: the static use over 1, figures) at ``poses``: the holding torque over
    each motor's peak (any pose) and over its continuous rating (their mean)."""
    from ..analytic.closed_form import position_ik_masked

    q = position_ik_masked(robot.params, poses)[0][:, :12]
    K, _ = kinematic_matrices(robot, q)
    tau, _ = holding_torques(robot, q, K)  # (3, 6) actuated joint torques [N·m]
    n = actuators.column("gear_ratio")
    motor = np.abs(tau) / n + actuators.column("coulomb")
    peak = float((motor / actuators.column("peak_torque")).max())
    rated = float((motor.mean(axis=0) / actuators.column("continuous_torque")).max())
    use = max(peak, rated)
    return use - 1.0, {"static_peak_use": peak, "static_rated_use": rated}


__all__ = ["SCREEN_STEP", "SCREEN_STROKES", "held_poses", "motors", "panel_reach", "reach",
           "screen_margin", "turn_runon"]
