"""Closed-loop simulation of a tool trajectory (docs/model.md §18): a controller of
:mod:`.control` drives the plant (:class:`~pollard_pin.dynamics.plant.Plant`) along the
reference.

* Sensing (:func:`sensed_state`): the controller sees what the robot measures, the six actuator
  angles and rates (with optional seeded noise); the passive joints come from forward
  kinematics of those angles, their rates from the closed-loop velocity map. The loop senses
  by one compiled call per tick (:class:`~pollard_pin.kinematics.sensing.LoopSensor`, the
  same to round-off, Pinocchio's path where it is not sure).
* :func:`simulate_tracking`: the plant integrated by fixed-step RK4 under the controller's
  torque, held over each control period (zero-order hold), saturated per actuator
  (:class:`~.tracking_options.TrackingOptions`). One row per sample time of the input
  trajectory, a :class:`~.tracking_result.TrackingResult`.
"""
from __future__ import annotations

import dataclasses
import math
import re
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..analytic.taskspace import rotation
from ..checks import shorten
from ..errors import say_less
from ..kinematics.closure import close_loops, tool_pose
from ..kinematics.errors import ClosureError, SingularityError
from ..kinematics.kernels import rk4_step
from ..kinematics.limits import first_violation, limit_bounds, violation_text
from ..kinematics.sensing import LoopSensor
from ..kinematics.singularity import actuator_velocity_map
from ..model.build import Robot, check_robot
from .control import (
    ComputedTorque,
    ControlError,
    DesiredTrajectory,
    FeedforwardPD,
    Gains,
    PDGravity,
    desired_trajectory,
    make_controller,
)
from .drives.flexible import (
    FlexiblePlant,
    flexible_step,
    mode_configurations,
    motor_reference,
)
from .forward import SimulationError
from .plant import Plant
from .tracking_options import (
    DT,
    LOOP_TOLERANCE,
    MAX_STEPS,
    STEP_SECONDS,
    TICK_SECONDS,
    MeasurementNoise,
    TrackingOptions,
    check_step_count,
    check_steps,
    default_step,
    estimated_wall,
    integration_steps,
    step_used,
)
from .tracking_result import TrackingResult

START_TOL = 1e-6  # m and rad: a start configuration this close to the first pose is on the path
DIVERGED_ANGLE = 1e4  # rad (1,600 turns): a joint this far out means the simulation diverged

def sensed_state(robot: Robot, theta: np.ndarray, dtheta: np.ndarray,
                 q_guess: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(q (12,), v (12,)) from the measured actuator angles ``theta`` and rates ``dtheta`` (6,):
    the passive joints by forward kinematics (:func:`solve_closure`, warm-started at
    ``q_guess``, loops closed to 1e-12 m), their rates by v = N(q)·θ̇ (docs/model.md §12)."""
    return sensed_kinematics(robot, theta, dtheta, q_guess)[:2]


def sensed_kinematics(robot: Robot, theta: np.ndarray, dtheta: np.ndarray,
                      q_guess: np.ndarray | None = None):
    """(q, v, Jc, N): :func:`sensed_state` with the constraint Jacobian Jc (6 × 12) and the
    velocity map N (12 × 6) at q that it built, for the controller to reuse."""
    q, Jc = close_loops(robot, theta, q_guess)
    N = actuator_velocity_map(Jc, robot.actuated_v, robot.passive_v)
    return q, N @ dtheta, Jc, N


def _start_state(plant: Plant, desired: DesiredTrajectory, trajectory, start):
    """(q0, v0): the reference's start, or ``start`` = q0 (at rest) checked against the path."""
    if start is None:
        return desired.q[0].copy(), desired.v[0].copy()
    q0 = np.asarray(start, dtype=float).reshape(-1)
    if q0.shape != (plant.robot.model.nq,) or not np.all(np.isfinite(q0)):
        raise ControlError(f"start configuration must be {plant.robot.model.nq} finite joint "
                           f"angles, got shape {q0.shape}")
    residual = plant.closure_residual(q0)
    if residual > 1e-9:
        raise ControlError(f"start configuration does not close the loops: residual "
                           f"{residual:.3g} m (> 1e-09 m)")
    M = tool_pose(plant.nominal, q0)
    p_err = float(np.linalg.norm(M.translation - trajectory.poses[0, :3]))
    o_err = float(np.linalg.norm(pin.log3(M.rotation @ rotation(trajectory.poses[0]).T)))
    rate = float(np.abs(trajectory.d_poses[0]).max())
    if rate > START_TOL >= max(p_err, o_err):
        # On the path but moving: say so, rather than "off the path" at 1e-16 m.
        raise ControlError(
            f"trajectory starts moving (pose rate {rate:.4g} > {START_TOL:g}) but a given start "
            "configuration is at rest: start the trajectory at rest or start on the path")
    if p_err > START_TOL or o_err > START_TOL or rate > START_TOL:
        raise ControlError(
            f"trajectory starts off the path: its first pose is {p_err:.4g} m and "
            f"{o_err:.4g} rad from the start configuration's tool pose, with rate "
            f"{rate:.4g} (the robot starts at rest; tolerance {START_TOL:g})")
    return q0, np.zeros(plant.robot.model.nv)


def _nearest(sorted_points: np.ndarray, x: np.ndarray) -> np.ndarray:
    j = np.clip(np.searchsorted(sorted_points, x), 1, len(sorted_points) - 1)
    return np.where(np.abs(sorted_points[j - 1] - x) <= np.abs(sorted_points[j] - x), j - 1, j)


def _grid(ticks: np.ndarray, samples: np.ndarray, dt: float):
    """Integration breakpoints: each control interval split in equal steps ≤ dt, output sample
    times inserted. Returns (points, tick flag, sample index or −1)."""
    pts = []
    for a, b in zip(ticks[:-1], ticks[1:]):
        n = max(1, int(math.ceil((b - a) / dt - 1e-9)))
        pts.append(a + (b - a) * np.arange(n) / n)
    pts.append(ticks[-1:])
    pts = np.concatenate(pts)
    is_tick = np.zeros(len(pts), bool)
    is_tick[np.searchsorted(pts, ticks)] = True
    # Snap each sample to a breakpoint within 1e-9·dt, else insert it.
    new = np.abs(pts[_nearest(pts, samples)] - samples) > 1e-9 * dt
    if new.any():
        pts = np.concatenate([pts, samples[new]])
        is_tick = np.concatenate([is_tick, np.zeros(int(new.sum()), bool)])
        order = np.argsort(pts, kind="stable")
        pts, is_tick = pts[order], is_tick[order]
    near = _nearest(pts, samples)
    sample = np.full(len(pts), -1)
    sample[near] = np.arange(len(samples))
    return pts, is_tick, sample


def _unstable_hint(gains: Gains, control_period: float) -> str:
    """What to change when the plant runs away while the torque is not saturated."""
    # A sampled PD is stable only for ω·T well below 1 (torque held for T).
    wt = gains.wn * control_period
    return (f"the gains are too high for the control period (ω·T = {wt:.3g}; keep it below "
            "about 0.5)" if wt > 0.5 else
            "the controller does not hold the path: reduce the time step, check the gains and "
            "the model mismatch")


def _stop_hint(saturated_since: float | None, gains: Gains, control_period: float) -> str:
    """What to change when the plant leaves its limits or loop tolerance."""
    if saturated_since is not None:
        return (f"the torque has been saturated since t = {saturated_since:.6g} s: raise the "
                "torque limit or slow the trajectory")
    return _unstable_hint(gains, control_period)


def _check_plant(plant: Plant, q: np.ndarray, residual: float, t: float, joint_limits,
                 tolerance: float, hint: Callable[[], str]) -> None:
    """Stop where the plant is no longer the robot: loops open beyond ``tolerance`` [m], or
    (``joint_limits``: the joint names and their :func:`limit_bounds`, or None) a joint
    outside its limits. ``hint()`` says what to change (built only on failure: this runs every
    tick)."""
    why = None
    if residual > tolerance:
        why = (f"the plant's loops opened to {residual:.3g} m (loop tolerance "
               f"{tolerance:g} m, docs/model.md §18)")
    elif joint_limits is not None:
        names, bounds = joint_limits
        bad = first_violation(plant.robot.params, q, names, bounds)
        if bad is not None:
            _, j, excess = bad
            why = "the plant left its joint limits: " + violation_text(
                plant.robot.params, names[j], float(q[j]), excess)
    if why is not None:
        said = f"simulation stopped at t = {t:.6g} s: {why}"
        bare = re.sub(r" \[[^\]]*\]", "", said)  # the joint's limits left out
        h = hint()
        raise SimulationError(say_less(f"{said}; {h}", f"{bare}; {h}",
                                       f"{bare}; {h.split(': ')[0]}",
                                       f"{said}; {h.split(': ')[-1]}", said))


class _Ticking:
    """The controller's side of the loop: at each control tick the actuators sensed (with
    their noise), the controller asked, its torque saturated; the time spent saturated."""

    def __init__(self, robot: Robot, plant: Plant, controller, desired: DesiredTrajectory,
                 opts: TrackingOptions):
        self.controller = controller
        self.builtin = isinstance(controller, (ComputedTorque, FeedforwardPD, PDGravity))
        self.ia = plant.sensed_v
        self.noise = opts.noise
        self.rng = np.random.default_rng(opts.noise.seed) if opts.noise is not None else None
        self.sense = LoopSensor(robot)  # sensed_kinematics, compiled (one call per tick)
        self.limit = opts.limits
        self.guess, self.v_seen = desired.q[0], desired.v[0]  # the first FK's warm start
        # equal coefficients as arrays: cheaper than a Python float times an array, same bits
        self.P, self.C15, self.C05 = (np.full(plant.robot.model.nv, x)
                                      for x in (opts.control_period, 1.5, 0.5))
        self.gains, self.period = opts.gains, opts.control_period
        self.saturated_since, self.saturation = None, 0.0

    def hint(self) -> str:
        return _unstable_hint(self.gains, self.period)

    def stop_hint(self) -> str:
        return _stop_hint(self.saturated_since, self.gains, self.period)

    def torque(self, t: float, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The held actuator torque (6,) from the tick at time ``t``, plant state q, v."""
        theta, dtheta = q[self.ia], v[self.ia]  # copies (an index array)
        noise = self.noise
        if self.rng is not None:
            theta += self.rng.normal(0.0, noise.position, 6) if noise.position else 0.0
            dtheta += self.rng.normal(0.0, noise.velocity, 6) if noise.velocity else 0.0
        try:
            qm, vm, Jc, N, a0 = self.sense(theta, dtheta, self.guess)
        except ClosureError as exc:  # the plant ran away between ticks, or the noise
            what = ("close the loops only on a parallel singularity"
                    if isinstance(exc, SingularityError) or exc.residual is None else
                    f"close no loop (leg {exc.leg} is {exc.residual * 1e3:.4g} mm off)")
            raise SimulationError(f"simulation stopped at t = {t:.6g} s: the sensed actuator "
                                  f"angles {what}; {self.hint()}") from None
        # The next tick's FK warm start, second order: Newton then needs one step.
        self.guess = qm + self.P * (self.C15 * vm - self.C05 * self.v_seen)
        self.v_seen = vm
        c = self.controller
        command = c(t, qm, vm, Jc, N, a0) if self.builtin else c(t, qm, vm)
        command = np.asarray(command, dtype=float).reshape(-1)
        if command.shape != (6,) or not math.isfinite(sum(command.tolist())) and not np.all(
                np.isfinite(command)):  # (a finite sum: all finite, the common case)
            raise ControlError(f"controller returned {command!r} at t = {t:.6g} s; "
                               "expected 6 finite actuator torques")
        limit = self.limit
        tau = command if limit is None else np.clip(command, -limit, limit)
        clipped = limit is not None and bool(np.any(np.abs(command) > limit))
        if self.saturated_since is not None and not clipped:
            self.saturation += t - self.saturated_since
            self.saturated_since = None
        elif clipped and self.saturated_since is None:
            self.saturated_since = t
        return tau

    def finish(self, t_end: float) -> None:
        if self.saturated_since is not None:
            self.saturation += t_end - self.saturated_since


@dataclass
class _Record:
    """The plant at the output samples, from :func:`_integrate`."""

    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    tau: np.ndarray
    residual: np.ndarray
    max_residual: float
    steps: int
    wall: float


def _integrate(plant: Plant, ticking: _Ticking, q: np.ndarray, v: np.ndarray, grid, n: int,
               opts: TrackingOptions) -> _Record:
    """RK4 over the breakpoints of ``grid`` (:func:`_grid`) from (q, v), the torque of each
    tick held; the state at the ``n`` output samples. Small-vector arithmetic
    (docs/model.md §18): numpy's fixed cost dominates, so each form below is the cheapest of
    the same bits: RK4's stages compiled (kernels.rk4_step), dot products and Python's min
    over a list for reductions (≈ 0.5 µs against 1.5)."""
    # as Python scalars: the loop reads three per step (numpy scalars cost more, same bits)
    pts, is_tick, sample_of = (x.tolist() for x in grid)
    nv, nx = plant.robot.model.nv, len(q)  # nx: the state's size (flexible: 12 + 6 motors)
    Q, V, A = np.empty((n, nx)), np.empty((n, nx)), np.empty((n, nx))
    TAU, RES = np.empty((n, 6)), np.empty(n)
    f = plant.held(np.zeros(6))
    tau = np.zeros(6)
    max_res = 0.0
    names = plant.robot.joint_names
    limits = (names, limit_bounds(plant.robot.params, names)) if opts.joint_limits else None
    lo, hi = limits[1] if opts.joint_limits else (None, None)
    if lo is not None and nx > nv:  # the motors have no limits
        pad = np.full(nx - nv, np.inf)
        lo, hi = np.append(lo, -pad), np.append(hi, pad)
    tolerance, progress = opts.loop_tolerance, opts.progress
    stage_q, stage_v = np.empty(nx), np.empty(nx)
    clock = time.perf_counter()
    last = len(pts) - 1
    for i in range(len(pts)):
        t = pts[i]
        # Non-finite, or spun through thousands of turns: the loop closure would fail first
        # and hide the cause. (NaN fails every comparison; q·q < Θ² bounds every |q_j| < Θ,
        # the exact test decides when it fails.)
        if not (q.dot(q) < DIVERGED_ANGLE ** 2 and v.dot(v) < math.inf) and not (
                np.abs(q).max() < DIVERGED_ANGLE and np.abs(v).max() < math.inf):
            raise SimulationError(f"simulation diverged at t = {t:.6g} s: state not finite or "
                                  f"beyond {DIVERGED_ANGLE:g} rad; {ticking.hint()}")
        tick = is_tick[i]
        if tick:
            tau = ticking.torque(t, q, v)
            f = plant.held(tau)
        a1 = f(q, v)
        k = sample_of[i]
        if tick or k >= 0:  # the loop residual at q, where f just placed the closures
            res = plant.last_closure_residual()
            if tick:
                max_res = max(max_res, res)
                # (q − lo)(hi − q) > 0 for every joint: strictly inside its limits (the common
                # case); at a bound, outside or NaN, the exact rule (turns counted) decides
                if res > tolerance or lo is not None and not min(
                        ((q - lo) * (hi - q)).tolist()) > 0.0:
                    _check_plant(plant, q[:nv], res, t, limits, tolerance,
                                 ticking.stop_hint)
        if k >= 0:
            Q[k], V[k], A[k], TAU[k] = q, v, a1, tau
            RES[k] = res
            if progress is not None:
                progress(k + 1, n)
        if i == last:
            break
        q, v = rk4_step(f, q, v, a1, pts[i + 1] - t, stage_q, stage_v)
    ticking.finish(pts[-1])
    wall = time.perf_counter() - clock
    return _Record(Q, V, A, TAU, RES, max(max_res, float(RES.max())), last, wall)


def _result(robot: Robot, plant: Plant, trajectory, samples: np.ndarray, record: _Record,
            ticking: _Ticking, opts: TrackingOptions) -> TrackingResult:
    """The result table: the tool pose of every output sample against the trajectory's."""
    n, nv = len(samples), plant.robot.model.nv
    tip = np.empty((n, 3))
    o_err = np.empty(n)
    R_des = rotation(trajectory.poses)
    for k in range(n):
        M = tool_pose(plant.robot, record.q[k, :nv])
        tip[k] = M.translation
        o_err[k] = np.linalg.norm(pin.log3(M.rotation @ R_des[k].T))
    tip_des = np.asarray(trajectory.poses, dtype=float)[:, :3]
    limit, noise = opts.limits, opts.noise
    settings = {"controller": opts.label,
                "wn": opts.gains.wn, "zeta": opts.gains.zeta,
                "dt": step_used(opts.step, opts.control_period),
                "control_period": opts.control_period,
                "payload": plant.errors.payload, "mass_error": plant.errors.mass_error,
                "torque_limit": None if limit is None else limit.tolist(),
                "noise": None if noise is None else [noise.position, noise.velocity,
                                                     noise.seed]}
    motors = record.q.shape[1] > nv  # flexible drives: the motors' angles and rates
    return TrackingResult(
        t=samples.copy(), q=record.q[:, :nv], v=record.v[:, :nv], a=record.a[:, :nv],
        tau=record.tau, tip=tip,
        tip_desired=tip_des, tip_position_error=np.linalg.norm(tip - tip_des, axis=1),
        tip_orientation_error=o_err, closure_residual=record.residual,
        joint_names=plant.robot.joint_names, actuated=robot.actuated,
        saturation_time=ticking.saturation, max_closure_residual=record.max_residual,
        steps=record.steps, wall=record.wall, settings=settings,
        phi=record.q[:, nv:] if motors else None, d_phi=record.v[:, nv:] if motors else None)


def simulate_tracking(robot: Robot, trajectory,
                      options: TrackingOptions | None = None) -> TrackingResult:
    """Simulate the closed loop along ``trajectory`` (``t``, ``poses``, ``d_poses``,
    ``dd_poses``, e.g. :class:`~pollard_pin.paths.trajectory.Trajectory`; its ``curve``, if
    any, is the path between the samples the reference follows) as ``options`` say
    (:class:`TrackingOptions`: controller, plant errors, gains, steps, torque limit, noise,
    start; default its defaults).

    The run stops with a ``SimulationError`` when, at a control tick, the plant's loops open
    beyond ``options.loop_tolerance`` [m] (default 1e-5 m) or (``joint_limits``, the default)
    a joint leaves its limits: past either the motion is not the robot's (e.g. saturated
    torques let it fall). With ``joint_limits`` the reference must keep the limits too
    (:func:`~pollard_pin.dynamics.desired_trajectory`). Past 500,000 RK4 steps it refuses at once.

    Parameters
    ----------
    robot : Robot
        The nominal model (the controller's); the plant is ``robot`` changed by
        ``options.errors``.
    trajectory : Trajectory
        The tool path to track.
    options : TrackingOptions or None, optional
        Controller (``"computed-torque"``, ``"feedforward-pd"``, ``"pd"`` or a callable
        ``controller(t, q, v) → τ (6,)``), plant errors, gains, steps, torque limit, noise,
        start (default: computed torque on the exact model).

    Returns
    -------
    TrackingResult
        The plant's motion, the applied torques and the tracking errors at the trajectory's
        times.

    Raises
    ------
    pollard_pin.dynamics.tracking.SimulationError
        The loops open or a joint leaves its limits during the run.
    pollard_pin.dynamics.control.ControlError
        Options that are not a :class:`~pollard_pin.TrackingOptions`, too many RK4 steps.
    KinematicsError
        The reference cannot be solved.

    Examples
    --------
    >>> import pollard_pin as pp
    >>> robot = pp.load()
    >>> traj = pp.thesis_trajectory(duration=5.0, samples=21)     # the thesis curve, 4x faster
    >>> res = pp.simulate_tracking(robot, traj, pp.TrackingOptions("computed-torque"))
    >>> res.steps, bool(res.summary()["max_tip_position_error"] < 1e-3)     # 0.12 mm
    (5000, True)
    """
    opts = TrackingOptions() if options is None else options
    if not isinstance(opts, TrackingOptions):
        raise ControlError(f"options must be a TrackingOptions, got {type(opts).__name__}")
    check_robot(robot)
    if not all(hasattr(trajectory, a) for a in ("t", "poses", "d_poses", "dd_poses")):
        raise ControlError(f"trajectory = {shorten(trajectory)}: expected a Trajectory (t, "
                           f"poses, d_poses, dd_poses), got {type(trajectory).__name__}")
    samples = np.asarray(trajectory.t, dtype=float)
    drives = opts.drives
    if drives is not None and opts.known_losses is None:
        # the controller knows its own motors (N²Jm, friction) unless it is told otherwise: a
        # feedforward blind to the rotors behind the springs misses by centimetres
        opts = dataclasses.replace(opts, known_losses=drives.losses(robot.model.nv,
                                                                     robot.actuated_v))
    if drives is None and samples.ndim == 1 and len(samples) >= 2:  # (else refused below)
        check_step_count(float(samples[-1] - samples[0]), opts.step, opts.control_period)
    plant = (Plant(robot, opts.errors, opts.baumgarte) if drives is None else
             FlexiblePlant(robot, opts.errors, drives, opts.baumgarte))
    desired = opts.desired
    if desired is None:
        desired = desired_trajectory(robot, trajectory, opts.control_period, opts.curve,
                                     opts.known_losses, joint_limits=opts.joint_limits)
    reference, fastest = desired, None
    if drives is not None:  # the controller tracks the motors' reference (docs/model.md §28)
        step, fastest = flexible_step(plant, mode_configurations(desired.q),
                                      default_step(opts.control_period), opts.dt)
        opts = dataclasses.replace(opts, dt=step)
        check_step_count(float(samples[-1] - samples[0]), opts.step, opts.control_period)
        reference = motor_reference(robot, desired, drives, opts.known_losses)
    controller = opts.controller
    if isinstance(controller, str):
        controller = make_controller(controller, robot, reference, opts.gains, opts.known_losses)
    q, v = _start_state(plant, desired, trajectory, opts.start)
    if drives is not None:  # the motors where the springs carry the link
        q, v = plant.start(q, v, reference, at_rest=opts.start is not None)
    ticking = _Ticking(robot, plant, controller, reference, opts)
    grid = _grid(desired.t, samples, opts.step)
    # a plant that runs away overflows on its way out: the loop names it once, no warnings
    with np.errstate(over="ignore", invalid="ignore"):
        record = _integrate(plant, ticking, q, v, grid, len(samples), opts)
    result = _result(robot, plant, trajectory, samples, record, ticking, opts)
    if drives is not None:
        result.settings["drives"] = drives.settings(fastest)
    return result


__all__ = ["DT", "LOOP_TOLERANCE", "MAX_STEPS", "STEP_SECONDS", "TICK_SECONDS",
           "MeasurementNoise", "TrackingOptions", "check_step_count",
           "check_steps", "default_step", "estimated_wall", "integration_steps",
           "sensed_kinematics", "sensed_state", "simulate_tracking", "step_used"]
